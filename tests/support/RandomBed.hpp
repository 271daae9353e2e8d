#pragma once
// Random overlapping beds and per-particle load comparisons, for tests that run one scene on
// two engines (backends or precisions) and compare what they compute.
#include <algorithm>
#include <map>
#include <vector>

#include "core/ParticleSources.hpp"
#include "core/Scene.hpp"
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

}  // namespace gpudem::test
