// Cell list and full neighbour list on the host backend, checked against an O(n^2) search with
// the same criterion, |minimum image of x_j - x_i| < r_i + r_j + skin. Neighbour sets must match
// exactly: both sides evaluate the same expression, and random coordinates land within an ulp of
// a cutoff with negligible probability. Rows built for a rank's owned particles (binned with
// their ghosts over the rank's region) are checked the same way, as sequences of global ids.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/BinRegion.hpp"
#include "engine/CellList.hpp"
#include "engine/NeighborList.hpp"
#include "engine/Permute.hpp"

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

/// The host search tests a run of slots `vector_doubles` at a time (eight where the CPU runs
/// AVX-512, four where it runs AVX2) and slot by slot elsewhere: both keep the same slots, in the
/// same order, on runs of every length up to 40, with the particle's own slot inside or outside
/// the run, and periodic axes whose nearest images decide (particles crowd both faces of a box a
/// few radii long); partners at exactly the cutoff are left out by both.
void expect_runs_in_vectors_keep_the_slots_one_by_one(int vector_doubles) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<Real> unit(0, 1);
  for (const bool periodic : {false, true}) {
    NeighborSearch search{};
    search.grids.box.length = make_vec3(0.03, 0.05, 0.04);
    for (int k = 0; k < 3; ++k) search.grids.box.periodic[k] = periodic && k != 1;
    search.grids.skin = 0.002;
    std::vector<Real4> p(600);
    for (Real4& q : p) {
      const auto near_a_face = [&](Real length) {
        const Real x = 0.2 * length * unit(rng);
        return unit(rng) < 0.5 ? x : length - x;
      };
      q = Real4{near_a_face(0.03), near_a_face(0.05), near_a_face(0.04), 0.003 + 0.004 * unit(rng)};
    }
    search.position_radius = p.data();
    std::size_t kept = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const auto self = static_cast<std::uint32_t>(rng() % 560);
      const std::uint32_t begin = self - std::min<std::uint32_t>(self, rng() % 30);
      const std::uint32_t end = begin + static_cast<std::uint32_t>(rng() % 41);  // often holds self
      std::vector<std::uint32_t> one_by_one, in_vectors;
      neighbor_list_kernels::RunAppender scalar{&search, {}, &one_by_one, 1};
      neighbor_list_kernels::RunAppender lanes{&search, {}, &in_vectors, vector_doubles};
      scalar(self, p[self], begin, end);
      lanes(self, p[self], begin, end);
      one_by_one.resize(scalar.used);
      in_vectors.resize(lanes.used);
      ASSERT_EQ(in_vectors, one_by_one) << "run [" << begin << ", " << end << "), self " << self;
      ASSERT_EQ(lanes.examined, scalar.examined);
      std::vector<std::uint32_t> expected;
      for (std::uint32_t j = begin; j < end; ++j)
        if (j != self && search.within(p[self], j)) expected.push_back(j);
      ASSERT_EQ(one_by_one, expected);
      kept += expected.size();
    }
    EXPECT_GT(kept, 2000u) << "too few neighbours to test";
  }
  // Partners at exactly the cutoff (dyadic numbers: no rounding anywhere) are not neighbours;
  // one just inside is.
  NeighborSearch ties{};
  ties.grids.box.length = make_vec3(1, 1, 1);
  ties.grids.skin = 1.0 / 64;
  const Real r = 1.0 / 128, cutoff = 1.0 / 32, c = 0.25;
  const std::vector<Real4> t = {{c, c, c, r},
                                {c + cutoff, c, c, r},
                                {c, c - cutoff, c, r},
                                {c, c, c + cutoff - 1.0 / 1024, r}};
  ties.position_radius = t.data();
  for (const int doubles : {1, vector_doubles}) {
    std::vector<std::uint32_t> kept;
    neighbor_list_kernels::RunAppender append{&ties, {}, &kept, doubles};
    append(0, t[0], 0, 4);
    kept.resize(append.used);
    EXPECT_EQ(kept, std::vector<std::uint32_t>{3}) << doubles << " slots at a time";
  }
}

