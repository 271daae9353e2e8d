// The limits beside the contact law's: the step in which the fastest particle or tool point
// moves a fraction of the smallest radius, and the peak overlap of an undamped impact (and the
// start-up refusal it drives), each against closed forms written out here.
#include "engine/TimeStepLimits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/InputError.hpp"
#include "engine/SceneSetup.hpp"
#include "support/InputErrorText.hpp"

namespace gpudem {
namespace {

constexpr double kPi = 3.14159265358979323846;

double ball_mass(double density, double r) { return 4.0 / 3.0 * kPi * r * r * r * density; }

/// One material "grain" (ρ 2500, E 1e7, ν 0.3), Hooke k_n = 1e4 N/m, no gravity, a 1 m box.
Scene grain_scene() {
  Scene s;
  s.file = "scene.toml";
  s.simulation.end_time = 1;
  s.simulation.gravity = {0, 0, 0};
  s.domain.min = {0, 0, 0};
  s.domain.max = {1, 1, 1};
  Material grain;
  grain.name = "grain";
  grain.density = 2500;
  grain.young = 1e7;
  grain.poisson = 0.3;
  s.materials = {grain};
  s.contact.stiffness = 1e4;
  return s;
}

void add_grain(ParticleStore& p, double r, Vec3 v = {}) {
  p.add(p.size(), {0.5, 0.5, 0.5}, r, 0, v, 1 / ball_mass(2500, r));
}

void add_floor(Scene& s) {
  WallSettings floor;
  floor.normal = {0, 0, 1};
  floor.material = 0;
  s.walls.push_back(floor);
}

/// Hooke, two 5 mm grains at 2 m/s: δ_max = v √(m*/k_n), m* = m/2 (½ m* v² = ½ k_n δ²).
TEST(PeakOverlap, HookePairOfEqualGrains) {
  Scene s = grain_scene();
  s.simulation.impact_speed = 2;
  ParticleStore p;
  add_grain(p, 5e-3);
  const double m = ball_mass(2500, 5e-3);
  const PeakOverlap o = peak_overlap(s, p, s.simulation.impact_speed);
  EXPECT_NEAR(o.ratio, 2 * std::sqrt(m / 2 / 1e4) / 5e-3, 1e-12);
  EXPECT_EQ(o.speed, 2);
  EXPECT_EQ(o.radius, 5e-3);
  EXPECT_FALSE(o.wall);
  // δ_max is linear in v: 50 % of the radius at v = 0.5 r / √(m*/k_n).
  EXPECT_NEAR(o.unstable_speed, 0.5 * 5e-3 / std::sqrt(m / 2 / 1e4), 1e-9);
}

/// A wall is the deeper contact (m* = m), and a larger grain overlaps more of its radius under
/// Hooke (√m / r grows as √r).
TEST(PeakOverlap, HookeWallAndLargestGrainAreDeepest) {
  Scene s = grain_scene();
  s.simulation.impact_speed = 2;
  add_floor(s);
  ParticleStore p;
  add_grain(p, 2e-3);
  add_grain(p, 5e-3);
  const double m = ball_mass(2500, 5e-3);
  const PeakOverlap o = peak_overlap(s, p, s.simulation.impact_speed);
  EXPECT_NEAR(o.ratio, 2 * std::sqrt(m / 1e4) / 5e-3, 1e-12);
  EXPECT_TRUE(o.wall);
  EXPECT_EQ(o.radius, 5e-3);
}

/// Hertz, a grain against a wall of its own material: δ_max = (15 m v² / (16 E* √r))^{2/5}
/// (Johnson 1985, ch. 11), E* = E / (2 (1 − ν²)).
TEST(PeakOverlap, HertzGrainOnAWall) {
  Scene s = grain_scene();
  s.contact.model.normal = NormalLaw::Hertz;
  s.contact.model.damping = DampingLaw::Restitution;
  s.contact.model.tangential = TangentialLaw::Mindlin;
  s.simulation.impact_speed = 3;
  add_floor(s);
  ParticleStore p;
  add_grain(p, 4e-3);
  const double m = ball_mass(2500, 4e-3), e_star = 1e7 / (2 * (1 - 0.09));
  const double delta = std::pow(15 * m * 9 / (16 * e_star * std::sqrt(4e-3)), 0.4);
  const PeakOverlap o = peak_overlap(s, p, s.simulation.impact_speed);
  EXPECT_NEAR(o.ratio, delta / 4e-3, 1e-12);
  // δ_max ∝ v^{4/5}: the ratio reaches 0.5 at v (0.5 / ratio)^{5/4}.
  EXPECT_NEAR(o.unstable_speed, 3 * std::pow(0.5 / o.ratio, 1.25), 1e-6);
}

/// Past the instability limit the setup is refused, naming the key that stiffens the contact,
/// the overlap and the speed the contact holds; allow_unstable_dt lets it run with a warning.
TEST(PeakOverlap, ImpactPastTheLimitIsRefusedUnlessAllowed) {
  Scene s = grain_scene();
  s.simulation.impact_speed = 20;
  ParticleStore p;
  add_grain(p, 5e-3);
  const double m = ball_mass(2500, 5e-3);
  const double ratio = 20 * std::sqrt(m / 2 / 1e4) / 5e-3;
  ASSERT_GT(ratio, 0.5);
  try {
    make_engine_setup(s, p);
    ADD_FAILURE() << "an impact overlapping " << ratio << " of the radius was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "contact.stiffness");
    const std::string what = e.what();
    char overlap[32], holds[32];
    std::snprintf(overlap, sizeof overlap, "%.4g %%", 100 * ratio);
    std::snprintf(holds, sizeof holds, "%.4g m/s", 0.5 * 5e-3 / std::sqrt(m / 2 / 1e4));
    EXPECT_NE(what.find(std::string("would overlap by ") + overlap), std::string::npos) << what;
    EXPECT_NE(what.find(std::string("holds impacts up to ") + holds), std::string::npos) << what;
  }
  s.contact.model.normal = NormalLaw::Hertz;
  s.simulation.impact_speed = 1e3;
  EXPECT_EQ(test::input_error_text([&] { make_engine_setup(s, p); }).find("'material[0].young'"),
            std::string("scene.toml: key ").size())
      << test::input_error_text([&] { make_engine_setup(s, p); });
  s.simulation.allow_unstable_dt = true;
  const EngineSetup setup = make_engine_setup(s, p);
  const std::vector<std::string> warnings = time_step_warnings(s, p, setup);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("run anyway: simulation.allow_unstable_dt"), std::string::npos);
}

/// Free fall over the whole domain height is an upper bound a settled bed never reaches: past
/// the limit it is warned of, and only the speeds the scene surely has (particles, tools, an
/// explicit impact_speed) are refused.
TEST(PeakOverlap, FreeFallPastTheLimitIsWarnedOfNotRefused) {
  Scene s = grain_scene();
  s.simulation.gravity = {0, 0, -9.81};
  s.contact.stiffness = 300;  // 5 mm grains: 50 % at 3.4 m/s, under √(2 g 1 m) = 4.4 m/s
  ParticleStore p;
  add_grain(p, 5e-3, {0, 0, 0.5});
  EXPECT_EQ(launch_speed(s, p, {}), 0.5);
  const EngineSetup setup = make_engine_setup(s, p);
  const std::vector<std::string> w = time_step_warnings(s, p, setup);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("falling that far at once would stop the run"), std::string::npos) << w[0];
  s.simulation.impact_speed = 4;
  EXPECT_THROW(make_engine_setup(s, p), InputError);
}

