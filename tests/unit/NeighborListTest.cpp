// Cell list and full neighbour list on the host backend, checked against an O(n^2) search with
// the same criterion, |minimum image of x_j - x_i| < r_i + r_j + skin. Neighbour sets must match
// exactly: both sides evaluate the same expression, and random coordinates land within an ulp of
// a cutoff with negligible probability.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/CellList.hpp"
#include "kernels/NeighborList.hpp"
#include "kernels/Permute.hpp"

namespace gpudem {
namespace {

constexpr Real kMm = 1e-3;
constexpr Real kPi = 3.14159265358979323846;
using Lists = std::vector<std::vector<std::uint32_t>>;

enum class RadiusLaw { monodisperse, uniform, bimodal };

/// Monodisperse: 5 mm. Uniform: 8.5 ± 1.5 mm. Bimodal: 1 mm and, for one particle in 150,
/// 10 mm (a 10:1 radius ratio with the large ones about 87% of the solid volume).
struct Sizes {
  RadiusLaw law;
  Real skin;
  Real r_max;
  Real mean_volume;  ///< [m^3] mean particle volume, sizes the box
};

Sizes sizes_of(RadiusLaw law) {
  const Real sphere = 4.0 / 3.0 * kPi;
  switch (law) {
    case RadiusLaw::monodisperse:
      return {law, 0.5 * kMm, 5 * kMm, sphere * std::pow(5 * kMm, 3)};
    case RadiusLaw::uniform:
      return {law, 1 * kMm, 10 * kMm, sphere * std::pow(8.5 * kMm, 3)};
    case RadiusLaw::bimodal:
      return {law, 0.2 * kMm, 10 * kMm,
              sphere * (std::pow(kMm, 3) * 149 + std::pow(10 * kMm, 3)) / 150};
  }
  return {};
}

Real radius_of(RadiusLaw law, std::size_t i, std::mt19937_64& rng) {
  switch (law) {
    case RadiusLaw::monodisperse:
      return 5 * kMm;
    case RadiusLaw::uniform:
      return std::uniform_real_distribution<Real>(7 * kMm, 10 * kMm)(rng);
    case RadiusLaw::bimodal:
      return i % 150 == 0 ? 10 * kMm : 1 * kMm;
  }
  return 0;
}

enum class Shape { cube, thin_x };

struct SearchCase {
  std::string name;
  RadiusLaw law;
  bool periodic[3];
  Shape shape;
  std::size_t n;
};

void PrintTo(const SearchCase& c, std::ostream* os) { *os << c.name; }

/// Box for a solid volume fraction of 0.4 (particles may overlap). A thin_x box is 0.1% longer
/// along x than the smallest periodic length allowed, 2 (2 r_max + skin).
PeriodicBox make_box(const SearchCase& c) {
  const Sizes s = sizes_of(c.law);
  const Real volume = c.n * s.mean_volume / 0.4;
  PeriodicBox box;
  box.lo = make_vec3(-0.05, 0.02, 1.0);
  if (c.shape == Shape::cube) {
    const Real side = std::cbrt(volume);
    box.length = make_vec3(side, side, side);
  } else {
    const Real thin = 1.001 * 2 * (2 * s.r_max + s.skin);
    const Real side = std::sqrt(volume / thin);
    box.length = make_vec3(thin, side, side);
  }
  for (int k = 0; k < 3; ++k) box.periodic[k] = c.periodic[k];
  return box;
}

/// Uniform positions: inside [lo, lo + L) on periodic axes, up to skin / 2 outside the box on
/// the others. The first eight particles sit on the box corners (extreme allowed positions).
std::vector<Real4> make_particles(const SearchCase& c, const PeriodicBox& box) {
  const Sizes s = sizes_of(c.law);
  std::mt19937_64 rng(12345);
  std::vector<Real4> p(c.n);
  for (std::size_t i = 0; i < c.n; ++i) {
    Real x[3];
    for (int k = 0; k < 3; ++k) {
      const Real lo = axis(box.lo, k), hi = lo + axis(box.length, k);
      const Real low = box.periodic[k] ? lo : lo - s.skin / 2;
      const Real high = box.periodic[k] ? std::nextafter(hi, lo) : hi + s.skin / 2;
      const bool corner = i < 8;
      x[k] = corner ? ((i >> k) & 1 ? high : low)
                    : std::uniform_real_distribution<Real>(low, high)(rng);
    }
    p[i] = {x[0], x[1], x[2], radius_of(c.law, i, rng)};
  }
  return p;
}

/// Every pair tested: the reference neighbour sets, ascending.
Lists brute_force(const std::vector<Real4>& p, const PeriodicBox& box, Real skin) {
  Lists lists(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < p.size(); ++j) {
      if (i == j) continue;
      Real d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const Real length = axis(box.length, k);
        Real d = axis(xyz(p[j]), k) - axis(xyz(p[i]), k);
        if (box.periodic[k]) d -= length * std::round(d / length);
        d2 += d * d;
      }
      const Real cutoff = p[i].w + p[j].w + skin;
      if (d2 < cutoff * cutoff) lists[i].push_back(static_cast<std::uint32_t>(j));
    }
  return lists;
}

/// The result of bin + permute + build, in cell-order slots.
struct Built {
  std::vector<std::uint32_t> order, offsets, neighbors;
  std::uint64_t candidates = 0, kept = 0;
};

Built build(CellList<HostSpace>& cells, NeighborList<HostSpace>& list, const std::vector<Real4>& p,
            const PeriodicBox& box, Real skin) {
  cells.bin(p.data(), p.size(), box, skin);
  std::vector<Real4> sorted(p.size());
  permute(HostSpace{}, cells.order(), p.data(), sorted.data(), p.size());
  list.build(cells, sorted.data(), sorted.size(), box, skin);
  Built b;
  b.order.assign(cells.order(), cells.order() + p.size());
  b.offsets.assign(list.offsets(), list.offsets() + p.size() + 1);
  b.neighbors.assign(list.neighbors(), list.neighbors() + list.pairs_kept());
  b.candidates = list.candidates_examined();
  b.kept = list.pairs_kept();
  return b;
}

/// CSR layout, ascending lists, symmetry, and the neighbour sets against the reference.
void expect_matches(const Built& b, const Lists& reference) {
  const std::size_t n = reference.size();
  ASSERT_EQ(b.offsets.size(), n + 1);
  ASSERT_EQ(b.offsets.front(), 0u);
  ASSERT_EQ(b.offsets.back(), b.kept);
  const auto list_of = [&b](std::size_t k) {
    return std::vector<std::uint32_t>(b.neighbors.begin() + b.offsets[k],
                                      b.neighbors.begin() + b.offsets[k + 1]);
  };
  std::size_t reference_entries = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::vector<std::uint32_t> slots = list_of(k);
    ASSERT_TRUE(std::adjacent_find(slots.begin(), slots.end(),
                                   std::greater_equal<std::uint32_t>()) == slots.end())
        << "list of slot " << k << " is not strictly ascending";
    std::vector<std::uint32_t> originals;
    for (std::uint32_t m : slots) {
      const std::vector<std::uint32_t> back = list_of(m);
      ASSERT_TRUE(std::binary_search(back.begin(), back.end(), std::uint32_t(k)))
          << "pair (" << k << ", " << m << ") is missing from the list of " << m;
      originals.push_back(b.order[m]);
    }
    std::sort(originals.begin(), originals.end());
    ASSERT_EQ(originals, reference[b.order[k]]) << "neighbours of particle " << b.order[k];
    reference_entries += reference[k].size();
  }
  EXPECT_EQ(b.kept, reference_entries);
  EXPECT_GE(b.candidates, b.kept);
}

