// Oblique and spinning impacts with Hertz–Mindlin contacts against rigid-body impact theory
// with Coulomb friction (Maw, Barber & Fawcett 1976; Chung & Ooi 2011, tests 4, 6, 7 and 8).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Alumina of Chung & Ooi (Granular Matter 13 (2011) 643), test 4: ρ = 4000 kg/m³,
/// E = 380 GPa, ν = 0.23, μ = 0.092, here with restitution 0.5: strongly damped, so that the
/// test sees whether the friction impulse stays μ times the normal impulse (J_t = μ J_n of
/// rigid-body theory) although the dashpot pulls briefly at separation.
Material alumina() {
  Material m;
  m.name = "alumina";
  m.density = 4000;
  m.young = 3.8e11;
  m.poisson = 0.23;
  m.restitution = 0.5;
  m.friction = 0.092;
  return m;
}

/// Records `name` (measured), `name_expected` and `name_relative_error` for the validation table.
void record(const std::string& name, double measured, double expected) {
  ::testing::Test::RecordProperty(name, significant(measured));
  ::testing::Test::RecordProperty(name + "_expected", significant(expected));
  ::testing::Test::RecordProperty(name + "_relative_error", significant(measured / expected - 1));
}

/// 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
double effective_young(const Material& a, const Material& b) {
  return 1 / ((1 - a.poisson * a.poisson) / a.young + (1 - b.poisson * b.poisson) / b.young);
}

/// Hertz contact duration t_c = 2.87 (m*² / (R* E*² v))^{1/5} at normal approach speed v.
double hertz_duration(double e_star, double r_star, double m_star, double v) {
  return 2.87 * std::pow(m_star * m_star / (r_star * e_star * e_star * v), 0.2);
}

/// Hertz normal law, restitution damping and the Mindlin tangential spring; no gravity; a
/// 0.2 m box around the origin; dt = t_c / 1000 for the given normal approach speed.
Scene mindlin_scene(const Material& material, double r_star, double m_star, double vn) {
  Scene scene = basic_scene({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}, 0, 1, 0);
  scene.materials = {material};
  scene.contact.model = ContactModel{NormalLaw::Hertz, DampingLaw::Restitution,
                                     TangentialLaw::Mindlin, RollingLaw::None, CohesionLaw::None};
  scene.simulation.gravity = {0, 0, 0};
  scene.simulation.dt_auto = false;
  const double e_star = effective_young(material, material);
  scene.simulation.dt = hertz_duration(e_star, r_star, m_star, vn) / 1000;
  return scene;
}

std::size_t index_of(const ParticleStore& p, ParticleId id) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] == id) return i;
  return p.size();
}

/// Velocity and spin of one particle.
struct Motion {
  Vec3 velocity, spin;
};

Motion motion_of(const ParticleStore& p, ParticleId id) {
  const std::size_t i = index_of(p, id);
  return {xyz(p.velocity_inv_mass[i]), p.angular_velocity[i]};
}

class ObliqueImpact : public BackendTest {
 protected:
  /// Steps until the contact count has been non-zero and is zero again; the state after.
  ParticleStore collide(const Scene& scene, const ParticleStore& particles) {
    auto engine = make_engine(make_engine_setup(scene, particles));
    engine->set_particles(particles);
    bool touched = false;
    for (long n = 0; n < 1000000; ++n) {
      engine->step();
      const bool touching = engine->diagnostics().contact_count > 0;
      if (touching) touched = true;
      if (touched && !touching) break;
    }
    EXPECT_TRUE(touched);
    ParticleStore after;
    engine->get_particles(after);
    return after;
  }
};

