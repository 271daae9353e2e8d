// Domain decomposition geometry: coarse cells, owners of grid blocks, ghost ranks against a
// brute-force distance check, neighbour ranks, binning regions, grid dims chosen by cut area,
// balanced and rebalanced cuts, and METIS parts.
#include "comm/Decomposition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "core/InputError.hpp"
#include "engine/BinRegion.hpp"
#include "engine/PeriodicBox.hpp"

namespace gpudem {
namespace {

using Cuts = std::array<std::vector<int>, 3>;

PeriodicBox make_box(Vec3 lo, Vec3 length, bool px = false, bool py = false, bool pz = false) {
  PeriodicBox box;
  box.lo = lo;
  box.length = length;
  box.periodic[0] = px;
  box.periodic[1] = py;
  box.periodic[2] = pz;
  return box;
}

/// Distance from p to the box [lo, hi].
Real distance_to_box(Vec3 p, Vec3 lo, Vec3 hi) {
  Real d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const Real d = std::max({Real(0), axis(lo, k) - axis(p, k), axis(p, k) - axis(hi, k)});
    d2 += d * d;
  }
  return std::sqrt(d2);
}

/// The ranks other than `rank` owning a cell whose box, or one of its periodic images shifted
/// by up to 2 L along each periodic axis, lies within `reach` of p: every cell checked.
std::vector<int> brute_force_ghost_ranks(const Decomposition& d, Vec3 p, int rank, Real reach) {
  const CoarseGrid& g = d.cells();
  std::vector<int> result;
  for (std::size_t i = 0; i < g.count(); ++i) {
    const std::array<int, 3> c = g.coords(i);
    Vec3 lo, hi;
    for (int k = 0; k < 3; ++k) {
      const Real e = axis(g.length, k) / g.n[k];
      axis(lo, k) = axis(g.lo, k) + c[k] * e;
      axis(hi, k) = axis(lo, k) + e;
    }
    bool near = false;
    for (int sz = -2; sz <= 2; ++sz)
      for (int sy = -2; sy <= 2; ++sy)
        for (int sx = -2; sx <= 2; ++sx) {
          const int s[3] = {sx, sy, sz};
          bool allowed = true;
          Vec3 shift;
          for (int k = 0; k < 3; ++k) {
            allowed = allowed && (s[k] == 0 || g.periodic[k]);
            axis(shift, k) = s[k] * axis(g.length, k);
          }
          near = near || (allowed && distance_to_box(p, lo + shift, hi + shift) <= reach);
        }
    const int owner = d.owner_of_cell(i);
    if (near && owner != rank && std::find(result.begin(), result.end(), owner) == result.end())
      result.push_back(owner);
  }
  std::sort(result.begin(), result.end());
  return result;
}

std::vector<int> ghost_ranks_of(const Decomposition& d, Vec3 p, int rank, Real reach) {
  std::vector<int> out{-7};  // stale content, to be cleared
  d.ghost_ranks(p, rank, reach, out);
  return out;
}

/// Work of every block of a grid (rank a + dims0 (b + dims1 c)), summed cell by cell.
std::vector<double> block_work(const CoarseGrid& g, const Cuts& cuts,
                               const std::vector<double>& work) {
  const int d0 = static_cast<int>(cuts[0].size()) - 1, d1 = static_cast<int>(cuts[1].size()) - 1;
  const int d2 = static_cast<int>(cuts[2].size()) - 1;
  std::vector<double> sums(static_cast<std::size_t>(d0 * d1 * d2), 0.0);
  for (std::size_t i = 0; i < g.count(); ++i) {
    const std::array<int, 3> c = g.coords(i);
    int block[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      while (c[k] >= cuts[k][static_cast<std::size_t>(block[k]) + 1]) ++block[k];
    sums[static_cast<std::size_t>(block[0] + d0 * (block[1] + d1 * block[2]))] += work[i];
  }
  return sums;
}

double largest(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

double max_over_mean(const std::vector<double>& v) {
  double total = 0, largest = 0;
  for (double x : v) {
    total += x;
    largest = std::max(largest, x);
  }
  return largest * static_cast<double>(v.size()) / total;
}

/// Separable corner-heavy work w = f(x) f(y), f(c) = exp(-c / decay), heaviest at cell (0, 0).
std::vector<double> corner_heavy_work(const CoarseGrid& g, double decay) {
  std::vector<double> w(g.count());
  for (std::size_t i = 0; i < g.count(); ++i) {
    const std::array<int, 3> c = g.coords(i);
    w[i] = std::exp(-c[0] / decay) * std::exp(-c[1] / decay);
  }
  return w;
}

bool strictly_ascending(const std::vector<int>& cuts) {
  for (std::size_t i = 1; i < cuts.size(); ++i)
    if (cuts[i] <= cuts[i - 1]) return false;
  return true;
}

// --- CoarseGrid ---------------------------------------------------------------------------

TEST(CoarseGrid, SizesAndIndices) {
  // 1 / 0.125 = 8, 0.75 / 0.125 = 6, 0.25 / 0.125 = 2 (exact in binary).
  const CoarseGrid g = CoarseGrid::over(make_box({-0.5, 0, 1}, {1.0, 0.75, 0.25}), 0.125);
  EXPECT_EQ(g.n[0], 8);
  EXPECT_EQ(g.n[1], 6);
  EXPECT_EQ(g.n[2], 2);
  EXPECT_EQ(g.count(), 96u);
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(g.edge(k), 0.125);
  EXPECT_EQ(g.index(3, 2, 1), 3u + 8u * (2u + 6u * 1u));
  for (std::size_t i = 0; i < g.count(); ++i) {
    const std::array<int, 3> c = g.coords(i);
    EXPECT_EQ(g.index(c[0], c[1], c[2]), i);
  }
  // Point (x, y, z) = lo + (3.5, 2.5, 1.5) edges lies in cell (3, 2, 1).
  EXPECT_EQ(g.cell_of({-0.5 + 3.5 * 0.125, 2.5 * 0.125, 1 + 1.5 * 0.125}), g.index(3, 2, 1));
}

TEST(CoarseGrid, EdgeIsAtLeastMinSideAndAsSmallAsAllowed) {
  // n = max(1, floor(L / s)): the most cells of edge >= s, so L / (n + 1) < s.
  const CoarseGrid coarse = CoarseGrid::over(make_box({0, 0, 0}, {1.0, 0.75, 0.25}), 0.3);
  EXPECT_EQ(coarse.n[0], 3);
  EXPECT_EQ(coarse.n[1], 2);
  EXPECT_EQ(coarse.n[2], 1);  // L < s: one cell, narrower than s
  // Lengths at and one or two ulps below a multiple of s, where L / s rounds to either side of
  // an integer, and 0.7 / 0.1, which rounds below 7.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> side(0.001, 0.5);
  std::uniform_int_distribution<int> multiple(1, 400);
  for (int trial = 0; trial < 3000; ++trial) {
    const double s = trial % 10 == 0 ? 0.1 : side(rng);
    double x = multiple(rng) * s;
    for (int ulps = 0; ulps < trial % 3; ++ulps) x = std::nextafter(x, 0.0);
    const Vec3 L{x, 0.7, 0.3};
    const CoarseGrid g =
        CoarseGrid::over(make_box({0, 0, 0}, L), s, std::numeric_limits<std::size_t>::max());
    for (int k = 0; k < 3; ++k) {
      const double Lk = axis(L, k);
      if (Lk < s) {
        EXPECT_EQ(g.n[k], 1);
        continue;
      }
      EXPECT_GE(g.edge(k), s) << "L = " << Lk << ", s = " << s;
      EXPECT_LT(Lk / (g.n[k] + 1), s) << "L = " << Lk << ", s = " << s;
    }
  }
}

TEST(CoarseGrid, ALargeBoxTakesWiderCellsUpToTheLimit) {
  const std::size_t limit = kMaxCoarseCells;
  // Boxes of 4.6e9, 1.2e10 (a thin sheet, one cell deep) and 5.8e14 cells of the side: each
  // capped near the limit, with edges wider than the side.
  const std::array<Vec3, 3> lengths{Vec3{100, 40, 2}, Vec3{1000, 1000, 0.02}, Vec3{1e4, 1e4, 10}};
  const double side = 0.012;
  for (const Vec3& L : lengths) {
    const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, L), side);
    EXPECT_LE(g.count(), limit) << L.x;
    EXPECT_GT(g.count(), limit / 4) << L.x;
    for (int k = 0; k < 3; ++k) EXPECT_GE(g.edge(k), side) << L.x << " axis " << k;
  }
  // The thin sheet stays one cell deep; the others have cubic-ish cells.
  const CoarseGrid sheet = CoarseGrid::over(make_box({0, 0, 0}, lengths[1]), side);
  EXPECT_EQ(sheet.n[2], 1);
  const CoarseGrid bed = CoarseGrid::over(make_box({0, 0, 0}, lengths[0]), side);
  EXPECT_NEAR(bed.edge(0) / bed.edge(1), 1, 0.05);
  // A small limit, counted exactly: 1 x 0.5 x 0.25 m in 0.01 m cells (1.25e5) at most 1000.
  const CoarseGrid small = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.5, 0.25}), 0.01, 1000);
  EXPECT_LE(small.count(), 1000u);
  EXPECT_GT(small.count(), 250u);
  EXPECT_THROW(CoarseGrid::over(make_box({0, 0, 0}, {1, 1, 1}), 0.1, 0), std::invalid_argument);
}