TEST(NeighborSearch, RunsTestedInAvx512KeepTheSlotsTestedOneByOne) {
  if (!(GPUDEM_HOST_LANES && host_runs_x86_64_v4())) GTEST_SKIP() << "no AVX-512 on this CPU";
  expect_runs_in_vectors_keep_the_slots_one_by_one(8);
}

TEST(NeighborSearch, RunsTestedInAvx2KeepTheSlotsTestedOneByOne) {
  if (!(GPUDEM_HOST_LANES && host_runs_x86_64_v3())) GTEST_SKIP() << "no AVX2 on this CPU";
  expect_runs_in_vectors_keep_the_slots_one_by_one(4);
}

TEST(NeighborList, EmptySetGivesEmptyList) {
  PeriodicBox box;
  box.length = make_vec3(1, 1, 1);
  CellList<HostSpace> cells;
  NeighborList<HostSpace> list;
  cells.bin(static_cast<const Real4*>(nullptr), 0, box, 0.1);
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

// Rows for a rank's owned particles. A cloud is split between two ranks by x; each rank holds
// its owned particles, then ghost copies of every other particle within the ghost width
// 2 r_max + skin of its block (by minimum image on a periodic x), at their global coordinates, and
// bins a region: its block grown by the ghost width, or the whole x axis where that would not
// fit the periodic box. Rows, as global ids, are compared with the O(n^2) search over the cloud.

constexpr ParticleId kFirstId = ParticleId(1) << 40;  // ids beyond 32 bits

/// Global ids: kFirstId + a random permutation of 0 .. n - 1.
std::vector<ParticleId> shuffled_ids(std::size_t n, std::uint64_t seed) {
  std::vector<ParticleId> id(n);
  std::iota(id.begin(), id.end(), kFirstId);
  std::shuffle(id.begin(), id.end(), std::mt19937_64(seed));
  return id;
}

/// A rank's slab [lo, hi) along x.
struct Block {
  Real lo, hi;
};

/// Two halves of the box along x, shifted by `shift` box lengths (on a periodic x, a shifted
/// block straddles the periodic boundary).
std::vector<Block> two_blocks(const PeriodicBox& box, Real shift) {
  const Real lo = box.lo.x + shift * box.length.x, mid = lo + box.length.x / 2;
  return {{lo, mid}, {mid, lo + box.length.x}};
}

/// The image of x in [lo, lo + L) on a periodic x (up to rounding); x itself otherwise.
Real image_from(Real lo, const PeriodicBox& box, Real x) {
  const Real L = box.length.x;
  return box.periodic[0] ? x - L * std::floor((x - lo) / L) : x;
}

/// The block that owns x: block 0 below the cut at blocks[1].lo, block 1 from it on (on a
/// non-periodic x, particles up to skin / 2 outside the box belong to the end blocks).
std::size_t owner_of(const std::vector<Block>& blocks, const PeriodicBox& box, Real x) {
  if (!box.periodic[0]) return x < blocks[1].lo ? 0 : 1;
  const Real y = image_from(blocks[0].lo, box, x);
  return y >= blocks[0].lo && y < blocks[1].lo ? 0 : 1;
}

/// Distance along x from x to the block, by minimum image on a periodic x.
Real distance_to_block(const Block& b, const PeriodicBox& box, Real x) {
  const Real y = image_from(b.lo, box, x);
  const Real above = std::max(y - b.hi, Real(0)), below = std::max(b.lo - y, Real(0));
  return box.periodic[0] ? std::min(above, b.lo + box.length.x - y) : std::max(above, below);
}

/// The block grown by the ghost width along x, the whole box along y and z; the whole periodic
/// x axis when the grown block plus the ghost width (= 2 r_max + skin) exceeds the box length.
BinRegion region_of(const Block& b, const PeriodicBox& box, Real ghost_width) {
  BinRegion r = whole_box_region(box);
  const Real grown = b.hi - b.lo + 2 * ghost_width;
  if (box.periodic[0] && grown + ghost_width > box.length.x) return r;
  r.lo.x = b.lo - ghost_width;
  r.length.x = grown;
  r.periodic[0] = false;
  return r;
}

/// One rank's particles: owned first, ghosts after, each group in random storage order.
struct RankParticles {
  std::vector<Real4> position_radius;
  std::vector<ParticleId> id;
  std::size_t owned = 0;
};

RankParticles split(const std::vector<Real4>& cloud, const std::vector<ParticleId>& id,
                    const PeriodicBox& box, const std::vector<Block>& blocks,
                    std::size_t rank_index, Real ghost_width, std::uint64_t seed) {
  std::vector<std::size_t> owned, ghosts;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (owner_of(blocks, box, cloud[i].x) == rank_index)
      owned.push_back(i);
    else if (distance_to_block(blocks[rank_index], box, cloud[i].x) < ghost_width)
      ghosts.push_back(i);
  }
  std::mt19937_64 rng(seed);
  std::shuffle(owned.begin(), owned.end(), rng);
  std::shuffle(ghosts.begin(), ghosts.end(), rng);
  RankParticles rank;
  rank.owned = owned.size();
  owned.insert(owned.end(), ghosts.begin(), ghosts.end());
  for (std::size_t i : owned) {
    rank.position_radius.push_back(cloud[i]);
    rank.id.push_back(id[i]);
  }
  return rank;
}

