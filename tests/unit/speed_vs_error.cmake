# The speed-against-error study (scripts/speed_vs_error.py) with the real solver on a cut-down
# impact scene: the table, the recommendation, the Pareto front, resuming after a kill and the
# refusals.
add_test(NAME speed_vs_error
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_speed_vs_error.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/speed_vs_error
          $<TARGET_FILE:gpudem-mpi>)
set_tests_properties(speed_vs_error PROPERTIES LABELS unit TIMEOUT 120
  ENVIRONMENT "OMP_NUM_THREADS=1;OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")