/// v_max = √(2 |g| H) + the fastest particle + the fastest mesh point |v| + |ω| ρ + the
/// fastest piston √(2 a L).
TEST(DisplacementLimit, MaxSpeedAddsFallParticleToolAndPistonSpeeds) {
  Scene s = grain_scene();
  s.simulation.gravity = {0, 0, -9.81};
  ParticleStore p;
  add_grain(p, 2e-3, {0, 3, 4});
  add_grain(p, 4e-3, {1, 0, 0});
  EXPECT_NEAR(max_speed(s, p, {}), std::sqrt(2 * 9.81 * 1.0) + 5, 1e-12);
  MeshSettings tool;
  tool.centre = {0.5, 0.5, 0.5};
  tool.keyframes = {{0, {1, 0, 0}, {0, 0, 0}}, {0.5, {0.5, 0, 0}, {0, 0, 10}}};
  s.meshes = {tool};
  MeshWallSetup mesh;
  mesh.mesh.vertices = {{0.5, 0.5, 0.5}, {0.7, 0.5, 0.5}, {0.5, 0.65, 0.5}};
  // keyframe 2: 0.5 + 10 × 0.2 beats keyframe 1's 1 m/s
  EXPECT_NEAR(max_speed(s, p, {mesh}), std::sqrt(2 * 9.81 * 1.0) + 5 + 2.5, 1e-12);
  // A piston of 2 kg pressed down with 30 N across the unit box: a = (30 + 2 × 9.81) / 2.
  WallSettings piston;
  piston.point = {0, 0, 1};
  piston.normal = {0, 0, -1};
  piston.mass = 2;
  piston.load = 30;
  s.walls = {piston};
  EXPECT_NEAR(max_speed(s, p, {mesh}),
              std::sqrt(2 * 9.81 * 1.0) + 5 + 2.5 + std::sqrt(2 * (30 + 2 * 9.81) / 2 * 1.0),
              1e-12);
}

