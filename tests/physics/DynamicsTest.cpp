// Point-particle dynamics against closed forms, and energy conservation of an elastic gas.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/ParticleSources.hpp"
#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SameBits.hpp"
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
  RecordProperty("position_error_m", significant(norm(x - expected)));
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
  const double expected_z = 1 + n * dt * 2 + g * dt * dt * n * (n + 1) / 2.0;
  RecordProperty("position_error_m",
                 significant(std::fabs(particles.position_radius[0].z - expected_z)));
  EXPECT_NEAR(particles.position_radius[0].z, 1 + n * dt * 2 + g * dt * dt * n * (n + 1) / 2.0,
              1e-11);
  EXPECT_NEAR(particles.velocity_inv_mass[0].z, 2 + n * dt * g, 1e-11);
}

/// A damped sphere comes to rest on a floor with overlap δ = m g / k, and the floor carries m g.
TEST_P(Dynamics, SphereRestsOnPlaneWithStaticOverlap) {
  Scene scene = basic_scene({-1, -1, 0}, {1, 1, 1}, 1e4, 0.3, 0.5);
  add_floor(scene);
  const double r = 0.01;
  ParticleStore particles = single_particle(scene, {0, 0, r}, {0, 0, 0}, r);
  const double m = 1.0 / particles.velocity_inv_mass[0].w;
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  for (int n = 0; n < 20000; ++n) engine->step();
  engine->get_particles(particles);
  const double weight = -m * scene.simulation.gravity.z;
  const double overlap = r - particles.position_radius[0].z;
  RecordProperty("static_overlap_relative_error",
                 significant(std::fabs(overlap - weight / 1e4) / (weight / 1e4)));
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
  scene.contact.model.tangential = TangentialLaw::None;
  add_box_walls(scene);
  add_box_source(scene, scene.domain.min, scene.domain.max, 300, 4e-3, 1e-3);
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
  RecordProperty("max_relative_energy_error", significant(worst));
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(engine->diagnostics().kinetic_translational, 0.5 * e0);  // still a gas
  EXPECT_EQ(engine->removed_count(), 0u);
  EXPECT_GT(engine->rebuild_count(), 10u);  // particles really moved through the lists
}

GPUDEM_INSTANTIATE_BACKENDS(Dynamics);

/// The snapshot copy an engine stages for output while it steps on.
class Staging : public BackendTest {};

/// Particles staged at a step and collected only after more steps hold that step's state, bit
/// for bit in every field, with the step's particle count; later steps changed the engine.
TEST_P(Staging, StagedParticlesHoldTheStepTheyWereStagedAt) {
  Scene scene = basic_scene({0, 0, 0}, {0.1, 0.1, 0.1}, 1e4, 0.5, 0.5);
  add_box_walls(scene);
  add_box_source(scene, scene.domain.min, scene.domain.max, 300, 4e-3, 1e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  for (int n = 0; n < 200; ++n) engine->step();
  ParticleStore at_staging;
  engine->get_particles(at_staging);
  StagedParticles& staged = engine->stage_particles();
  for (int n = 0; n < 200; ++n) engine->step();
  ParticleStore later, collected;
  engine->get_particles(later);
  staged.collect(collected);

  EXPECT_EQ(staged.expected_tally.count, at_staging.size());
  EXPECT_TRUE(same_bits(collected.position_radius, at_staging.position_radius));
  EXPECT_TRUE(same_bits(collected.velocity_inv_mass, at_staging.velocity_inv_mass));
  EXPECT_TRUE(same_bits(collected.angular_velocity, at_staging.angular_velocity));
  EXPECT_TRUE(same_bits(collected.force, at_staging.force));
  EXPECT_TRUE(same_bits(collected.torque, at_staging.torque));
  EXPECT_TRUE(same_bits(collected.id, at_staging.id));
  EXPECT_TRUE(same_bits(collected.material, at_staging.material));
  EXPECT_FALSE(same_bits(later.position_radius, at_staging.position_radius));
  EXPECT_FALSE(same_bits(later.velocity_inv_mass, at_staging.velocity_inv_mass));
}

GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Staging);

}  // namespace
}  // namespace gpudem::test

