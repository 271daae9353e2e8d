# scripts/brazilian_test.py on one small realisation: a cemented packing cut into a bar pulled
# by grips and a disc split between platens, the study's resume and its refusals.
add_test(NAME brazilian_clod
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_brazilian_test.py
          ${PROJECT_SOURCE_DIR} $<TARGET_FILE:gpudem-mpi> ${CMAKE_CURRENT_BINARY_DIR}/brazilian)
set_tests_properties(brazilian_clod PROPERTIES LABELS physics TIMEOUT 300
  ENVIRONMENT "OMP_NUM_THREADS=1")
