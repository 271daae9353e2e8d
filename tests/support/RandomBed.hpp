#pragma once
// Random overlapping beds and per-particle load comparisons, for tests that run one scene on
// two engines (backends or precisions) and compare what they compute.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "core/ParticleSources.hpp"
#include "core/Scene.hpp"
#include "engine/StepEngine.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {

/// Hertz–Mindlin with restitution damping and constant-torque rolling resistance in a walled
/// box of `count` spheres of radius mean ± 30 %.
inline Scene hertz_mindlin_box(Vec3 hi, std::uint64_t count, double mean_radius) {
  Scene scene = basic_scene({0, 0, 0}, hi, 0, 0.5, 0.5);
  scene.materials[0].young = 5e6;
  scene.materials[0].rolling_friction = 0.1;
  scene.contact.model = {NormalLaw::Hertz, DampingLaw::Restitution, TangentialLaw::Mindlin,
                         RollingLaw::ConstantTorque, CohesionLaw::None};
  scene.simulation.gravity = {0, 0, -9.81};
  add_box_walls(scene);
  add_box_source(scene, {0, 0, 0}, hi, count, mean_radius, 0.3 * mean_radius);
  return scene;
}

/// The particles of `scene` at random positions, grown by 30 % in place so that many pairs
/// overlap, and spinning (for the rolling slot).
inline ParticleStore overlapping_bed(const Scene& scene) {
  ParticleStore particles;
  create_particles(scene, particles);  // random positions, not touching
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles.position_radius[i].w *= 1.3;
    const double s = double(i % 97) / 97.0 - 0.5;
    particles.angular_velocity[i] = {10 * s, -7 * s, 3 * s};
  }
  return particles;
}

/// Largest |a − b| over the particles of two stores (matched by id), over the largest |a|.
inline double relative_spread(const ParticleStore& a, const ParticleStore& b,
                              std::vector<Vec3> ParticleStore::*field) {
  std::map<ParticleId, std::size_t> in_b;
  for (std::size_t i = 0; i < b.size(); ++i) in_b[b.id[i]] = i;
  double largest = 0, worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec3 x = (a.*field)[i], y = (b.*field)[in_b.at(a.id[i])];
    largest = std::max(largest, norm(x));
    worst = std::max(worst, norm(x - y));
  }
  return largest > 0 ? worst / largest : worst;
}

/// Largest force and torque differences of two engines over the particles they both hold.
struct LoadSpread {
  double force = 0;   ///< relative_spread of the forces
  double torque = 0;  ///< relative_spread of the torques
};

/// The load spread of engines a and b (a's loads the reference), recorded as the test
/// properties force_spread_<when> and torque_spread_<when>.
inline LoadSpread recorded_load_spread(const StepEngine& a, const StepEngine& b,
                                       const std::string& when) {
  ParticleStore pa, pb;
  a.get_particles(pa);
  b.get_particles(pb);
  EXPECT_EQ(pa.size(), pb.size());
  const LoadSpread spread{relative_spread(pa, pb, &ParticleStore::force),
                          relative_spread(pa, pb, &ParticleStore::torque)};
  ::testing::Test::RecordProperty("force_spread_" + when, significant(spread.force));
  ::testing::Test::RecordProperty("torque_spread_" + when, significant(spread.torque));
  return spread;
}

/// Steps engines a and b, holding the same falling bed, `steps` times and checks that they end
/// in the same state in the mean (the flow is chaotic, so particles are not compared one by
/// one): potential and kinetic energy within 1 % of the energy the bed released falling,
/// contact count within 5 %, the same particles removed. Records the potential difference and
/// each engine's contacts (contacts_<a_name>, contacts_<b_name>). Returns a's diagnostics.
inline Diagnostics expect_same_in_the_mean(StepEngine& a, StepEngine& b, int steps,
                                           const std::string& a_name, const std::string& b_name) {
  const double start = a.diagnostics().potential_gravity;
  for (int n = 0; n < steps; ++n) {
    a.step();
    b.step();
  }
  const Diagnostics da = a.diagnostics(), db = b.diagnostics();
  const double fall = start - da.potential_gravity;
  ::testing::Test::RecordProperty(
      "potential_difference_over_fall",
      significant(std::abs(da.potential_gravity - db.potential_gravity) / fall));
  ::testing::Test::RecordProperty("contacts_" + a_name, significant(double(da.contact_count)));
  ::testing::Test::RecordProperty("contacts_" + b_name, significant(double(db.contact_count)));
  EXPECT_GT(fall, 0);
  EXPECT_LT(std::abs(da.potential_gravity - db.potential_gravity), 0.01 * fall);
  EXPECT_NEAR(double(db.contact_count), double(da.contact_count), 0.05 * da.contact_count);
  const double kinetic_a = da.kinetic_translational + da.kinetic_rotational;
  const double kinetic_b = db.kinetic_translational + db.kinetic_rotational;
  EXPECT_LT(std::abs(kinetic_a - kinetic_b), 0.01 * fall);
  EXPECT_EQ(a.removed_count(), b.removed_count());
  return da;
}

}  // namespace gpudem::test
