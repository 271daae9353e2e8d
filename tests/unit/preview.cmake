gpudem_add_test(test_preview SOURCES unit/PreviewTest.cpp LIBS gpudem_mesh LABELS unit
  TIMEOUT 120)
add_dependencies(test_preview gpudem-mpi)