TEST(CoarseGrid, ABoxWithinTheLimitKeepsCellsOfTheSide) {
  // 1.6 x 1 x 0.5 m in 0.01 m cells: 8e5 cells, below the limit.
  const PeriodicBox box = make_box({0, 0, 0}, {1.6, 1.0, 0.5});
  const CoarseGrid g = CoarseGrid::over(box, 0.01);
  const CoarseGrid unlimited = CoarseGrid::over(box, 0.01, std::numeric_limits<std::size_t>::max());
  for (int k = 0; k < 3; ++k) EXPECT_EQ(g.n[k], unlimited.n[k]);
  EXPECT_NEAR(static_cast<double>(g.count()), 8e5, 1e4);
}

TEST(CoarseGrid, CoordinateClampsOrWraps) {
  const CoarseGrid open = CoarseGrid::over(make_box({0, 0, 0}, {1, 1, 1}), 0.25);
  EXPECT_EQ(open.coordinate(0, -0.01), 0);
  EXPECT_EQ(open.coordinate(0, 1.01), 3);
  EXPECT_EQ(open.coordinate(0, 0.3), 1);
  const CoarseGrid wrapped = CoarseGrid::over(make_box({0, 0, 0}, {1, 1, 1}, true), 0.25);
  EXPECT_EQ(wrapped.coordinate(0, -0.01), 3);
  EXPECT_EQ(wrapped.coordinate(0, 1.01), 0);
  EXPECT_EQ(wrapped.coordinate(0, 2.3), 1);
  EXPECT_EQ(wrapped.coordinate(1, -0.01), 0);  // y is not periodic
}

// --- Owners -------------------------------------------------------------------------------

TEST(Decomposition, OwnerOfSlabs) {
  // 8 x 4 x 4 cells of 0.125; four slabs of 2 cells along x: rank = floor(x / 0.25).
  const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.5, 0.5}), 0.125);
  const Decomposition d = Decomposition::grid(g, {{{0, 2, 4, 6, 8}, {0, 4}, {0, 4}}});
  EXPECT_EQ(d.ranks(), 4);
  EXPECT_TRUE(d.is_grid());
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p{u(rng), 0.5 * u(rng), 0.5 * u(rng)};
    EXPECT_EQ(d.owner_of(p), static_cast<int>(std::floor(p.x / 0.25))) << p.x;
  }
}

TEST(Decomposition, OwnerOfTwoByTwoBlocks) {
  // Blocks split at x = 0.5 and y = 0.25: rank = a + 2 b, a = [x >= 0.5], b = [y >= 0.25].
  const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.5, 0.5}), 0.125);
  const Decomposition d = Decomposition::grid(g, {{{0, 4, 8}, {0, 2, 4}, {0, 4}}});
  EXPECT_EQ(d.ranks(), 4);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p{u(rng), 0.5 * u(rng), 0.5 * u(rng)};
    EXPECT_EQ(d.owner_of(p), (p.x >= 0.5 ? 1 : 0) + 2 * (p.y >= 0.25 ? 1 : 0));
  }
}