/// Neighbour rows of owned particles as global ids, by the owned particle's id.
using IdRows = std::map<ParticleId, std::vector<ParticleId>>;

IdRows reference_rows(const std::vector<Real4>& cloud, const std::vector<ParticleId>& id,
                      const PeriodicBox& box, Real skin) {
  const Lists lists = brute_force(cloud, box, skin);
  IdRows rows;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    std::vector<ParticleId>& row = rows[id[i]];
    for (std::uint32_t j : lists[i]) row.push_back(id[j]);
    std::sort(row.begin(), row.end());
  }
  return rows;
}

/// The rows the list holds for the rank's owned particles.
struct RankRows {
  IdRows by_id;                   ///< rows as global ids, in list order
  std::size_t ghost_entries = 0;  ///< entries that are ghosts
};

/// bin over the region, permute, build rows for the owned particles; checks the CSR layout.
RankRows build_rows(const RankParticles& rank, const PeriodicBox& box, Real skin,
                    const BinRegion& region) {
  const std::size_t n = rank.position_radius.size();
  CellList<HostSpace> cells;
  cells.bin(rank.position_radius.data(), n, box, skin, region);
  std::vector<Real4> sorted(n);
  permute(HostSpace{}, cells.order(), rank.position_radius.data(), sorted.data(), n);
  std::vector<std::uint32_t> slot_of_index(n);
  for (std::uint32_t k = 0; k < n; ++k) slot_of_index[cells.order()[k]] = k;
  const NeighborRows rows{slot_of_index.data(), rank.owned, cells.order(), rank.id.data()};
  NeighborList<HostSpace> list;
  list.build(cells, sorted.data(), n, box, skin, &rows);
  EXPECT_EQ(list.size(), rank.owned);
  EXPECT_EQ(list.offsets()[0], 0u);
  EXPECT_EQ(list.offsets()[rank.owned], list.pairs_kept());
  RankRows result;
  for (std::size_t r = 0; r < rank.owned; ++r) {
    std::vector<ParticleId>& row = result.by_id[rank.id[r]];
    for (std::uint32_t e = list.offsets()[r]; e < list.offsets()[r + 1]; ++e) {
      const std::uint32_t index = list.neighbors()[e];
      row.push_back(rank.id.at(index));  // throws, failing the test, for an index >= n
      result.ghost_entries += index >= rank.owned ? 1 : 0;
    }
  }
  return result;
}

