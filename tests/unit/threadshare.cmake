gpudem_add_test(test_thread_share SOURCES unit/ThreadShareTest.cpp LABELS unit)
