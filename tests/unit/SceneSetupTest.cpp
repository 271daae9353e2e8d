// From scene to engine setup: the contact pair table (effective moduli, mixing rules, [[pair]]
// entries, restitution damping ratio) and the time-step limits (Rayleigh, Hooke and Hertz
// contact durations, the stable limit of an explicit dt) and the units of the integer load sums,
// each against closed forms written out here.
#include "engine/SceneSetup.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/InputError.hpp"
#include "core/RowShare.hpp"
#include "core/SceneLoader.hpp"
#include "support/InputErrorText.hpp"
#include "support/RunBinary.hpp"

namespace gpudem {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Relative tolerance of values that differ from the closed form only by rounding.
constexpr double kRounding = 1e-13;

void expect_relative(double actual, double expected, double tolerance = kRounding) {
  EXPECT_NEAR(actual, expected, tolerance * std::abs(expected)) << "expected " << expected;
}

Material material(const std::string& name, double density, double young, double poisson) {
  Material m;
  m.name = name;
  m.density = density;
  m.young = young;
  m.poisson = poisson;
  return m;
}

/// Two materials, "grain" (soft) and "steel", Hooke contact, no particles.
Scene two_material_scene() {
  Scene s;
  s.file = "scene.toml";
  s.simulation.end_time = 1;
  s.domain.min = {0, 0, 0};
  s.domain.max = {1, 1, 1};
  s.materials = {material("grain", 2500, 1e7, 0.3), material("steel", 7800, 2e11, 0.25)};
  s.contact.stiffness = 1e4;
  return s;
}

/// Table entry of materials a and b.
const ContactPairParams& entry(const EngineSetup& setup, MaterialId a, MaterialId b) {
  return setup.pair_params[a * setup.material_count + b];
}

/// |ln e| / √(ln² e + π²), written out.
double beta_of(double e) { return std::abs(std::log(e)) / std::hypot(std::log(e), kPi); }

TEST(PairTable, EffectiveModuliOfTwoMaterials) {
  const Scene s = two_material_scene();
  const EngineSetup setup = make_engine_setup(s, ParticleStore{});
  ASSERT_EQ(setup.material_count, 2u);
  ASSERT_EQ(setup.pair_params.size(), 4u);
  // 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ = 0.91/1e7 + 0.9375/2e11.
  const double young_mixed = 1 / (0.91 / 1e7 + 0.9375 / 2e11);
  // G = E/(2(1 + ν)): 1e7/2.6 and 2e11/2.5; 1/G* = (2 − ν₁)/G₁ + (2 − ν₂)/G₂.
  const double shear_mixed = 1 / (1.7 / (1e7 / 2.6) + 1.75 / (2e11 / 2.5));
  for (const auto& [a, b] : {std::pair{0u, 1u}, std::pair{1u, 0u}}) {
    expect_relative(entry(setup, a, b).effective_young, young_mixed);
    expect_relative(entry(setup, a, b).effective_shear, shear_mixed);
  }
  expect_relative(young_mixed, 1.0988445e7, 1e-7);  // the hand computation, to 8 digits
  expect_relative(entry(setup, 0, 0).effective_young, 1e7 / (2 * 0.91));
  expect_relative(entry(setup, 0, 0).effective_shear, (1e7 / 2.6) / (2 * 1.7));
  expect_relative(entry(setup, 1, 1).effective_young, 2e11 / (2 * 0.9375));
}

TEST(PairTable, HookeStiffnessesAndModel) {
  Scene s = two_material_scene();
  EngineSetup setup = make_engine_setup(s, ParticleStore{});
  EXPECT_TRUE(setup.contact_model == s.contact.model);
  for (const ContactPairParams& p : setup.pair_params) {
    EXPECT_EQ(p.hooke_stiffness, 1e4);
    expect_relative(p.hooke_tangential_stiffness, 1e4 * 2 / 7);
  }
  s.contact.model.tangential = TangentialLaw::None;
  setup = make_engine_setup(s, ParticleStore{});
  EXPECT_TRUE(setup.contact_model == s.contact.model);
  for (const ContactPairParams& p : setup.pair_params) EXPECT_EQ(p.hooke_tangential_stiffness, 0);
}

TEST(PairTable, RestitutionDampingRatio) {
  Scene s = two_material_scene();
  s.materials[0].restitution = 0.5;
  s.materials[1].restitution = 1;
  const EngineSetup setup = make_engine_setup(s, ParticleStore{});
  // |ln 0.5| / √(ln² 0.5 + π²) = 0.693147 / 3.217154 = 0.215454.
  expect_relative(entry(setup, 0, 0).restitution_beta, beta_of(0.5));
  EXPECT_NEAR(entry(setup, 0, 0).restitution_beta, 0.215454, 1e-6);
  EXPECT_EQ(entry(setup, 1, 1).restitution_beta, 0);
  expect_relative(entry(setup, 0, 1).restitution_beta, beta_of(0.75));  // mean of 0.5 and 1
}

/// Materials with distinct values of every mixed property.
Scene mixing_scene(MixingRule rule) {
  Scene s = two_material_scene();
  Material& a = s.materials[0];
  Material& b = s.materials[1];
  a.restitution = 0.4, b.restitution = 0.8;
  a.friction = 0.6, b.friction = 0.2;
  a.friction_dynamic = 0.5, b.friction_dynamic = 0.1;
  a.rolling_friction = 0.1, b.rolling_friction = 0.3;
  a.rolling_damping = 0.2, b.rolling_damping = 0.6;
  a.viscoelastic_time = 1e-5, b.viscoelastic_time = 3e-5;
  a.cohesion_energy_density = 1e3, b.cohesion_energy_density = 3e3;
  s.contact.mixing = rule;
  return s;
}

void expect_mixed(const ContactPairParams& p, const std::function<double(double, double)>& rule) {
  expect_relative(p.restitution_beta, beta_of(rule(0.4, 0.8)));
  expect_relative(p.friction_static, rule(0.6, 0.2));
  expect_relative(p.friction_dynamic, rule(0.5, 0.1));
  expect_relative(p.rolling_friction, rule(0.1, 0.3));
  expect_relative(p.rolling_damping, rule(0.2, 0.6));
  expect_relative(p.viscoelastic_time, rule(1e-5, 3e-5));
  expect_relative(p.cohesion_energy_density, rule(1e3, 3e3));
}

TEST(PairTable, EachMixingRule) {
  const std::vector<std::pair<MixingRule, std::function<double(double, double)>>> rules = {
      {MixingRule::Mean, [](double a, double b) { return (a + b) / 2; }},
      {MixingRule::Min, [](double a, double b) { return a < b ? a : b; }},
      {MixingRule::Max, [](double a, double b) { return a > b ? a : b; }},
      {MixingRule::Harmonic, [](double a, double b) { return 2 * a * b / (a + b); }}};
  for (const auto& [rule, formula] : rules) {
    SCOPED_TRACE(static_cast<int>(rule));
    const EngineSetup setup = make_engine_setup(mixing_scene(rule), ParticleStore{});
    expect_mixed(entry(setup, 0, 1), formula);
    expect_mixed(entry(setup, 1, 0), formula);
    expect_relative(entry(setup, 0, 0).friction_static, 0.6);  // a rule of equal values
  }
  // Harmonic mean of two zeros is 0, not 0/0.
  Scene s = mixing_scene(MixingRule::Harmonic);
  s.materials[0].cohesion_energy_density = s.materials[1].cohesion_energy_density = 0;
  EXPECT_EQ(entry(make_engine_setup(s, ParticleStore{}), 0, 1).cohesion_energy_density, 0);
}

TEST(PairTable, DynamicFrictionDefaultsToStatic) {
  Scene s = two_material_scene();
  s.materials[0].friction = 0.6;
  s.materials[1].friction = 0.2;  // friction_dynamic left "not given"
  const EngineSetup setup = make_engine_setup(s, ParticleStore{});
  expect_relative(entry(setup, 0, 1).friction_dynamic, 0.4);
  expect_relative(entry(setup, 1, 1).friction_dynamic, 0.2);
}

TEST(PairTable, PairEntryOverridesBothOrders) {
  Scene s = mixing_scene(MixingRule::Mean);
  PairOverride given;
  given.a = 1, given.b = 0;
  given.restitution = 0.9;
  given.friction = 0.7;
  given.friction_dynamic = 0.65;
  given.rolling_friction = 0.05;
  given.cohesion_energy_density = 5e3;
  s.contact.pairs.push_back(given);
  const EngineSetup setup = make_engine_setup(s, ParticleStore{});
  for (const auto& [a, b] : {std::pair{0u, 1u}, std::pair{1u, 0u}}) {
    const ContactPairParams& p = entry(setup, a, b);
    expect_relative(p.restitution_beta, beta_of(0.9));
    EXPECT_EQ(p.friction_static, 0.7);
    EXPECT_EQ(p.friction_dynamic, 0.65);
    EXPECT_EQ(p.rolling_friction, 0.05);
    EXPECT_EQ(p.cohesion_energy_density, 5e3);
    expect_relative(p.rolling_damping, 0.4);  // not given by the entry: still the mean
    expect_relative(p.viscoelastic_time, 2e-5);
  }
  expect_relative(entry(setup, 0, 0).friction_static, 0.6);  // other pairs keep the rule
  expect_relative(entry(setup, 1, 1).friction_static, 0.2);
}

TEST(PairTable, WallsKeepTheirMaterial) {
  Scene s = two_material_scene();
  WallSettings wall;
  wall.name = "floor";
  wall.normal = {0, 0, 1};
  wall.material = 1;
  s.walls.push_back(wall);
  const EngineSetup setup = make_engine_setup(s, ParticleStore{});
  ASSERT_EQ(setup.walls.size(), 1u);
  EXPECT_EQ(setup.walls[0].material, 1u);
}

double sphere_mass_of(double density, double r) { return 4.0 / 3.0 * kPi * r * r * r * density; }

void add_particle(ParticleStore& p, const Scene& s, MaterialId mat, double r, Vec3 v = {}) {
  p.add(p.size(), {0.5, 0.5, 0.5}, r, mat, v, 1 / sphere_mass_of(s.materials[mat].density, r));
}

/// T_R = π r √(ρ/G) / (0.1631 ν + 0.8766) of one particle, written out.
double rayleigh_of(const Material& m, double r) {
  const double shear = m.young / (2 * (1 + m.poisson));
  return kPi * r * std::sqrt(m.density / shear) / (0.1631 * m.poisson + 0.8766);
}

/// Reduced radius and mass, E* and G* of one Hertz contact.
struct Contact {
  double radius, mass, young, shear;
};

/// Johnson (1985): t_c = 2.87 (m*² / (R* E*² v))^{1/5}.
double hertz_duration(const Contact& c, double v) {
  return 2.87 * std::pow(c.mass * c.mass / (c.radius * c.young * c.young * v), 0.2);
}

/// 2/ω at the peak overlap of an impact at v, the faster of the normal mode (S_n = 2E*√(R*δ),
/// mass m*) and the Mindlin tangential mode (S_t = 8G*√(R*δ), mass 2/7 m*).
double hertz_stable(const Contact& c, double v) {
  const double peak = std::pow(15 * c.mass * v * v / (16 * c.young * std::sqrt(c.radius)), 0.4);
  const double normal = 2 * std::sqrt(c.mass / (2 * c.young * std::sqrt(c.radius * peak)));
  const double tangential =
      2 * std::sqrt(2.0 / 7.0 * c.mass / (8 * c.shear * std::sqrt(c.radius * peak)));
  return std::min(normal, tangential);
}

/// Grains of radius 2 and 3 mm, a steel ball of 5 mm and a steel floor, Hertz contact at the
/// impact speed v. At v = 2 m/s the steel ball's Rayleigh time (5.35e-6 s) is below every Hertz
/// limit; the Hertz limits fall only as v^{-1/5}, so v = 1000 m/s brings 2/ω, and v = 1e4 m/s
/// t_c (4.91e-6 s), below it.
struct HertzFixture {
  Scene scene = two_material_scene();
  ParticleStore particles;
  double v;
  explicit HertzFixture(double speed) : v(speed) {
    scene.materials[0].young = 1e8;
    scene.contact.model = {NormalLaw::Hertz, DampingLaw::Restitution, TangentialLaw::Mindlin,
                           RollingLaw::None, CohesionLaw::None};
    scene.contact.stiffness = 0;
    scene.simulation.impact_speed = speed;
    WallSettings floor;
    floor.normal = {0, 0, 1};
    floor.material = 1;
    scene.walls.push_back(floor);
    add_particle(particles, scene, 0, 3e-3);
    add_particle(particles, scene, 1, 5e-3);
    add_particle(particles, scene, 0, 2e-3);
  }
  /// Every contact the limits consider, by hand: the smallest grain (2 mm) and the steel ball,
  /// with each other, themselves and the floor.
  std::vector<Contact> contacts() const {
    const double mg = sphere_mass_of(2500, 2e-3), ms = sphere_mass_of(7800, 5e-3);
    const double e_gg = 1 / (2 * 0.91 / 1e8), e_ss = 1 / (2 * 0.9375 / 2e11);
    const double e_gs = 1 / (0.91 / 1e8 + 0.9375 / 2e11);
    const double g_grain = 1e8 / 2.6, g_steel = 2e11 / 2.5;  // G = E / (2 (1 + ν))
    const double g_gg = 1 / (2 * 1.7 / g_grain), g_ss = 1 / (2 * 1.75 / g_steel);
    const double g_gs = 1 / (1.7 / g_grain + 1.75 / g_steel);
    return {{1e-3, mg / 2, e_gg, g_gg},
            {2e-3 * 5e-3 / 7e-3, mg * ms / (mg + ms), e_gs, g_gs},
            {2.5e-3, ms / 2, e_ss, g_ss},
            {2e-3, mg, e_gs, g_gs},
            {5e-3, ms, e_ss, g_ss}};
  }
  double duration() const {
    double t = std::numeric_limits<double>::infinity();
    for (const Contact& c : contacts()) t = std::min(t, hertz_duration(c, v));
    return t;
  }
  double hertz_stable_limit() const {
    double t = std::numeric_limits<double>::infinity();
    for (const Contact& c : contacts()) t = std::min(t, hertz_stable(c, v));
    return t;
  }
  double rayleigh() const {
    return std::min(rayleigh_of(scene.materials[0], 2e-3), rayleigh_of(scene.materials[1], 5e-3));
  }
};

TEST(TimeStep, HertzLimitsWhereRayleighTimeBinds) {
  const HertzFixture f(2);
  const TimeStepLimits limits = time_step_limits(f.scene, f.particles, {});
  expect_relative(limits.contact_duration, f.duration());
  expect_relative(limits.rayleigh, f.rayleigh());
  ASSERT_LT(f.rayleigh(), f.hertz_stable_limit());
  expect_relative(limits.stable, f.rayleigh());
  RecordProperty("contact_duration_s", std::to_string(f.duration()));
  RecordProperty("rayleigh_s", std::to_string(f.rayleigh()));
}

TEST(TimeStep, HertzLimitsWhereContactBinds) {
  const HertzFixture f(1000);
  const TimeStepLimits limits = time_step_limits(f.scene, f.particles, {});
  expect_relative(limits.contact_duration, f.duration());
  ASSERT_LT(f.hertz_stable_limit(), f.rayleigh());
  expect_relative(limits.stable, f.hertz_stable_limit());
  RecordProperty("hertz_stable_s", std::to_string(f.hertz_stable_limit()));
}

TEST(TimeStep, HookeContactDurationAndStableLimit) {
  Scene s = two_material_scene();
  ParticleStore particles;
  add_particle(particles, s, 0, 3e-3);
  add_particle(particles, s, 0, 1e-3);
  const double lightest_pair = sphere_mass_of(2500, 1e-3) / 2;
  const double oscillation_limit = 2 * std::sqrt(lightest_pair / 1e4);  // 2/ω = 4.58e-5 s
  TimeStepLimits limits = time_step_limits(s, particles, {});
  expect_relative(limits.contact_duration, kPi * std::sqrt(lightest_pair / 1e4));
  expect_relative(limits.rayleigh, rayleigh_of(s.materials[0], 1e-3));  // 8.65e-5 s
  expect_relative(limits.stable, oscillation_limit);
  // A steel ball is heavier (same t_c) but its Rayleigh time, 3.2e-6 s, now binds.
  add_particle(particles, s, 1, 3e-3);
  limits = time_step_limits(s, particles, {});
  expect_relative(limits.contact_duration, kPi * std::sqrt(lightest_pair / 1e4));
  expect_relative(limits.rayleigh, rayleigh_of(s.materials[1], 3e-3));
  expect_relative(limits.stable, rayleigh_of(s.materials[1], 3e-3));
}

TEST(TimeStep, NoParticlesNoLimits) {
  const TimeStepLimits limits = time_step_limits(two_material_scene(), ParticleStore{}, {});
  EXPECT_TRUE(std::isinf(limits.contact_duration));
  EXPECT_TRUE(std::isinf(limits.rayleigh));
  EXPECT_TRUE(std::isinf(limits.stable));
  EXPECT_EQ(make_engine_setup(two_material_scene(), ParticleStore{}).dt, 1.0);  // end_time
}

TEST(TimeStep, AutoImpactSpeed) {
  Scene s = two_material_scene();
  s.domain.max = {1, 2, 0.5};
  ParticleStore particles;
  add_particle(particles, s, 0, 1e-3, {0.3, 0.4, 0});
  add_particle(particles, s, 0, 1e-3, {0.1, 0, 0});
  // Free fall over H = 0.5 m plus the fastest particle (0.5 m/s).
  expect_relative(impact_speed(s, particles), std::sqrt(2 * 9.81 * 0.5) + 0.5);
  // Tilted gravity, |g| = 5, ĝ = (0.6, 0, −0.8): H = 1·0.6 + 0.5·0.8 = 1 m.
  s.simulation.gravity = {3, 0, -4};
  expect_relative(impact_speed(s, ParticleStore{}), std::sqrt(2 * 5 * 1.0));
  s.simulation.gravity = {0, 0, 0};
  expect_relative(impact_speed(s, particles), 0.5);
  EXPECT_EQ(impact_speed(s, ParticleStore{}), 1.0);
  s.simulation.impact_speed = 7;
  EXPECT_EQ(impact_speed(s, particles), 7.0);
}

/// 3000 particles of three materials with random radii and velocities, one much lighter than
/// its size and material make it (as a saved bed's masses may be).
ParticleStore varied_particles(const Scene& s) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> radius(1e-3, 5e-3), speed(-2, 2);
  ParticleStore p;
  for (int i = 0; i < 3000; ++i)
    add_particle(p, s, static_cast<MaterialId>(i % 3), radius(rng),
                 {speed(rng), speed(rng), speed(rng)});
  p.velocity_inv_mass[1234].w *= 1e3;
  return p;
}

