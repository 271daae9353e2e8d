#pragma once
// This process's rank and the number of ranks in MPI_COMM_WORLD, for tests.
#include <mpi.h>

namespace gpudem::test {

inline int comm_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

inline int comm_size() {
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

}  // namespace gpudem::test
