# The depth and speed study (scripts/tillage_study.py) on a stand-in solver
# (tests/scripts/fake_gpudem_mpi.py): the table's numbers, resuming after a kill, and the refusals.
add_test(NAME tillage_study
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_tillage_study.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/tillage_study)
set_tests_properties(tillage_study PROPERTIES LABELS unit TIMEOUT 120)
