gpudem_add_test(test_neighbor_list
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/NeighborListTest.cpp
  LIBS gpudem_engine
  LABELS unit)