/// A sphere hits the floor z = 0 at speed V and angle θ from the normal. In gross sliding,
/// tan θ > 3.5 μ (1 + e), the tangential impulse is μ J_n = μ m (1 + e) v_n, so
/// v_t' = v_t − μ (1 + e) v_n and ω' = 2.5 μ (1 + e) v_n / r: within 2 % there. All angles
/// from 5° to 85° are recorded.
TEST_P(ObliqueImpact, GrossSlidingMatchesRigidBodyTheory) {
  const Material material = alumina();
  const double r = 0.0025, speed = 3.9, mu = material.friction, e = material.restitution;
  const double inv_mass = 1 / sphere_mass(material.density, r);
  for (int degrees = 5; degrees <= 85; degrees += 5) {
    const double theta = degrees * kPi / 180;
    const double vn = speed * std::cos(theta), vt = speed * std::sin(theta);
    Scene scene = mindlin_scene(material, r, 1 / inv_mass, vn);
    add_floor(scene, 0);
    ParticleStore particles;
    particles.add(0, {0, 0, 1.001 * r}, r, 0, {vt, 0, -vn}, inv_mass);
    const Motion m = motion_of(collide(scene, particles), 0);
    const std::string key = "theta_" + std::to_string(degrees) + "_";
    if (std::tan(theta) <= 3.5 * mu * (1 + e)) {
      RecordProperty(key + "tangential_velocity", significant(m.velocity.x));
      RecordProperty(key + "spin", significant(m.spin.y));
      continue;
    }
    const double vt_expected = vt - mu * (1 + e) * vn;
    const double spin_expected = 2.5 * mu * (1 + e) * vn / r;
    record(key + "tangential_velocity", m.velocity.x, vt_expected);
    record(key + "spin", m.spin.y, spin_expected);
    EXPECT_NEAR(m.velocity.x, vt_expected, 0.02 * vt_expected) << degrees << "°";
    EXPECT_NEAR(m.spin.y, spin_expected, 0.02 * spin_expected) << degrees << "°";
  }
}

/// Impulses of one particle over an impact along normal n (from the particle to its partner):
/// normal J_n, tangential J_t and the spin change, from its motion before and after.
struct Impulses {
  double normal, tangential, spin_change;
};

Impulses impulses(const Motion& before, const Motion& after, Vec3 n, double mass) {
  const Vec3 dv = after.velocity - before.velocity;
  const Vec3 dv_t = dv - dot(dv, n) * n;
  return {mass * std::fabs(dot(dv, n)), mass * norm(dv_t), norm(after.spin - before.spin)};
}

/// Coulomb sliding throughout the contact: J_t = μ J_n and I Δω = r J_t, within 1 %.
void expect_coulomb_sliding(const Impulses& j, double mu, double r, double mass) {
  const double inertia = 0.4 * mass * r * r;
  ::testing::Test::RecordProperty("tangential_over_normal_impulse",
                                  significant(j.tangential / j.normal));
  ::testing::Test::RecordProperty("spin_change_over_expected",
                                  significant(inertia * j.spin_change / (r * j.tangential)));
  EXPECT_NEAR(j.tangential, mu * j.normal, 0.01 * mu * j.normal);
  EXPECT_NEAR(inertia * j.spin_change, r * j.tangential, 0.01 * r * j.tangential);
}