bool strictly_ascending(const std::vector<ParticleId>& row) {
  return std::adjacent_find(row.begin(), row.end(), std::greater_equal<ParticleId>()) == row.end();
}

struct RegionCase {
  SearchCase cloud;
  bool whole_axis;  ///< the region must be the whole periodic x axis
  Real shift;       ///< of the blocks, in box lengths
};

void PrintTo(const RegionCase& c, std::ostream* os) { *os << c.cloud.name; }

class RegionRows : public ::testing::TestWithParam<RegionCase> {};

/// Each owned particle's row holds exactly its brute-force neighbours over the whole cloud, as
/// global ids in strictly ascending order; every particle is owned by one rank; pairs across
/// the cut exist (ghost entries), so the ghost layer is exercised.
TEST_P(RegionRows, OwnedRowsEqualBruteForceOverTheCloud) {
  const RegionCase& c = GetParam();
  const PeriodicBox box = make_box(c.cloud);
  const std::vector<Real4> cloud = make_particles(c.cloud, box);
  const std::vector<ParticleId> id = shuffled_ids(cloud.size(), 777);
  const Sizes s = sizes_of(c.cloud.law);
  const Real ghost_width = 2 * s.r_max + s.skin;
  const IdRows reference = reference_rows(cloud, id, box, s.skin);
  const std::vector<Block> blocks = two_blocks(box, c.shift);
  std::size_t owned = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const Block& block = blocks[b];
    const BinRegion region = region_of(block, box, ghost_width);
    ASSERT_EQ(region.periodic[0], c.whole_axis);
    const RankParticles rank = split(cloud, id, box, blocks, b, ghost_width, 99 + b);
    const RankRows rows = build_rows(rank, box, s.skin, region);
    std::cout << c.cloud.name << " block [" << block.lo << ", " << block.hi << "): " << rank.owned
              << " owned, " << rank.id.size() - rank.owned << " ghosts, " << rows.ghost_entries
              << " ghost entries\n";
    EXPECT_GT(rows.ghost_entries, 0u);
    ASSERT_EQ(rows.by_id.size(), rank.owned);
    for (const auto& row : rows.by_id) {
      ASSERT_TRUE(strictly_ascending(row.second)) << "row of id " << row.first;
      ASSERT_EQ(row.second, reference.at(row.first)) << "neighbours of id " << row.first;
    }
    owned += rank.owned;
  }
  EXPECT_EQ(owned, cloud.size());
}

std::vector<RegionCase> region_cases() {
  const bool open[3] = {false, false, false}, x[3] = {true, false, false},
             all[3] = {true, true, true};
  std::vector<RegionCase> cases;
  const auto add = [&cases](std::string name, RadiusLaw law, const bool* periodic, Shape shape,
                            bool whole_axis, Real shift) {
    cases.push_back(
        {{name, law, {periodic[0], periodic[1], periodic[2]}, shape, 3000}, whole_axis, shift});
  };
  add("uniform_open", RadiusLaw::uniform, open, Shape::cube, false, 0);
  add("bimodal_open", RadiusLaw::bimodal, open, Shape::cube, false, 0);
  add("uniform_periodic_all", RadiusLaw::uniform, all, Shape::cube, false, 0);
  add("uniform_periodic_all_straddling", RadiusLaw::uniform, all, Shape::cube, false, 0.25);
  add("monodisperse_periodic_x", RadiusLaw::monodisperse, x, Shape::cube, false, 0);
  add("bimodal_periodic_x_small", RadiusLaw::bimodal, x, Shape::cube, true, 0.25);
  add("monodisperse_periodic_thin", RadiusLaw::monodisperse, all, Shape::thin_x, true, 0);
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Clouds, RegionRows, ::testing::ValuesIn(region_cases()),
                         [](const auto& info) { return info.param.cloud.name; });

