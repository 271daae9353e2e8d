gpudem_add_test(test_stl_reader
  SOURCES unit/StlReaderTest.cpp
  LIBS gpudem_mesh
  LABELS unit)
