# Checkpoints and restart: the checkpoint file itself (also written from 2 ranks and read
# back on one), and the gpudem-mpi binary restarted from its checkpoints.
gpudem_add_test(test_checkpoint
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/CheckpointTest.cpp
  LIBS gpudem_comm
  LABELS unit
  TIMEOUT 60)

add_test(NAME test_checkpoint_np2
  COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 ${MPIEXEC_PREFLAGS}
          $<TARGET_FILE:test_checkpoint> ${MPIEXEC_POSTFLAGS}
          --gtest_filter=CheckpointFile.RoundTrip*:CheckpointFile.Parts*:CheckpointFile.Empty*:CheckpointFile.Stale*:CheckpointFile.Snapshot*:CheckpointFile.Ranks*)
set_tests_properties(test_checkpoint_np2 PROPERTIES
  LABELS mpi
  TIMEOUT 120
  PROCESSORS 2
  ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")

gpudem_add_test(test_restart_cli
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/RestartCommandLineTest.cpp
  LIBS gpudem_comm
  LABELS unit
  TIMEOUT 120)
add_dependencies(test_restart_cli gpudem-mpi)
set_tests_properties(test_restart_cli PROPERTIES PROCESSORS 2)  # one case runs on 2 ranks
