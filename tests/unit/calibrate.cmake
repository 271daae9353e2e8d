# The calibration (scripts/calibrate.py): its two optimizers on a noisy synthetic objective of
# known optimum, Bayesian optimization in far fewer evaluations than differential evolution
# (no solver run); and the script on a stand-in solver (tests/scripts/fake_calibration_solver.py):
# the stored evaluations, kill and resume, Slurm job arrays, the refusals and the sensitivity.
add_test(NAME calibration_optimizers
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_calibration_optimizers.py
          ${PROJECT_SOURCE_DIR})
add_test(NAME calibrate
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_calibrate.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/calibrate)
set_tests_properties(calibration_optimizers calibrate PROPERTIES LABELS unit TIMEOUT 300)
