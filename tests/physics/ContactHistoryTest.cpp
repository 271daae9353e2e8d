// Contact history survives neighbour rebuilds: the tangential springs of a loaded, resting
// pile are carried over by partner global id when particles are re-sorted and lists rebuilt.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/ParticleSources.hpp"
#include "core/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

class ContactHistory : public BackendTest {};

std::map<ParticleId, Vec3> forces_by_id(const StepEngine& engine) {
  ParticleStore p;
  engine.get_particles(p);
  std::map<ParticleId, Vec3> out;
  for (std::size_t i = 0; i < p.size(); ++i) out[p.id[i]] = p.force[i];
  return out;
}

TEST_P(ContactHistory, SpringsSurviveRebuild) {
  // A small frictional bed at rest: friction carries part of the contact loads.
  Scene scene = basic_scene({0, 0, 0}, {0.05, 0.05, 0.2}, 2000, 0.2, 0.8);
  scene.domain.periodic = {true, true, false};
  add_floor(scene);
  add_box_source(scene, {0, 0, 0}, {0.05, 0.05, 0.05}, 300, 2.5e-3, 0.5e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  for (int n = 0; n < 40000; ++n) engine->step();  // KE falls below 1e-7 of the potential

  const auto before = forces_by_id(*engine);
  double weight = 0;  // the largest particle weight: the load scale of the bed
  for (const Real4& v : particles.velocity_inv_mass)
    weight = std::max(weight, norm(scene.simulation.gravity) / v.w);
  const std::uint64_t rebuilds = engine->rebuild_count();
  engine->rebuild_neighbors();
  EXPECT_EQ(engine->rebuild_count(), rebuilds + 1);
  const auto after = forces_by_id(*engine);
  ASSERT_EQ(before.size(), after.size());
  double worst = 0;
  for (const auto& [id, f] : before) worst = std::max(worst, norm(after.at(id) - f));
  // Springs advance by v_t·dt in the re-evaluation and the bed is at rest, so the net forces
  // (zero at equilibrium) stay tiny; dropping the springs would unbalance contacts carrying a
  // good part of a weight.
  RecordProperty("force_change_over_weight", significant(worst / weight));
  EXPECT_LT(worst, 1e-4 * weight) << "largest weight " << weight;
}

GPUDEM_INSTANTIATE_BACKENDS(ContactHistory);

}  // namespace
}  // namespace gpudem::test
