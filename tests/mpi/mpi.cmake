# Rank-count cases run through mpirun. Until the domain is decomposed, a start with more than
# one rank must stop at once with exit code 2 and a message, writing nothing.
find_program(GPUDEM_MPIRUN NAMES mpirun mpiexec REQUIRED)
add_test(NAME cli_refuses_two_ranks
  COMMAND ${CMAKE_COMMAND}
    -DMPIRUN=${GPUDEM_MPIRUN} -DBINARY=$<TARGET_FILE:gpudem-mpi>
    -DSCENE=${PROJECT_SOURCE_DIR}/inputs/quickstart.toml
    -DOUT=${CMAKE_CURRENT_BINARY_DIR}/two_ranks_out
    -P ${CMAKE_CURRENT_SOURCE_DIR}/mpi/scripts/RefuseRanks.cmake)
set_tests_properties(cli_refuses_two_ranks PROPERTIES LABELS mpi TIMEOUT 60
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
