// Tiled box insertion: the tile grid and its colouring, parts run in lockstep (as ranks run
// them) that put together give the whole region whatever their number (and the number of
// threads), valid fills by count and by volume fraction, earlier spheres larger than a tile,
// failures that name the same tile on any number of parts, and the mark the tile faces leave.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#if defined(GPUDEM_HAVE_OPENMP)
#include <omp.h>
#endif

#include "core/InputError.hpp"
#include "core/ParticleSources.hpp"
#include "core/TiledInsertion.hpp"
#include "support/InsertionChecks.hpp"

namespace gpudem {
namespace {

using test::ball_volume;
using test::box;
using test::expect_inside;
using test::expect_no_overlaps;
using test::uniform;

/// A scene whose one source is a tiled box.
Scene tiled_scene(ParticleSource source, std::uint64_t seed = 7) {
  Scene scene = test::insertion_scene(seed);
  source.placement = Placement::Tiled;
  scene.sources.push_back(source);
  return scene;
}

/// A long bed: 60000 spheres of radius 0.5 ± 0.1 mm in 1.2 m × 2 cm × 2 cm, 75 layers of tiles.
Scene long_bed() {
  return tiled_scene(box({0, 0.3, 0.3}, {1.2, 0.32, 0.32}, 60000, uniform(0.5e-3, 0.1e-3)));
}

ParticleStore whole(const Scene& scene) {
  ParticleStore store;
  create_particles(scene, store);
  return store;
}

LayerSide opposite(LayerSide side) {
  return side == LayerSide::Below ? LayerSide::Above : LayerSide::Below;
}

/// The fills of `count` parts of `scene`'s tiled source run in lockstep as ranks run them:
/// after each phase, each part's boundary spheres go to the neighbour on that side.
std::vector<TiledFill> lockstep_fills(const Scene& scene, int count) {
  std::vector<TiledFill> fills;
  fills.reserve(static_cast<std::size_t>(count));
  for (int p = 0; p < count; ++p)
    fills.emplace_back(scene, 0, FilePart{p, count}, std::vector<Real4>{});
  for (int phase = 0; phase < kTilePhases; ++phase) {
    for (TiledFill& fill : fills) fill.fill_phase(phase);
    for (TiledFill& fill : fills)
      for (const LayerSide side : {LayerSide::Below, LayerSide::Above})
        if (fill.neighbour(side) >= 0)
          fills[static_cast<std::size_t>(fill.neighbour(side))].receive(opposite(side),
                                                                        fill.boundary(side));
  }
  return fills;
}

/// Part p's particles, ids from 0.
ParticleStore particles_of(const TiledFill& fill) {
  ParticleStore part;
  ParticleId next_id = 0;
  fill.append_to(part, next_id);
  return part;
}

// ---------------------------------------------------------------- the grid

TEST(InsertionTiles, EqualTilesOfAtLeastTheEdgeCoverTheRegion) {
  const Vec3 lo{0.1, 0.2, 0.3}, hi{0.5, 0.3, 0.35};
  const InsertionTiles g(lo, hi, 0.03);
  EXPECT_EQ(g.along(0), 13);  // ⌊0.4 / 0.03⌋
  EXPECT_EQ(g.along(1), 3);
  EXPECT_EQ(g.along(2), 1);  // shorter than the edge: one tile
  EXPECT_EQ(g.slab_axis(), 0);
  ASSERT_EQ(g.count(), 39u);
  EXPECT_EQ(g.layer_size(), 3u);
  for (int k = 0; k < 2; ++k) EXPECT_GE(axis(g.edge(), k), 0.03);
  EXPECT_NEAR(g.tile_volume(), (0.4 / 13) * (0.1 / 3) * 0.05, 1e-18);
  EXPECT_EQ(norm2(g.tile_lo({0, 0, 0}) - lo), 0.0);
  EXPECT_EQ(norm2(g.tile_hi({12, 2, 0}) - hi), 0.0);  // the last tile ends on the face exactly
  for (std::size_t t = 0; t < g.count(); ++t) {
    const InsertionTiles::Coords c = g.coords(t);
    EXPECT_EQ(g.index(c), t);
    EXPECT_TRUE(g.contains(c));
    if (t > 0) {  // the slab axis runs slowest
      EXPECT_EQ(g.coords(t - 1)[0], c[1] == 0 ? c[0] - 1 : c[0]);
    }
    for (int k = 0; k < 3; ++k) {
      InsertionTiles::Coords next = c;
      next[k] += 1;
      if (g.contains(next)) {
        EXPECT_NEAR(axis(g.tile_hi(c), k), axis(g.tile_lo(next), k), 1e-15);
      }
    }
  }
  EXPECT_FALSE(g.contains({13, 0, 0}));
  EXPECT_FALSE(g.contains({0, -1, 0}));
}

TEST(InsertionTiles, NeighboursNeverShareAColourAndTheSlabParityIsItsTopBit) {
  const InsertionTiles g({0, 0, 0}, {0.4, 0.5, 0.7}, 0.1);
  ASSERT_EQ(g.slab_axis(), 2);
  std::size_t clashes = 0, pairs = 0;
  for (std::size_t t = 0; t < g.count(); ++t) {
    const InsertionTiles::Coords c = g.coords(t);
    EXPECT_EQ(g.colour(c) >> 2, c[2] & 1);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const InsertionTiles::Coords u{c[0] + dx, c[1] + dy, c[2] + dz};
          if ((dx | dy | dz) == 0 || !g.contains(u)) continue;
          ++pairs;
          if (g.colour(u) == g.colour(c)) ++clashes;
        }
  }
  EXPECT_GT(pairs, 1000u);
  EXPECT_EQ(clashes, 0u);
}

TEST(InsertionTiles, FewerThan2To31TilesInAHugeRegion) {
  const InsertionTiles g({0, 0, 0}, {100, 100, 100}, 1e-3);
  EXPECT_LT(static_cast<double>(g.count()), 2147483648.0);
  EXPECT_GT(static_cast<double>(g.count()), 2147483648.0 / 8);
  for (int k = 0; k < 3; ++k) EXPECT_GE(axis(g.edge(), k), 1e-3);
}

TEST(InsertionTiles, SizedForTheSourceAndAtLeastTheLargestDiameter) {
  const Scene scene = long_bed();
  const InsertionTiles g = insertion_tiles(scene, 0);
  EXPECT_EQ(g.slab_axis(), 0);
  EXPECT_EQ(g.layer_size(), 1u);
  // ⌊L/edge⌋ tiles along an axis: each holds at least kSpheresPerTile, fewer than one more row
  double widening = 1;
  for (int k = 0; k < 3; ++k) widening *= (g.along(k) + 1.0) / g.along(k);
  const double per_tile = 60000.0 / static_cast<double>(g.count());
  EXPECT_GE(per_tile, kSpheresPerTile);
  EXPECT_LT(per_tile, kSpheresPerTile * widening);
  const Scene coarse = tiled_scene(box({0, 0, 0}, {0.1, 0.1, 0.1}, 100, uniform(5e-3, 4e-3)));
  const InsertionTiles few = insertion_tiles(coarse, 0);
  for (int k = 0; k < 3; ++k) EXPECT_GE(axis(few.edge(), k), 2 * 9e-3);
}

// ---------------------------------------------------------------- parts and threads

void expect_same_rows(const ParticleStore& a, std::size_t offset, const ParticleStore& part) {
  ASSERT_LE(offset + part.size(), a.size());
  std::size_t differ = 0;
  for (std::size_t n = 0; n < part.size(); ++n) {
    const Real4 p = a.position_radius[offset + n], q = part.position_radius[n];
    const Real4 v = a.velocity_inv_mass[offset + n], w = part.velocity_inv_mass[n];
    if (p.x != q.x || p.y != q.y || p.z != q.z || p.w != q.w || v.x != w.x || v.y != w.y ||
        v.z != w.z || v.w != w.w || a.material[offset + n] != part.material[n] || part.id[n] != n)
      ++differ;
  }
  EXPECT_EQ(differ, 0u) << "rows from " << offset;
}

TEST(TiledInsertion, PartsInOrderAreTheWholeRegionForAnyNumberOfParts) {
  const Scene scene = long_bed();
  const ParticleStore all = whole(scene);
  ASSERT_EQ(all.size(), 60000u);
  for (const int parts : {2, 3, 8, 37, 100}) {  // 100 parts: more than layers, some without
    std::size_t offset = 0;
    for (const TiledFill& fill : lockstep_fills(scene, parts)) {
      const ParticleStore part = particles_of(fill);
      expect_same_rows(all, offset, part);
      offset += part.size();
    }
    EXPECT_EQ(offset, all.size()) << parts << " parts";
  }
}

TEST(TiledInsertion, APartPlacesOnlyItsShareOfTheLayers) {
  const Scene scene = long_bed();
  const std::vector<TiledFill> fills = lockstep_fills(scene, 5);
  const InsertionTiles& g = fills[2].tiles();
  ASSERT_EQ(g.layer_size(), 1u);
  EXPECT_EQ(fills[0].neighbour(LayerSide::Below), -1);
  EXPECT_EQ(fills[2].neighbour(LayerSide::Below), 1);
  EXPECT_EQ(fills[2].neighbour(LayerSide::Above), 3);
  EXPECT_EQ(fills[4].neighbour(LayerSide::Above), -1);
  const RowRange layers = share_of_rows(g.count(), 2, 5);
  const double lo = g.tile_lo({static_cast<std::int64_t>(layers.first), 0, 0}).x;
  const double hi = g.tile_hi({static_cast<std::int64_t>(layers.first + layers.count - 1), 0, 0}).x;
  const ParticleStore part = particles_of(fills[2]);
  EXPECT_GT(part.size(), 60000u / 5 * 9 / 10);
  EXPECT_LT(part.size(), 60000u / 5 * 11 / 10);
  std::size_t outside = 0;
  for (const Real4& p : part.position_radius)
    if (p.x < lo || p.x > hi) ++outside;
  EXPECT_EQ(outside, 0u);
}

#if defined(GPUDEM_HAVE_OPENMP)
TEST(TiledInsertion, TheNumberOfThreadsChangesNothing) {
  const Scene scene = long_bed();
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const ParticleStore one = whole(scene);
  omp_set_num_threads(3);
  const ParticleStore three = whole(scene);
  omp_set_num_threads(threads);
  ASSERT_EQ(one.size(), three.size());
  expect_same_rows(one, 0, three);
}
#endif

TEST(TiledInsertion, OtherSeedOtherBed) {
  const ParticleStore a = whole(long_bed());
  Scene other = long_bed();
  other.simulation.seed = 8;
  const ParticleStore b = whole(other);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NE(a.position_radius[0].x, b.position_radius[0].x);
}

// ---------------------------------------------------------------- fills

TEST(TiledInsertion, FillsItsCountDenselyInsideTheRegionWithoutOverlaps) {
  // radius 0.5 to 1.5 mm at a solid fraction of 0.35
  const double side = std::cbrt(30000 * 5.236e-9 / 0.35);
  Scene scene = tiled_scene(box({0, 0, 0}, {side, side, side}, 30000, uniform(1e-3, 0.5e-3)));
  scene.sources[0].material = 1;
  scene.sources[0].velocity = {0.1, 0, -1};
  const ParticleStore store = whole(scene);
  ASSERT_EQ(store.size(), 30000u);
  EXPECT_GE(insertion_tiles(scene, 0).count(), 27u);
  expect_inside(store, 0, store.size(), {0, 0, 0}, {side, side, side});
  expect_no_overlaps(store);
  std::size_t wrong = 0;
  for (std::size_t n = 0; n < store.size(); ++n) {
    const Real4& v = store.velocity_inv_mass[n];
    const double r = store.position_radius[n].w;
    if (store.id[n] != n || store.material[n] != 1 || v.x != 0.1 || v.z != -1 ||
        std::abs(v.w * ball_volume(r) * 7800 - 1) > 1e-12)
      ++wrong;
  }
  EXPECT_EQ(wrong, 0u);
}

TEST(TiledInsertion, VolumeFractionReachedWithinOneSpherePerTile) {
  const Vec3 lo{0, 0, 0}, hi{0.16, 0.08, 0.08};
  const RadiusDistribution radius = uniform(1e-3, 0.5e-3);
  Scene scene = tiled_scene(box(lo, hi, 0, radius));
  scene.sources[0].volume_fraction = 0.3;
  const ParticleStore store = whole(scene);
  const std::size_t tiles = insertion_tiles(scene, 0).count();
  ASSERT_GE(tiles, 27u);
  double solid = 0;
  for (const Real4& p : store.position_radius) solid += ball_volume(p.w);
  const double region = 0.16 * 0.08 * 0.08;
  EXPECT_GE(solid / region, 0.3);
  EXPECT_LE(solid / region, 0.3 + static_cast<double>(tiles) * ball_volume(1.5e-3) / region);
  expect_inside(store, 0, store.size(), lo, hi);
  expect_no_overlaps(store);
}

TEST(TiledInsertion, AvoidsEarlierSpheresLargerThanItsTiles) {
  Scene scene = test::insertion_scene();
  scene.sources.push_back(box({0.3, 0, 0}, {0.5, 0.1, 0.1}, 2000, uniform(2e-3, 0.5e-3)));
  scene.sources.push_back(box({0, 0, 0}, {0.4, 0.1, 0.1}, 20000, uniform(1e-3, 0.2e-3)));
  scene.sources[1].placement = Placement::Tiled;
  ParticleStore store;
  store.add(0, {0.1, 0.05, 0.05}, 0.045, 0, {}, 1.0);  // spans tiles in every direction
  store.add(1, {0.2, 0.05, 0.11}, 0.02, 0, {}, 1.0);   // centre outside, reaching in
  create_particles(scene, store);
  ASSERT_EQ(store.size(), 22002u);
  ASSERT_GE(insertion_tiles(scene, 1).count(), 8u);
  expect_inside(store, 2002, store.size(), {0, 0, 0}, {0.4, 0.1, 0.1});
  expect_no_overlaps(store);
}

/// The message of the InputError that `create` throws, or none.
template <class Create>
std::optional<std::string> failure_of(const Create& create) {
  try {
    create();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "insert[0]");
    return std::string(e.what());
  }
  return std::nullopt;
}