class NeighborSearchCase : public ::testing::TestWithParam<SearchCase> {};

TEST_P(NeighborSearchCase, FullListEqualsBruteForce) {
  const SearchCase& c = GetParam();
  const PeriodicBox box = make_box(c);
  const std::vector<Real4> p = make_particles(c, box);
  const Real skin = sizes_of(c.law).skin;
  CellList<HostSpace> cells;
  NeighborList<HostSpace> list;
  const Built b = build(cells, list, p, box, skin);
  expect_matches(b, brute_force(p, box, skin));
  EXPECT_GT(b.kept, c.n) << "too sparse to test anything";
}

/// order() is a permutation; cell_begin() partitions the slots; each particle lies in its
/// cell's bounds (edge cells of non-periodic axes reach out to infinity) and in its class's
/// radius range; each grid's cell edge is at least 2 r_c + skin and tiles periodic lengths.
TEST_P(NeighborSearchCase, CellOrderGroupsParticlesByCell) {
  const SearchCase& c = GetParam();
  const PeriodicBox box = make_box(c);
  const std::vector<Real4> p = make_particles(c, box);
  const Real skin = sizes_of(c.law).skin;
  CellList<HostSpace> cells;
  cells.bin(p.data(), p.size(), box, skin);
  const SizeClassGrids& grids = cells.grids();

  std::vector<std::uint32_t> order(cells.order(), cells.order() + c.n);
  std::sort(order.begin(), order.end());
  for (std::size_t k = 0; k < c.n; ++k) ASSERT_EQ(order[k], k) << "order is no permutation";

  const std::uint32_t* begin = cells.cell_begin();
  ASSERT_EQ(begin[0], 0u);
  ASSERT_EQ(begin[grids.total_cells], c.n);
  const Real tolerance = 1e-12;  // [m] rounding of cell bounds
  for (int s = 0; s < grids.class_count; ++s) {
    const CellGrid& g = grids.grid[s];
    if (g.particles == 0) continue;  // an empty class has no cells in use
    const Real r_hi = grids.radius_top / std::pow(2.0, s);
    const Real r_lo = s + 1 == grids.class_count ? 0 : r_hi / 2;
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(g.side[k], 2 * g.radius_max + skin);
      if (box.periodic[k]) {
        EXPECT_NEAR(g.side[k] * g.cells[k], axis(box.length, k), tolerance);
      }
    }
    for (std::uint32_t cell = 0; cell < g.cell_count(); ++cell) {
      const int index[3] = {int(cell % g.cells[0]), int(cell / g.cells[0] % g.cells[1]),
                            int(cell / g.cells[0] / g.cells[1])};
      const std::uint32_t first = begin[g.first_cell + cell], last = begin[g.first_cell + cell + 1];
      ASSERT_LE(first, last);
      for (std::uint32_t slot = first; slot < last; ++slot) {
        const Real4& q = p[cells.order()[slot]];
        ASSERT_TRUE(q.w > r_lo && q.w <= r_hi) << "radius " << q.w << " outside class " << s;
        for (int k = 0; k < 3; ++k) {
          const bool open = !box.periodic[k];
          const Real lo = axis(box.lo, k) + index[k] * g.side[k];
          const Real lower = open && index[k] == 0 ? -INFINITY : lo - tolerance;
          const Real upper =
              open && index[k] + 1 == g.cells[k] ? INFINITY : lo + g.side[k] + tolerance;
          const Real x = axis(xyz(q), k);
          const Real image = open ? x : x - axis(box.length, k);  // a point at lo + L is at lo
          ASSERT_TRUE((x >= lower && x <= upper) || (image >= lower && image <= upper))
              << "particle " << cells.order()[slot] << " outside its cell along axis " << k;
        }
      }
    }
  }
}

