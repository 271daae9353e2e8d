#pragma once
/// Load balance (docs/architecture.md, "Ranks"): the work of each rank (its particles, or its
/// neighbour-list entries plus one per particle with balance = "contacts"), its imbalance max/mean,
/// and the periodic rebalance: grid cut planes move toward equal work by at most one coarse cell
/// per rebalance (so no block gets narrower than the ghost width), METIS re-partitions the coarse
/// cells by their work. The new decomposition takes over at the engine's next rebuild step,
/// so a rebalance never changes the physics.
#include <cstdint>
#include <vector>

#include "comm/MpiContext.hpp"
#include "comm/MpiDomain.hpp"
#include "core/Scene.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

class LoadBalance {
 public:
  /// domain: null on one rank. dt [s]: the run's time step.
  LoadBalance(const Scene& scene, const MpiContext& mpi, MpiDomain* domain, double dt);

  /// max / mean of the ranks' work; 1 on one rank. Collective.
  double imbalance(const EngineIo& engine) const;

  /// On every rebalance step, proposes the rebalanced decomposition. Collective.
  void maybe_rebalance(std::uint64_t step, const EngineIo& engine) const;

 private:
  /// Work of each owned particle, in the order of get_particles.
  std::vector<double> particle_work(const EngineIo& engine) const;
  /// Work per coarse cell, summed over all ranks.
  std::vector<double> cell_work(const EngineIo& engine) const;

  const MpiContext& mpi_;
  MpiDomain* domain_;
  BalanceWork measure_;
  std::uint64_t every_ = 0;  ///< steps between rebalances; 0: never
};

}  // namespace gpudem
