// Friction, rolling resistance and cohesion of a sphere on a plane against closed forms:
// sliding at μ_d, stick below μ_s, constant-torque and EPSD rolling resistance, and the
// equilibrium overlap of simplified JKR cohesion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;       // [m/s²]
constexpr double kRadius = 0.01;  // [m]

/// Records `name` (measured), `name_expected` and `name_relative_error` for the validation table.
void record(const std::string& name, double measured, double expected) {
  ::testing::Test::RecordProperty(name, significant(measured));
  ::testing::Test::RecordProperty(name + "_expected", significant(expected));
  ::testing::Test::RecordProperty(name + "_relative_error", significant(measured / expected - 1));
}

/// Soft glass-like spheres, ρ = 2500 kg/m³, E = 10 MPa, ν = 0.3: slow contacts, long steps.
Material soft_material(double restitution, double static_friction, double dynamic_friction) {
  Material m;
  m.name = "soft";
  m.density = 2500;
  m.young = 1e7;
  m.poisson = 0.3;
  m.restitution = restitution;
  m.friction = static_friction;
  m.friction_dynamic = dynamic_friction;
  return m;
}

/// 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ (sphere and wall of the same material).
double effective_young(const Material& m) { return m.young / (2 * (1 - m.poisson * m.poisson)); }

/// 1/G* = (2 − ν₁)/G₁ + (2 − ν₂)/G₂, G = E / (2 (1 + ν)) (sphere and wall of the same material).
double effective_shear(const Material& m) {
  return m.young / (2 * (1 + m.poisson)) / (2 * (2 - m.poisson));
}

/// Hertz overlap of a sphere pressed on a plane by `load`: δ = (3 F / (4 E* √r))^{2/3}.
double hertz_overlap(const Material& m, double load) {
  return std::pow(3 * load / (4 * effective_young(m) * std::sqrt(kRadius)), 2.0 / 3.0);
}

/// Mass of a sphere of radius kRadius.
double mass_of(const Material& m) { return sphere_mass(m.density, kRadius); }

/// A time step of 1/400 of the period 2π √(m / S_n) of the resting contact, S_n = 2E*√(rδ).
double resting_step(const Material& m, double load) {
  const double stiffness = 2 * effective_young(m) * std::sqrt(kRadius * hertz_overlap(m, load));
  return 2 * kPi * std::sqrt(mass_of(m) / stiffness) / 400;
}

/// One material, the floor z = 0 of that material, gravity `gravity`, a long box along x.
Scene floor_scene(const ContactModel& model, const Material& material, Vec3 gravity, double dt) {
  Scene scene = basic_scene({-1, -0.5, -0.5}, {5, 0.5, 0.5}, 0, 1, 0);
  scene.materials = {material};
  scene.contact.model = model;
  scene.simulation.gravity = gravity;
  scene.simulation.dt_auto = false;
  scene.simulation.dt = dt;
  add_floor(scene, 0);
  return scene;
}

/// A sphere of radius kRadius on the floor at the overlap `overlap`, with velocity and spin.
ParticleStore sphere_on_floor(const Material& m, double overlap, Vec3 velocity, Vec3 spin) {
  ParticleStore p;
  p.add(0, {0, 0, kRadius - overlap}, kRadius, 0, velocity, 1 / mass_of(m));
  p.angular_velocity[0] = spin;
  return p;
}

ContactModel hertz_mindlin(RollingLaw rolling) {
  return {NormalLaw::Hertz, DampingLaw::Restitution, TangentialLaw::Mindlin, rolling,
          CohesionLaw::None};
}

class Friction : public BackendTest {
 protected:
  void start(const Scene& scene, const ParticleStore& particles) {
    dt_ = scene.simulation.dt;
    engine_ = make_engine(make_engine_setup(scene, particles));
    engine_->set_particles(particles);
    engine_->get_particles(state_);
    steps_ = 0;
  }
  /// Steps until time t, calling `each_step` after every step with the new state.
  void advance_to(double t, const std::function<void()>& each_step = {}) {
    while (steps_ * dt_ < t) {
      engine_->step();
      ++steps_;
      engine_->get_particles(state_);
      if (each_step) each_step();
    }
  }
  double time() const { return steps_ * dt_; }
  Vec3 position() const { return xyz(state_.position_radius[0]); }
  Vec3 velocity() const { return xyz(state_.velocity_inv_mass[0]); }
  Vec3 spin() const { return state_.angular_velocity[0]; }
  /// Force on the floor: tangential magnitude over normal magnitude.
  double wall_force_ratio() const {
    const Vec3 f = engine_->diagnostics().wall_force[0];
    return std::hypot(f.x, f.y) / std::fabs(f.z);
  }

