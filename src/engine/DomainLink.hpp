#pragma once
/// What the step engine asks of the domain decomposition (docs/architecture.md, "One time step"
/// and "Ranks"): where this rank bins, who owns a position, which ranks need a particle as a ghost,
/// the ranks' collectives (a RankGroup) and the ghost refresh's contiguous exchange. The engine
/// knows nothing of MPI: comm/MpiDomain implements this over MPI, OneRankDomain for a run on one
/// rank (nothing to exchange).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/Config.hpp"
#include "core/RankGroup.hpp"
#include "core/Vec3.hpp"
#include "engine/BinRegion.hpp"
#include "engine/CoarseGrid.hpp"
#include "engine/PeriodicBox.hpp"

namespace gpudem {

/// The messages of one DomainLink::start_exchange, until finish_exchange completes them.
class PendingExchange {
 public:
  virtual ~PendingExchange() = default;
};

class DomainLink {
 public:
  virtual ~DomainLink() = default;

  /// The ranks of the decomposed run and their collectives.
  virtual const RankGroup& group() const = 0;
  int rank() const { return group().rank(); }
  int ranks() const { return group().size(); }
  /// Called by the engine at the start of each rebuild step, before any particle moves
  /// between ranks: the moment a new decomposition may take over (a rebalance).
  virtual void begin_rebuild() {}
  /// Where this rank bins its owned particles and ghosts.
  virtual BinRegion region() const = 0;
  /// The rank that owns a particle at p (a position in the global box).
  virtual int owner_of(Vec3 p) const = 0;
  /// The ranks other than this one that need a particle at p as a ghost (ascending).
  virtual void ghost_ranks(Vec3 p, std::vector<int>& out) const = 0;
  /// The owner of each coarse cell and the cells near another rank's, for the engine's
  /// kernels: owner_of(p) is owner[grid.cell_of(p)], and ghost_ranks(p) is empty where
  /// near_other[grid.cell_of(p)] is 0.
  virtual const CellOwnership& cell_ownership() const = 0;

  /// Starts sending send_bytes[q] bytes to each rank q and receiving receive_bytes[q] bytes
  /// from each rank q (both known to both sides beforehand; ranks() entries each, zero for no
  /// message). `send` and `receive` hold the messages back to back in rank order; both stay
  /// untouched until finish_exchange. They are host memory, or device memory when
  /// device_buffers(). Collective over the ranks that exchange.
  virtual std::unique_ptr<PendingExchange> start_exchange(
      const char* send, const std::vector<std::size_t>& send_bytes, char* receive,
      const std::vector<std::size_t>& receive_bytes) const = 0;
  /// Waits until the messages of `exchange` have been sent and received.
  virtual void finish_exchange(std::unique_ptr<PendingExchange> exchange) const = 0;
  /// Whether start_exchange takes device memory (GPU-aware MPI).
  virtual bool device_buffers() const { return false; }
};

/// A run on one rank: the region is the whole box, every particle is owned, nothing travels.
class OneRankDomain final : public DomainLink {
 public:
  explicit OneRankDomain(const PeriodicBox& box) : region_(whole_box_region(box)) {
    ownership_.grid.lo = box.lo;
    ownership_.grid.length = box.length;
    for (int k = 0; k < 3; ++k) ownership_.grid.periodic[k] = box.periodic[k];
    ownership_.owner = {0};
    ownership_.near_other = {0};
  }
  const RankGroup& group() const override { return group_; }
  BinRegion region() const override { return region_; }
  int owner_of(Vec3) const override { return 0; }
  void ghost_ranks(Vec3, std::vector<int>& out) const override { out.clear(); }
  const CellOwnership& cell_ownership() const override { return ownership_; }
  /// Copies the message to this rank; nothing stays pending.
  std::unique_ptr<PendingExchange> start_exchange(
      const char* send, const std::vector<std::size_t>& send_bytes, char* receive,
      const std::vector<std::size_t>& receive_bytes) const override {
    if (send_bytes.size() != 1 || receive_bytes != send_bytes)
      throw std::invalid_argument("OneRankDomain: byte counts differ from the one message");
    if (send_bytes[0] > 0) std::memcpy(receive, send, send_bytes[0]);
    return nullptr;
  }
  void finish_exchange(std::unique_ptr<PendingExchange>) const override {}

 private:
  SingleRank group_;
  BinRegion region_;
  CellOwnership ownership_;  ///< one cell, this rank's
};

}  // namespace gpudem
