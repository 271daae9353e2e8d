// dt = "adaptive": the substeps chosen for a base step against the displacement bound, with
// their hysteresis and cap, and the time of a point of the step grid.
#include "app/AdaptiveStep.hpp"

#include <gtest/gtest.h>

#include "core/StepClock.hpp"

namespace gpudem {
namespace {

// A base step of 1 ms and a reach of 1 mm: a speed of s m/s moves s reaches per base step.
constexpr double kBaseDt = 1e-3, kReach = 1e-3;

TEST(AdaptiveStep, SplitsABaseStepIntoTheLeastPowerOfTwoThatKeepsWithinTheReach) {
  AdaptiveStep step(kBaseDt, kReach, 0, 1);
  EXPECT_EQ(step.next(0.5), 1u);
  EXPECT_EQ(step.next(1.0), 1u);  // exactly the reach
  EXPECT_EQ(step.next(3.0), 4u);
  EXPECT_EQ(step.next(4.5), 8u);
  EXPECT_EQ(step.substeps(), 8u);
}

TEST(AdaptiveStep, ShrinksOnlyAsFarAsKeepsWithinHalfTheReach) {
  AdaptiveStep step(kBaseDt, kReach, 0, 8);
  EXPECT_EQ(step.next(7.9), 8u);  // 4 would do, at less than half the reach only 8
  EXPECT_EQ(step.next(3.9), 8u);  // half the reach needs 8 still
  EXPECT_EQ(step.next(3.5), 8u);
  EXPECT_EQ(step.next(1.9), 4u);  // 1.9 / 4 < 0.5
  EXPECT_EQ(step.next(1.5), 4u);  // grows back only when needed: 2 would do
  EXPECT_EQ(step.next(0.4), 1u);
}

TEST(AdaptiveStep, CountsTheFastestToolAndStopsAtTheCap) {
  AdaptiveStep step(kBaseDt, kReach, 2.0, 1);
  EXPECT_EQ(step.next(0.5), 4u);  // (0.5 + 2) reaches
  EXPECT_EQ(step.next(1e9), kMaxSubsteps);
}

TEST(StepClock, TimeIsTheBaseStepsPlusTheSubstepsDone) {
  StepClock clock{7, 0, 4};
  const double dt = 1.0 / 3.0;
  EXPECT_EQ(clock.time(dt), 7 * dt);
  clock.advance();
  EXPECT_EQ(clock.time(dt), 7 * dt + 1 * (dt / 4));
  for (int k = 0; k < 3; ++k) clock.advance();
  EXPECT_EQ(clock.step, 8u);
  EXPECT_EQ(clock.substep, 0u);
  EXPECT_EQ(clock.time(dt), 8 * dt);
}

}  // namespace
}  // namespace gpudem