  std::unique_ptr<StepEngine> engine_;
  ParticleStore state_;
  double dt_ = 0;
  long steps_ = 0;
};

/// Rotation blocked by constant-torque rolling resistance with μ_r = 1 (the cap μ_r F_n r
/// exceeds the friction torque): a sphere launched at 1 m/s slides and decelerates at μ_d g
/// (μ_s = 0.5, μ_d = 0.3), and the floor carries |F_t| = μ_d |F_n|; both within 1 %.
TEST_P(Friction, SlidingDeceleratesAtDynamicFriction) {
  Material material = soft_material(0.5, 0.5, 0.3);
  material.rolling_friction = 1;
  const double weight = mass_of(material) * kG;
  const Scene scene = floor_scene(hertz_mindlin(RollingLaw::ConstantTorque), material, {0, 0, -kG},
                                  resting_step(material, weight));
  start(scene, sphere_on_floor(material, hertz_overlap(material, weight), {1, 0, 0}, {}));
  advance_to(0.05);
  const double t1 = time(), v1 = velocity().x;
  advance_to(0.25);
  const double deceleration = (v1 - velocity().x) / (time() - t1);
  const double expected = material.friction_dynamic * kG;
  record("deceleration", deceleration, expected);
  RecordProperty("wall_force_ratio", significant(wall_force_ratio()));
  EXPECT_NEAR(deceleration, expected, 0.01 * expected);
  EXPECT_NEAR(wall_force_ratio(), material.friction_dynamic, 0.01 * material.friction_dynamic);
  EXPECT_GT(velocity().x, 0.1);  // still sliding
}

/// A sphere rolling without slip at v0 = 0.5 m/s with constant-torque resistance μ_r = 0.05
/// (EDEM type A) decelerates at 5/7 μ_r g and stops after d = v0² / (2 · 5/7 μ_r g), within 2 %.
TEST_P(Friction, ConstantTorqueRollingStopsAtClosedFormDistance) {
  Material material = soft_material(0.5, 0.5, 0.5);
  material.rolling_friction = 0.05;
  const double weight = mass_of(material) * kG, v0 = 0.5;
  const Scene scene = floor_scene(hertz_mindlin(RollingLaw::ConstantTorque), material, {0, 0, -kG},
                                  resting_step(material, weight));
  start(scene, sphere_on_floor(material, hertz_overlap(material, weight), {v0, 0, 0},
                               {0, v0 / kRadius, 0}));
  const double deceleration = 5.0 / 7.0 * material.rolling_friction * kG;
  advance_to(1.2 * v0 / deceleration);
  const double expected = v0 * v0 / (2 * deceleration);
  record("stopping_distance", position().x, expected);
  EXPECT_NEAR(position().x, expected, 0.02 * expected);
  EXPECT_LT(std::fabs(velocity().x), 1e-3 * v0);
  EXPECT_LT(std::fabs(spin().y), 1e-3 * v0 / kRadius);
}

/// Gravity tilted by θ along x, rotation blocked as above (μ_r = 1), μ_s = 0.5, μ_d = 0.3.
class TiltedFloor : public Friction {
 protected:
  void start_tilted(double tan_theta, double restitution) {
    material_ = soft_material(restitution, 0.5, 0.3);
    material_.rolling_friction = 1;
    const double theta = std::atan(tan_theta);
    const double normal_load = mass_of(material_) * kG * std::cos(theta);
    const Scene scene = floor_scene(hertz_mindlin(RollingLaw::ConstantTorque), material_,
                                    {kG * std::sin(theta), 0, -kG * std::cos(theta)},
                                    resting_step(material_, normal_load));
    overlap_ = hertz_overlap(material_, normal_load);
    start(scene, sphere_on_floor(material_, overlap_, {}, {}));
  }
  /// Contact-point velocity along x: v_x + (ω × (−(r − δ/2) ẑ))_x = v_x − (r − δ/2) ω_y.
  double contact_point_velocity() const {
    return velocity().x - (kRadius - overlap_ / 2) * spin().y;
  }
  Material material_;
  double overlap_ = 0;
};

