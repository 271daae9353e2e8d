# Restart equivalence through the engine API and a checkpoint file, per backend.
gpudem_add_test(test_restart
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/RestartTest.cpp
  LIBS gpudem_sim gpudem_comm
  LABELS physics
  TIMEOUT 120)