std::vector<SearchCase> search_cases() {
  const bool open[3] = {false, false, false}, x[3] = {true, false, false},
             all[3] = {true, true, true};
  std::vector<SearchCase> cases;
  const auto add = [&cases](std::string name, RadiusLaw law, const bool* periodic, Shape shape,
                            std::size_t n) {
    cases.push_back({name, law, {periodic[0], periodic[1], periodic[2]}, shape, n});
  };
  add("monodisperse_open", RadiusLaw::monodisperse, open, Shape::cube, 3000);
  add("monodisperse_periodic_x", RadiusLaw::monodisperse, x, Shape::cube, 3000);
  add("monodisperse_periodic_thin", RadiusLaw::monodisperse, all, Shape::thin_x, 3000);
  add("uniform_open", RadiusLaw::uniform, open, Shape::cube, 3000);
  add("uniform_periodic_x", RadiusLaw::uniform, x, Shape::cube, 3000);
  add("uniform_periodic_all", RadiusLaw::uniform, all, Shape::cube, 3000);
  add("bimodal_open", RadiusLaw::bimodal, open, Shape::cube, 3000);
  add("bimodal_periodic_x", RadiusLaw::bimodal, x, Shape::cube, 3000);
  add("bimodal_periodic_thin", RadiusLaw::bimodal, all, Shape::thin_x, 3000);
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Sets, NeighborSearchCase, ::testing::ValuesIn(search_cases()),
                         [](const auto& info) { return info.param.name; });

/// The 10:1 mix: 2980 particles of 1 mm and 20 of 10 mm in a 62 mm cube, skin 0.2 mm (number
/// densities 0.0124 and 8.3e-5 per mm^3). With radius classes the small grid has 2.2 mm cells and
/// the large one 20.7 mm cells. A small particle scans 27 small cells (~3 candidates, ~0.6 kept)
/// and about 8 large cells (~5 candidates, ~0.4 kept); a large one scans a ~27 mm cube of small
/// cells (~200 candidates, fewer near the walls, for ~70 inside its 11.2 mm reach).
/// Estimate: ~6 candidates per kept pair; we require < 30. A single grid sized by r_max (20.7 mm
/// cells, 3 per axis) makes every small particle scan 8 to 27 of the 27 cells, i.e. hundreds of
/// candidates for ~1 kept: a ratio of several hundred, required to be > 10 times the classes'.
TEST(NeighborList, SizeClassesKeepCandidatesNearKeptPairs) {
  const SearchCase c{"bimodal", RadiusLaw::bimodal, {false, false, false}, Shape::cube, 3000};
  const PeriodicBox box = make_box(c);
  const std::vector<Real4> p = make_particles(c, box);
  const Real skin = sizes_of(c.law).skin;
  const Lists reference = brute_force(p, box, skin);

  CellList<HostSpace> classes;
  NeighborList<HostSpace> list;
  const Built by_class = build(classes, list, p, box, skin);
  expect_matches(by_class, reference);
  EXPECT_EQ(classes.grids().class_count, 4);  // ceil(log2(10)) classes of ratio 2

  CellList<HostSpace> single(1);
  const Built by_r_max = build(single, list, p, box, skin);
  expect_matches(by_r_max, reference);
  EXPECT_EQ(single.grids().class_count, 1);

  const double ratio = double(by_class.candidates) / by_class.kept;
  const double single_ratio = double(by_r_max.candidates) / by_r_max.kept;
  std::cout << "candidates / kept, 10:1 mix: size classes " << ratio << ", single grid "
            << single_ratio << "\n";
  EXPECT_LT(ratio, 30);
  EXPECT_GT(single_ratio, 10 * ratio);
}

