gpudem_add_test(test_contact_law
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/ContactLawTest.cpp
  LIBS gpudem_kernels
  LABELS unit)
