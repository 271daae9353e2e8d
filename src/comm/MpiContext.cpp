#include "comm/MpiContext.hpp"

#include "comm/MpiInit.hpp"

namespace gpudem {

MpiContext::MpiContext(int& argc, char**& argv) {
  init_mpi(argc, argv);
  world_.emplace(MPI_COMM_WORLD);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank(), MPI_INFO_NULL, &node);
  MPI_Comm_rank(node, &local_rank_);
  MPI_Comm_size(node, &local_size_);
  MPI_Comm_free(&node);
}

MpiContext::~MpiContext() { MPI_Finalize(); }

}  // namespace gpudem