/// `p` followed by a heavier twin of each of its deciding particles (same radius, material and
/// velocity, twice the mass): ties that a later share sees and an earlier one decides.
ParticleStore with_heavier_twins(const Scene& s, ParticleStore p) {
  const ParticleStore deciding = setup_deciding_particles(s, p);
  for (std::size_t k = 0; k < deciding.size(); ++k) {
    const Real4 v = deciding.velocity_inv_mass[k];
    add_particle(p, s, deciding.material[k], deciding.position_radius[k].w, {v.x, v.y, v.z});
    p.velocity_inv_mass.back().w = v.w / 2;
  }
  return p;
}

TEST(TimeStep, DecidingParticlesGiveTheLimitsOfAllAndOfConcatenatedShares) {
  Scene s = two_material_scene();
  s.materials.push_back(material("clay", 1800, 5e6, 0.4));
  s.simulation.dt_auto = true;
  s.simulation.allow_unstable_dt = true;  // the soft Hooke contacts overlap past the limit
  for (const NormalLaw law : {NormalLaw::Hooke, NormalLaw::Hertz}) {
    s.contact.model.normal = law;
    const ParticleStore all = with_heavier_twins(s, varied_particles(s));
    const ParticleStore deciding = setup_deciding_particles(s, all);
    EXPECT_LE(deciding.size(), s.materials.size() + 4);
    const TimeStepLimits expected = time_step_limits(s, all, {}),
                         got = time_step_limits(s, deciding, {});
    EXPECT_EQ(got.rayleigh, expected.rayleigh);
    EXPECT_EQ(got.contact_duration, expected.contact_duration);
    EXPECT_EQ(got.stable, expected.stable);
    EXPECT_EQ(got.max_speed, expected.max_speed);
    EXPECT_EQ(got.displacement, expected.displacement);
    EXPECT_EQ(impact_speed(s, deciding), impact_speed(s, all));
    EXPECT_EQ(make_engine_setup(s, deciding).dt, make_engine_setup(s, all).dt);
    EXPECT_EQ(make_engine_setup(s, deciding).skin, make_engine_setup(s, all).skin);
    EXPECT_EQ(exact_units(s, deciding).force, exact_units(s, all).force);
    EXPECT_EQ(exact_units(s, deciding).torque, exact_units(s, all).torque);
    double r_max = 0, r_max_deciding = 0;
    for (const Real4& q : all.position_radius) r_max = std::max(r_max, q.w);
    for (const Real4& q : deciding.position_radius) r_max_deciding = std::max(r_max_deciding, q.w);
    EXPECT_EQ(r_max_deciding, r_max);
    double least_inverse_mass = 1e300, least_inverse_mass_deciding = 1e300;
    for (const Real4& v : all.velocity_inv_mass)
      least_inverse_mass = std::min(least_inverse_mass, v.w);
    for (const Real4& v : deciding.velocity_inv_mass)
      least_inverse_mass_deciding = std::min(least_inverse_mass_deciding, v.w);
    EXPECT_EQ(least_inverse_mass_deciding, least_inverse_mass);  // the heaviest: pistons' mass
    for (const int ranks : {2, 3, 7}) {
      ParticleStore gathered;
      for (int r = 0; r < ranks; ++r) {
        const ParticleStore part = setup_deciding_particles(s, share_of(all, r, ranks));
        gathered.id.insert(gathered.id.end(), part.id.begin(), part.id.end());
        gathered.position_radius.insert(gathered.position_radius.end(),
                                        part.position_radius.begin(), part.position_radius.end());
        gathered.velocity_inv_mass.insert(gathered.velocity_inv_mass.end(),
                                          part.velocity_inv_mass.begin(),
                                          part.velocity_inv_mass.end());
        gathered.angular_velocity.insert(gathered.angular_velocity.end(),
                                         part.angular_velocity.begin(),
                                         part.angular_velocity.end());
        gathered.material.insert(gathered.material.end(), part.material.begin(),
                                 part.material.end());
      }
      EXPECT_EQ(setup_deciding_particles(s, gathered).id, deciding.id) << ranks << " shares";
    }
  }
}

