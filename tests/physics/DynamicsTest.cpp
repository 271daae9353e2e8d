// Point-particle dynamics against closed forms, and energy conservation of an elastic gas.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/ParticleSources.hpp"
#include "core/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

class Dynamics : public BackendTest {};

ParticleStore single_particle(const Scene& scene, Vec3 x, Vec3 v, double r) {
  ParticleStore p;
  p.add(0, x, r, 0, v, 1.0 / sphere_mass(scene.materials[0].density, r));
  return p;
}

/// Velocity Verlet is exact for constant acceleration: x = x0 + v0 t + ½ g t².
TEST_P(Dynamics, FreeFallVelocityVerletIsExact) {
  Scene scene = basic_scene({-10, -10, -10}, {10, 10, 10}, 1e4, 0.5, 0.5);
  scene.simulation.dt_auto = false;
  scene.simulation.dt = 1e-4;
  const Vec3 x0{0.1, -0.2, 1.0}, v0{0.3, 0.0, 2.0};
  ParticleStore particles = single_particle(scene, x0, v0, 0.01);
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  const int steps = 2000;
  for (int n = 0; n < steps; ++n) engine->step();
  engine->get_particles(particles);
  const double t = steps * 1e-4;
  const Vec3 g = scene.simulation.gravity;
  const Vec3 expected = x0 + t * v0 + (0.5 * t * t) * g;
  const Vec3 x = xyz(particles.position_radius[0]);
  EXPECT_NEAR(x.x, expected.x, 1e-12);
  EXPECT_NEAR(x.y, expected.y, 1e-12);
  EXPECT_NEAR(x.z, expected.z, 1e-11);
  EXPECT_NEAR(particles.velocity_inv_mass[0].z, v0.z + g.z * t, 1e-11);
}

/// Symplectic Euler: v_n = v0 + n·dt·g, x_n = x0 + n·dt·v0 + g·dt²·n(n+1)/2.
TEST_P(Dynamics, FreeFallSymplecticEulerMatchesItsRecurrence) {
  Scene scene = basic_scene({-10, -10, -10}, {10, 10, 10}, 1e4, 0.5, 0.5);
  scene.simulation.dt_auto = false;
  scene.simulation.dt = 1e-4;
  scene.simulation.integrator = IntegratorKind::SymplecticEuler;
  const Vec3 x0{0, 0, 1}, v0{0, 0, 2};
  ParticleStore particles = single_particle(scene, x0, v0, 0.01);
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  const int n = 2000;
  for (int s = 0; s < n; ++s) engine->step();
  engine->get_particles(particles);
  const double dt = 1e-4, g = scene.simulation.gravity.z;
  EXPECT_NEAR(particles.position_radius[0].z, 1 + n * dt * 2 + g * dt * dt * n * (n + 1) / 2.0,
              1e-11);
  EXPECT_NEAR(particles.velocity_inv_mass[0].z, 2 + n * dt * g, 1e-11);
}

/// A damped sphere comes to rest on a floor with overlap δ = m g / k, and the floor carries m g.
TEST_P(Dynamics, SphereRestsOnPlaneWithStaticOverlap) {
  Scene scene = basic_scene({-1, -1, 0}, {1, 1, 1}, 1e4, 0.3, 0.5);
  WallSettings floor;
  floor.name = "floor";
  floor.normal = {0, 0, 1};
  scene.walls.push_back(floor);
  const double r = 0.01;
  ParticleStore particles = single_particle(scene, {0, 0, r}, {0, 0, 0}, r);
  const double m = 1.0 / particles.velocity_inv_mass[0].w;
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  for (int n = 0; n < 20000; ++n) engine->step();
  engine->get_particles(particles);
  const double weight = -m * scene.simulation.gravity.z;
  const double overlap = r - particles.position_radius[0].z;
  EXPECT_NEAR(overlap, weight / 1e4, 1e-6 * weight / 1e4);
  EXPECT_LT(std::fabs(particles.velocity_inv_mass[0].z), 1e-9);
  const Diagnostics d = engine->diagnostics();
  ASSERT_EQ(d.wall_force.size(), 1u);
  EXPECT_NEAR(d.wall_force[0].z, -weight, 1e-6 * weight);
  EXPECT_EQ(d.contact_count, 1u);
}

/// An elastic (e = 1), frictionless gas in a walled box conserves kinetic + elastic energy.
TEST_P(Dynamics, ElasticGasConservesEnergy) {
  Scene scene = basic_scene({0, 0, 0}, {0.1, 0.1, 0.1}, 1e4, 1.0, 0.0);
  scene.simulation.gravity = {0, 0, 0};
  scene.simulation.dt_fraction = 0.05;  // energy error of velocity Verlet scales with dt²
  scene.contact.tangential = "none";
  add_box_walls(scene);
  ParticleSource source;
  source.region_min = scene.domain.min;
  source.region_max = scene.domain.max;
  source.count = 300;
  source.radius.mean = 4e-3;
  source.radius.spread = 1e-3;
  scene.sources.push_back(source);
  ParticleStore particles;
  create_particles(scene, particles);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> speed(0.0, 0.5);
  for (Real4& v : particles.velocity_inv_mass) {
    v.x = speed(rng);
    v.y = speed(rng);
    v.z = speed(rng);
  }
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  auto energy = [&] {
    const Diagnostics d = engine->diagnostics();
    return d.kinetic_translational + d.kinetic_rotational + d.potential_elastic;
  };
  const double e0 = energy();
  double worst = 0;
  for (int block = 0; block < 100; ++block) {
    for (int n = 0; n < 1000; ++n) engine->step();
    worst = std::max(worst, std::fabs(energy() - e0) / e0);
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(engine->diagnostics().kinetic_translational, 0.5 * e0);  // still a gas
  EXPECT_EQ(engine->removed_count(), 0u);
  EXPECT_GT(engine->rebuild_count(), 10u);  // particles really moved through the lists
}

GPUDEM_INSTANTIATE_BACKENDS(Dynamics);

}  // namespace
}  // namespace gpudem::test
