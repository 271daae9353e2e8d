# How the programs start MPI: a file opens although a killed job left the semaphore of its name
# taken (a hang, caught by the short timeout, when the setting is lost).
gpudem_add_test(test_mpi_init
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/MpiInitTest.cpp
  LABELS unit
  TIMEOUT 30)