// The integer sums' units: 2^-40 of the lightest grain's weight under standard gravity, and that
// times the smallest radius, each rounded down to a power of two. A grain of 2 mm and 2500 kg/m³
// weighs 8.21 · 10^-4 N (2^-40 of it 7.47 · 10^-16 N, between 2^-51 and 2^-50); a fixed one
// (inverse mass 0) weighs what its material and radius make it.
TEST(SumUnits, FromTheLightestGrainAndTheSmallestRadius) {
  const Scene s = two_material_scene();
  ParticleStore p;
  add_particle(p, s, 0, 2e-3);
  add_particle(p, s, 1, 3e-3);
  EXPECT_EQ(exact_units(s, p).force, 0x1p-51);
  EXPECT_EQ(exact_units(s, p).torque, 0x1p-60);  // 2^-51 · 2 mm = 8.9 · 10^-19 N m, above 2^-60
  EXPECT_EQ(exact_units(s, p).per_force, 0x1p51);
  // a fixed steel grain of 0.5 mm (4.0 · 10^-5 N; 2^-40 of it 3.6 · 10^-17 N, between 2^-55 and
  // 2^-54): the lightest
  add_particle(p, s, 1, 0.5e-3);
  p.velocity_inv_mass.back().w = 0;
  EXPECT_EQ(exact_units(s, p).force, 0x1p-55);
  EXPECT_EQ(exact_units(s, p).torque, 0x1p-66);  // 2^-55 · 0.5 mm = 1.4 · 10^-20 N m
}

