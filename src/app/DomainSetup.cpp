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

/// Largest radius over all ranks' shares, or 0. Collective.
Real largest_radius(const RankGroup& ranks, const ParticleStore& share) {
  double r_max = 0;
  for (const Real4& p : share.position_radius) r_max = std::max(r_max, double(p.w));
  return Real(ranks.max(r_max));
}

/// The bounding box [lo, hi] of the spheres of all ranks' shares; the box without particles.
/// Collective.
std::pair<Vec3, Vec3> bed_bounds(const RankGroup& ranks, const ParticleStore& share,
                                 const PeriodicBox& box, std::uint64_t count) {
  if (count == 0) return {box.lo, box.lo + box.length};
  constexpr double kHuge = std::numeric_limits<double>::max();
  double lo[3] = {kHuge, kHuge, kHuge}, minus_hi[3] = {kHuge, kHuge, kHuge};
  for (const Real4& p : share.position_radius)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], double(axis(xyz(p), k) - p.w));
      minus_hi[k] = std::min(minus_hi[k], -double(axis(xyz(p), k) + p.w));
    }
  ranks.reduce(Reduction::Min, lo, 3);
  ranks.reduce(Reduction::Min, minus_hi, 3);
  return {Vec3{Real(lo[0]), Real(lo[1]), Real(lo[2])},
          Vec3{Real(-minus_hi[0]), Real(-minus_hi[1]), Real(-minus_hi[2])}};
}

/// Solid fraction of a settled random packing, for the settled-bed estimate.
constexpr Real kSettledPacking = 0.6;

/// Σ 4/3 π r³ over all ranks' shares [m³]. Collective.
Real solid_volume(const RankGroup& ranks, const ParticleStore& share) {
  double solid = 0;
  for (const Real4& p : share.position_radius) solid += 4.0 / 3.0 * M_PI * p.w * p.w * p.w;
  return Real(ranks.sum(solid));
}

/// The bed as auto dims judge it, from the bounding box `bed` and the spheres' volume `solid`.
/// Particles that have yet to settle (their volume fills, at kSettledPacking over the bounding
/// box's section across gravity, less height than the box has along gravity) will move along
/// gravity, so cuts across gravity balanced now would not stay balanced: the bed counts as
/// shallow, its height along gravity cut below its other two extents. A packed bed or column
/// keeps its box.
std::pair<Vec3, Vec3> settled_bed(Real solid, std::uint64_t count, std::pair<Vec3, Vec3> bed,
                                  Vec3 gravity) {
  int g = -1;
  for (int k = 0; k < 3; ++k)
    if (axis(gravity, k) != 0 && (g < 0 || std::abs(axis(gravity, k)) > std::abs(axis(gravity, g))))
      g = k;
  if (g < 0 || count == 0) return bed;
  const Vec3 extent = bed.second - bed.first;
  const Real base = axis(extent, (g + 1) % 3) * axis(extent, (g + 2) % 3);
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

/// Particles per coarse cell over all ranks' shares. Collective.
std::vector<double> particles_per_cell(const RankGroup& ranks, const CoarseGrid& cells,
                                       const ParticleStore& share) {
  std::vector<double> work(cells.count(), 0.0);
  for (const Real4& p : share.position_radius) work[cells.cell_of(xyz(p))] += 1;
  ranks.sum(work);
  return work;
}

/// METIS parts of the coarse cells; more ranks than cells is an input error.
std::vector<int> metis_parts(const Scene& scene, const CoarseGrid& cells,
                             const std::vector<double>& work, int ranks) {
  if (static_cast<std::size_t>(ranks) > cells.count())
    throw InputError(scene.file, 0, "decomposition.method",
                     "metis needs at least one coarse cell per rank: " + std::to_string(ranks) +
                         " ranks but " + std::to_string(cells.count()) +
                         " coarse cells; use fewer ranks");
  return metis_owners(cells, work, ranks);
}

}  // namespace

std::unique_ptr<MpiDomain> make_domain(const Scene& scene, const MpiContext& mpi,
                                       const ParticleStore& share, std::uint64_t count,
                                       const EngineSetup& setup, bool gpu_aware) {
  if (mpi.size() == 1) return nullptr;
  const RankGroup& ranks = mpi.group();
  const Real ghost_width = 2 * largest_radius(ranks, share) + setup.skin;
  const CoarseGrid cells = CoarseGrid::over(setup.box, ghost_width);
  const std::vector<double> work = particles_per_cell(ranks, cells, share);
  const DecompositionSettings& settings = scene.decomposition;
  if (settings.method == DecompositionMethod::Metis)
    return std::make_unique<MpiDomain>(
        mpi.comm(),
        Decomposition::from_owners(cells, metis_parts(scene, cells, work, mpi.size()), mpi.size()),
        ghost_width, gpu_aware);
  // Collectives one by one: the order of evaluation within one argument list is unspecified.
  const Real volume = solid_volume(ranks, share);
  const auto bounds = bed_bounds(ranks, share, setup.box, count);
  const auto [bed_lo, bed_hi] = settled_bed(volume, count, bounds, setup.gravity);
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
  std::printf(
      " over %d x %d x %d coarse cells of %.4g x %.4g x %.4g m, ghost width %.4g m; MPI "
      "buffers %s\n",
      cells.n[0], cells.n[1], cells.n[2], cells.edge(0), cells.edge(1), cells.edge(2),
      domain.ghost_width(),
      domain.gpu_aware() ? "on the device (GPU-aware MPI)" : "staged through host memory");
}

}  // namespace gpudem
