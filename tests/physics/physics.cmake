gpudem_add_test(test_dynamics SOURCES physics/DynamicsTest.cpp LIBS gpudem_sim LABELS physics)
gpudem_add_test(test_settling SOURCES physics/SettlingTest.cpp LIBS gpudem_sim LABELS physics TIMEOUT 900)
