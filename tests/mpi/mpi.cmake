# Decomposed runs through mpirun at 1 to 4 ranks (--oversubscribe): the same physics as one
# rank, restarts across rank counts, load balance, momentum conservation, particles leaving the
# box while others cross between ranks, a bed placed by tiles with each rank creating its part, a
# sliding contact across a rank boundary, checkpoints of runs killed with SIGKILL, a tool mesh
# across ranks, a piston across ranks, sticky (JKR) grains, a bonded clod that breaks, adaptive
# steps, a bed preparation and the CUDA backend on 1 to 4 ranks (skipped without a device)
# (scripts/decomposed_runs.py).
find_program(GPUDEM_MPIRUN NAMES mpirun mpiexec REQUIRED)
foreach(case same-physics restart balance momentum leaving tiled sliding-pair killed-checkpoint tool
             piston sticky bonded adaptive bed cuda)
  add_test(NAME mpi_${case}
    COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/mpi/scripts/decomposed_runs.py
      --binary $<TARGET_FILE:gpudem-mpi> --mpirun ${GPUDEM_MPIRUN}
      --work ${CMAKE_CURRENT_BINARY_DIR}/mpi_${case} ${case})
  set_tests_properties(mpi_${case} PROPERTIES LABELS mpi TIMEOUT 900 SKIP_RETURN_CODE 77
    ENVIRONMENT "OMPI_MCA_rmaps_base_oversubscribe=1")
endforeach()