namespace gpudem::test {
namespace {

class Incline : public BackendTest {
 protected:
  /// Acceleration along the slope of a sphere on a floor under gravity tilted by θ, measured
  /// between t = 0.2 s and 0.4 s; also the angular acceleration about y.
  void measure(double theta, double friction, double& accel, double& angular_accel) {
    Scene scene = basic_scene({-100, -1, -1}, {100, 1, 1}, 1e4, 0.3, friction);
    scene.simulation.gravity = {9.81 * std::sin(theta), 0, -9.81 * std::cos(theta)};
    // A free fall along the 200 m slope (50 m/s) would bound the step; the sphere only rolls.
    scene.simulation.displacement_fraction = 1;
    add_floor(scene, -0.5);
    const double r = 0.01;
    ParticleStore particles = single_particle(scene, {0, 0, -0.5 + r}, {0, 0, 0}, r);
    auto engine = make_engine(make_engine_setup(scene, particles));
    engine->set_particles(particles);
    const EngineSetup setup = make_engine_setup(scene, particles);
    auto advance_to = [&](double t) {
      while (steps_ * setup.dt < t) {
        engine->step();
        ++steps_;
      }
      engine->get_particles(particles);
      return std::make_pair(steps_ * setup.dt, particles);
    };
    const auto [t1, p1] = advance_to(0.2);
    const auto [t2, p2] = advance_to(0.4);
    accel = (p2.velocity_inv_mass[0].x - p1.velocity_inv_mass[0].x) / (t2 - t1);
    angular_accel = (p2.angular_velocity[0].y - p1.angular_velocity[0].y) / (t2 - t1);
  }
  long steps_ = 0;
};

/// Below tan θ = 3.5 μ a sphere rolls without slipping: a = 5/7 g sin θ, α = a / r.
TEST_P(Incline, SphereRollsWithoutSlipping) {
  const double theta = 20 * 3.14159265358979 / 180, mu = 0.5;
  double a = 0, alpha = 0;
  measure(theta, mu, a, alpha);
  const double expected = 5.0 / 7.0 * 9.81 * std::sin(theta);
  RecordProperty("acceleration", significant(a));
  RecordProperty("acceleration_expected", significant(expected));
  EXPECT_NEAR(a, expected, 0.01 * expected);
  EXPECT_NEAR(alpha, expected / 0.01, 0.01 * expected / 0.01);
}

/// Above tan θ = 3.5 μ it slides: a = g (sin θ − μ cos θ), α = 5 μ g cos θ / (2 r).
TEST_P(Incline, SphereSlidesAtCoulombLimit) {
  const double theta = 40 * 3.14159265358979 / 180, mu = 0.1;
  double a = 0, alpha = 0;
  measure(theta, mu, a, alpha);
  const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  const double expected_alpha = 5 * mu * 9.81 * std::cos(theta) / (2 * 0.01);
  RecordProperty("acceleration", significant(a));
  RecordProperty("acceleration_expected", significant(expected));
  RecordProperty("angular_acceleration", significant(alpha));
  RecordProperty("angular_acceleration_expected", significant(expected_alpha));
  EXPECT_NEAR(a, expected, 0.01 * expected);
  EXPECT_NEAR(alpha, expected_alpha, 0.01 * expected_alpha);
}

GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Incline);

}  // namespace
}  // namespace gpudem::test

namespace gpudem::test {
namespace {

class Rolling : public BackendTest {};

/// With constant-torque rolling resistance a sphere rolling on a floor decelerates at
/// 5/7·μ_r·g and stops after s = 7 v0² / (10 μ_r g), then stays at rest.
TEST_P(Rolling, ConstantTorqueStopsSphereAtClosedFormDistance) {
  const double r = 0.01, v0 = 0.5, mu_r = 0.05;
  Scene scene = basic_scene({-10, -1, -1}, {10, 1, 1}, 1e4, 0.3, 0.5);
  scene.materials[0].rolling_friction = mu_r;
  scene.contact.model.rolling = RollingLaw::ConstantTorque;
  add_floor(scene, -0.5);
  ParticleStore particles = single_particle(scene, {0, 0, -0.5 + r}, {v0, 0, 0}, r);
  const double m = 1.0 / particles.velocity_inv_mass[0].w;
  particles.position_radius[0].z -= m * 9.81 / 1e4;  // start at the static overlap
  particles.angular_velocity[0] = {0, v0 / r, 0};    // rolling without slip
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  const double stop_time = v0 / (5.0 / 7.0 * mu_r * 9.81);
  const double dt = make_engine_setup(scene, particles).dt;
  const long steps = static_cast<long>(1.5 * stop_time / dt);
  for (long n = 0; n < steps; ++n) engine->step();
  engine->get_particles(particles);
  const double expected = 7 * v0 * v0 / (10 * mu_r * 9.81);
  RecordProperty("stopping_distance", significant(particles.position_radius[0].x));
  RecordProperty("stopping_distance_expected", significant(expected));
  EXPECT_NEAR(particles.position_radius[0].x, expected, 0.02 * expected);
  EXPECT_LT(std::fabs(particles.velocity_inv_mass[0].x), 1e-6 * v0);
  EXPECT_LT(std::fabs(particles.angular_velocity[0].y), 1e-6 * v0 / r);
}

GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Rolling);

}  // namespace
}  // namespace gpudem::test

namespace gpudem::test {
namespace {

class Boundaries : public BackendTest {};

/// A particle that leaves along a non-periodic axis is removed and counted; one crossing a
/// periodic face re-enters on the other side.
TEST_P(Boundaries, LeaversAreRemovedAndPeriodicImagesWrap) {
  Scene scene = basic_scene({0, 0, 0}, {1, 1, 1}, 1e4, 0.5, 0.5);
  scene.simulation.gravity = {0, 0, 0};
  scene.simulation.dt_auto = false;
  scene.simulation.dt = 5e-4;
  scene.domain.periodic = {false, true, false};
  const double r = 0.01, inv_m = 1.0 / sphere_mass(scene.materials[0].density, r);
  ParticleStore particles;
  particles.add(7, {0.9, 0.5, 0.5}, r, 0, {2.0, 0, 0}, inv_m);   // leaves through x = 1
  particles.add(8, {0.5, 0.95, 0.5}, r, 0, {0, 1.0, 0}, inv_m);  // wraps through y = 1
  particles.add(9, {0.5, 0.5, 0.5}, r, 0, {0, 0, 0}, inv_m);     // stays
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  for (int n = 0; n < 400; ++n) engine->step();  // 0.2 s
  EXPECT_EQ(engine->removed_count(), 1u);
  EXPECT_EQ(engine->particle_count(), 2u);
  engine->get_particles(particles);
  ASSERT_EQ(particles.size(), 2u);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    EXPECT_NE(particles.id[i], 7u);
    if (particles.id[i] == 8u) {
      EXPECT_NEAR(particles.position_radius[i].y, 0.15, 0.02);
    }
  }
}

GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Boundaries);

}  // namespace
}  // namespace gpudem::test
