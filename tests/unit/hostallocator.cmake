gpudem_add_test(test_host_allocator SOURCES unit/HostAllocatorTest.cpp LIBS gpudem_engine
                LABELS unit)
