# Launch tuning agrees across ranks: the same injected-timing test alone (one rank) and through
# mpiexec at 2 and 4 ranks.
gpudem_add_test(test_launch_tuning_agreement
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/LaunchTuningAgreementTest.cpp
  LIBS gpudem_comm gpudem_engine
  LABELS mpi
  TIMEOUT 60)
gpudem_add_test_on_ranks(test_launch_tuning_agreement RANKS 2 4)
