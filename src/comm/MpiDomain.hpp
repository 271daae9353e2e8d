#pragma once
/// The engine's DomainLink over MPI (docs/architecture.md, "Ranks"): ownership, ghost destinations
/// and bin region from a Decomposition, reductions by MPI_Allreduce, byte exchanges by
/// point-to-point messages (sizes first by MPI_Alltoall where the receiver cannot know them),
/// non-blocking where the caller overlaps them with work.
#include <mpi.h>

#include <memory>
#include <optional>
#include <vector>

#include "comm/Decomposition.hpp"
#include "kernels/DomainLink.hpp"

namespace gpudem {

class MpiDomain final : public DomainLink {
 public:
  /// ghost_width [m]: 2 r_max + skin, the reach of a ghost beyond its owner's cells and the
  /// largest contact distance.
  /// gpu_aware: the MPI library accepts device pointers (GpuAwareMpi.hpp).
  MpiDomain(MPI_Comm comm, Decomposition decomposition, Real ghost_width, bool gpu_aware);

  int rank() const override { return rank_; }
  int ranks() const override { return size_; }
  BinRegion region() const override { return region_; }
  int owner_of(Vec3 p) const override { return decomposition_.owner_of(p); }
  const CellOwnership& cell_ownership() const override { return ownership_; }
  void ghost_ranks(Vec3 p, std::vector<int>& out) const override {
    decomposition_.ghost_ranks(p, rank_, ghost_width_, out);
  }
  double max(double value) const override;
  void sum(std::vector<double>& values) const override;
  using DomainLink::sum;
  std::uint64_t wrapping_sum(std::uint64_t value) const override;
  int first_rank_with(bool flag) const override;
  void broadcast(std::vector<char>& bytes, int root) const override;
  void exchange(const RankBuffers& outgoing, RankBuffers& incoming) const override;
  std::unique_ptr<PendingExchange> start_exchange(
      const char* send, const std::vector<std::size_t>& send_bytes, char* receive,
      const std::vector<std::size_t>& receive_bytes) const override;
  void finish_exchange(std::unique_ptr<PendingExchange> exchange) const override;
  bool device_buffers() const override { return gpu_aware_; }

  /// Hands over a decomposition (a rebalance) that takes over at the next rebuild step;
  /// every rank must propose the same one.
  void propose(Decomposition next);
  void begin_rebuild() override;

  const Decomposition& decomposition() const { return decomposition_; }
  Real ghost_width() const { return ghost_width_; }
  /// Whether buffers in device memory may go to MPI as they are.
  bool gpu_aware() const { return gpu_aware_; }
  /// The largest message exchange() posts (MPI counts are ints); a longer buffer travels as
  /// several messages of at most this many bytes. 2^30 unless lowered (tests).
  void limit_message_bytes(std::size_t bytes) { max_message_bytes_ = bytes; }

 private:
  /// Throws std::invalid_argument unless `d` is for this rank count and every coarse cell edge
  /// (along an axis of more than one cell) is at least the ghost width, which ghost_ranks and
  /// the cell map's reach of kGhostReachCells assume.
  void require_fits(const Decomposition& d) const;
  /// region_ and ownership_ of decomposition_ (a new map version).
  void adopt_decomposition();
  /// exchange once the receiver knows the sizes: incoming[q] sized by the caller.
  void exchange_known(const RankBuffers& outgoing, RankBuffers& incoming) const;

  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  Decomposition decomposition_;
  std::optional<Decomposition> pending_;
  Real ghost_width_;
  bool gpu_aware_;
  BinRegion region_;
  CellOwnership ownership_;  ///< of decomposition_ for this rank
  std::size_t max_message_bytes_ = std::size_t(1) << 30;
};

}  // namespace gpudem