TEST(Decomposition, RefusesBadCutsAndOwners) {
  const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.5, 0.5}), 0.125);
  EXPECT_THROW(Decomposition::grid(g, {{{0, 4, 7}, {0, 4}, {0, 4}}}), std::invalid_argument);
  EXPECT_THROW(Decomposition::grid(g, {{{0, 4, 4, 8}, {0, 4}, {0, 4}}}), std::invalid_argument);
  EXPECT_THROW(Decomposition::grid(g, {{{1, 8}, {0, 4}, {0, 4}}}), std::invalid_argument);
  EXPECT_THROW(Decomposition::from_owners(g, std::vector<int>(g.count() - 1, 0), 1),
               std::invalid_argument);
  EXPECT_THROW(Decomposition::from_owners(g, std::vector<int>(g.count(), 2), 2),
               std::invalid_argument);
  const Decomposition metis = Decomposition::from_owners(g, std::vector<int>(g.count(), 0), 1);
  EXPECT_FALSE(metis.is_grid());
  EXPECT_THROW(metis.cuts(), std::logic_error);
}

TEST(Decomposition, RankWorkAndImbalance) {
  // Two slabs of 4 x-cells each; cell work = x index + 1: rank 0 sums 16 (1+2+3+4) per y-z
  // column, rank 1 sums 26 (5+6+7+8), over 4 x 4 columns.
  const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.5, 0.5}), 0.125);
  const Decomposition d = Decomposition::grid(g, {{{0, 4, 8}, {0, 4}, {0, 4}}});
  std::vector<double> work(g.count());
  for (std::size_t i = 0; i < g.count(); ++i) work[i] = g.coords(i)[0] + 1;
  const std::vector<double> sums = d.rank_work(work);
  ASSERT_EQ(sums.size(), 2u);
  EXPECT_DOUBLE_EQ(sums[0], 10 * 16);
  EXPECT_DOUBLE_EQ(sums[1], 26 * 16);
  EXPECT_DOUBLE_EQ(imbalance(sums), 26.0 / 18.0);  // max / mean = 26 / ((10 + 26) / 2)
  EXPECT_DOUBLE_EQ(imbalance({1, 1, 1, 1}), 1);
  EXPECT_DOUBLE_EQ(imbalance({3, 1}), 1.5);
  EXPECT_DOUBLE_EQ(imbalance({0, 0, 0}), 1);
}

// --- Ghost ranks --------------------------------------------------------------------------

/// Checks ghost_ranks against the brute force for a point and a rank, and that the rank's cell
/// map marks the point's cell as near another rank's wherever the point has ghost ranks.
/// Returns whether it has any.
bool expect_ghost_ranks_at(const Decomposition& d, const std::vector<CellOwnership>& maps, Vec3 p,
                           int rank, Real reach) {
  const std::vector<int> expected = brute_force_ghost_ranks(d, p, rank, reach);
  EXPECT_EQ(ghost_ranks_of(d, p, rank, reach), expected)
      << "p = (" << p.x << ", " << p.y << ", " << p.z << "), rank " << rank;
  const std::size_t cell = d.cells().cell_of(p);
  if (!expected.empty()) {
    EXPECT_EQ(maps[static_cast<std::size_t>(rank)].near_other[cell], 1)
        << "p = (" << p.x << ", " << p.y << ", " << p.z << ") has ghost ranks, rank " << rank;
  }
  return !expected.empty();
}

/// Compares ghost_ranks with the brute force at random points within reach of the box, for
/// the owner of each point and for another rank, and at every cell's lower corner (a point on
/// the faces of its cell, one edge from the cells two below) for every rank.
void expect_ghost_ranks_match(const Decomposition& d, Real reach, std::uint64_t seed) {
  const CoarseGrid& g = d.cells();
  std::vector<CellOwnership> maps;
  for (int rank = 0; rank < d.ranks(); ++rank) maps.push_back(d.ownership(rank, 1));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<int> any_rank(0, d.ranks() - 1);
  int with_ghosts = 0;
  for (int i = 0; i < 1500; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k)
      axis(p, k) = axis(g.lo, k) - reach + (axis(g.length, k) + 2 * reach) * u(rng);
    for (int rank : {d.owner_of(p), any_rank(rng)})
      with_ghosts += expect_ghost_ranks_at(d, maps, p, rank, reach);
  }
  EXPECT_GT(with_ghosts, 100);  // the check saw points near other ranks
  for (std::size_t i = 0; i < g.count(); ++i) {
    const std::array<int, 3> c = g.coords(i);
    Vec3 corner;
    for (int k = 0; k < 3; ++k) axis(corner, k) = axis(g.lo, k) + c[k] * g.edge(k);
    for (int rank = 0; rank < d.ranks(); ++rank)
      expect_ghost_ranks_at(d, maps, corner, rank, reach);
  }
}

TEST(GhostRanks, MatchBruteForceOnGrids) {
  const CoarseGrid open = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.75, 0.5}), 0.125);
  const Decomposition blocks = Decomposition::grid(open, {{{0, 3, 8}, {0, 4, 6}, {0, 4}}});
  expect_ghost_ranks_match(blocks, 0.1, 11);
  expect_ghost_ranks_match(blocks, 0.125, 12);  // reach = edge
  const CoarseGrid wrapped =
      CoarseGrid::over(make_box({-1, 0, 2}, {1, 0.75, 0.5}, true, false, true), 0.125);
  const Decomposition slabs = Decomposition::grid(wrapped, {{{0, 2, 5, 8}, {0, 6}, {0, 1, 4}}});
  expect_ghost_ranks_match(slabs, 0.1, 13);
  expect_ghost_ranks_match(slabs, 0.125, 14);
}

