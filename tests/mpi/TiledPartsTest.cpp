// Tiled insertion by ranks (comm/TiledParts.hpp) on however many ranks this runs (1, 2, 3 and 4
// through ctest): each rank's part, with its global ids, against the rows of the whole region
// placed on one rank; a region too full fails on every rank with the message one rank gives.
#include <gtest/gtest.h>
#include <mpi.h>

#include <string>
#include <vector>

#include "comm/TiledParts.hpp"
#include "core/InputError.hpp"
#include "core/ParticleSources.hpp"
#include "support/InputErrorText.hpp"
#include "support/InsertionChecks.hpp"
#include "support/MpiRank.hpp"

namespace gpudem {
namespace {

/// 60000 spheres of radius 0.5 ± 0.1 mm in 1.2 m × 2 cm × 2 cm (74 layers of tiles).
Scene long_bed() {
  Scene scene = test::insertion_scene(3);
  scene.sources.push_back(
      test::box({0, 0.3, 0.3}, {1.2, 0.32, 0.32}, 60000, test::uniform(0.5e-3, 0.1e-3)));
  scene.sources[0].placement = Placement::Tiled;
  return scene;
}

std::uint64_t sum_over_ranks(std::uint64_t n) {
  std::uint64_t sum = 0;
  MPI_Allreduce(&n, &sum, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return sum;
}

TEST(TiledParts, EachRankPlacesItsRowsOfTheWholeWithGlobalIds) {
  const Scene scene = long_bed();
  ParticleStore all;
  create_particles(scene, all);
  ParticleStore part;
  const std::size_t placed = append_tiled_part(MpiRankGroup(MPI_COMM_WORLD), scene, 0, part, 0);
  EXPECT_EQ(placed, part.size());
  EXPECT_EQ(sum_over_ranks(part.size()), all.size());
  std::size_t differ = 0;
  for (std::size_t n = 0; n < part.size(); ++n) {
    const std::uint64_t row = part.id[n];  // the whole region's ids are its rows
    ASSERT_LT(row, all.size());
    const Real4 p = part.position_radius[n], q = all.position_radius[row];
    const Real4 v = part.velocity_inv_mass[n], w = all.velocity_inv_mass[row];
    if (p.x != q.x || p.y != q.y || p.z != q.z || p.w != q.w || v.w != w.w ||
        (n > 0 && part.id[n] != part.id[n - 1] + 1))
      ++differ;
  }
  EXPECT_EQ(differ, 0u) << "on rank " << test::comm_rank();
}

TEST(TiledParts, ARegionTooFullFailsOnEveryRankAsOnOne) {
  Scene scene = long_bed();
  scene.sources[0].count = 1000000;
  const std::string alone = test::input_error_text([&] {
    ParticleStore all;
    create_particles(scene, all);
  });
  ASSERT_NE(alone.find("could only place"), std::string::npos) << alone;
  EXPECT_EQ(test::input_error_text([&] {
              ParticleStore part;
              append_tiled_part(MpiRankGroup(MPI_COMM_WORLD), scene, 0, part, 0);
            }),
            alone)
      << "on rank " << test::comm_rank();
}

TEST(TiledParts, ASourceThatIsNotATiledBoxIsALogicError) {
  Scene scene = long_bed();
  scene.sources[0].placement = Placement::Sequential;
  ParticleStore part;
  EXPECT_THROW(append_tiled_part(MpiRankGroup(MPI_COMM_WORLD), scene, 0, part, 0),
               std::logic_error);
}

}  // namespace
}  // namespace gpudem
