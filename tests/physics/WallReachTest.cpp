// The plane walls in each particle's reach (engine/WallReach.hpp): which walls a build puts in
// reach and which history it blanks, and a grain bouncing in a box of walls at nearly half the
// skin per step, which must meet every wall at the first step it overlaps it.
#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <vector>

#include "engine/SceneSetup.hpp"
#include "engine/WallReach.hpp"
#include "support/Backends.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

PlaneWall floor_at(Real height) {
  PlaneWall w;
  w.point = {0, 0, height};
  w.normal = {0, 0, 1};
  return w;
}

/// Bits of the walls a particle of radius 0.01 m at height z reaches over the floors at the
/// given heights, skin 0.002 m; the walls listed in `pistons` always.
std::uint32_t reach_at(Real z, const std::vector<Real>& floors, WallReachBits pistons = {}) {
  std::vector<PlaneWall> walls;
  for (const Real h : floors) walls.push_back(floor_at(h));
  const std::vector<Real4> x{{0, 0, z, 0.01}};
  std::uint32_t reach = 0;
  FindWallReach<Real>{x.data(), walls.data(), static_cast<std::uint32_t>(walls.size()),
                      pistons,  0.002,        &reach}(0);
  return reach;
}

TEST(WallReach, AWallIsInReachWithinRadiusPlusSkinOfTheCentre) {
  EXPECT_EQ(reach_at(0.0119, {0}), 1u);
  EXPECT_EQ(reach_at(0.0121, {0}), 0u);
  EXPECT_EQ(reach_at(0.0121, {0, 0.001}), 2u);
  EXPECT_EQ(reach_at(0.005, {0, -1}), 1u);  // overlapping the first, far above the second
}

TEST(WallReach, APistonIsAlwaysInReach) {
  WallReachBits pistons;
  pistons.add(1);
  EXPECT_EQ(reach_at(0.5, {0, -1}, pistons), 2u);
}

TEST(WallReach, BeyondThirtyTwoWallsABitStandsForEveryWallOfItsResidue) {
  std::vector<Real> floors(34, -1);
  floors[33] = 0;  // only wall 33 is near
  WallReachBits found{reach_at(0.0119, floors)};
  EXPECT_EQ(found.bits, 2u);
  EXPECT_TRUE(found.holds(1));
  EXPECT_TRUE(found.holds(33));
  EXPECT_FALSE(found.holds(32));
}

TEST(WallReach, TheHistoryOfTheWallsOutOfReachIsBlanked) {
  const std::uint32_t walls = 3, width = 2;
  const std::vector<std::uint32_t> reach{0b101, 0b010};
  std::vector<Real> history(2 * walls * width, 7.0);
  const BlankWallsOutOfReach<Real> blank{reach.data(), walls, width, history.data()};
  blank(0);
  blank(1);
  const std::vector<Real> expected{7, 7, 0, 0, 7, 7, 0, 0, 7, 7, 0, 0};
  EXPECT_EQ(history, expected);
}

class WallReachInABox : public BackendTest {};

constexpr double kRadius = 0.01;  // [m]
constexpr double kSkin = 2e-4;    // [m]
constexpr double kDt = 1e-5;      // [s]

/// Overlap of the grain at x with each face of the box [−0.05, 0.05]³ [m].
std::vector<double> face_overlaps(Vec3 x) {
  std::vector<double> overlap;
  for (int k = 0; k < 3; ++k) {
    overlap.push_back(kRadius - (axis(x, k) + 0.05));
    overlap.push_back(kRadius - (0.05 - axis(x, k)));
  }
  return overlap;
}

/// No gravity, no damping and no friction: the grain's velocity changes at a step exactly when
/// it overlaps a wall at the step's end (the closing half kick) or at the step before (the
/// opening half kick). It moves 0.45 skin per step, so a build that left a wall it can reach
/// out of its reach would let it run into that wall unfelt.
TEST_P(WallReachInABox, AGrainMeetsEachWallAtTheFirstStepItOverlapsIt) {
  Scene scene = basic_scene({-0.05, -0.05, -0.05}, {0.05, 0.05, 0.05}, 1e7, 1, 0);
  add_box_walls(scene);
  scene.simulation.gravity = {0, 0, 0};
  scene.simulation.dt_auto = false;
  scene.simulation.dt = kDt;
  scene.neighbor.skin = kSkin;
  ParticleStore grain;
  const Vec3 direction{0.8, -0.5, 0.33};
  const double speed = 0.45 * kSkin / kDt;  // [m/s]
  grain.add(0, {0.001, -0.002, 0.003}, kRadius, 0, direction * (speed / norm(direction)),
            1 / (2500 * 4.18879 * kRadius * kRadius * kRadius));
  auto engine = make_engine(make_engine_setup(scene, grain));
  engine->set_particles(grain);
  ParticleStore state;
  engine->get_particles(state);
  std::set<int> walls_met;
  bool touched_before = false;
  for (int step = 1; step <= 6000; ++step) {
    const Vec3 before = xyz(state.velocity_inv_mass[0]);
    engine->step();
    engine->get_particles(state);
    const std::vector<double> overlap = face_overlaps(xyz(state.position_radius[0]));
    bool touching = false;
    for (int w = 0; w < 6; ++w) {
      if (overlap[w] <= 0) continue;
      touching = true;
      walls_met.insert(w);
    }
    const Vec3 after = xyz(state.velocity_inv_mass[0]);
    const bool pushed = after.x != before.x || after.y != before.y || after.z != before.z;
    ASSERT_EQ(pushed, touching || touched_before) << "step " << step;
    touched_before = touching;
  }
  EXPECT_EQ(walls_met.size(), 6u);
}

GPUDEM_INSTANTIATE_BACKENDS(WallReachInABox);

}  // namespace
}  // namespace gpudem::test
