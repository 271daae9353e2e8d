#include "core/TiledInsertion.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/FreeCentre.hpp"
#include "core/InputError.hpp"
#include "core/ParticleSources.hpp"
#include "core/PeriodicImages.hpp"
#include "core/SphereHash.hpp"

namespace gpudem {
namespace {

/// SplitMix64's finaliser (Steele, Lea & Flood, OOPSLA 2014): one well-mixed 64-bit word.
std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Random stream `stream` of tile `tile` of source `source`: 0 its radii, 1 + k its centres
/// in round k (all ~0: the source's sizing stream).
std::mt19937_64 tile_rng(std::uint64_t seed, std::size_t source, std::uint64_t tile,
                         std::uint64_t stream) {
  return std::mt19937_64(mix64(mix64(mix64(mix64(seed) ^ source) ^ tile) ^ stream));
}

/// Expected number of spheres of a source, for the tile size: its count, or the volume to
/// fill over the mean volume of 4096 radii from the source's sizing stream.
double expected_spheres(const ParticleSource& src, std::uint64_t seed, std::size_t source) {
  if (src.count > 0) return static_cast<double>(src.count);
  std::mt19937_64 rng = tile_rng(seed, source, ~std::uint64_t{0}, ~std::uint64_t{0});
  double mean_volume = 0;
  const std::vector<double> radii = sample_radii(src.radius, 4096, rng);
  for (double r : radii) mean_volume += sphere_volume(r) / static_cast<double>(radii.size());
  const Vec3 extent = src.region_max - src.region_min;
  return src.volume_fraction * extent.x * extent.y * extent.z / mean_volume;
}

/// Tile t's share ⌊N (t+1)/T⌋ − ⌊N t/T⌋ of N spheres (no overflow for N, T < 2^32).
std::size_t count_share(std::uint64_t count, std::size_t t, std::size_t tiles) {
  const auto bound = [&](std::uint64_t k) { return count / tiles * k + count % tiles * k / tiles; };
  return static_cast<std::size_t>(bound(t + 1) - bound(t));
}

/// Tile t's radii, largest first: its share of the count, or drawn until their volume reaches
/// volume_fraction × the tile's volume.
std::vector<double> tile_radii(const ParticleSource& src, const InsertionTiles& tiles,
                               std::size_t t, std::mt19937_64& rng) {
  std::vector<double> radii;
  if (src.count > 0) {
    radii = sample_radii(src.radius, count_share(src.count, t, tiles.count()), rng);
  } else {
    const double target = src.volume_fraction * tiles.tile_volume();
    double volume = 0;
    while (volume < target)
      for (double r : sample_radii(src.radius, 16, rng)) {
        if (volume >= target) break;
        radii.push_back(r);
        volume += sphere_volume(r);
      }
  }
  std::sort(radii.begin(), radii.end(), std::greater<double>());
  return radii;
}

/// Squared distance from `p` to the box [lo, hi].
double distance2_to_box(Vec3 p, Vec3 lo, Vec3 hi) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max({axis(lo, k) - axis(p, k), 0.0, axis(p, k) - axis(hi, k)});
    d2 += d * d;
  }
  return d2;
}

