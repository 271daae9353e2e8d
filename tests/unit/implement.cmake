gpudem_add_test(test_implement SOURCES unit/ImplementTest.cpp LIBS gpudem_mesh LABELS unit
  TIMEOUT 120)
add_dependencies(test_implement gpudem-mpi)
