#pragma once
/// The engine's DomainLink over MPI (docs/architecture.md, "Ranks"): ownership, ghost destinations
/// and bin region from a Decomposition, collectives by an MpiRankGroup, the ghost refresh's
/// contiguous exchange by non-blocking point-to-point messages (completed by complete_requests,
/// comm/MpiWait.hpp).
#include <mpi.h>

#include <memory>
#include <optional>
#include <vector>

#include "comm/Decomposition.hpp"
#include "comm/MpiRankGroup.hpp"
#include "engine/DomainLink.hpp"

namespace gpudem {

class MpiDomain final : public DomainLink {
 public:
  /// ghost_width [m]: 2 r_max + skin, the reach of a ghost beyond its owner's cells and the
  /// largest contact distance.
  /// gpu_aware: the MPI library accepts device pointers (GpuAwareMpi.hpp).
  MpiDomain(MPI_Comm comm, Decomposition decomposition, Real ghost_width, bool gpu_aware);

  const RankGroup& group() const override { return group_; }
  BinRegion region() const override { return region_; }
  int owner_of(Vec3 p) const override { return decomposition_.owner_of(p); }
  const CellOwnership& cell_ownership() const override { return ownership_; }
  void ghost_ranks(Vec3 p, std::vector<int>& out) const override {
    decomposition_.ghost_ranks(p, group_.rank(), ghost_width_, out);
  }
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
  /// MpiRankGroup::limit_message_bytes of group() (tests).
  void limit_message_bytes(std::size_t bytes) { group_.limit_message_bytes(bytes); }

 private:
  /// Throws std::invalid_argument unless `d` is for this rank count and every coarse cell edge
  /// (along an axis of more than one cell) is at least the ghost width, which ghost_ranks and
  /// the cell map's reach of kGhostReachCells assume.
  void require_fits(const Decomposition& d) const;
  /// region_ and ownership_ of decomposition_ (a new map version).
  void adopt_decomposition();
  MpiRankGroup group_;
  Decomposition decomposition_;
  std::optional<Decomposition> pending_;
  Real ghost_width_;
  bool gpu_aware_;
  BinRegion region_;
  CellOwnership ownership_;  ///< of decomposition_ for this rank
};

}  // namespace gpudem
