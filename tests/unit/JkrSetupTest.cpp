// What JKR adhesion asks of the engine setup: the pair's surface energy from the mixing rule or a
// [[pair]] entry, a neighbour skin that covers the pull-off gap (the list must keep a contact
// until it parts), and a stable step from the JKR contact radius, which stays a₀ > 0 at the
// slowest impact, each against values written out here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/InputError.hpp"
#include "engine/SceneSetup.hpp"

namespace gpudem {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadius = 1e-3, kDensity = 2500;

Material sticky(const std::string& name, double gamma) {
  Material m;
  m.name = name;
  m.density = kDensity;
  m.young = 1e7;
  m.poisson = 0.3;
  m.surface_energy = gamma;
  return m;
}

/// Two sticky materials, Hertz–Mindlin with JKR, one grain of each at rest, no walls.
Scene sticky_scene() {
  Scene s;
  s.file = "scene.toml";
  s.simulation.end_time = 1;
  s.domain.min = {0, 0, 0};
  s.domain.max = {1, 1, 1};
  s.materials = {sticky("wet", 0.4), sticky("dry", 0.1)};
  s.contact.model = {NormalLaw::Hertz, DampingLaw::Restitution, TangentialLaw::Mindlin,
                     RollingLaw::None, CohesionLaw::Jkr};
  return s;
}

ParticleStore one_grain_each() {
  ParticleStore p;
  const double inv_mass = 1 / (4.0 / 3.0 * kPi * kRadius * kRadius * kRadius * kDensity);
  p.add(0, {0.5, 0.5, 0.5}, kRadius, 0, {}, inv_mass);
  p.add(1, {0.2, 0.5, 0.5}, kRadius, 1, {}, inv_mass);
  return p;
}

/// E* of two like materials, E / (2 (1 − ν²)).
double pair_young() { return 1e7 / (2 * (1 - 0.09)); }

/// |δ_c| = (3/4)(π²γ²R*/E*²)^{1/3}.
double parting_gap(double gamma, double radius) {
  return 0.75 * std::cbrt(kPi * kPi * gamma * gamma * radius / (pair_young() * pair_young()));
}

TEST(JkrSetup, SurfaceEnergyMixesByTheRuleUnlessAPairEntryGivesIt) {
  Scene s = sticky_scene();
  s.contact.mixing = MixingRule::Harmonic;
  EXPECT_NEAR(pair_params(s, 0, 1).surface_energy, 2 * 0.4 * 0.1 / 0.5, 1e-15);
  EXPECT_NEAR(pair_params(s, 0, 0).surface_energy, 0.4, 1e-15);
  PairOverride given;
  given.a = 1, given.b = 0;
  given.surface_energy = 0.05;
  s.contact.pairs.push_back(given);
  EXPECT_EQ(pair_params(s, 0, 1).surface_energy, 0.05);
  EXPECT_EQ(pair_params(s, 1, 0).surface_energy, 0.05);
  EXPECT_EQ(make_engine_setup(s, one_grain_each()).pair_params[1].surface_energy, 0.05);
}

/// The largest gap: the stickiest pair (γ = 0.4, mean rule: wet–wet) at R* = r_max, a wall's.
TEST(JkrSetup, ASkinThatDoesNotCoverThePullOffGapIsRefused) {
  Scene s = sticky_scene();
  const double gap = parting_gap(0.4, kRadius);
  s.neighbor.skin = 1.01 * gap;
  EXPECT_EQ(make_engine_setup(s, one_grain_each()).skin, 1.01 * gap);
  s.neighbor.skin = 0.99 * gap;
  try {
    make_engine_setup(s, one_grain_each());
    ADD_FAILURE() << "a skin of 0.99 the pull-off gap accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "neighbor.skin");
    EXPECT_NE(std::string(e.what()).find("pull-off gap"), std::string::npos) << e.what();
  }
  s.contact.model.cohesion = CohesionLaw::Sjkr;  // parts at touch: any skin will do
  EXPECT_NO_THROW(make_engine_setup(s, one_grain_each()));
}

/// The contact radius a with δ(a) = a²/R* − √(2πγa/E*) = δ on the branch a ≥ a_c, by bisection.
double jkr_radius(double gamma, double radius, double overlap) {
  const double young = pair_young();
  double lo = std::cbrt(kPi * gamma * radius * radius / (8 * young)), hi = 1;
  for (int k = 0; k < 200; ++k) {
    const double a = 0.5 * (lo + hi);
    (a * a / radius - std::sqrt(2 * kPi * gamma * a / young) < overlap ? lo : hi) = a;
  }
  return 0.5 * (lo + hi);
}

/// At 1 mm/s the Hertz peak overlap is tiny and JKR's contact radius far larger than
/// √(R* δ_max): the stable step, 2/ω of the normal (2E* a on m*) and Mindlin (8G* a on 2/7 m*)
/// modes, is that of the JKR radius. γ = 20 J/m² makes it shorter than the Rayleigh time.
TEST(JkrSetup, TheStableStepTakesTheJkrContactRadiusAtThePeakOverlap) {
  const double gamma = 20;
  Scene s = sticky_scene();
  s.materials = {sticky("wet", gamma)};
  s.simulation.impact_speed = 1e-3;
  ParticleStore p;
  const double mass = 4.0 / 3.0 * kPi * kRadius * kRadius * kRadius * kDensity;
  p.add(0, {0.5, 0.5, 0.5}, kRadius, 0, {}, 1 / mass);
  const double r_star = kRadius / 2, m_star = mass / 2, v = 1e-3, e = pair_young();
  const double peak = std::pow(15 * m_star * v * v / (16 * e * std::sqrt(r_star)), 0.4);
  const double a = jkr_radius(gamma, r_star, peak);
  ASSERT_GT(a, 3 * std::sqrt(r_star * peak));
  const double shear = 1 / (2 * (2 - 0.3) / (1e7 / 2.6));
  const double normal = 2 * std::sqrt(m_star / (2 * e * a));
  const double tangential = 2 * std::sqrt(2.0 / 7.0 * m_star / (8 * shear * a));
  const double expected = std::min(normal, tangential);
  const TimeStepLimits limits = time_step_limits(s, p, {});
  ASSERT_LT(expected, limits.rayleigh);
  EXPECT_NEAR(limits.stable, expected, 1e-9 * expected);
}

}  // namespace
}  // namespace gpudem
