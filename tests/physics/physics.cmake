gpudem_add_test(test_dynamics SOURCES physics/DynamicsTest.cpp LIBS gpudem_sim LABELS physics)
gpudem_add_test(test_settling SOURCES physics/SettlingTest.cpp LIBS gpudem_sim LABELS physics TIMEOUT 900)
gpudem_add_test(test_contact_history SOURCES physics/ContactHistoryTest.cpp LIBS gpudem_sim LABELS physics)
gpudem_add_test(test_backend_agreement SOURCES physics/BackendAgreementTest.cpp LIBS gpudem_sim LABELS physics TIMEOUT 900)
