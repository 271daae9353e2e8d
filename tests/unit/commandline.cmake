gpudem_add_test(test_command_line SOURCES unit/CommandLineTest.cpp LABELS unit)
add_dependencies(test_command_line gpudem-mpi)
