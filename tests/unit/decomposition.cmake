gpudem_add_test(test_decomposition
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/DecompositionTest.cpp
  LIBS gpudem_decomposition
  LABELS unit
  TIMEOUT 60)
