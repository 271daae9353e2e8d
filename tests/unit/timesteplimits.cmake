gpudem_add_test(test_time_step_limits SOURCES ${CMAKE_CURRENT_LIST_DIR}/TimeStepLimitsTest.cpp
  LIBS gpudem_sim LABELS unit)
