# The two optimizers of scripts/calibrate.py (scripts/calibration_optimizers.py) on a noisy
# synthetic objective of known optimum, no solver run: both reach it, Bayesian optimization in at
# most a fifth of the evaluations differential evolution needs; both reproducible from the seed.
add_test(NAME calibration_optimizers
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_calibration_optimizers.py
          ${PROJECT_SOURCE_DIR})
set_tests_properties(calibration_optimizers PROPERTIES LABELS unit TIMEOUT 300)
