# The portable layer's sort and the launch tuner (block-size table, medians, rank agreement with
# injected timings).
gpudem_add_test(test_sort_by_key
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/SortByKeyTest.cpp
  LIBS gpudem_engine
  LABELS unit
  TIMEOUT 60)
gpudem_add_test(test_launch_tuning
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/LaunchTuningTest.cpp
  LIBS gpudem_engine
  LABELS unit
  TIMEOUT 60)
if(GPUDEM_HAVE_CUDA)
  gpudem_add_test(test_portable_cuda
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/PortableCudaTest.cu
    LIBS gpudem_engine
    LABELS unit
    TIMEOUT 60)
endif()
