# Checkpoints and restart: the checkpoint file itself (also written from 2 ranks and read
# back on one), and the gpudem-mpi binary restarted from its checkpoints.
gpudem_add_test(test_checkpoint
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/CheckpointTest.cpp
  LIBS gpudem_comm
  LABELS unit
  TIMEOUT 60)
gpudem_add_test_on_ranks(test_checkpoint RANKS 2
  FILTER "CheckpointFile.RoundTrip*:CheckpointFile.Parts*:CheckpointFile.Empty*:CheckpointFile.Stale*:CheckpointFile.Snapshot*:CheckpointFile.Ranks*")

gpudem_add_test(test_restart_cli
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/RestartCommandLineTest.cpp
  LIBS gpudem_comm
  LABELS unit
  TIMEOUT 120)
add_dependencies(test_restart_cli gpudem-mpi)
set_tests_properties(test_restart_cli PROPERTIES PROCESSORS 2)  # one case runs on 2 ranks
