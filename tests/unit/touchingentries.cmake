gpudem_add_test(test_touching_entries SOURCES unit/TouchingEntriesTest.cpp LIBS gpudem_engine
                LABELS unit)