/// Rows for every particle of one rank, ids a random permutation: each row strictly ascending in
/// id and equal to the brute-force neighbours.
TEST(NeighborRows, RowsAscendInGlobalId) {
  const SearchCase c{"uniform", RadiusLaw::uniform, {true, true, true}, Shape::cube, 3000};
  const PeriodicBox box = make_box(c);
  const std::vector<Real4> cloud = make_particles(c, box);
  const std::vector<ParticleId> id = shuffled_ids(cloud.size(), 2024);
  const Real skin = sizes_of(c.law).skin;
  RankParticles rank{cloud, id, cloud.size()};
  const RankRows rows = build_rows(rank, box, skin, whole_box_region(box));
  const IdRows reference = reference_rows(cloud, id, box, skin);
  ASSERT_EQ(rows.by_id.size(), cloud.size());
  std::size_t entries = 0;
  for (const auto& row : rows.by_id) {
    ASSERT_TRUE(strictly_ascending(row.second)) << "row of id " << row.first;
    ASSERT_EQ(row.second, reference.at(row.first)) << "neighbours of id " << row.first;
    entries += row.second.size();
  }
  EXPECT_GT(entries, cloud.size()) << "too sparse to test anything";
  EXPECT_EQ(rows.ghost_entries, 0u);
}

/// A rank's rows, as id sequences, do not depend on the storage order of its particles.
TEST(NeighborRows, RowsDoNotDependOnStorageOrder) {
  const SearchCase c{"bimodal", RadiusLaw::bimodal, {true, false, true}, Shape::cube, 3000};
  const PeriodicBox box = make_box(c);
  const std::vector<Real4> cloud = make_particles(c, box);
  const std::vector<ParticleId> id = shuffled_ids(cloud.size(), 5);
  const Sizes s = sizes_of(c.law);
  const Real ghost_width = 2 * s.r_max + s.skin;
  const std::vector<Block> blocks = two_blocks(box, 0);
  const BinRegion region = region_of(blocks[1], box, ghost_width);
  const RankParticles first = split(cloud, id, box, blocks, 1, ghost_width, 1);
  const RankParticles second = split(cloud, id, box, blocks, 1, ghost_width, 2);
  ASSERT_NE(first.id, second.id) << "the two storage orders must differ";
  const RankRows a = build_rows(first, box, s.skin, region),
                 b = build_rows(second, box, s.skin, region);
  EXPECT_GT(a.ghost_entries, 0u);
  EXPECT_EQ(a.by_id, b.by_id);
}

/// A region on a periodic axis: not periodic, its length plus 2 r_max + skin must not exceed
/// the box length; periodic, it must span the box length on an axis periodic in the box.
TEST(CellList, RejectsRegionsThatDoNotFitThePeriodicBox) {
  PeriodicBox box;
  box.length = make_vec3(1.0, 1.0, 1.0);
  box.periodic[0] = true;
  const Real skin = 0.01, radius = 0.02;  // 2 r_max + skin = 0.05 m
  const std::vector<Real4> p = {{0.5, 0.5, 0.5, radius}, {0.55, 0.5, 0.5, radius}};
  CellList<HostSpace> cells;
  BinRegion region = whole_box_region(box);
  region.periodic[0] = false;
  region.lo.x = 0.3;
  region.length.x = 0.949;  // 0.949 + 0.05 <= 1
  EXPECT_NO_THROW(cells.bin(p.data(), p.size(), box, skin, region));
  region.length.x = 0.951;  // 0.951 + 0.05 > 1
  EXPECT_THROW(cells.bin(p.data(), p.size(), box, skin, region), std::invalid_argument);
  region.periodic[0] = true;  // periodic, but shorter than the box
  EXPECT_THROW(cells.bin(p.data(), p.size(), box, skin, region), std::invalid_argument);
  region.length.x = 1.0;
  EXPECT_NO_THROW(cells.bin(p.data(), p.size(), box, skin, region));
  region.periodic[1] = true;  // periodic on an axis the box does not wrap
  EXPECT_THROW(cells.bin(p.data(), p.size(), box, skin, region), std::invalid_argument);
}

}  // namespace
}  // namespace gpudem