TEST(TimeStep, AutoDtIsFractionOfCriticalStep) {
  for (const double v : {2.0, 1e4}) {  // T_R binds, then t_c
    HertzFixture f(v);
    f.scene.simulation.dt_fraction = 0.2;
    f.scene.simulation.allow_unstable_dt = true;  // 10^4 m/s impacts pass the overlap limit
    EXPECT_EQ(f.duration() < f.rayleigh(), v == 1e4);
    expect_relative(make_engine_setup(f.scene, f.particles).dt,
                    0.2 * std::min(f.rayleigh(), f.duration()));
  }
}

/// "%.4g" of x, as the refusal message writes numbers.
std::string four_digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

TEST(TimeStep, ExplicitDtAboveStableLimitIsRefused) {
  HertzFixture f(1000);
  const double stable = f.hertz_stable_limit();  // below T_R at this speed
  f.scene.simulation.dt_auto = false;
  f.scene.simulation.dt_line = 4;
  f.scene.simulation.dt = 1.01 * stable;
  try {
    make_engine_setup(f.scene, f.particles);
    ADD_FAILURE() << "dt = 1.01 x stable limit accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.file(), "scene.toml");
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.key(), "simulation.dt");
    EXPECT_NE(message.find("stable limit " + four_digits(stable) + " s"), std::string::npos)
        << message;
    EXPECT_NE(message.find("set simulation.allow_unstable_dt = true to run anyway"),
              std::string::npos)
        << message;
  }
  f.scene.simulation.allow_unstable_dt = true;
  EXPECT_EQ(make_engine_setup(f.scene, f.particles).dt, 1.01 * stable);
  f.scene.simulation.allow_unstable_dt = false;
  f.scene.simulation.dt = 0.99 * stable;
  // The step passes; what is refused now is the 1,000 m/s impact itself (peak_overlap).
  const std::string refusal =
      test::input_error_text([&] { make_engine_setup(f.scene, f.particles); });
  EXPECT_EQ(refusal.find("simulation.dt"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("key 'material[0].young'"), std::string::npos) << refusal;
}