TEST(TiledInsertion, AFailureNamesTheFirstStuckTileOnAnyNumberOfParts) {
  Scene scene = long_bed();
  scene.sources[0].count = 1000000;  // a solid fraction of 0.87
  const std::optional<std::string> message = failure_of([&] { whole(scene); });
  ASSERT_TRUE(message);
  EXPECT_NE(message->find("could only place"), std::string::npos) << *message;
  EXPECT_NE(message->find("in tile ("), std::string::npos) << *message;
  for (const int parts : {3, 7}) {
    std::optional<std::string> first;
    for (const TiledFill& fill : lockstep_fills(scene, parts))
      if (!first) first = failure_of([&] { particles_of(fill); });
    EXPECT_EQ(first, message) << parts << " parts";
  }
}

TEST(TiledInsertion, SpheresForALayerItDoesNotMirrorAreALogicError) {
  const Scene scene = long_bed();
  std::vector<TiledFill> fills = lockstep_fills(scene, 3);
  const std::vector<BoundarySphere> stray{{0, {0.01, 0.31, 0.31, 0.5e-3}}};
  EXPECT_THROW(fills[2].receive(LayerSide::Below, stray), std::logic_error);  // part 0's layer
  EXPECT_THROW(fills[0].receive(LayerSide::Below, stray), std::logic_error);  // no neighbour
}

