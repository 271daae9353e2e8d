#include "app/DomainSetup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/InputError.hpp"

namespace gpudem {

namespace {

Real largest_radius(const ParticleStore& particles) {
  Real r_max = 0;
  for (const Real4& p : particles.position_radius) r_max = std::max(r_max, p.w);
  return r_max;
}

/// The bounding box of the particles' spheres, [lo, hi].
std::pair<Vec3, Vec3> bed_bounds(const ParticleStore& particles, const PeriodicBox& box) {
  if (particles.size() == 0) return {box.lo, box.lo + box.length};
  constexpr Real kHuge = std::numeric_limits<Real>::max();
  Vec3 lo{kHuge, kHuge, kHuge}, hi{-kHuge, -kHuge, -kHuge};
  for (const Real4& p : particles.position_radius)
    for (int k = 0; k < 3; ++k) {
      axis(lo, k) = std::min(axis(lo, k), axis(xyz(p), k) - p.w);
      axis(hi, k) = std::max(axis(hi, k), axis(xyz(p), k) + p.w);
    }
  return {lo, hi};
}

/// Solid fraction of a settled random packing, for the settled-bed estimate.
constexpr Real kSettledPacking = 0.6;

/// The bed as auto dims judge it. Particles that have yet to settle (their volume fills, at
/// kSettledPacking over the bounding box's section across gravity, less height than the box
/// has along gravity) will move along gravity, so cuts across gravity balanced now would not
/// stay balanced: the bed counts as shallow, its height along gravity cut below its other two
/// extents. A packed bed or column keeps its box.
std::pair<Vec3, Vec3> settled_bed(const ParticleStore& particles, std::pair<Vec3, Vec3> bed,
                                  Vec3 gravity) {
  int g = -1;
  for (int k = 0; k < 3; ++k)
    if (axis(gravity, k) != 0 && (g < 0 || std::abs(axis(gravity, k)) > std::abs(axis(gravity, g))))
      g = k;
  if (g < 0 || particles.size() == 0) return bed;
  const Vec3 extent = bed.second - bed.first;
  const Real base = axis(extent, (g + 1) % 3) * axis(extent, (g + 2) % 3);
  Real solid = 0;
  for (const Real4& p : particles.position_radius)
    solid += Real(4.0 / 3.0 * M_PI) * p.w * p.w * p.w;
  const Real settled = solid / (kSettledPacking * base);
  if (!(settled < axis(extent, g))) return bed;
  const Real across = std::min(axis(extent, (g + 1) % 3), axis(extent, (g + 2) % 3));
  const Real height = std::min(settled, Real(0.5) * across);
  if (axis(gravity, g) < 0)
    axis(bed.second, g) = axis(bed.first, g) + height;
  else
    axis(bed.first, g) = axis(bed.second, g) - height;
  return bed;
}

/// Particles per coarse cell.
std::vector<double> particles_per_cell(const CoarseGrid& cells, const ParticleStore& particles) {
  std::vector<double> work(cells.count(), 0.0);
  for (const Real4& p : particles.position_radius) work[cells.cell_of(xyz(p))] += 1;
  return work;
}

/// METIS parts of the coarse cells; more ranks than cells is an input error.
std::vector<int> metis_parts(const Scene& scene, const CoarseGrid& cells,
                             const std::vector<double>& work, int ranks) {
  if (static_cast<std::size_t>(ranks) > cells.count())
    throw InputError(scene.file, 0, "decomposition.method",
                     "metis needs at least one coarse cell per rank: " + std::to_string(ranks) +
                         " ranks but " + std::to_string(cells.count()) +
                         " cells of the ghost width; use fewer ranks");
  return metis_owners(cells, work, ranks);
}

}  // namespace

std::unique_ptr<MpiDomain> make_domain(const Scene& scene, const MpiContext& mpi,
                                       const ParticleStore& particles, const EngineSetup& setup,
                                       bool gpu_aware) {
  if (mpi.size() == 1) return nullptr;
  const Real ghost_width = 2 * largest_radius(particles) + setup.skin;
  const CoarseGrid cells = CoarseGrid::over(setup.box, ghost_width);
  const std::vector<double> work = particles_per_cell(cells, particles);
  const DecompositionSettings& settings = scene.decomposition;
  if (settings.method == DecompositionMethod::Metis)
    return std::make_unique<MpiDomain>(
        mpi.comm(),
        Decomposition::from_owners(cells, metis_parts(scene, cells, work, mpi.size()), mpi.size()),
        ghost_width, gpu_aware);
  const auto [bed_lo, bed_hi] =
      settled_bed(particles, bed_bounds(particles, setup.box), setup.gravity);
  const std::array<int, 3> dims = choose_grid_dims(mpi.size(), bed_lo, bed_hi, setup.gravity, cells,
                                                   settings.dims, scene.file, settings.dims_line);
  return std::make_unique<MpiDomain>(mpi.comm(),
                                     Decomposition::grid(cells, balanced_cuts(cells, dims, work)),
                                     ghost_width, gpu_aware);
}

void print_decomposition(const MpiDomain& domain) {
  const Decomposition& d = domain.decomposition();
  const CoarseGrid& cells = d.cells();
  if (d.is_grid())
    std::printf("decomposition: grid %zu x %zu x %zu blocks", d.cuts()[0].size() - 1,
                d.cuts()[1].size() - 1, d.cuts()[2].size() - 1);
  else
    std::printf("decomposition: metis, %d parts", d.ranks());
  std::printf(" over %d x %d x %d coarse cells, ghost width %.4g m; MPI buffers %s\n", cells.n[0],
              cells.n[1], cells.n[2], domain.ghost_width(),
              domain.gpu_aware() ? "on the device (GPU-aware MPI)" : "staged through host memory");
}

}  // namespace gpudem