/// Writes scenes to a private temporary directory, removed after each test.
class SceneFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("gpudem-setup-test-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& text) {
    const std::string path = (dir_ / "scene.toml").string();
    std::ofstream(path) << text;
    return path;
  }
  std::filesystem::path dir_;
};

/// One 1 cm grain (ρ = 2500, E = 1e7, ν = 0.3) resting on nothing, Hooke with k = 1e4: the
/// stable limit is T_R = 8.654e-4 s (2/ω = 1.447e-3 s is larger), so dt = 1e-3 is refused.
const char* const kUnstableScene = R"([simulation]
end_time = 0.01
gravity = [0, 0, 0]
dt = 1e-3
[domain]
min = [0, 0, 0]
max = [0.1, 0.1, 0.1]
[[material]]
name = "grain"
density = 2500
young = 1e7
[contact]
stiffness = 1e4
[[insert]]
region = {min = [0, 0, 0], max = [0.1, 0.1, 0.1]}
count = 1
radius = 0.01
material = "grain"
[output]
dir = "OUTDIR"
)";

TEST_F(SceneFile, RefusalNamesTheLineOfDt) {
  const Scene s = load_scene(write(kUnstableScene));
  ParticleStore particles;
  add_particle(particles, s, 0, 0.01);
  const double rayleigh = rayleigh_of(s.materials[0], 0.01);
  EXPECT_NEAR(rayleigh, 8.654e-4, 1e-7);
  try {
    make_engine_setup(s, particles);
    ADD_FAILURE() << "dt = 1e-3 accepted above T_R = " << rayleigh;
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(std::string(e.what()).rfind(s.file + ":4: key 'simulation.dt': dt = 0.001 s", 0), 0u)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("T_R = " + four_digits(rayleigh) + " s"),
              std::string::npos)
        << e.what();
  }
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

