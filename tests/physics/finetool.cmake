# The quickstart pass with the sweep split into 20,000 triangles against the shipped 32-triangle
# sweep: the fine tool runs and gives the same steady draft within its fluctuation.
add_test(NAME fine_tool_draft
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_fine_tool.sh ${PROJECT_SOURCE_DIR}
          $<TARGET_FILE:gpudem-mpi> ${CMAKE_CURRENT_BINARY_DIR}/fine_tool_draft)
set_tests_properties(fine_tool_draft PROPERTIES LABELS physics TIMEOUT 900 PROCESSORS 2
  ENVIRONMENT "OMP_NUM_THREADS=2;OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")
