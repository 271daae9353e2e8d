#pragma once
/// MPI for the lifetime of the program: initialised on construction, at the thread level
/// MPI_THREAD_MULTIPLE where the library offers it (SnapshotQueue.hpp), finalised on destruction;
/// the group of all ranks, through which the rest of the program makes its collectives.
#include <mpi.h>

#include <optional>

#include "comm/MpiRankGroup.hpp"

namespace gpudem {

class MpiContext {
 public:
  MpiContext(int& argc, char**& argv);
  ~MpiContext();
  MpiContext(const MpiContext&) = delete;
  MpiContext& operator=(const MpiContext&) = delete;

  MPI_Comm comm() const { return MPI_COMM_WORLD; }
  /// All ranks of the run.
  const MpiRankGroup& group() const { return *world_; }
  int rank() const { return world_->rank(); }
  int size() const { return world_->size(); }
  bool is_root() const { return rank() == 0; }
  /// Rank among the ranks on this node (MPI_COMM_TYPE_SHARED), and their number.
  int local_rank() const { return local_rank_; }
  int local_size() const { return local_size_; }

 private:
  std::optional<MpiRankGroup> world_;  ///< made once MPI is initialised
  int local_rank_ = 0;
  int local_size_ = 1;
};

}  // namespace gpudem
