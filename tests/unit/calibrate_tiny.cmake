# scripts/calibrate.py end to end with gpudem-mpi on the tiny case (inputs/calibration/tiny.toml):
# four evaluations, two at a time, each with its own bed; the stored results against the runs'
# output, resuming, and the refusals that gpudem-mpi --check finds.
add_test(NAME calibrate_tiny
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_calibrate_tiny.py
          ${PROJECT_SOURCE_DIR} $<TARGET_FILE:gpudem-mpi>
          ${CMAKE_CURRENT_BINARY_DIR}/calibrate_tiny)
set_tests_properties(calibrate_tiny PROPERTIES LABELS unit TIMEOUT 300 PROCESSORS 2
  ENVIRONMENT "OMP_NUM_THREADS=1")
