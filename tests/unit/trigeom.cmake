gpudem_add_test(test_triangle_contact
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/TriangleContactTest.cpp
  LIBS gpudem_engine
  LABELS unit)
