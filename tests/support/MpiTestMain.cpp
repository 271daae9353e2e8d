// GoogleTest main for every test executable: MPI is initialised once, at the program's thread
// level (singleton runs work without mpirun), then all tests run.
#include <gtest/gtest.h>
#include <mpi.h>

#include "comm/MpiInit.hpp"

int main(int argc, char** argv) {
  gpudem::init_mpi(argc, argv);  // as the program does
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  MPI_Finalize();
  return result;
}