TEST(GhostRanks, MatchBruteForceOnAnyOwnerMap) {
  std::mt19937_64 rng(3);
  // 2 x 1 x 4 cells, periodic everywhere: one and two cells along a periodic axis.
  const CoarseGrid tiny =
      CoarseGrid::over(make_box({0, 0, 0}, {0.25, 0.125, 0.5}, true, true, true), 0.125);
  std::vector<int> owner(tiny.count());
  std::uniform_int_distribution<int> of3(0, 2);
  for (int& o : owner) o = of3(rng);
  expect_ghost_ranks_match(Decomposition::from_owners(tiny, owner, 3), 0.125, 21);
  // A box thinner along z (0.1) than the reach (0.125): one cell along z, periodic or not.
  for (bool periodic_z : {false, true}) {
    const CoarseGrid thin =
        CoarseGrid::over(make_box({0, 0, 0}, {0.5, 0.375, 0.1}, true, false, periodic_z), 0.125);
    ASSERT_EQ(thin.n[2], 1);
    owner.assign(thin.count(), 0);
    for (int& o : owner) o = of3(rng);
    expect_ghost_ranks_match(Decomposition::from_owners(thin, owner, 3), 0.125, 24);
  }
  // 8 x 6 x 4 cells, periodic along y, random owners among 5 ranks.
  const CoarseGrid g =
      CoarseGrid::over(make_box({0, 0, 0}, {1, 0.75, 0.5}, false, true, false), 0.125);
  owner.assign(g.count(), 0);
  std::uniform_int_distribution<int> of5(0, 4);
  for (int& o : owner) o = of5(rng);
  expect_ghost_ranks_match(Decomposition::from_owners(g, owner, 5), 0.1, 22);
  // METIS parts of the same cells.
  const std::vector<double> work(g.count(), 3.0);
  expect_ghost_ranks_match(Decomposition::from_owners(g, metis_owners(g, work, 4), 4), 0.12, 23);
}

/// near_other of `rank`'s map, cell by cell: whether any cell at most kGhostReachCells away
/// along every axis (periodic wrap, nothing beyond a non-periodic face) belongs to another rank.
std::vector<std::uint8_t> brute_force_near_other(const Decomposition& d, int rank) {
  const CoarseGrid& g = d.cells();
  std::vector<std::uint8_t> near(g.count(), 0);
  for (std::size_t i = 0; i < g.count(); ++i) {
    const std::array<int, 3> c = g.coords(i);
    for (std::size_t j = 0; j < g.count(); ++j) {
      const std::array<int, 3> o = g.coords(j);
      bool within = true;
      for (int k = 0; k < 3; ++k) {
        int gap = std::abs(o[k] - c[k]);
        if (g.periodic[k]) gap = std::min(gap, g.n[k] - gap);
        within = within && gap <= kGhostReachCells;
      }
      if (within && d.owner_of_cell(j) != rank) near[i] = 1;
    }
  }
  return near;
}

TEST(CellOwnership, NearOtherMarksExactlyTheCellsWithinReachOfAnotherRank) {
  std::mt19937_64 rng(5);
  const CoarseGrid g =
      CoarseGrid::over(make_box({0, 0, 0}, {2, 0.75, 1}, true, false, false), 0.125);
  const Decomposition slabs = Decomposition::grid(g, {{{0, 5, 16}, {0, 6}, {0, 8}}});
  std::vector<int> owner(g.count());
  std::uniform_int_distribution<int> of3(0, 2);
  for (std::size_t i = 0; i < g.count(); ++i) owner[i] = g.coords(i)[0] < 8 ? 0 : of3(rng);
  const Decomposition patches = Decomposition::from_owners(g, owner, 3);
  for (const Decomposition* d : {&slabs, &patches})
    for (int rank = 0; rank < d->ranks(); ++rank) {
      const CellOwnership map = d->ownership(rank, 9);
      EXPECT_EQ(map.version, 9u);
      EXPECT_EQ(map.owner.size(), g.count());
      for (std::size_t i = 0; i < g.count(); ++i) EXPECT_EQ(map.owner[i], d->owner_of_cell(i));
      const std::vector<std::uint8_t> expected = brute_force_near_other(*d, rank);
      EXPECT_EQ(map.near_other, expected) << "rank " << rank;
      // The map spares the cells deep inside the rank's own part (48 of them in the slab).
      if (rank == 0) {
        EXPECT_GE(std::count(expected.begin(), expected.end(), std::uint8_t(0)), 48);
      }
    }
}

TEST(GhostRanks, PeriodicAxisWithTwoRanksAlongIt) {
  // x periodic over [0, 1), 8 cells, split at x = 0.5: a point near x = 0 of rank 0 is within
  // 0.1 of rank 1's cells across the periodic face only.
  const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.5, 0.5}, true), 0.125);
  const Decomposition d = Decomposition::grid(g, {{{0, 4, 8}, {0, 4}, {0, 4}}});
  EXPECT_EQ(ghost_ranks_of(d, {0.01, 0.25, 0.25}, 0, 0.1), std::vector<int>{1});
  EXPECT_EQ(ghost_ranks_of(d, {0.99, 0.25, 0.25}, 1, 0.1), std::vector<int>{0});
  EXPECT_EQ(ghost_ranks_of(d, {0.25, 0.25, 0.25}, 0, 0.1), std::vector<int>{});  // 0.25 away
  // Two cells along x, one per rank: the centre of cell 0 is 0.0625 from cell 1 on both sides,
  // and rank 1 is listed once.
  const CoarseGrid two = CoarseGrid::over(make_box({0, 0, 0}, {0.25, 0.5, 0.5}, true), 0.125);
  const Decomposition pair = Decomposition::grid(two, {{{0, 1, 2}, {0, 4}, {0, 4}}});
  EXPECT_EQ(ghost_ranks_of(pair, {0.0625, 0.25, 0.25}, 0, 0.125), std::vector<int>{1});
}

TEST(GhostRanks, PeriodicAxisWithOneRankAlongIt) {
  // x periodic, not cut; y cut at 0.25. Across the periodic x face lies rank 0 itself.
  const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.5, 0.5}, true), 0.125);
  const Decomposition d = Decomposition::grid(g, {{{0, 8}, {0, 2, 4}, {0, 4}}});
  EXPECT_EQ(ghost_ranks_of(d, {0.01, 0.1, 0.25}, 0, 0.1), std::vector<int>{});
  EXPECT_EQ(ghost_ranks_of(d, {0.01, 0.24, 0.25}, 0, 0.1), std::vector<int>{1});
  EXPECT_EQ(ghost_ranks_of(d, {0.99, 0.26, 0.25}, 1, 0.1), std::vector<int>{0});
}