/// Runs `body(k)` for k in [0, count) on all threads; the first exception is rethrown after.
template <class Body>
void on_all_threads(std::size_t count, const Body& body) {
  std::exception_ptr failure;
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t k = 0; k < n; ++k) {
    try {
      body(static_cast<std::size_t>(k));
    } catch (...) {
#pragma omp critical(gpudem_tiled_insertion_failure)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

/// The layers `part` holds (HeldLayers).
HeldLayers held_layers(const InsertionTiles& tiles, FilePart part) {
  const std::size_t layers = tiles.count() / tiles.layer_size();
  const auto layers_of = [&](int p) { return share_of_rows(layers, p, part.count); };
  HeldLayers held;
  held.own = layers_of(part.index);
  if (held.own.count == 0) return held;
  for (int p = part.index - 1; p >= 0 && held.neighbour[0] < 0; --p)
    if (layers_of(p).count > 0) held.neighbour[0] = p;
  for (int p = part.index + 1; p < part.count && held.neighbour[1] < 0; ++p)
    if (layers_of(p).count > 0) held.neighbour[1] = p;
  held.first = held.own.first - (held.neighbour[0] >= 0 ? 1 : 0);
  held.end = held.own.first + held.own.count + (held.neighbour[1] >= 0 ? 1 : 0);
  return held;
}

}  // namespace

InsertionTiles insertion_tiles(const Scene& scene, std::size_t i) {
  const ParticleSource& src = scene.sources[i];
  const Vec3 extent = src.region_max - src.region_min;
  const double region_volume = extent.x * extent.y * extent.z;
  const double expected = expected_spheres(src, scene.simulation.seed, i);
  const double sized_edge = std::cbrt(region_volume * kSpheresPerTile / expected);
  return InsertionTiles(src.region_min, src.region_max,
                        std::max(2 * max_radius(src.radius), sized_edge));
}

TiledFill::TiledFill(const Scene& scene, std::size_t i, FilePart part,
                     const std::vector<Real4>& earlier)
    : scene_(scene),
      src_(scene.sources[i]),
      index_(i),
      tiles_(insertion_tiles(scene, i)),
      r_min_(min_radius(src_.radius)),
      r_max_(max_radius(src_.radius)),
      held_(held_layers(tiles_, part)) {
  if (held_.own.count == 0) return;
  const std::size_t layer = tiles_.layer_size();
  own_first_ = held_.own.first * layer;
  own_count_ = held_.own.count * layer;
  first_held_ = held_.first * layer;
  tiles_held_.resize((held_.end - held_.first) * layer);
  on_all_threads(own_count_, [&](std::size_t k) {
    std::mt19937_64 rng = tile_rng(scene_.simulation.seed, index_, own_first_ + k, 0);
    tile(own_first_ + k).radii = tile_radii(src_, tiles_, own_first_ + k, rng);
  });
  copy_earlier_spheres(earlier);
}

void TiledFill::copy_earlier_spheres(const std::vector<Real4>& earlier) {
  for (const Real4& p : earlier)
    for_each_image_in_domain(scene_.domain, p, [&](const Real4& image) { copy_to_tiles(image); });
}

void TiledFill::copy_to_tiles(const Real4& p) {
  const InsertionTiles::Coords first = tiles_.coords(first_held_);
  const InsertionTiles::Coords last = tiles_.coords(first_held_ + tiles_held_.size() - 1);
  const int slab = tiles_.slab_axis();
  InsertionTiles::Coords lo{}, hi{};
  for (int k = 0; k < 3; ++k) {  // the tiles whose box the sphere's, widened by r_max, meets
    const double reach = p.w + r_max_;
    lo[k] = std::max<std::int64_t>(0, tiles_.index_along(k, axis(xyz(p), k) - reach));
    hi[k] =
        std::min<std::int64_t>(tiles_.along(k) - 1, tiles_.index_along(k, axis(xyz(p), k) + reach));
  }
  lo[slab] = std::max(lo[slab], first[slab]);
  hi[slab] = std::min(hi[slab], last[slab]);
  InsertionTiles::Coords c{};
  for (c[2] = lo[2]; c[2] <= hi[2]; ++c[2])
    for (c[1] = lo[1]; c[1] <= hi[1]; ++c[1])
      for (c[0] = lo[0]; c[0] <= hi[0]; ++c[0]) tile(tiles_.index(c)).earlier.push_back(p);
}

std::vector<Real4> TiledFill::neighbour_spheres_near(std::size_t t, Vec3 lo, Vec3 hi) const {
  const InsertionTiles::Coords c = tiles_.coords(t);
  std::vector<Real4> near;
  for (std::int64_t dz = -1; dz <= 1; ++dz)
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const InsertionTiles::Coords u{c[0] + dx, c[1] + dy, c[2] + dz};
        if ((dx | dy | dz) == 0 || !tiles_.contains(u) || !holds(tiles_.index(u))) continue;
        for (const Real4& p : tile(tiles_.index(u)).spheres) {
          const double reach = p.w + r_max_;
          if (distance2_to_box(xyz(p), lo, hi) < reach * reach) near.push_back(p);
        }
      }
  return near;
}

/// Places run `round` of tile t's radii, largest first, at free centres inside both the tile
/// and the region (shrunk by the radius), avoiding the tile's spheres, those of its neighbours
/// that a sphere in it could reach (closer to it than their radius plus r_max) and the earlier
/// spheres; a sphere that finds no free centre leaves the tile stuck.
void TiledFill::fill_tile(std::size_t t, int round) {
  Tile& fill = tile(t);
  fill.last_phase_first = fill.spheres.size();
  const RowRange run = share_of_rows(fill.radii.size(), round, kRounds);
  if (fill.stuck || run.count == 0) return;
  const InsertionTiles::Coords c = tiles_.coords(t);
  const Vec3 lo = tiles_.tile_lo(c), hi = tiles_.tile_hi(c);
  const std::vector<Real4> near = neighbour_spheres_near(t, lo, hi);
  SphereHash hash(r_min_, fill.spheres.size() + run.count + near.size() + fill.earlier.size());
  for (const std::vector<Real4>& spheres :
       {std::cref(fill.spheres), std::cref(near), std::cref(fill.earlier)})
    for (const Real4& p : spheres) hash.insert(xyz(p), p.w);
  std::mt19937_64 rng = tile_rng(scene_.simulation.seed, index_, t, 1 + round);
  for (std::size_t n = run.first; n < run.first + run.count; ++n) {
    const double r = fill.radii[n];
    Vec3 first, width;
    for (int k = 0; k < 3; ++k) {
      axis(first, k) = std::max(axis(lo, k), axis(src_.region_min, k) + r);
      axis(width, k) = std::min(axis(hi, k), axis(src_.region_max, k) - r) - axis(first, k);
    }
    const std::optional<Vec3> centre = free_centre(first, width, r, hash, rng);
    if (!centre) {
      fill.stuck = true;
      return;
    }
    hash.insert(*centre, r);
    fill.spheres.push_back({centre->x, centre->y, centre->z, r});
  }
}

