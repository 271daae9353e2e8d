# The owned particles split by whether their neighbour-list rows read a ghost (GhostRowSplit).
gpudem_add_test(test_ghost_rows
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/GhostRowSplitTest.cpp
  LIBS gpudem_engine
  LABELS unit
  TIMEOUT 60)