/// tan θ = 0.35, between μ_d and μ_s (a law with μ_d only would slide): the contact sticks.
/// Its displacement u (centre displacement plus the rolled arc, ∫ contact-point velocity dt)
/// stops growing, and equals the elastic displacement of the Mindlin spring carrying the
/// slope load, u = m g sin θ / S_t with S_t = 8 G* √(r δ), within 1 %. Heavy damping (e = 0.1)
/// keeps the load overshoot of the sudden tilt below μ_s.
TEST_P(TiltedFloor, SticksBelowStaticFriction) {
  const double tan_theta = 0.35;
  start_tilted(tan_theta, 0.1);
  double displacement = 0, previous = contact_point_velocity(), largest_ratio = 0;
  auto integrate = [&] {
    const double current = contact_point_velocity();
    displacement += 0.5 * (previous + current) * dt_;
    previous = current;
    largest_ratio = std::max(largest_ratio, wall_force_ratio());
  };
  advance_to(0.15, integrate);
  const double halfway = displacement;
  advance_to(0.3, integrate);
  const double theta = std::atan(tan_theta);
  const double load = mass_of(material_) * kG * std::sin(theta);
  const double expected = load / (8 * effective_shear(material_) * std::sqrt(kRadius * overlap_));
  record("contact_displacement", displacement, expected);
  RecordProperty("creep_over_last_half", significant(displacement - halfway));
  RecordProperty("largest_friction_ratio", significant(largest_ratio));
  RecordProperty("centre_velocity", significant(velocity().x));
  EXPECT_NEAR(displacement, expected, 0.01 * expected);
  EXPECT_NEAR(displacement, halfway, 1e-3 * expected);
  EXPECT_LT(std::fabs(contact_point_velocity()), 1e-6);
  EXPECT_LT(largest_ratio, material_.friction);
}

/// tan θ = tan 30° > μ_s: the sphere slides at a = g (sin θ − μ_d cos θ) and the floor carries
/// |F_t| = μ_d |F_n|; both within 1 %.
TEST_P(TiltedFloor, SlidesAboveStaticFriction) {
  const double theta = kPi / 6;
  start_tilted(std::tan(theta), 0.1);
  advance_to(0.1);
  const double t1 = time(), v1 = velocity().x;
  advance_to(0.3);
  const double accel = (velocity().x - v1) / (time() - t1);
  const double mu_d = material_.friction_dynamic;
  const double expected = kG * (std::sin(theta) - mu_d * std::cos(theta));
  record("acceleration", accel, expected);
  RecordProperty("wall_force_ratio", significant(wall_force_ratio()));
  EXPECT_NEAR(accel, expected, 0.01 * expected);
  EXPECT_NEAR(wall_force_ratio(), mu_d, 0.01 * mu_d);
}

/// EPSD rolling resistance (Ai et al., Powder Technol. 206 (2011) 269), μ_r = 0.2, critically
/// damped (η_r = 1): a sphere rolling at 2 m/s stops within 5 % of the constant-torque
/// distance v0² / (2 · 5/7 μ_r g) (the spring torque is at its limit μ_r F_n r during most of
/// the roll), springs back once without oscillating (ω changes sign once, when it stops) and
/// comes to rest.
TEST_P(Friction, EpsdRollingStopsWithoutChatter) {
  Material material = soft_material(0.5, 0.5, 0.5);
  material.rolling_friction = 0.2;
  material.rolling_damping = 1;
  const double weight = mass_of(material) * kG, v0 = 2;
  const Scene scene = floor_scene(hertz_mindlin(RollingLaw::Epsd), material, {0, 0, -kG},
                                  resting_step(material, weight));
  start(scene, sphere_on_floor(material, hertz_overlap(material, weight), {v0, 0, 0},
                               {0, v0 / kRadius, 0}));
  const double deceleration = 5.0 / 7.0 * material.rolling_friction * kG;
  int sign_changes = 0;
  double last_spin = spin().y;
  advance_to(1.2 * v0 / deceleration, [&] {
    if ((spin().y > 0) != (last_spin > 0)) ++sign_changes;
    last_spin = spin().y;
  });
  const double expected = v0 * v0 / (2 * deceleration);
  record("stopping_distance", position().x, expected);
  RecordProperty("spin_sign_changes", std::to_string(sign_changes));
  RecordProperty("final_spin", significant(spin().y));
  EXPECT_NEAR(position().x, expected, 0.05 * expected);
  EXPECT_EQ(sign_changes, 1);
  EXPECT_LT(std::fabs(spin().y), 1e-6 * v0 / kRadius);
  EXPECT_LT(std::fabs(velocity().x), 1e-6 * v0);
}

