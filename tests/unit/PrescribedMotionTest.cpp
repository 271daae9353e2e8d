// Prescribed tool motion: piecewise-linear velocities, their exact integrals, and the rigid
// step, against hand integration.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/PrescribedMotion.hpp"

namespace gpudem {
namespace {

constexpr double kPi = 3.14159265358979323846;

void expect_near(Vec3 a, Vec3 b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

/// 0.7 m/s along x from t = 0.1 s to t = 1.1 s: a constant-speed pass with a start and a stop.
PrescribedMotion constant_pass() {
  return PrescribedMotion({0, 0, 0}, {{0.1, {0.7, 0, 0}, {}}, {1.1, {0.7, 0, 0}, {}}});
}

TEST(PrescribedMotion, StandsStillOutsideItsKeyframes) {
  const PrescribedMotion m = constant_pass();
  expect_near(m.velocity(0.05), {0, 0, 0}, 0);
  expect_near(m.velocity(0.6), {0.7, 0, 0}, 0);
  expect_near(m.velocity(1.2), {0, 0, 0}, 0);
  expect_near(m.displacement(0, 2), {0.7, 0, 0}, 1e-15);  // 0.7 m/s for 1 s
  expect_near(m.displacement(0.6, 0.8), {0.14, 0, 0}, 1e-15);
  expect_near(m.centre(0.35), {0.7 * 0.25, 0, 0}, 1e-15);
}

/// A ramp from 0 to 1 m/s over 1 s, then 1 m/s until 3 s: x(t) = t²/2 on the ramp.
TEST(PrescribedMotion, IntegratesARampExactly) {
  const PrescribedMotion m({0, 0, 0}, {{0, {}, {}}, {1, {0, 0, 1}, {}}, {3, {0, 0, 1}, {}}});
  expect_near(m.velocity(0.25), {0, 0, 0.25}, 1e-15);
  expect_near(m.displacement(0, 0.5), {0, 0, 0.125}, 1e-15);
  expect_near(m.displacement(0.5, 2), {0, 0, 0.5 - 0.125 + 1}, 1e-15);
  double sum = 0;  // steps that cross the keyframe at 1 s add up to the whole
  for (int k = 0; k < 30; ++k) sum += m.displacement(0.1 * k, 0.1 * (k + 1)).z;
  EXPECT_NEAR(sum, 0.5 + 2, 1e-13);
}

/// A tool spinning at 2π rad/s about z through a centre at (1, 0, 0) for 0.25 s turns a quarter.
TEST(PrescribedMotion, RotatesAboutItsCentre) {
  const PrescribedMotion m({1, 0, 0}, {{0, {}, {0, 0, 2 * kPi}}, {1, {}, {0, 0, 2 * kPi}}});
  const RigidIncrement step = m.increment(0, 0.25);
  expect_near(step.move({2, 0, 0}), {1, 1, 0}, 1e-15);
  expect_near(step.move({1, 0, 5}), {1, 0, 5}, 1e-15);  // on the axis
  expect_near(m.rotation_vector(0, 0.25), {0, 0, kPi / 2}, 1e-15);
}

/// Translation and rotation together: the centre moves, and each step turns about the centre
/// where the step starts. 100 steps of 0.01 s at 1 m/s along y and π/2 rad/s about z bring
/// (1, 0, 0), one metre from the centre, to the centre + (0, 1, 0) + (0, 1, 0).
TEST(PrescribedMotion, StepsComposeTranslationAndRotation) {
  const PrescribedMotion m({0, 0, 0},
                           {{0, {0, 1, 0}, {0, 0, kPi / 2}}, {2, {0, 1, 0}, {0, 0, kPi / 2}}});
  Vec3 x{1, 0, 0};
  for (int k = 0; k < 100; ++k) x = m.increment(0.01 * k, 0.01).move(x);
  expect_near(m.centre(1), {0, 1, 0}, 1e-14);
  expect_near(x, {0, 2, 0}, 1e-12);
}

TEST(PrescribedMotion, RefusesKeyframesOutOfOrderOrNotFinite) {
  EXPECT_THROW(PrescribedMotion({0, 0, 0}, {{1, {}, {}}, {1, {}, {}}}), std::invalid_argument);
  EXPECT_THROW(PrescribedMotion({0, 0, 0}, {{1, {}, {}}, {0.5, {}, {}}}), std::invalid_argument);
  EXPECT_THROW(PrescribedMotion({0, 0, 0}, {{0, {NAN, 0, 0}, {}}}), std::invalid_argument);
  EXPECT_THROW(PrescribedMotion({INFINITY, 0, 0}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace gpudem