TEST(GhostRanks, ReachBeyondTheCellEdgeIsRefused) {
  const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.5, 0.5}), 0.125);
  const Decomposition d = Decomposition::grid(g, {{{0, 4, 8}, {0, 4}, {0, 4}}});
  std::vector<int> out;
  EXPECT_THROW(d.ghost_ranks({0.5, 0.25, 0.25}, 0, 0.13, out), std::invalid_argument);
}

// --- Neighbour ranks ----------------------------------------------------------------------

TEST(NeighborRanks, SlabsBlocksAndPeriodicWrap) {
  const Cuts three_slabs{{{0, 2, 4, 6}, {0, 2}, {0, 2}}};
  const CoarseGrid open = CoarseGrid::over(make_box({0, 0, 0}, {0.75, 0.25, 0.25}), 0.125);
  const Decomposition slabs = Decomposition::grid(open, three_slabs);
  EXPECT_EQ(slabs.neighbor_ranks(0), (std::vector<int>{1}));
  EXPECT_EQ(slabs.neighbor_ranks(1), (std::vector<int>{0, 2}));
  EXPECT_EQ(slabs.neighbor_ranks(2), (std::vector<int>{1}));
  const CoarseGrid ring = CoarseGrid::over(make_box({0, 0, 0}, {0.75, 0.25, 0.25}, true), 0.125);
  const Decomposition ring_slabs = Decomposition::grid(ring, three_slabs);
  EXPECT_EQ(ring_slabs.neighbor_ranks(0), (std::vector<int>{1, 2}));
  EXPECT_EQ(ring_slabs.neighbor_ranks(2), (std::vector<int>{0, 1}));
  const CoarseGrid ring8 = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.25, 0.25}, true), 0.125);
  const Decomposition four = Decomposition::grid(ring8, {{{0, 2, 4, 6, 8}, {0, 2}, {0, 2}}});
  EXPECT_EQ(four.neighbor_ranks(0), (std::vector<int>{1, 3}));
  EXPECT_EQ(four.neighbor_ranks(2), (std::vector<int>{1, 3}));
  // 2 x 2 blocks: every block touches the other three (diagonal neighbours included).
  const CoarseGrid plate = CoarseGrid::over(make_box({0, 0, 0}, {1, 1, 0.25}), 0.125);
  const Decomposition blocks = Decomposition::grid(plate, {{{0, 4, 8}, {0, 4, 8}, {0, 2}}});
  for (int r = 0; r < 4; ++r) {
    std::vector<int> others;
    for (int o = 0; o < 4; ++o)
      if (o != r) others.push_back(o);
    EXPECT_EQ(blocks.neighbor_ranks(r), others) << "rank " << r;
  }
  // Two cells along a periodic axis, one per rank: the other is listed once.
  const CoarseGrid two = CoarseGrid::over(make_box({0, 0, 0}, {0.25, 0.25, 0.25}, true), 0.125);
  EXPECT_EQ(Decomposition::grid(two, {{{0, 1, 2}, {0, 2}, {0, 2}}}).neighbor_ranks(0),
            (std::vector<int>{1}));
}

// --- Regions ------------------------------------------------------------------------------

void expect_region(const BinRegion& r, Vec3 lo, Vec3 length, std::array<bool, 3> periodic) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(axis(r.lo, k), axis(lo, k), 1e-12) << "lo along "
                                                   << "xyz"[k];
    EXPECT_NEAR(axis(r.length, k), axis(length, k), 1e-12) << "length along "
                                                           << "xyz"[k];
    EXPECT_EQ(r.periodic[k], periodic[k]) << "periodic along "
                                          << "xyz"[k];
  }
}

TEST(Region, GridBlockGrownByGhostWidth) {
  // 8 x 6 x 2 cells of 0.125, x cut after 3 cells; ghost width 0.05.
  const CoarseGrid g = CoarseGrid::over(make_box({0, 0, 0}, {1, 0.75, 0.25}), 0.125);
  const Decomposition d = Decomposition::grid(g, {{{0, 3, 8}, {0, 6}, {0, 2}}});
  expect_region(d.region(0, 0.05, 0.1), {-0.05, -0.05, -0.05}, {0.475, 0.85, 0.35},
                {false, false, false});
  expect_region(d.region(1, 0.05, 0.1), {0.325, -0.05, -0.05}, {0.725, 0.85, 0.35},
                {false, false, false});
}

TEST(Region, PeriodicAxesAndWholeAxisPromotion) {
  // x and y periodic (L = 1 and 0.75). Along y every rank holds all cells: the whole axis.
  // Along x rank 0 spans 0.375 + 2 (0.05) = 0.475 and rank 1 0.625 + 0.1 = 0.725.
  const CoarseGrid g =
      CoarseGrid::over(make_box({0, 0, 0}, {1, 0.75, 0.25}, true, true, false), 0.125);
  const Decomposition d = Decomposition::grid(g, {{{0, 3, 8}, {0, 6}, {0, 2}}});
  expect_region(d.region(0, 0.05, 0.1), {-0.05, 0, -0.05}, {0.475, 0.75, 0.35},
                {false, true, false});
  expect_region(d.region(1, 0.05, 0.1), {0.325, 0, -0.05}, {0.725, 0.75, 0.35},
                {false, true, false});
  // Cutoff 0.3: 0.725 + 0.3 >= 1 makes rank 1's x the whole axis; 0.475 + 0.3 < 1 does not.
  expect_region(d.region(1, 0.05, 0.3), {0, 0, -0.05}, {1, 0.75, 0.35}, {true, true, false});
  expect_region(d.region(0, 0.05, 0.3), {-0.05, 0, -0.05}, {0.475, 0.75, 0.35},
                {false, true, false});
}