TEST_F(SceneFile, CommandLineExitsWithInputErrorBeforeWriting) {
  const std::filesystem::path out = dir_ / "out";
  const std::string scene = write(replace_all(kUnstableScene, "OUTDIR", out.string()));
  const test::RunResult refused = test::run_binary("--quiet --backend host " + scene);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("key 'simulation.dt'"), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const test::RunResult allowed = test::run_binary("--quiet --backend host " + scene +
                                                   " --set simulation.allow_unstable_dt=true");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  EXPECT_TRUE(std::filesystem::exists(out));
}

/// A piston (a wall with a mass) of the given mass on top of the unit box, facing down.
WallSettings piston_wall(double mass) {
  WallSettings wall;
  wall.name = "piston";
  wall.point = {0, 0, 1};
  wall.normal = {0, 0, -1};
  wall.mass = mass;
  wall.load = 5;
  wall.mass_line = 9;
  return wall;
}

TEST(Pistons, APistonSlidesWithItsMassAndLoad) {
  Scene s = two_material_scene();
  s.walls = {piston_wall(1e3)};
  WallSettings fixed = piston_wall(0);
  fixed.name = "floor";
  s.walls.push_back(fixed);
  const EngineSetup setup = make_engine_setup(s, ParticleStore{});
  ASSERT_EQ(setup.pistons.size(), 1u);
  EXPECT_EQ(setup.pistons[0].wall, 0u);
  EXPECT_EQ(setup.pistons[0].mass, 1e3);
  EXPECT_EQ(setup.pistons[0].load, 5);
}

// The least mass: a close-packed layer, A / (2√3 r²) spheres of the largest radius on the unit
// box's section A = 1 m², each of the heaviest particle's mass.
TEST(Pistons, APistonLighterThanALayerOfParticlesIsRefused) {
  Scene s = two_material_scene();
  ParticleStore p;
  add_particle(p, s, 0, 0.01);   // the largest radius
  add_particle(p, s, 1, 0.008);  // the heaviest: steel
  const double layer = 1 / (2 * std::sqrt(3.0) * 0.01 * 0.01);
  const double least = layer * sphere_mass_of(7800, 0.008);
  s.walls = {piston_wall(1.01 * least)};
  EXPECT_EQ(make_engine_setup(s, p).pistons.size(), 1u);
  s.walls = {piston_wall(0.99 * least)};
  try {
    make_engine_setup(s, p);
    ADD_FAILURE() << "a piston of 0.99 the least mass accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.line(), 9);
    EXPECT_EQ(e.key(), "wall[0].mass");
    EXPECT_NE(message.find(four_digits(least) + " kg"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace gpudem