/// dt = "auto" is dt_fraction × the critical step, at most displacement_fraction × r_min / v_max.
TEST(DisplacementLimit, BoundsTheAutomaticStepOfFastParticles) {
  Scene s = grain_scene();
  s.contact.stiffness = 1e6;
  s.simulation.impact_speed = 1;  // the contact law's limits at 1 m/s
  ParticleStore p;
  add_grain(p, 1e-3);
  add_grain(p, 1e-3, {0, 0, 200});
  const double m = ball_mass(2500, 1e-3);
  const double rayleigh = kPi * 1e-3 * std::sqrt(2500 / (1e7 / 2.6)) / (0.1631 * 0.3 + 0.8766);
  const double contact = std::min(kPi * std::sqrt(m / 2 / 1e6), rayleigh);
  const double displacement = 0.1 * 1e-3 / 200;
  ASSERT_LT(displacement, 0.1 * contact);
  const TimeStepLimits limits = time_step_limits(s, p, {});
  EXPECT_NEAR(limits.displacement, displacement, 1e-18);
  EXPECT_EQ(limits.max_speed, 200);
  EXPECT_NEAR(make_engine_setup(s, p).dt, displacement, 1e-18);
  s.simulation.displacement_fraction = 1;
  EXPECT_NEAR(make_engine_setup(s, p).dt, std::min(0.1 * contact, 1e-3 / 200), 1e-15);
}

/// An explicit dt that lets the fastest particle move more than displacement_fraction of the
/// smallest radius is run with a warning; within it, without.
TEST(DisplacementLimit, ExplicitStepBeyondItIsWarnedOf) {
  Scene s = grain_scene();
  s.simulation.impact_speed = 0.1;  // impacts well held: only the displacement is at stake
  ParticleStore p;
  add_grain(p, 1e-3, {0, 0, 10});
  s.simulation.dt_auto = false;
  s.simulation.dt = 2e-5;  // 10 m/s × 2e-5 s = 0.2 r
  const std::vector<std::string> w = time_step_warnings(s, p, make_engine_setup(s, p));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("move 0.2 of the smallest radius"), std::string::npos) << w[0];
  s.simulation.dt = 5e-6;
  EXPECT_TRUE(time_step_warnings(s, p, make_engine_setup(s, p)).empty());
}

}  // namespace
}  // namespace gpudem