TEST(Region, CircularIntervalAndEmptyRank) {
  // x periodic, 8 cells of 0.125: rank 0 owns x-cells {7, 0, 1}, rank 1 {2..6}, rank 2 none.
  const PeriodicBox box = make_box({0, 0, 0}, {1, 0.125, 0.125}, true);
  const CoarseGrid g = CoarseGrid::over(box, 0.125);
  const Decomposition d = Decomposition::from_owners(g, {0, 0, 1, 1, 1, 1, 1, 0}, 3);
  // The shortest circular interval of rank 0 starts at cell 7: lo = 0.875 - 0.05.
  const BinRegion r0 = d.region(0, 0.05, 0.1);
  expect_region(r0, {0.825, -0.05, -0.05}, {0.475, 0.225, 0.225}, {false, false, false});
  expect_region(d.region(1, 0.05, 0.1), {0.2, -0.05, -0.05}, {0.725, 0.225, 0.225},
                {false, false, false});
  expect_region(d.region(2, 0.05, 0.1), {0, 0, 0}, {0, 0, 0}, {false, false, false});
  // Equally short intervals: rank 0's x-cells {0, 4} are covered by [0, 5) and by [4, 9); the
  // one starting at the lower cell is taken.
  const Decomposition split = Decomposition::from_owners(g, {0, 1, 1, 1, 0, 1, 1, 1}, 2);
  expect_region(split.region(0, 0.05, 0.1), {-0.05, -0.05, -0.05}, {0.725, 0.225, 0.225},
                {false, false, false});
  // Every point of rank 0's cells, seen through region_image, lies inside its region.
  for (double x = 0.0; x < 1.0; x += 0.01) {
    if (d.owner_of({x, 0.06, 0.06}) != 0) continue;
    const Real image = region_image(box, r0, 0, x);
    EXPECT_GE(image, r0.lo.x) << x;
    EXPECT_LE(image, r0.lo.x + r0.length.x) << x;
  }
}

// --- Grid dims ----------------------------------------------------------------------------

CoarseGrid cells_of_counts(int nx, int ny, int nz) {
  CoarseGrid g;
  g.length = {1, 1, 1};
  g.n[0] = nx;
  g.n[1] = ny;
  g.n[2] = nz;
  return g;
}

const Vec3 kDown{0, 0, -9.81};

TEST(ChooseGridDims, ShallowBedAtFourRanksTakesTheLeastAreaWithoutCuttingZ) {
  // Bed 1.0 x 0.7 x 0.3: a cut across x has area 0.7 * 0.3 = 0.21, across y 1.0 * 0.3 = 0.3,
  // across z 0.7. Without z cuts: 4x1x1 = 3 * 0.21 = 0.63, 1x4x1 = 0.9, 2x2x1 = 0.51.
  const std::array<int, 3> dims = choose_grid_dims(4, {0, 0, 0}, {1.0, 0.7, 0.3}, kDown,
                                                   cells_of_counts(20, 14, 6), {0, 0, 0}, "", 0);
  EXPECT_EQ(dims, (std::array<int, 3>{2, 2, 1}));
}

TEST(ChooseGridDims, ShallowBedIsNotCutAlongGravityEvenWhenThatCostsArea) {
  // One cell along x, 16 ranks: 1x8x2 would cut 7 * 0.3 + 0.7 = 2.8, but the shallow bed is not
  // cut along z, so 1x16x1 (15 * 0.3 = 4.5) is taken.
  EXPECT_EQ(choose_grid_dims(16, {0, 0, 0}, {1.0, 0.7, 0.3}, kDown, cells_of_counts(1, 16, 16),
                             {0, 0, 0}, "", 0),
            (std::array<int, 3>{1, 16, 1}));
  // 8 ranks on 2 x 2 x 4 cells: no grid without a z cut fits, so the least area is taken:
  // 2x2x2 = 0.21 + 0.3 + 0.7 = 1.21 against 1x2x4 = 0.3 + 2.1 and 2x1x4 = 0.21 + 2.1.
  EXPECT_EQ(choose_grid_dims(8, {0, 0, 0}, {1.0, 0.7, 0.3}, kDown, cells_of_counts(2, 2, 4),
                             {0, 0, 0}, "", 0),
            (std::array<int, 3>{2, 2, 2}));
}

TEST(ChooseGridDims, TallColumnIsCutAlongGravity) {
  // Column 0.2 x 0.2 x 1: 1x1x4 = 3 * 0.04 = 0.12 against 2x1x2 = 0.2 + 0.04, 2x2x1 = 0.4.
  EXPECT_EQ(choose_grid_dims(4, {0, 0, 0}, {0.2, 0.2, 1.0}, kDown, cells_of_counts(8, 8, 8),
                             {0, 0, 0}, "", 0),
            (std::array<int, 3>{1, 1, 4}));
}

TEST(ChooseGridDims, EqualAreasGoToFewerCutsAlongGravityThenXThenY) {
  // Unit cube, 2 ranks: every single cut has area 1.
  const CoarseGrid cells = cells_of_counts(4, 4, 4);
  EXPECT_EQ(choose_grid_dims(2, {0, 0, 0}, {1, 1, 1}, kDown, cells, {0, 0, 0}, "", 0),
            (std::array<int, 3>{1, 2, 1}));
  EXPECT_EQ(choose_grid_dims(2, {0, 0, 0}, {1, 1, 1}, {-9.81, 0, 0}, cells, {0, 0, 0}, "", 0),
            (std::array<int, 3>{1, 1, 2}));
  EXPECT_EQ(choose_grid_dims(2, {0, 0, 0}, {1, 1, 1}, {0, 0, 0}, cells, {0, 0, 0}, "", 0),
            (std::array<int, 3>{1, 1, 2}));
}

TEST(ChooseGridDims, GivenDimsAreCheckedAgainstRanksAndCells) {
  const CoarseGrid cells = cells_of_counts(2, 4, 4);
  EXPECT_EQ(choose_grid_dims(4, {0, 0, 0}, {1, 1, 1}, kDown, cells, {1, 1, 4}, "s.toml", 17),
            (std::array<int, 3>{1, 1, 4}));
  try {
    choose_grid_dims(4, {0, 0, 0}, {1, 1, 1}, kDown, cells, {2, 2, 2}, "s.toml", 17);
    ADD_FAILURE() << "dims 2 x 2 x 2 accepted for 4 ranks";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "s.toml");
    EXPECT_EQ(e.line(), 17);
    EXPECT_EQ(e.key(), "decomposition.dims");
    EXPECT_NE(std::string(e.what()).find("8 blocks, but the run has 4 ranks"), std::string::npos)
        << e.what();
  }
  try {
    choose_grid_dims(4, {0, 0, 0}, {1, 1, 1}, kDown, cells, {4, 1, 1}, "s.toml", 17);
    ADD_FAILURE() << "dims 4 x 1 x 1 accepted with 2 cells along x";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "decomposition.dims");
    EXPECT_NE(std::string(e.what()).find("do not fit the box's 2 x 4 x 4 coarse cells"),
              std::string::npos)
        << e.what();
  }
}

