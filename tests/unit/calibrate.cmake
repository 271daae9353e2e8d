# scripts/calibrate.py on a stand-in solver (tests/scripts/fake_calibration_solver.py): the stored
# evaluations and their beds' times, a kill and resume against an uninterrupted calibration (also
# with a run stopped as unstable), Slurm job arrays, the refusals and the sensitivity of
# synthetic evaluations.
add_test(NAME calibrate
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_calibrate.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/calibrate)
set_tests_properties(calibrate PROPERTIES LABELS unit TIMEOUT 300 PROCESSORS 2)
