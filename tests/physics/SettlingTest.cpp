// A polydisperse bed of 10^4 spheres poured into a periodic box onto a floor comes to rest
// with a random packing fraction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/ParticleSources.hpp"
#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"
#include "support/SphereSlab.hpp"

namespace gpudem::test {
namespace {

class Settling : public BackendTest {};

TEST_P(Settling, BedComesToRestWithRandomPacking) {
  const double side = 0.12;
  Scene scene = basic_scene({0, 0, 0}, {side, side, 0.3}, 2000, 0.2, 0.5);
  scene.materials[0].young = 1e6;
  scene.domain.periodic = {true, true, false};
  add_floor(scene);
  add_box_source(scene, {0, 0, 0}, {side, side, 0.3}, 10000, 2.5e-3, 0.5e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  ASSERT_EQ(particles.size(), 10000u);

  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  const double initial_potential = engine->diagnostics().potential_gravity;
  double kinetic = 0;
  int blocks = 0;
  for (; blocks < 400; ++blocks) {  // at most 400 × 200 steps
    for (int n = 0; n < 200; ++n) engine->step();
    const Diagnostics d = engine->diagnostics();
    kinetic = d.kinetic_translational + d.kinetic_rotational;
    if (blocks > 20 && kinetic < 1e-6 * initial_potential) break;
  }
  RecordProperty("kinetic_over_initial_potential", significant(kinetic / initial_potential));
  RecordProperty("steps", significant(blocks * 200));
  EXPECT_LT(kinetic, 1e-6 * initial_potential)
      << "bed still moving after " << blocks * 200 << " steps";
  EXPECT_EQ(engine->removed_count(), 0u);
  HealthFailure failure;
  EXPECT_FALSE(engine->find_unhealthy(0.05, failure)) << "overlap ratio " << failure.overlap_ratio;

  // Packing fraction of a slab away from the floor and the free surface.
  engine->get_particles(particles);
  std::vector<double> heights;
  for (const Real4& p : particles.position_radius) heights.push_back(p.z);
  std::sort(heights.begin(), heights.end());
  const double diameter = 2 * scene.sources[0].radius.mean;
  const double top = heights[heights.size() * 99 / 100];
  const double lo = 4 * diameter, hi = top - 4 * diameter;
  ASSERT_GT(hi - lo, 5 * diameter);
  double solid = 0;
  for (const Real4& p : particles.position_radius) solid += sphere_volume_between(p.z, p.w, lo, hi);
  const double packing = solid / (side * side * (hi - lo));
  RecordProperty("packing_fraction", significant(packing));
  EXPECT_GE(packing, 0.55);
  EXPECT_LE(packing, 0.64);
}

GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Settling);

}  // namespace
}  // namespace gpudem::test