TEST(ChooseGridDims, TooFewCellsSaysHowManyRanksAtMost) {
  for (const auto& [ranks, cells, most] : {std::make_tuple(3, cells_of_counts(1, 1, 2), 2),
                                           std::make_tuple(7, cells_of_counts(4, 4, 4), 64)}) {
    try {
      choose_grid_dims(ranks, {0, 0, 0}, {1, 1, 1}, kDown, cells, {0, 0, 0}, "s.toml", 0);
      ADD_FAILURE() << ranks << " ranks accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "s.toml");
      EXPECT_NE(std::string(e.what()).find("at most " + std::to_string(most) + " ranks"),
                std::string::npos)
          << e.what();
    }
  }
}

// --- Balanced cuts ------------------------------------------------------------------------

TEST(BalancedCuts, HandComputedSplit) {
  // Marginal work along x: 5, 1, 1, ..., 1 (10 cells, total 14): 5 + 1 + 1 = 7 = the rest.
  const CoarseGrid g = cells_of_counts(10, 1, 1);
  std::vector<double> work(10, 1.0);
  work[0] = 5;
  const Cuts cuts = balanced_cuts(g, {2, 1, 1}, work);
  EXPECT_EQ(cuts[0], (std::vector<int>{0, 3, 10}));
  EXPECT_EQ(cuts[1], (std::vector<int>{0, 1}));
  EXPECT_EQ(cuts[2], (std::vector<int>{0, 1}));
}

TEST(BalancedCuts, LargestPartIsTheLeastPossible) {
  // Against every placement of 2 cuts in 9 cells, for random work.
  const CoarseGrid g = cells_of_counts(9, 1, 1);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(0, 10);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> work(9);
    for (double& w : work) w = u(rng);
    double best = std::numeric_limits<double>::infinity();
    for (int a = 1; a < 9; ++a)
      for (int b = a + 1; b < 9; ++b)
        best = std::min(best, largest(block_work(g, {{{0, a, b, 9}, {0, 1}, {0, 1}}}, work)));
    const Cuts cuts = balanced_cuts(g, {3, 1, 1}, work);
    ASSERT_TRUE(strictly_ascending(cuts[0]));
    const std::vector<double> parts = block_work(g, cuts, work);
    EXPECT_NEAR(largest(parts), best, 1e-12 * best);
  }
}

TEST(BalancedCuts, CornerHeavyWorkIsBalanced) {
  // w = exp(-x/5) exp(-y/5) on 16 x 16 x 4 cells, 2 x 2 blocks: the best split per axis is
  // 3 | 13 cells with max/mean 1.0593 each, 1.1221 for the blocks; halving the cells gives 2.77.
  const CoarseGrid g = cells_of_counts(16, 16, 4);
  const std::vector<double> work = corner_heavy_work(g, 5);
  const Cuts cuts = balanced_cuts(g, {2, 2, 1}, work);
  const double balanced = max_over_mean(block_work(g, cuts, work));
  const double halved = max_over_mean(block_work(g, {{{0, 8, 16}, {0, 8, 16}, {0, 4}}}, work));
  EXPECT_LT(balanced, 1.2);
  EXPECT_NEAR(balanced, 1.059277343371491 * 1.059277343371491, 1e-9);
  EXPECT_GT(halved, 2.5);
  // 4 x 4 blocks of w = exp(-x/10) exp(-y/10): best per axis 1.0635 (cuts 2, 5, 9).
  const std::vector<double> gentle = corner_heavy_work(g, 10);
  const Cuts cuts4 = balanced_cuts(g, {4, 4, 1}, gentle);
  EXPECT_EQ(cuts4[0], (std::vector<int>{0, 2, 5, 9, 16}));
  EXPECT_LT(max_over_mean(block_work(g, cuts4, gentle)), 1.2);
  EXPECT_EQ(Decomposition::grid(g, cuts4).rank_work(gentle), block_work(g, cuts4, gentle));
}

TEST(BalancedCuts, NoWorkSplitsIntoEqualCellCounts) {
  const CoarseGrid g = cells_of_counts(8, 8, 1);
  const Cuts cuts = balanced_cuts(g, {2, 4, 1}, std::vector<double>(g.count(), 0.0));
  EXPECT_EQ(cuts[0], (std::vector<int>{0, 4, 8}));
  EXPECT_EQ(cuts[1], (std::vector<int>{0, 2, 4, 6, 8}));
}

// --- Rebalanced cuts ----------------------------------------------------------------------

TEST(RebalanceCuts, HandComputedBoundedMoves) {
  // 12 cells, work 10 in cells 0..2 and 0.01 elsewhere (total 30.09); four blocks of 3 cells.
  // Cut i aims at the prefix nearest i/4 of the total: 7.52 -> boundary 1 (prefix 10), 15.05 ->
  // 2 (20), 22.57 -> 2. With moves of at most 2 cells: 3 -> 1, 6 -> 4, 9 -> 7; then 6 -> 4 -> 2
  // and 9 -> 7 -> 5; then 5 -> 3, and the cuts stay one cell apart from there on.
  const CoarseGrid g = cells_of_counts(12, 1, 1);
  std::vector<double> work(12, 0.01);
  work[0] = work[1] = work[2] = 10;
  Cuts cuts{{{0, 3, 6, 9, 12}, {0, 1}, {0, 1}}};
  const std::vector<std::vector<int>> expected = {
      {0, 1, 4, 7, 12}, {0, 1, 2, 5, 12}, {0, 1, 2, 3, 12}, {0, 1, 2, 3, 12}};
  for (const std::vector<int>& next : expected) {
    cuts = rebalance_cuts(g, cuts, work, 2);
    EXPECT_EQ(cuts[0], next);
    EXPECT_EQ(cuts[1], (std::vector<int>{0, 1}));
  }
}