void TiledFill::fill_phase(int phase) {
  if (phase < 0 || phase >= kTilePhases) throw std::out_of_range("TiledFill: no such phase");
  last_colour_ = phase % 8;
  on_all_threads(own_count_, [&](std::size_t k) {
    const std::size_t t = own_first_ + k;
    if (tiles_.colour(tiles_.coords(t)) == last_colour_) fill_tile(t, phase / 8);
  });
}

std::size_t TiledFill::boundary_layer_first(LayerSide side) const {
  return side == LayerSide::Below ? own_first_ : own_first_ + own_count_ - tiles_.layer_size();
}

std::vector<BoundarySphere> TiledFill::boundary(LayerSide side) const {
  std::vector<BoundarySphere> out;
  if (own_count_ == 0) return out;
  const std::size_t first = boundary_layer_first(side);
  for (std::size_t t = first; t < first + tiles_.layer_size(); ++t) {
    if (tiles_.colour(tiles_.coords(t)) != last_colour_) continue;
    const Tile& fill = tile(t);
    for (std::size_t n = fill.last_phase_first; n < fill.spheres.size(); ++n)
      out.push_back({t, fill.spheres[n]});
  }
  return out;
}

void TiledFill::receive(LayerSide side, const std::vector<BoundarySphere>& spheres) {
  if (spheres.empty()) return;
  if (neighbour(side) < 0) throw std::logic_error("TiledFill::receive: no neighbour there");
  const std::size_t layer = tiles_.layer_size();
  const std::size_t first = side == LayerSide::Below ? first_held_ : own_first_ + own_count_;
  for (const BoundarySphere& b : spheres) {
    if (b.tile < first || b.tile >= first + layer)
      throw std::logic_error("TiledFill::receive: a sphere outside the mirrored layer");
    tile(b.tile).spheres.push_back(b.sphere);
  }
}

void TiledFill::append_to(ParticleStore& store, ParticleId& next_id) const {
  for (std::size_t t = own_first_; t < own_first_ + own_count_; ++t) {
    const Tile& fill = tile(t);
    if (!fill.stuck) continue;
    const InsertionTiles::Coords c = tiles_.coords(t);
    double solid = 0;
    for (const Real4& p : fill.spheres) solid += sphere_volume(p.w);
    throw InputError(scene_.file, 0, "insert[" + std::to_string(index_) + "]",
                     "could only place " + std::to_string(fill.spheres.size()) + " of " +
                         std::to_string(fill.radii.size()) + " particles in tile (" +
                         std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
                         std::to_string(c[2]) + ") of " + std::to_string(tiles_.along(0)) + " x " +
                         std::to_string(tiles_.along(1)) + " x " + std::to_string(tiles_.along(2)) +
                         " (its solid fraction " + four_digits(solid / tiles_.tile_volume()) +
                         "); enlarge the region or lower count/volume_fraction");
  }
  std::size_t placed = 0;
  for (std::size_t t = own_first_; t < own_first_ + own_count_; ++t)
    placed += tile(t).spheres.size();
  store.reserve(store.size() + placed);
  const double density = scene_.materials[src_.material].density;
  for (std::size_t t = own_first_; t < own_first_ + own_count_; ++t)
    for (const Real4& p : tile(t).spheres)
      store.add(next_id++, xyz(p), p.w, src_.material, src_.velocity,
                1.0 / sphere_mass(density, p.w));
}

void insert_tiled_box(const Scene& scene, std::size_t i, const std::vector<Real4>& avoid,
                      ParticleStore& out, ParticleId& next_id) {
  TiledFill fill(scene, i, FilePart{}, avoid);
  for (int phase = 0; phase < kTilePhases; ++phase) fill.fill_phase(phase);
  fill.append_to(out, next_id);
}

}  // namespace gpudem