/// One class for radius ratios below 2 (monodisperse and 8.5 ± 1.5 mm).
TEST(CellList, NarrowSizeRangeUsesOneGrid) {
  for (RadiusLaw law : {RadiusLaw::monodisperse, RadiusLaw::uniform}) {
    const SearchCase c{"narrow", law, {false, false, false}, Shape::cube, 500};
    const PeriodicBox box = make_box(c);
    const std::vector<Real4> p = make_particles(c, box);
    CellList<HostSpace> cells;
    cells.bin(p.data(), p.size(), box, sizes_of(law).skin);
    EXPECT_EQ(cells.grids().class_count, 1);
  }
}

/// Reusing the objects for a smaller set (as on every rebuild) gives that set's list.
TEST(NeighborList, RebuildWithFewerParticles) {
  const SearchCase c{"uniform", RadiusLaw::uniform, {true, false, true}, Shape::cube, 3000};
  const PeriodicBox box = make_box(c);
  std::vector<Real4> p = make_particles(c, box);
  const Real skin = sizes_of(c.law).skin;
  CellList<HostSpace> cells;
  NeighborList<HostSpace> list;
  build(cells, list, p, box, skin);
  p.resize(1000);
  expect_matches(build(cells, list, p, box, skin), brute_force(p, box, skin));
}

/// Any periodic image of a position gives the same list as the wrapped position.
TEST(NeighborList, AcceptsAnyPeriodicImage) {
  const SearchCase c{"uniform", RadiusLaw::uniform, {true, true, false}, Shape::cube, 2000};
  const PeriodicBox box = make_box(c);
  const std::vector<Real4> wrapped = make_particles(c, box);
  const Real skin = sizes_of(c.law).skin;
  std::vector<Real4> shifted = wrapped;
  for (std::size_t i = 0; i < shifted.size(); ++i) {
    const Real shift = Real(int(i % 3) - 1);  // -1, 0, +1 box lengths
    shifted[i].x += shift * box.length.x;
    shifted[i].y -= shift * box.length.y;
  }
  CellList<HostSpace> cells;
  NeighborList<HostSpace> list;
  expect_matches(build(cells, list, shifted, box, skin), brute_force(wrapped, box, skin));
}

TEST(NeighborList, EmptySetGivesEmptyList) {
  PeriodicBox box;
  box.length = make_vec3(1, 1, 1);
  CellList<HostSpace> cells;
  NeighborList<HostSpace> list;
  cells.bin(nullptr, 0, box, 0.1);
  list.build(cells, nullptr, 0, box, 0.1);
  EXPECT_EQ(list.offsets()[0], 0u);
  EXPECT_EQ(list.pairs_kept(), 0u);
}

TEST(CellList, RejectsBadSizes) {
  PeriodicBox box;
  box.length = make_vec3(0.1, 0.1, 0.1);
  box.periodic[1] = true;
  const Real skin = 1e-3;
  // Smallest periodic length 2 (2 r_max + skin): 0.0996 m for r_max = 0.0244 m, 0.1004 m for
  // r_max = 0.0246 m.
  std::vector<Real4> p = {{0.05, 0.05, 0.05, 0.0244}, {0.06, 0.05, 0.05, 0.001}};
  CellList<HostSpace> cells;
  EXPECT_NO_THROW(cells.bin(p.data(), p.size(), box, skin));
  p[0].w = 0.0246;
  EXPECT_THROW(cells.bin(p.data(), p.size(), box, skin), std::invalid_argument);
  p[0].w = 0;
  EXPECT_THROW(cells.bin(p.data(), p.size(), box, skin), std::invalid_argument);
  p[0].w = 0.01;
  EXPECT_THROW(cells.bin(p.data(), p.size(), box, -skin), std::invalid_argument);
  EXPECT_THROW(CellList<HostSpace>(0), std::invalid_argument);
  EXPECT_THROW(CellList<HostSpace>(kMaxSizeClasses + 1), std::invalid_argument);
}

}  // namespace
}  // namespace gpudem
