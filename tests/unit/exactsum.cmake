gpudem_add_test(test_exact_sum SOURCES unit/ExactSumTest.cpp LIBS gpudem_engine LABELS unit)
