#include "comm/TiledParts.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/ParticleSources.hpp"
#include "core/PeriodicImages.hpp"
#include "core/RowShare.hpp"
#include "core/TiledInsertion.hpp"

namespace gpudem {
namespace {

/// `rank`, or MPI_PROC_NULL for none (-1).
int rank_or_null(int rank) { return rank < 0 ? MPI_PROC_NULL : rank; }

/// Sends `out` to rank `to` and returns what rank `from` sends (either may be MPI_PROC_NULL).
std::vector<BoundarySphere> send_receive(const MpiRankGroup& group,
                                         const std::vector<BoundarySphere>& out, int to, int from) {
  constexpr int kCountTag = 41, kSpheresTag = 42;
  std::uint64_t count_out = out.size(), count_in = 0;
  MPI_Sendrecv(&count_out, 1, MPI_UINT64_T, to, kCountTag, &count_in, 1, MPI_UINT64_T, from,
               kCountTag, group.comm(), MPI_STATUS_IGNORE);
  const std::uint64_t limit = INT_MAX / sizeof(BoundarySphere);
  throw_first_failure(group, {count_out > limit || count_in > limit
                                  ? "tiled insertion: the spheres one phase placed in a layer of "
                                    "tiles are too many for one message"
                                  : ""});
  std::vector<BoundarySphere> in(count_in);
  MPI_Sendrecv(out.data(), static_cast<int>(count_out * sizeof(BoundarySphere)), MPI_BYTE, to,
               kSpheresTag, in.data(), static_cast<int>(count_in * sizeof(BoundarySphere)),
               MPI_BYTE, from, kSpheresTag, group.comm(), MPI_STATUS_IGNORE);
  return in;
}

/// After a phase: the first layer's new spheres go down and the upper neighbour's come in
/// above, then the last layer's go up and the lower neighbour's come in below.
void exchange_boundaries(const MpiRankGroup& group, TiledFill& fill) {
  const int below = rank_or_null(fill.neighbour(LayerSide::Below));
  const int above = rank_or_null(fill.neighbour(LayerSide::Above));
  fill.receive(LayerSide::Above,
               send_receive(group, fill.boundary(LayerSide::Below), below, above));
  fill.receive(LayerSide::Below,
               send_receive(group, fill.boundary(LayerSide::Above), above, below));
}

/// The parts that own the layers of tiles across the slab axis (their near-equal shares, as
/// TiledFill takes them).
class LayerOwners {
 public:
  LayerOwners(const InsertionTiles& tiles, int parts)
      : layers_(static_cast<std::int64_t>(tiles.count() / tiles.layer_size())), first_(parts + 1) {
    for (int p = 0; p <= parts; ++p)  // part `parts` (none) starts at the layer count
      first_[p] = static_cast<std::int64_t>(share_of_rows(layers_, p, parts).first);
  }
  /// The part owning layer `layer` (clamped to the grid).
  int owner(std::int64_t layer) const {
    layer = std::clamp<std::int64_t>(layer, 0, layers_ - 1);
    return static_cast<int>(std::upper_bound(first_.begin(), first_.end(), layer) -
                            first_.begin()) -
           1;
  }
  bool owns_layers(int part) const { return first_[part + 1] > first_[part]; }

 private:
  std::int64_t layers_;
  std::vector<std::int64_t> first_;  ///< first layer of each part; the layer count last
};

/// The spheres of every rank's `earlier_part` that may reach this rank's tiles of `tiles`: each
/// rank sends each sphere of its part to the ranks owning a layer that a periodic image of it
/// reaches, the tiles widened by twice the new source's largest radius `r_max` (a tile avoids
/// the earlier spheres within one r_max of it; the second r_max covers rounding). Collective.
std::vector<Real4> earlier_spheres_near_part(const MpiRankGroup& group,
                                             const DomainSettings& domain,
                                             const InsertionTiles& tiles, double r_max,
                                             const std::vector<Real4>& earlier_part) {
  const int ranks = group.size();
  const LayerOwners owners(tiles, ranks);
  const int slab = tiles.slab_axis();
  const double reach = 2 * r_max;
  const Vec3 widen{reach, reach, reach}, lo = tiles.lo() - widen, hi = tiles.hi() + widen;
  std::vector<std::vector<Real4>> out(ranks);
  std::vector<std::size_t> sent_last(ranks, ~std::size_t{0});  // the sphere last sent to a rank
  for (std::size_t n = 0; n < earlier_part.size(); ++n) {
    const Real4& s = earlier_part[n];
    for_each_image_in_domain(domain, s, [&](const Real4& q) {
      if (!sphere_reaches_box(q, lo, hi)) return;
      const double c = axis(xyz(q), slab);
      const int first = owners.owner(tiles.index_along(slab, c - q.w - reach));
      const int last = owners.owner(tiles.index_along(slab, c + q.w + reach));
      for (int p = first; p <= last; ++p)
        if (owners.owns_layers(p) && sent_last[p] != n) {
          out[p].push_back(s);
          sent_last[p] = n;
        }
    });
  }
  RankBuffers outgoing(ranks), incoming;
  for (int p = 0; p < ranks; ++p) {
    outgoing[p].resize(out[p].size() * sizeof(Real4));
    if (!out[p].empty()) std::memcpy(outgoing[p].data(), out[p].data(), outgoing[p].size());
    out[p] = std::vector<Real4>{};
  }
  group.exchange(outgoing, incoming);
  outgoing = RankBuffers{};
  std::vector<Real4> near;
  for (const std::vector<char>& bytes : incoming) {
    const std::size_t at = near.size();
    near.resize(at + bytes.size() / sizeof(Real4));
    if (!bytes.empty()) std::memcpy(near.data() + at, bytes.data(), bytes.size());
  }
  return near;
}

}  // namespace

std::size_t append_tiled_part(const MpiRankGroup& group, const Scene& scene, std::size_t i,
                              ParticleStore& part, ParticleId first_id) {
  const ParticleSource& src = scene.sources[i];
  if (!is_tiled_box(src))
    throw std::logic_error("append_tiled_part: source " + std::to_string(i) +
                           " is not a tiled box");
  const InsertionTiles tiles = agree_on_failure(group, [&] {
    check_box_source(scene, i);
    return insertion_tiles(scene, i);
  });
  std::optional<TiledFill> fill;
  {
    const std::vector<Real4> earlier = earlier_spheres_near_part(
        group, scene.domain, tiles, max_radius(src.radius), part.position_radius);
    agree_on_failure(group, [&] {
      fill.emplace(scene, i, FilePart{group.rank(), group.size()}, earlier);
      return 0;
    });
  }
  for (int phase = 0; phase < kTilePhases; ++phase) {
    fill->fill_phase(phase);
    exchange_boundaries(group, *fill);
  }
  const std::size_t first_row = part.size();
  agree_on_failure(group, [&] {
    ParticleId next_id = first_id;
    fill->append_to(part, next_id);
    return 0;
  });
  fill.reset();
  const std::size_t placed = part.size() - first_row;
  const ParticleId before = group.sum_before(placed);
  for (std::size_t n = first_row; n < part.size(); ++n) part.id[n] += before;
  return placed;
}

}  // namespace gpudem
