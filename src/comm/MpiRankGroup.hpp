#pragma once
/// RankGroup over an MPI communicator: reductions by MPI_Iallreduce, broadcast and gather with
/// their sizes first, all-to-all byte exchange by point-to-point messages (sizes first by
/// MPI_Ialltoall), each buffer split into messages of at most 2^30 bytes (MPI counts are ints).
/// Every operation is non-blocking, completed by complete_requests (comm/MpiWait.hpp), which
/// waits as the process was told to.
#include <mpi.h>

#include <cstddef>
#include <vector>

#include "core/RankGroup.hpp"

namespace gpudem {

class MpiRankGroup final : public RankGroup {
 public:
  explicit MpiRankGroup(MPI_Comm comm);

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void reduce(Reduction op, double* values, std::size_t n) const override;
  void reduce(Reduction op, std::uint64_t* values, std::size_t n) const override;
  void broadcast(std::vector<char>& bytes, int root) const override;
  void all_gather(const std::vector<char>& mine, RankBuffers& all) const override;
  void exchange(const RankBuffers& outgoing, RankBuffers& incoming) const override;

  MPI_Comm comm() const { return comm_; }
  /// The largest message exchange() posts; a longer buffer travels as several messages of at
  /// most this many bytes. 2^30 unless lowered (tests).
  void limit_message_bytes(std::size_t bytes) { max_message_bytes_ = bytes; }

 private:
  /// exchange once the receiver knows the sizes: incoming[q] sized by the caller.
  void exchange_known(const RankBuffers& outgoing, RankBuffers& incoming) const;

  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  std::size_t max_message_bytes_ = std::size_t(1) << 30;
};

/// The int count of an MPI call for `bytes` bytes; throws std::overflow_error beyond 2^31 - 1.
int mpi_message_size(std::size_t bytes);

}  // namespace gpudem