/// Hooke law with simplified JKR cohesion (LIGGGHTS sjkr): F_n = k_n δ + F_d − k_c π a².
ContactModel hooke_sjkr() {
  return {NormalLaw::Hooke, DampingLaw::Restitution, TangentialLaw::None, RollingLaw::None,
          CohesionLaw::Sjkr};
}

/// Squared contact-circle radius of two spheres at centre distance d (Johnson 1985):
/// a² = (r₁ + r₂ − d)(d + r₁ − r₂)(d − r₁ + r₂)(d + r₁ + r₂) / (4 d²).
double contact_radius_squared(double r1, double r2, double d) {
  return (r1 + r2 - d) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2) / (4 * d * d);
}

/// On the floor, a² = 2 r δ − δ², so k_n δ − k_c π (2 r δ − δ²) = m g: the positive root of
/// k_c π δ² + (k_n − 2π k_c r) δ − m g = 0, reached within 1e-6 relative. k_c makes the
/// cohesion slope half the spring stiffness, doubling the Hooke overlap.
TEST_P(Friction, SjkrSphereSettlesAtCohesiveOverlap) {
  const double stiffness = 1e4;
  Material material = soft_material(0.3, 0.5, 0.5);
  material.cohesion_energy_density = 0.25 * stiffness / (kPi * kRadius);
  Scene scene = floor_scene(hooke_sjkr(), material, {0, 0, -kG},
                            kPi * std::sqrt(mass_of(material) / stiffness) / 100);
  scene.contact.stiffness = stiffness;
  const double weight = mass_of(material) * kG;
  start(scene, sphere_on_floor(material, weight / stiffness, {}, {}));
  advance_to(0.3);
  const double a = kPi * material.cohesion_energy_density;
  const double b = stiffness - 2 * a * kRadius;
  const double expected = 2 * weight / (b + std::sqrt(b * b + 4 * a * weight));
  const double overlap = kRadius - position().z;
  record("overlap", overlap, expected);
  EXPECT_NEAR(overlap, expected, 1e-6 * expected);
}

/// Two spheres (r = 10 and 6 mm) start at half the equilibrium overlap without gravity and are
/// pulled together until k_n δ = k_c π a²(δ) (solved here by bisection), within 1e-6 relative;
/// their centre distance then stays constant. For small δ, a² ≈ 2 R* δ, so k_c is set just
/// above k_n / (2π R*) for a cohesive equilibrium.
TEST_P(Friction, SjkrPairSticksAtCohesiveOverlap) {
  const double stiffness = 1e4, r1 = kRadius, r2 = 0.006;
  const double r_star = r1 * r2 / (r1 + r2);
  Material material = soft_material(0.5, 0.5, 0.5);
  material.cohesion_energy_density = stiffness / (2 * kPi * r_star * 0.98);
  auto net_repulsion = [&](double overlap) {
    const double area = kPi * contact_radius_squared(r1, r2, r1 + r2 - overlap);
    return stiffness * overlap - material.cohesion_energy_density * area;
  };
  double lo = 1e-9 * r2, hi = r2;  // attraction at lo, repulsion at hi
  ASSERT_LT(net_repulsion(lo), 0);
  ASSERT_GT(net_repulsion(hi), 0);
  for (int k = 0; k < 200; ++k) (net_repulsion(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
  const double expected = 0.5 * (lo + hi);

  const double m1 = sphere_mass(material.density, r1);
  const double m2 = sphere_mass(material.density, r2);
  Scene scene = floor_scene(hooke_sjkr(), material, {0, 0, 0},
                            kPi * std::sqrt(m1 * m2 / (m1 + m2) / stiffness) / 100);
  scene.walls.clear();
  scene.contact.stiffness = stiffness;
  ParticleStore particles;
  particles.add(0, {0, 0, 0}, r1, 0, {}, 1 / m1);
  particles.add(1, {r1 + r2 - 0.5 * expected, 0, 0}, r2, 0, {}, 1 / m2);
  start(scene, particles);
  auto distance = [&] {
    return norm(xyz(state_.position_radius[1]) - xyz(state_.position_radius[0]));
  };
  advance_to(0.3);
  const double d1 = distance();
  advance_to(0.4);
  const double overlap = r1 + r2 - distance();
  record("overlap", overlap, expected);
  EXPECT_NEAR(overlap, expected, 1e-6 * expected);
  EXPECT_NEAR(distance(), d1, 1e-6 * expected);
}

GPUDEM_INSTANTIATE_BACKENDS(Friction);
GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(TiltedFloor);

}  // namespace
}  // namespace gpudem::test
