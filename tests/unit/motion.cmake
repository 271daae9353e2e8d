gpudem_add_test(test_prescribed_motion
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/PrescribedMotionTest.cpp
  LIBS gpudem_mesh
  LABELS unit)