void expect_vec_near(Vec3 a, Vec3 b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

/// Two equal spheres meet head-on along x at ±v, spinning about y at ω_a and ω_b.
ParticleStore spinning_pair(const Material& material, double r, double v, double omega_a,
                            double omega_b) {
  const double inv_mass = 1 / sphere_mass(material.density, r);
  ParticleStore p;
  p.add(0, {-1.001 * r, 0, 0}, r, 0, {v, 0, 0}, inv_mass);
  p.add(1, {1.001 * r, 0, 0}, r, 0, {-v, 0, 0}, inv_mass);
  p.angular_velocity[0] = {0, omega_a, 0};
  p.angular_velocity[1] = {0, omega_b, 0};
  return p;
}

/// Spins ω and −ω about y: the pair is its own mirror image in the plane x = 0, the surfaces
/// move together at the contact, so there is no slip and no friction: the spheres rebound as
/// mirror images with their spins and zero tangential velocity.
TEST_P(ObliqueImpact, MirrorSpinsReboundWithoutFriction) {
  Material material = alumina();
  material.friction = 0.3;
  const double r = 0.01, v = 1, omega = 500;
  const double mass = sphere_mass(material.density, r);
  const Scene scene = mindlin_scene(material, r / 2, mass / 2, 2 * v);
  const ParticleStore after = collide(scene, spinning_pair(material, r, v, omega, -omega));
  const Motion a = motion_of(after, 0), b = motion_of(after, 1);
  RecordProperty("restitution", significant((b.velocity.x - a.velocity.x) / (2 * v)));
  expect_vec_near(a.velocity, {-b.velocity.x, b.velocity.y, b.velocity.z}, 1e-9 * v);
  expect_vec_near(a.spin, {b.spin.x, -b.spin.y, -b.spin.z}, 1e-9 * omega);
  expect_vec_near(a.spin, {0, omega, 0}, 1e-9 * omega);
  EXPECT_NEAR(a.velocity.z, 0, 1e-9 * v);
  EXPECT_NEAR(b.velocity.x - a.velocity.x, 2 * v * material.restitution,
              0.01 * 2 * v * material.restitution);
}

/// Equal spins ω about y: the surfaces slide at 2 ω r against each other. Turning the pair by
/// 180° about y swaps the spheres, so their rebounds are images under that turn; with
/// 7 μ (1 + e) v < 2 ω r they slide throughout: J_t = μ J_n and I Δω = r J_t.
TEST_P(ObliqueImpact, EqualSpinsSlideWithCoulombImpulse) {
  Material material = alumina();
  material.friction = 0.3;
  const double r = 0.01, v = 1, omega = 500, mu = material.friction;
  ASSERT_LT(7 * mu * (1 + material.restitution) * v, 2 * omega * r);
  const double mass = sphere_mass(material.density, r);
  const Scene scene = mindlin_scene(material, r / 2, mass / 2, 2 * v);
  const ParticleStore before = spinning_pair(material, r, v, omega, omega);
  const ParticleStore after = collide(scene, before);
  const Motion a = motion_of(after, 0), b = motion_of(after, 1);
  expect_vec_near(a.velocity, {-b.velocity.x, b.velocity.y, -b.velocity.z}, 1e-9 * v);
  expect_vec_near(a.spin, {-b.spin.x, b.spin.y, -b.spin.z}, 1e-9 * omega);
  EXPECT_GT(a.velocity.z, 0);  // friction on sphere 0 opposes its surface moving to −z
  EXPECT_LT(a.spin.y, omega);  // and slows its spin
  expect_coulomb_sliding(impulses(motion_of(before, 0), a, {1, 0, 0}, mass), mu, r, mass);
}

/// A sphere spinning at ±ω about y falls on the floor: the two rebounds are mirror images in
/// the plane x = 0, and with 3.5 μ (1 + e) v < ω r it slides throughout: J_t = μ J_n and
/// I Δω = r J_t.
TEST_P(ObliqueImpact, SpinningDropSlidesWithCoulombImpulse) {
  Material material = alumina();
  material.friction = 0.3;
  const double r = 0.01, v = 1, omega = 500, mu = material.friction;
  ASSERT_LT(3.5 * mu * (1 + material.restitution) * v, omega * r);
  const double mass = sphere_mass(material.density, r);
  Scene scene = mindlin_scene(material, r, mass, v);
  add_floor(scene, 0);
  Motion rebound[2];
  for (int k = 0; k < 2; ++k) {
    ParticleStore before;
    before.add(0, {0, 0, 1.001 * r}, r, 0, {0, 0, -v}, 1 / mass);
    before.angular_velocity[0] = {0, k == 0 ? omega : -omega, 0};
    rebound[k] = motion_of(collide(scene, before), 0);
    expect_coulomb_sliding(impulses(motion_of(before, 0), rebound[k], {0, 0, -1}, mass), mu, r,
                           mass);
  }
  const Motion& a = rebound[0];
  const Motion& b = rebound[1];
  expect_vec_near(a.velocity, {-b.velocity.x, b.velocity.y, b.velocity.z}, 1e-9 * v);
  expect_vec_near(a.spin, {b.spin.x, -b.spin.y, -b.spin.z}, 1e-9 * omega);
  EXPECT_GT(a.velocity.x, 0);  // ω > 0 about y: the contact point moves to −x, friction to +x
  EXPECT_LT(a.spin.y, omega);
}

/// One rebound of a spin sweep: its tangential velocity and spin (about y) are recorded under
/// `key`; where the surfaces slide throughout (`sliding`) they are also compared with rigid-body
/// theory's `slide_v` and ω − `slide_spin`, within 2 % (of the change, for the spin).
void expect_sweep_rebound(const std::string& key, double tangential, double spin, double omega,
                          bool sliding, double slide_v, double slide_spin) {
  if (!sliding) {
    ::testing::Test::RecordProperty(key + "tangential_velocity", significant(tangential));
    ::testing::Test::RecordProperty(key + "spin", significant(spin));
    return;
  }
  record(key + "tangential_velocity", tangential, slide_v);
  record(key + "spin", spin, omega - slide_spin);
  EXPECT_NEAR(tangential, slide_v, 0.02 * slide_v) << key;
  EXPECT_NEAR(spin, omega - slide_spin, 0.02 * slide_spin) << key;
}

/// Chung & Ooi (2011) test 6: a sphere meets the floor at a fixed normal speed v_n with spins ω
/// about y from 0 to 800 rad/s. Its surface slips at ω r; with ω r ≥ 3.5 μ (1 + e) v_n it slides
/// throughout, and rigid-body theory gives v_x' = μ (1 + e) v_n and ω' = ω − 2.5 μ (1 + e) v_n / r
/// (within 2 %, and 2 % of the impulse's spin change for ω'). Every spin's rebound is recorded.
TEST_P(ObliqueImpact, SpinSweepOnAWallMatchesRigidBodyTheory) {
  const Material material = alumina();
  const double r = 0.0025, vn = 1, mu = material.friction, e = material.restitution;
  const double mass = sphere_mass(material.density, r);
  const double slide_v = mu * (1 + e) * vn, slide_spin = 2.5 * mu * (1 + e) * vn / r;
  for (int omega = 0; omega <= 800; omega += 100) {
    Scene scene = mindlin_scene(material, r, mass, vn);
    add_floor(scene, 0);
    ParticleStore before;
    before.add(0, {0, 0, 1.001 * r}, r, 0, {0, 0, -vn}, 1 / mass);
    before.angular_velocity[0] = {0, double(omega), 0};
    const Motion m = motion_of(collide(scene, before), 0);
    expect_sweep_rebound("omega_" + std::to_string(omega) + "_", m.velocity.x, m.spin.y, omega,
                         omega * r >= 3.5 * slide_v, slide_v, slide_spin);
  }
}

/// Chung & Ooi (2011) test 7: two equal spheres meet head-on at ±v_n along x, both spinning at
/// ω about y from 0 to 1000 rad/s: their surfaces slip at 2 ω r. With 2 ω r ≥ 7 μ (1 + e) v_n
/// they slide throughout: each gains |v_z'| = μ (1 + e) v_n and spins at ω − 2.5 μ (1 + e) v_n / r
/// (within 2 %). Every spin's rebound is recorded.
TEST_P(ObliqueImpact, SpinSweepOfTwoEqualSpheresMatchesRigidBodyTheory) {
  const Material material = alumina();
  const double r = 0.0025, v = 1, mu = material.friction, e = material.restitution;
  const double mass = sphere_mass(material.density, r);
  const double slide_v = mu * (1 + e) * v, slide_spin = 2.5 * mu * (1 + e) * v / r;
  const Scene scene = mindlin_scene(material, r / 2, mass / 2, 2 * v);
  for (int omega = 0; omega <= 1000; omega += 125) {
    const Motion m = motion_of(collide(scene, spinning_pair(material, r, v, omega, omega)), 0);
    expect_sweep_rebound("omega_" + std::to_string(omega) + "_", m.velocity.z, m.spin.y, omega,
                         2 * omega * r >= 7 * slide_v, slide_v, slide_spin);
  }
}

/// Chung & Ooi (2011) test 8: a sphere of 5 mm moving along x at v_n = 1 m/s, and along z at v_t
/// from 0 to 1 m/s, touches one of 2.5 mm at rest. J_n = m* (1 + e) v_n; with
/// v_t ≥ 3.5 μ (1 + e) v_n they slide throughout, J_t = μ J_n: Δv_z = ∓J_t / m_i and
/// Δω_y = r_i J_t / I_i = 2.5 J_t / (m_i r_i) for both (within 2 %). Rigid-body theory keeps the
/// normal fixed; here the centre line turns while the spheres pass each other along z, by about
/// v_t t_c / (r₁ + r₂), which tilts the normal impulse and shortens it: J_t was 2.3 % under
/// μ m* (1 + e) v_n at v_t = 2.5 m/s (μ = 0.3), so the sweep stays below twice the sliding
/// threshold. Every v_t's rebound is recorded.
TEST_P(ObliqueImpact, TangentialSweepOfUnequalSpheresMatchesRigidBodyTheory) {
  const Material material = alumina();
  const double r1 = 0.005, r2 = 0.0025, vn = 1, mu = material.friction, e = material.restitution;
  const double m1 = sphere_mass(material.density, r1), m2 = sphere_mass(material.density, r2);
  const double m_star = m1 * m2 / (m1 + m2), j_t = mu * m_star * (1 + e) * vn;
  const Scene scene = mindlin_scene(material, r1 * r2 / (r1 + r2), m_star, vn);
  for (int step = 0; step <= 8; ++step) {
    const double vt = 0.125 * step;
    ParticleStore before;
    before.add(0, {-r1, 0, 0}, r1, 0, {vn, 0, vt}, 1 / m1);
    before.add(1, {r2, 0, 0}, r2, 0, {0, 0, 0}, 1 / m2);
    const ParticleStore after = collide(scene, before);
    const Motion a = motion_of(after, 0), b = motion_of(after, 1);
    const std::string key = "vt_" + std::to_string(vt).substr(0, 5) + "_";
    if (vt < 3.5 * mu * (1 + e) * vn) {
      RecordProperty(key + "tangential_velocity_large", significant(a.velocity.z));
      RecordProperty(key + "spin_large", significant(a.spin.y));
      continue;
    }
    record(key + "tangential_velocity_large", a.velocity.z, vt - j_t / m1);
    record(key + "tangential_velocity_small", b.velocity.z, j_t / m2);
    record(key + "spin_large", a.spin.y, 2.5 * j_t / (m1 * r1));
    record(key + "spin_small", b.spin.y, 2.5 * j_t / (m2 * r2));
    EXPECT_NEAR(a.velocity.z, vt - j_t / m1, 0.02 * j_t / m1) << vt << " m/s";
    EXPECT_NEAR(b.velocity.z, j_t / m2, 0.02 * j_t / m2) << vt << " m/s";
    EXPECT_NEAR(a.spin.y, 2.5 * j_t / (m1 * r1), 0.02 * 2.5 * j_t / (m1 * r1)) << vt << " m/s";
    EXPECT_NEAR(b.spin.y, 2.5 * j_t / (m2 * r2), 0.02 * 2.5 * j_t / (m2 * r2)) << vt << " m/s";
  }
}

GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(ObliqueImpact);

}  // namespace
}  // namespace gpudem::test