// The solid volume of the centres lying within 1/16 of a tile of a tile face (the region's
// faces left out), against the mean over the sixteenths: 1.5 % below it at 8 rounds, 8 % at one.
TEST(TiledInsertion, TileFacesLeaveLittleMark) {
  const double side = std::cbrt(200000 * 5.236e-9 / 0.3);
  const Scene scene =
      tiled_scene(box({0, 0, 0}, {side, side, side}, 200000, uniform(1e-3, 0.5e-3)));
  const ParticleStore store = whole(scene);
  const InsertionTiles g = insertion_tiles(scene, 0);
  ASSERT_GE(g.along(0), 5);
  constexpr int kBins = 16;
  std::vector<double> solid(kBins, 0.0);
  for (const Real4& p : store.position_radius)
    for (int k = 0; k < 3; ++k) {
      const double e = axis(g.edge(), k), x = axis(xyz(p), k);
      if (x < e || x > side - e) continue;
      const int bin = std::min(kBins - 1, static_cast<int>(std::fmod(x, e) / e * kBins));
      solid[static_cast<std::size_t>(bin)] += ball_volume(p.w);
    }
  double mean = 0;
  for (double s : solid) mean += s / kBins;
  std::printf(
      "solid volume of the centres in the first and last 1/16 of a tile: %.3f and %.3f "
      "of the mean over the sixteenths\n",
      solid.front() / mean, solid.back() / mean);
  EXPECT_GT(solid.front() / mean, 0.97);
  EXPECT_GT(solid.back() / mean, 0.97);
}

}  // namespace
}  // namespace gpudem
