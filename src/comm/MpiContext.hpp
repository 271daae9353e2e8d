#pragma once
/// MPI for the lifetime of the program: initialised on construction, at the thread level
/// MPI_THREAD_MULTIPLE where the library offers it (SnapshotQueue.hpp), finalised on destruction.
#include <mpi.h>

namespace gpudem {

class MpiContext {
 public:
  MpiContext(int& argc, char**& argv);
  ~MpiContext();
  MpiContext(const MpiContext&) = delete;
  MpiContext& operator=(const MpiContext&) = delete;

  MPI_Comm comm() const { return MPI_COMM_WORLD; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }
  /// Rank among the ranks on this node (MPI_COMM_TYPE_SHARED), and their number.
  int local_rank() const { return local_rank_; }
  int local_size() const { return local_size_; }

 private:
  int rank_ = 0;
  int size_ = 1;
  int local_rank_ = 0;
  int local_size_ = 1;
};

}  // namespace gpudem