TEST(RebalanceCuts, MovesAreBoundedAndBlocksKeepOneCell) {
  const CoarseGrid g = cells_of_counts(20, 10, 3);
  std::mt19937_64 rng(4);
  std::exponential_distribution<double> heavy_tail(0.2);
  for (int max_shift : {1, 3}) {
    Cuts cuts{{{0, 5, 10, 15, 20}, {0, 3, 6, 10}, {0, 3}}};
    for (int call = 0; call < 30; ++call) {
      std::vector<double> work(g.count());
      for (double& w : work) w = heavy_tail(rng) * heavy_tail(rng);
      const Cuts moved = rebalance_cuts(g, cuts, work, max_shift);
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(moved[k].size(), cuts[k].size());
        EXPECT_EQ(moved[k].front(), 0);
        EXPECT_EQ(moved[k].back(), g.n[k]);
        EXPECT_TRUE(strictly_ascending(moved[k]));
        for (std::size_t i = 0; i < cuts[k].size(); ++i)
          EXPECT_LE(std::abs(moved[k][i] - cuts[k][i]), max_shift);
      }
      cuts = moved;
    }
  }
}

TEST(RebalanceCuts, ConvergesOnCornerHeavyWork) {
  // From equal cell counts, one cell per call, to max/mean < 1.2 (the best split is 1.12).
  const CoarseGrid g = cells_of_counts(16, 16, 4);
  const std::vector<double> work = corner_heavy_work(g, 5);
  Cuts cuts{{{0, 8, 16}, {0, 8, 16}, {0, 4}}};
  for (int call = 0; call < 10; ++call) cuts = rebalance_cuts(g, cuts, work, 1);
  EXPECT_EQ(cuts[0], (std::vector<int>{0, 3, 16}));
  EXPECT_LT(max_over_mean(block_work(g, cuts, work)), 1.2);
}

TEST(RebalanceCuts, NoWorkKeepsTheCuts) {
  const CoarseGrid g = cells_of_counts(12, 1, 1);
  const Cuts cuts{{{0, 2, 9, 12}, {0, 1}, {0, 1}}};
  EXPECT_EQ(rebalance_cuts(g, cuts, std::vector<double>(12, 0.0), 3), cuts);
}

// --- METIS --------------------------------------------------------------------------------

void expect_good_parts(const CoarseGrid& g, int ranks) {
  const std::vector<double> work(g.count(), 10.0);
  const std::vector<int> owner = metis_owners(g, work, ranks);
  ASSERT_EQ(owner.size(), g.count());
  std::vector<double> cells_per_rank(static_cast<std::size_t>(ranks), 0.0);
  for (int r : owner) {
    ASSERT_GE(r, 0);
    ASSERT_LT(r, ranks);
    cells_per_rank[static_cast<std::size_t>(r)] += 1;
  }
  for (int r = 0; r < ranks; ++r) EXPECT_GT(cells_per_rank[static_cast<std::size_t>(r)], 0) << r;
  const double uniform = imbalance(Decomposition::from_owners(g, owner, ranks).rank_work(work));
  EXPECT_LT(uniform, 1.1);
  EXPECT_DOUBLE_EQ(uniform, max_over_mean(cells_per_rank));
  EXPECT_EQ(metis_owners(g, work, ranks), owner);  // deterministic
  std::cout << "METIS " << ranks << " parts of " << g.n[0] << " x " << g.n[1] << " x " << g.n[2]
            << " cells: max/mean = " << uniform << "\n";
}

TEST(MetisOwners, UniformWorkGivesBalancedDeterministicParts) {
  expect_good_parts(CoarseGrid::over(make_box({0, 0, 0}, {1, 1, 0.5}), 0.125), 4);
  expect_good_parts(CoarseGrid::over(make_box({0, 0, 0}, {1, 1, 0.5}, true, true, false), 0.125),
                    4);
  expect_good_parts(CoarseGrid::over(make_box({0, 0, 0}, {1, 0.75, 0.5}, true, true, true), 0.125),
                    7);
}

TEST(MetisOwners, OneRankAndTooManyRanks) {
  const CoarseGrid g = cells_of_counts(2, 2, 1);
  EXPECT_EQ(metis_owners(g, std::vector<double>(4, 5.0), 1), std::vector<int>(4, 0));
  EXPECT_THROW(metis_owners(g, std::vector<double>(4, 5.0), 5), std::invalid_argument);
}

TEST(MetisOwners, NeighbourRanksAreThoseOfAdjacentCells) {
  // Brute force: rank r's neighbours are the owners of cells within one cell of r's cells
  // (coordinate differences of at most 1, wrapped on the periodic axis).
  const CoarseGrid g =
      CoarseGrid::over(make_box({0, 0, 0}, {1, 1, 0.5}, true, false, false), 0.125);
  const int ranks = 5;
  const Decomposition d = Decomposition::from_owners(
      g, metis_owners(g, std::vector<double>(g.count(), 1), ranks), ranks);
  for (int r = 0; r < ranks; ++r) {
    std::vector<int> expected;
    for (std::size_t i = 0; i < g.count(); ++i) {
      if (d.owner_of_cell(i) != r) continue;
      for (std::size_t j = 0; j < g.count(); ++j) {
        const std::array<int, 3> a = g.coords(i), b = g.coords(j);
        bool adjacent = true;
        for (int k = 0; k < 3; ++k) {
          int diff = std::abs(a[k] - b[k]);
          if (g.periodic[k]) diff = std::min(diff, g.n[k] - diff);
          adjacent = adjacent && diff <= 1;
        }
        const int o = d.owner_of_cell(j);
        if (adjacent && o != r && std::find(expected.begin(), expected.end(), o) == expected.end())
          expected.push_back(o);
      }
    }
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(d.neighbor_ranks(r), expected) << "rank " << r;
    EXPECT_FALSE(expected.empty());
  }
}

}  // namespace
}  // namespace gpudem
