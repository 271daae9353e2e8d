// A new run's particles made by parts (comm/StartParts.hpp) on however many ranks this runs (1,
// 2, 3 and 4 through ctest): a bed, boxes placed by tiles along different axes and placed
// sequentially, and CSV files, each overlapping the earlier ones (also through a periodic
// face), made by parts and gathered by id against the particles one rank makes of the whole
// scene; an input problem in one rank's part of the bed fails on every rank with the message
// one rank gives.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "comm/MpiRankGroup.hpp"
#include "comm/StartParts.hpp"
#include "core/InputError.hpp"
#include "core/ParticleGather.hpp"
#include "core/ParticleSources.hpp"
#include "core/RowShare.hpp"
#include "support/InputErrorText.hpp"
#include "support/InsertionChecks.hpp"
#include "support/MpiRank.hpp"
#include "support/TestPaths.hpp"

namespace gpudem {
namespace {

using test::box;
using test::uniform;

/// A saved bed stand-in: 6000 spheres of 1 ± 0.3 mm in a slab 0.4 m long along x, with ids
/// 3 n + 7 (gaps, and a largest id that sets where the other sources' ids start).
ParticleStore bed_particles() {
  Scene scene = test::insertion_scene(21);
  scene.sources.push_back(box({0.3, 0.45, 0.45}, {0.7, 0.5, 0.48}, 6000, uniform(1e-3, 0.3e-3)));
  ParticleStore bed;
  create_particles(scene, bed);
  for (ParticleId& id : bed.id) id = 3 * id + 7;
  for (Vec3& w : bed.angular_velocity) w = {1, -2, 3};
  return bed;
}

ParticleSource bed_source() {
  ParticleSource s;
  s.kind = SourceKind::Bed;
  s.bed_file = "bed.h5";
  return s;
}

ParticleSource tiled(ParticleSource s) {
  s.placement = Placement::Tiled;
  return s;
}

/// After an optional bed: three stones from a CSV file (clear of the bed), a tiled box along x
/// over the bed's top and around the stones, a sequential box of steel crossing all of them,
/// and a tiled box along y crossing everything (each box's region overlaps the earlier
/// sources').
Scene layered_scene(bool with_bed) {
  Scene scene = test::insertion_scene(5);
  if (with_bed) scene.sources.push_back(bed_source());
  ParticleSource stones;
  stones.kind = SourceKind::Csv;
  stones.csv_file = test::source_dir() + "/tests/data/csv/stones.csv";
  scene.sources.push_back(stones);
  scene.sources.push_back(
      tiled(box({0.3, 0.45, 0.46}, {0.7, 0.5, 0.5}, 8000, uniform(1e-3, 0.3e-3))));
  ParticleSource steel = box({0.4, 0.44, 0.47}, {0.6, 0.52, 0.53}, 3000, uniform(1.2e-3, 0.2e-3));
  steel.material = 1;
  steel.velocity = {0, 0, -1};
  scene.sources.push_back(steel);
  scene.sources.push_back(
      tiled(box({0.48, 0.4, 0.44}, {0.52, 0.6, 0.52}, 6000, uniform(0.8e-3, 0.2e-3))));
  return scene;
}

/// This rank's part of `bed`'s rows, as a bed file read by parts gives it.
BedReader part_reader(const ParticleStore& bed) {
  return [&bed](const std::string&) { return share_of(bed, test::comm_rank(), test::comm_size()); };
}

BedReader whole_reader(const ParticleStore& bed) {
  return [&bed](const std::string&) { return bed; };
}

/// The rows of `p` in the order of their ids.
ParticleStore by_id(const ParticleStore& p) {
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
  ParticleStore sorted;
  for (std::size_t n : order) {
    sorted.add(p.id[n], xyz(p.position_radius[n]), p.position_radius[n].w, p.material[n],
               xyz(p.velocity_inv_mass[n]), p.velocity_inv_mass[n].w);
    sorted.angular_velocity.back() = p.angular_velocity[n];
  }
  return sorted;
}

bool same(Real4 a, Real4 b) { return a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w; }
bool same(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/// Rows of `a` and `b` (the same length) that differ in any value.
std::size_t rows_differing(const ParticleStore& a, const ParticleStore& b) {
  std::size_t differ = 0;
  for (std::size_t n = 0; n < a.size(); ++n)
    if (a.id[n] != b.id[n] || a.material[n] != b.material[n] ||
        !same(a.position_radius[n], b.position_radius[n]) ||
        !same(a.velocity_inv_mass[n], b.velocity_inv_mass[n]) ||
        !same(a.angular_velocity[n], b.angular_velocity[n]))
      ++differ;
  return differ;
}

/// The particles of `scene` made by parts and gathered, in id order, after checking that they
/// are those one rank makes (`count` of them).
ParticleStore parts_checked_against_whole(const Scene& scene, const ParticleStore& bed,
                                          std::size_t count) {
  ParticleStore whole;
  create_particles(scene, whole, whole_reader(bed));
  EXPECT_EQ(whole.size(), count);
  const ParticleStore part =
      create_start_part(MpiRankGroup(MPI_COMM_WORLD), scene, part_reader(bed));
  ParticleStore all = by_id(gather_particles(MpiRankGroup(MPI_COMM_WORLD), part));
  EXPECT_EQ(all.size(), whole.size());
  if (all.size() == whole.size()) {
    EXPECT_EQ(rows_differing(all, by_id(whole)), 0u) << "on " << test::comm_size() << " ranks";
  }
  return all;
}

TEST(StartParts, TheRanksPartsOfEverySourceAreTheParticlesOneRankMakes) {
  const ParticleStore bed = bed_particles();
  for (const bool with_bed : {true, false}) {
    SCOPED_TRACE(with_bed ? "after a bed" : "without a bed");
    const ParticleStore all = parts_checked_against_whole(
        layered_scene(with_bed), bed, (with_bed ? 6000u : 0u) + 3 + 8000 + 3000 + 6000);
    test::expect_no_overlaps(all);
  }
}

/// A bin 0.2 m long along x and periodic along it: two stones from a CSV file across the faces
/// x = 0 and x = 0.2 (the second in the last rank's share of the rows), then a box filled by six
/// layers of tiles along x and a box at x = 0.15–0.2 placed sequentially, both of which must
/// avoid the stones' images across the opposite face.
Scene periodic_bin() {
  Scene scene = test::insertion_scene(8);
  scene.domain.max = {0.2, 0.05, 0.05};
  scene.domain.periodic = {true, false, false};
  ParticleSource stones;
  stones.kind = SourceKind::Csv;
  stones.csv_file = test::source_dir() + "/tests/data/csv/periodic_stones.csv";
  scene.sources.push_back(stones);
  scene.sources.push_back(tiled(box({0, 0, 0}, {0.2, 0.05, 0.05}, 10000, uniform(0.8e-3, 0.2e-3))));
  scene.sources.push_back(box({0.15, 0, 0}, {0.2, 0.05, 0.05}, 1000, uniform(1e-3, 0.2e-3)));
  return scene;
}

TEST(StartParts, EveryRankAvoidsTheImagesOfSpheresAcrossAPeriodicFace) {
  ParticleStore all = parts_checked_against_whole(periodic_bin(), {}, 2 + 10000 + 1000);
  all.add(20000, {0.203, 0.025, 0.02}, 0.005, 0, {}, 1.0);  // the stones' images, by hand
  all.add(20001, {-0.002, 0.025, 0.03}, 0.006, 0, {}, 1.0);
  test::expect_no_overlaps(all);
}

TEST(StartParts, AProblemInOneRanksPartOfTheBedFailsOnEveryRankAsOnOne) {
  ParticleStore bed = bed_particles();
  bed.material.back() = 5;  // in the last rank's part
  const Scene scene = layered_scene(true);
  const std::string alone = test::input_error_text([&] {
    ParticleStore whole;
    create_particles(scene, whole, whole_reader(bed));
  });
  ASSERT_NE(alone.find("material index 5"), std::string::npos) << alone;
  EXPECT_EQ(test::input_error_text(
                [&] { create_start_part(MpiRankGroup(MPI_COMM_WORLD), scene, part_reader(bed)); }),
            alone)
      << "on rank " << test::comm_rank();
}

TEST(StartParts, ABadCsvRowInOneRanksPartFailsOnEveryRankAsOnOne) {
  for (const char* name : {"not_a_number.csv", "field_count.csv", "radius_zero.csv",
                           "unknown_material.csv", "outside_domain.csv"}) {
    SCOPED_TRACE(name);
    Scene scene = test::insertion_scene();
    ParticleSource rows;
    rows.kind = SourceKind::Csv;
    rows.csv_file = test::source_dir() + "/tests/data/csv/" + name;  // the second row is bad
    scene.sources.push_back(rows);
    const std::string alone = test::input_error_text([&] {
      ParticleStore whole;
      create_particles(scene, whole);
    });
    ASSERT_FALSE(alone.empty());
    EXPECT_EQ(
        test::input_error_text([&] { create_start_part(MpiRankGroup(MPI_COMM_WORLD), scene, {}); }),
        alone)
        << "on rank " << test::comm_rank();
  }
}

}  // namespace
}  // namespace gpudem
