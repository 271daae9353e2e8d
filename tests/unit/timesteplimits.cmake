gpudem_add_test(test_time_step_limits SOURCES ${CMAKE_CURRENT_LIST_DIR}/TimeStepLimitsTest.cpp
  LIBS gpudem_sim LABELS unit)
# dt = "adaptive": the substeps of a base step and the time of a point of the step grid.
gpudem_add_test(test_adaptive_step SOURCES ${CMAKE_CURRENT_LIST_DIR}/AdaptiveStepTest.cpp
  LIBS gpudem_sim LABELS unit)
