#include "app/LoadBalance.hpp"

#include <algorithm>
#include <cmath>

namespace gpudem {

namespace {

/// Cut planes move at most this many coarse cells per rebalance.
constexpr int kMaxCutShift = 1;

}  // namespace

LoadBalance::LoadBalance(const Scene& scene, const MpiContext& mpi, MpiDomain* domain, double dt)
    : mpi_(mpi), domain_(domain), measure_(scene.decomposition.balance) {
  const double every = scene.decomposition.rebalance_every;
  if (domain_ && every > 0)
    every_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(every / dt)));
}

std::vector<double> LoadBalance::particle_work(const EngineIo& engine) const {
  std::vector<double> work(engine.owned_count(), 1.0);
  if (measure_ == BalanceWork::Contacts) {
    std::vector<std::uint32_t> lengths;
    engine.get_list_lengths(lengths);
    for (std::size_t i = 0; i < work.size(); ++i) work[i] += lengths[i];
  }
  return work;
}

double LoadBalance::imbalance(const EngineIo& engine) const {
  if (!domain_) return 1.0;
  const std::vector<double> work = particle_work(engine);
  double mine = 0;
  for (const double w : work) mine += w;
  return gpudem::imbalance(mpi_.group().gather(std::vector<double>{mine}));
}

std::vector<double> LoadBalance::cell_work(const EngineIo& engine) const {
  const CoarseGrid& cells = domain_->decomposition().cells();
  ParticleStore particles;
  engine.get_particles(particles);
  const std::vector<double> work = particle_work(engine);
  std::vector<double> per_cell(cells.count(), 0.0);
  for (std::size_t i = 0; i < particles.size(); ++i)
    per_cell[cells.cell_of(xyz(particles.position_radius[i]))] += work[i];
  mpi_.group().sum(per_cell);
  return per_cell;
}

void LoadBalance::maybe_rebalance(std::uint64_t step, const EngineIo& engine) const {
  if (every_ == 0 || step % every_ != 0) return;
  const Decomposition& now = domain_->decomposition();
  const std::vector<double> work = cell_work(engine);
  if (now.is_grid())
    domain_->propose(Decomposition::grid(
        now.cells(), rebalance_cuts(now.cells(), now.cuts(), work, kMaxCutShift)));
  else
    domain_->propose(Decomposition::from_owners(
        now.cells(), metis_owners(now.cells(), work, mpi_.size()), mpi_.size()));
}

}  // namespace gpudem
