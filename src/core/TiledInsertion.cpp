#include "core/TiledInsertion.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/FreeCentre.hpp"
#include "core/InputError.hpp"
#include "core/ParticleSources.hpp"
#include "core/SphereHash.hpp"

namespace gpudem {

InsertionTiles::InsertionTiles(Vec3 lo, Vec3 hi, double min_edge) : lo_(lo), hi_(hi) {
  constexpr double kMaxTiles = 2147483647.0;
  double edge = min_edge;
  for (;;) {
    double tiles = 1;
    for (int k = 0; k < 3; ++k) {
      n_[k] = std::max<std::int64_t>(1, static_cast<std::int64_t>((axis(hi, k) - axis(lo, k)) / edge));
      tiles *= static_cast<double>(n_[k]);
    }
    if (tiles < kMaxTiles) break;
    edge *= std::cbrt(2 * tiles / kMaxTiles);
  }
  for (int k = 0; k < 3; ++k)
    axis(edge_, k) = (axis(hi, k) - axis(lo, k)) / static_cast<double>(n_[k]);
  slab_ = 0;
  for (int k = 1; k < 3; ++k)
    if (n_[k] > n_[slab_]) slab_ = k;
}

InsertionTiles::Coords InsertionTiles::coords(std::size_t tile) const {
  const int a = (slab_ + 1) % 3, b = (slab_ + 2) % 3;
  const auto na = static_cast<std::size_t>(n_[a]), nb = static_cast<std::size_t>(n_[b]);
  Coords c{};
  c[a] = static_cast<std::int64_t>(tile % na);
  c[b] = static_cast<std::int64_t>(tile / na % nb);
  c[slab_] = static_cast<std::int64_t>(tile / (na * nb));
  return c;
}

std::size_t InsertionTiles::index(const Coords& c) const {
  const int a = (slab_ + 1) % 3, b = (slab_ + 2) % 3;
  return static_cast<std::size_t>(c[a] + n_[a] * (c[b] + n_[b] * c[slab_]));
}

bool InsertionTiles::contains(const Coords& c) const {
  for (int k = 0; k < 3; ++k)
    if (c[k] < 0 || c[k] >= n_[k]) return false;
  return true;
}

Vec3 InsertionTiles::tile_lo(const Coords& c) const {
  Vec3 p;
  for (int k = 0; k < 3; ++k) axis(p, k) = axis(lo_, k) + static_cast<double>(c[k]) * axis(edge_, k);
  return p;
}

Vec3 InsertionTiles::tile_hi(const Coords& c) const {
  Vec3 p;
  for (int k = 0; k < 3; ++k)  // the last tile ends on the region's face exactly
    axis(p, k) = c[k] + 1 == n_[k] ? axis(hi_, k)
                                   : axis(lo_, k) + static_cast<double>(c[k] + 1) * axis(edge_, k);
  return p;
}

namespace {

constexpr double pi = 3.14159265358979323846;

double sphere_volume(double r) { return 4.0 / 3.0 * pi * r * r * r; }

/// SplitMix64's finaliser (Steele, Lea & Flood, OOPSLA 2014): one well-mixed 64-bit word.
std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Random stream `stream` of tile `tile` of source `source` (all ~0: the source's sizing stream).
std::mt19937_64 tile_rng(std::uint64_t seed, std::size_t source, std::uint64_t tile,
                         std::uint64_t stream) {
  return std::mt19937_64(mix64(mix64(mix64(mix64(seed) ^ source) ^ tile) ^ stream));
}

/// Expected number of spheres of a source, for the tile size: its count, or the volume to
/// fill over the mean volume of 4096 radii from the source's sizing stream.
double expected_spheres(const ParticleSource& src, std::uint64_t seed, std::size_t source,
                        double region_volume) {
  if (src.count > 0) return static_cast<double>(src.count);
  std::mt19937_64 rng = tile_rng(seed, source, ~std::uint64_t{0}, ~std::uint64_t{0});
  double mean_volume = 0;
  const std::vector<double> radii = sample_radii(src.radius, 4096, rng);
  for (double r : radii) mean_volume += sphere_volume(r) / static_cast<double>(radii.size());
  return src.volume_fraction * region_volume / mean_volume;
}

/// Tile t's share ⌊N (t+1)/T⌋ − ⌊N t/T⌋ of N spheres (no overflow for N, T < 2^32).
std::size_t count_share(std::uint64_t count, std::size_t t, std::size_t tiles) {
  const auto bound = [&](std::uint64_t k) { return count / tiles * k + count % tiles * k / tiles; };
  return static_cast<std::size_t>(bound(t + 1) - bound(t));
}

/// One box source being placed: its region, its grid and the range of tiles filled.
struct TiledSource {
  const ParticleSource& src;
  std::uint64_t seed;
  std::size_t index;
  InsertionTiles tiles;
  std::size_t first = 0, last = 0;  ///< tiles filled: [first, last)
  double r_min = 0, r_max = 0;
};

/// A tile's radii, largest first, from its stream.
std::vector<double> tile_radii(const TiledSource& s, std::size_t t, std::mt19937_64& rng) {
  std::vector<double> radii;
  if (s.src.count > 0) {
    radii = sample_radii(s.src.radius, count_share(s.src.count, t, s.tiles.count()), rng);
  } else {
    const double target = s.src.volume_fraction * s.tiles.tile_volume();
    double volume = 0;
    while (volume < target)
      for (double r : sample_radii(s.src.radius, 16, rng)) {
        if (volume >= target) break;
        radii.push_back(r);
        volume += sphere_volume(r);
      }
  }
  std::sort(radii.begin(), radii.end(), std::greater<double>());
  return radii;
}

/// One tile's radii, largest first, and the spheres placed so far.
struct TileFill {
  std::vector<double> radii;
  std::vector<Real4> spheres;
  bool stuck = false;  ///< a sphere found no free centre: the tile takes no more
};

/// Indices into `store` of the spheres that a sphere centred in each filled tile could meet:
/// those whose box, widened by r_max, reaches the tile.
std::vector<std::vector<std::size_t>> earlier_spheres_by_tile(const TiledSource& s,
                                                              const ParticleStore& store) {
  std::vector<std::vector<std::size_t>> near(s.last - s.first);
  const InsertionTiles& g = s.tiles;
  const InsertionTiles::Coords first = g.coords(s.first), last = g.coords(s.last - 1);
  const Vec3 origin = g.lo(), unit = g.edge();
  for (std::size_t n = 0; n < store.size(); ++n) {
    const Real4& p = store.position_radius[n];
    InsertionTiles::Coords lo{}, hi{};
    for (int k = 0; k < 3; ++k) {
      const double reach = p.w + s.r_max;
      lo[k] = static_cast<std::int64_t>(std::floor((axis(xyz(p), k) - reach - axis(origin, k)) / axis(unit, k)));
      hi[k] = static_cast<std::int64_t>(std::floor((axis(xyz(p), k) + reach - axis(origin, k)) / axis(unit, k)));
      lo[k] = std::max<std::int64_t>(lo[k], 0);
      hi[k] = std::min<std::int64_t>(hi[k], g.along(k) - 1);
    }
    const int slab = g.slab_axis();
    lo[slab] = std::max(lo[slab], first[slab]);
    hi[slab] = std::min(hi[slab], last[slab]);
    InsertionTiles::Coords c{};
    for (c[2] = lo[2]; c[2] <= hi[2]; ++c[2])
      for (c[1] = lo[1]; c[1] <= hi[1]; ++c[1])
        for (c[0] = lo[0]; c[0] <= hi[0]; ++c[0]) near[g.index(c) - s.first].push_back(n);
  }
  return near;
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

/// The spheres of the filled neighbours of tile c (box [lo, hi]) that a sphere centred in it
/// could overlap: those closer to the box than their radius plus r_max.
std::vector<Real4> neighbour_spheres_near(const TiledSource& s, const InsertionTiles::Coords& c,
                                          Vec3 lo, Vec3 hi, const std::vector<TileFill>& fills) {
  std::vector<Real4> near;
  for (std::int64_t dz = -1; dz <= 1; ++dz)
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const InsertionTiles::Coords u{c[0] + dx, c[1] + dy, c[2] + dz};
        if ((dx | dy | dz) == 0 || !s.tiles.contains(u)) continue;
        const std::size_t k = s.tiles.index(u);
        if (k < s.first || k >= s.last) continue;
        for (const Real4& p : fills[k - s.first].spheres) {
          const double reach = p.w + s.r_max;
          if (distance2_to_box(xyz(p), lo, hi) < reach * reach) near.push_back(p);
        }
      }
  return near;
}

/// Places run `round` of tile t's radii, largest first, at free centres inside both the tile and
/// the region (shrunk by the radius), avoiding the tile's spheres, those of its neighbours and
/// the earlier spheres near it; a sphere that finds no free centre leaves the tile stuck.
void fill_tile(const TiledSource& s, std::size_t t, int round, std::vector<TileFill>& fills,
               const std::vector<std::size_t>& earlier, const ParticleStore& store) {
  const InsertionTiles& g = s.tiles;
  const InsertionTiles::Coords c = g.coords(t);
  TileFill& fill = fills[t - s.first];
  const RowRange run = share_of_rows(fill.radii.size(), round, kRounds);
  if (fill.stuck || run.count == 0) return;
  const Vec3 tile_lo = g.tile_lo(c), tile_hi = g.tile_hi(c);
  const std::vector<Real4> near = neighbour_spheres_near(s, c, tile_lo, tile_hi, fills);
  SphereHash hash(s.r_min, fill.spheres.size() + run.count + near.size() + earlier.size());
  for (const Real4& p : fill.spheres) hash.insert(xyz(p), p.w);
  for (const Real4& p : near) hash.insert(xyz(p), p.w);
  for (std::size_t n : earlier)
    hash.insert(xyz(store.position_radius[n]), store.position_radius[n].w);
  std::mt19937_64 rng = tile_rng(s.seed, s.index, t, 1 + round);
  for (std::size_t n = run.first; n < run.first + run.count; ++n) {
    const double r = fill.radii[n];
    Vec3 first, width;
    for (int k = 0; k < 3; ++k) {
      axis(first, k) = std::max(axis(tile_lo, k), axis(s.src.region_min, k) + r);
      axis(width, k) = std::min(axis(tile_hi, k), axis(s.src.region_max, k) - r) - axis(first, k);
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

/// Runs `body(k)` for k in [0, count) on all threads; the first exception is rethrown after.
template <class Body>
void for_each_tile(std::size_t count, const Body& body) {
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

/// Fills the tiles [s.first, s.last): their radii, then their centres round by round and colour
/// by colour, the tiles of one colour on all threads.
std::vector<TileFill> fill_tiles(const TiledSource& s, const ParticleStore& store) {
  std::vector<TileFill> fills(s.last - s.first);
  const std::vector<std::vector<std::size_t>> earlier = earlier_spheres_by_tile(s, store);
  for_each_tile(fills.size(), [&](std::size_t k) {
    std::mt19937_64 rng = tile_rng(s.seed, s.index, s.first + k, 0);
    fills[k].radii = tile_radii(s, s.first + k, rng);
  });
  for (int round = 0; round < kRounds; ++round)
    for (int colour = 0; colour < 8; ++colour)
      for_each_tile(fills.size(), [&](std::size_t k) {
        const std::size_t t = s.first + k;
        if (s.tiles.colour(s.tiles.coords(t)) == colour)
          fill_tile(s, t, round, fills, earlier[k], store);
      });
  return fills;
}

std::string format_number(double x) {
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

/// The error for tile t, which holds `fill` of the spheres it wanted.
InputError shortfall(const Scene& scene, const TiledSource& s, std::size_t t, const TileFill& fill) {
  const InsertionTiles::Coords c = s.tiles.coords(t);
  double solid = 0;
  for (const Real4& p : fill.spheres) solid += sphere_volume(p.w);
  return InputError(
      scene.file, 0, "insert[" + std::to_string(s.index) + "]",
      "could only place " + std::to_string(fill.spheres.size()) + " of " +
          std::to_string(fill.radii.size()) + " particles in tile (" + std::to_string(c[0]) + ", " +
          std::to_string(c[1]) + ", " + std::to_string(c[2]) + ") of " +
          std::to_string(s.tiles.along(0)) + " x " + std::to_string(s.tiles.along(1)) + " x " +
          std::to_string(s.tiles.along(2)) + " (its solid fraction " +
          format_number(solid / s.tiles.tile_volume()) +
          "); enlarge the region or lower count/volume_fraction");
}

}  // namespace

InsertionTiles insertion_tiles(const Scene& scene, std::size_t i) {
  const ParticleSource& src = scene.sources[i];
  const Vec3 extent = src.region_max - src.region_min;
  const double region_volume = extent.x * extent.y * extent.z;
  const double expected = expected_spheres(src, scene.simulation.seed, i, region_volume);
  const double sized_edge = std::cbrt(region_volume * kSpheresPerTile / expected);
  return InsertionTiles(src.region_min, src.region_max,
                        std::max(2 * max_radius(src.radius), sized_edge));
}

void insert_tiled_box(const Scene& scene, std::size_t i, FilePart part, ParticleStore& store,
                      ParticleId& next_id) {
  const ParticleSource& src = scene.sources[i];
  TiledSource s{src, scene.simulation.seed, i, insertion_tiles(scene, i)};
  s.r_min = min_radius(src.radius);
  s.r_max = max_radius(src.radius);
  const RowRange own = part.rows_of(s.tiles.count());
  if (own.count == 0) return;
  const std::size_t layer = s.tiles.layer_size(), layers = s.tiles.count() / layer;
  const std::size_t first_layer = own.first / layer;
  const std::size_t last_layer = (own.first + own.count - 1) / layer;
  s.first = (first_layer - std::min<std::size_t>(first_layer, kTileMarginLayers)) * layer;
  s.last = std::min<std::size_t>(last_layer + 1 + kTileMarginLayers, layers) * layer;
  const std::vector<TileFill> fills = fill_tiles(s, store);
  for (std::size_t t = own.first; t < own.first + own.count; ++t)
    if (fills[t - s.first].stuck) throw shortfall(scene, s, t, fills[t - s.first]);
  const double density = scene.materials[src.material].density;
  for (std::size_t t = own.first; t < own.first + own.count; ++t)
    for (const Real4& p : fills[t - s.first].spheres)
      store.add(next_id++, xyz(p), p.w, src.material, src.velocity,
                1.0 / sphere_mass(density, p.w));
}

}  // namespace gpudem
