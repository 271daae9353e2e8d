// Integer sums of contact loads in a run's unit: the same bits in any order, exact cancellation
// of a term and its negative, half a unit of resolution per term, exact results through
// intermediate wrap-around, terms beyond 2^50 units spilled without changing any value, NaN once
// a term is beyond the limit or not finite; the units chosen from a run's grains; and the
// particle arrays that read spills only after one was written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "engine/ExactSum.hpp"

namespace gpudem::test {
namespace {

/// Units of 2^-44 N and 2^-54 N m (ExactUnits' defaults): one-word terms up to 64 N.
const ExactUnits kUnits{};

/// Loads whose x spans ±scale, y ±scale · 10^(±6) and z nanonewtons.
std::vector<Vec3> random_loads(std::size_t n, double scale, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> loads(n);
  for (Vec3& f : loads) f = {scale * u(rng), scale * std::pow(10.0, 6 * u(rng)), u(rng) * 1e-9};
  return loads;
}

Vec3 exact_sum(const std::vector<Vec3>& loads) {
  ExactSum3 sum;
  for (const Vec3& f : loads) sum.add(exact_terms(f, kUnits.per_force));
  return sum.value<double>(kUnits.force);
}

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

TEST(ExactSum, TheSameBitsInAnyOrder) {
  std::vector<Vec3> loads = random_loads(500, 1e3, 7);  // y up to 10^9 N: many terms spill
  const Vec3 first = exact_sum(loads);
  std::mt19937_64 rng(3);
  for (int round = 0; round < 20; ++round) {
    std::shuffle(loads.begin(), loads.end(), rng);
    ASSERT_TRUE(same_bits(exact_sum(loads), first)) << "round " << round;
  }
}

TEST(ExactSum, ATermAndItsNegativeCancelExactly) {
  ExactSum3 sum;
  for (const Vec3& f : random_loads(300, 1e3, 11)) {
    const double u = kUnits.per_force;
    sum.add(exact_terms(f, u));
    sum.subtract(exact_terms(-f, u));  // subtracting −f adds f once more
    sum.subtract(exact_terms(f, u));
    sum.add(exact_terms(-f, u));
  }
  const Vec3 v = sum.value<double>(kUnits.force);
  EXPECT_TRUE(same_bits(v, Vec3{0, 0, 0})) << v.x << " " << v.y << " " << v.z;
}

TEST(ExactSum, WithinHalfAUnitPerTermOfTheTrueSum) {
  const std::vector<Vec3> loads = random_loads(1000, 50, 5);
  __float128 x = 0, y = 0, z = 0;  // 113-bit sums: their own error is below 10^-23 N here
  for (const Vec3& f : loads) {
    x += f.x;
    y += f.y;
    z += f.z;
  }
  const Vec3 v = exact_sum(loads);
  // Each term rounds by at most half a unit; the value's own rounding to double adds half an
  // ulp.
  const double per_term = 0.5 * kUnits.force * static_cast<double>(loads.size());
  const auto error = [](double value, __float128 truth) {
    return static_cast<double>(static_cast<__float128>(value) - truth);
  };
  EXPECT_LE(std::fabs(error(v.x, x)), per_term + std::fabs(v.x) * 0x1p-53);
  EXPECT_LE(std::fabs(error(v.y, y)), per_term + std::fabs(v.y) * 0x1p-53);
  EXPECT_LE(std::fabs(error(v.z, z)), per_term + std::fabs(v.z) * 0x1p-53);
  EXPECT_NE(v.z, 0.0);  // nanonewton terms are resolved, not lost
}

TEST(ExactSum, ExactThroughIntermediateWrapAround) {
  // 20,000 terms of 0.9 · 2^50 units, one word each, reach 1.8 · 2^64 units before as many
  // negative ones bring the sum back: the result is exact.
  const double big = 0.9 * exact_word_limit * kUnits.force;
  const Vec3 load{big, -big, 0.25};
  ExactSum3 sum;
  for (int k = 0; k < 20000; ++k) sum.add(exact_terms(load, kUnits.per_force));
  for (int k = 0; k < 20000; ++k) sum.subtract(exact_terms(load, kUnits.per_force));
  EXPECT_FALSE(exact_terms(load, kUnits.per_force).spilled);
  sum.add(exact_terms(Vec3{1.5, -2.5, 0.125}, kUnits.per_force));
  const Vec3 v = sum.value<double>(kUnits.force);
  EXPECT_EQ(v.x, 1.5);
  EXPECT_EQ(v.y, -2.5);
  EXPECT_EQ(v.z, 0.125);
}

TEST(ExactSum, ATermSpillsFromTwoToThe50UnitsAndKeepsItsValue) {
  const double u = kUnits.force;
  const double below = std::nextafter(exact_word_limit, 0.0) * u;
  EXPECT_FALSE(exact_terms(Vec3{below, -below, 0}, kUnits.per_force).spilled);
  EXPECT_TRUE(exact_terms(Vec3{0, exact_word_limit * u, 0}, kUnits.per_force).spilled);
  // 3 · 2^50 + 5 units, and 2^60 + 2^8 units: the spilled sum is the exact integer, rounded once
  for (const double units : {3 * exact_word_limit + 5, 0x1p60 + 0x1p8}) {
    ExactSum3 sum;
    sum.add(exact_terms(Vec3{units * u, -units * u, 0}, kUnits.per_force));
    sum.subtract(exact_terms(Vec3{256 * u, 0, 0}, kUnits.per_force));
    const Vec3 v = sum.value<double>(u);
    EXPECT_EQ(v.x, (units - 256) * u);
    EXPECT_EQ(v.y, -units * u);
  }
  // The same value split at either side of 2^50 units (as lanes that spill split every lane):
  // a term of 0.75 · 2^50 units as one word, and as a spill of 1 and a word of −0.25 · 2^50
  const double three_quarters = 0.75 * exact_word_limit;
  const ExactTerm3 one_word = exact_terms(Vec3{three_quarters * u, 0, 0}, kUnits.per_force);
  const ExactTerm3 split = exact_terms_in_units(three_quarters, 0, 0);
  ASSERT_FALSE(one_word.spilled);
  ASSERT_EQ(split.spill[0], 1u);
  ExactSum3 a, b;
  for (int k = 0; k < 5; ++k) {
    a.add(one_word);
    b.add(split);
  }
  a.add(exact_terms(Vec3{1e-3, 0, 0}, kUnits.per_force));
  b.add(exact_terms(Vec3{1e-3, 0, 0}, kUnits.per_force));
  EXPECT_TRUE(same_bits(a.value<double>(u), b.value<double>(u)));
}

TEST(ExactSum, TheValueIsTheExactIntegerRoundedOnce) {
  // One-word terms bring the word to 2^55 + 3 units, which a double holds only to 8 units; a
  // spilled term of −28 · 2^50 units then leaves 2^52 + 3, which a double holds exactly. The
  // word rounded on its own would give 2^52.
  const double u = kUnits.force, per_unit = kUnits.per_force;
  ExactSum3 sum;
  for (int k = 0; k < 32; ++k)
    sum.add(exact_terms(Vec3{(exact_word_limit - 1) * u, 0, 0}, per_unit));
  for (int k = 0; k < 35; ++k) sum.add(exact_terms(Vec3{u, 0, 0}, per_unit));
  sum.add(exact_terms(Vec3{-28 * exact_word_limit * u, 0, 0}, per_unit));
  EXPECT_EQ(sum.value<double>(u).x, (0x1p52 + 3) * u);
}

TEST(ExactSum, ATermBeyondTheLimitOrNotFiniteMakesTheSumNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double limit = exact_spill_limit * kUnits.force;
  for (const Vec3& bad :
       {Vec3{limit, 0, 0}, Vec3{0, -1.5 * limit, 0}, Vec3{0, 0, nan}, Vec3{inf, 0, 0}}) {
    ExactSum3 added;
    added.add(exact_terms(Vec3{1, 2, 3}, kUnits.per_force));
    added.add(exact_terms(bad, kUnits.per_force));
    const Vec3 a = added.value<double>(kUnits.force);
    EXPECT_TRUE(std::isnan(a.x) && std::isnan(a.y) && std::isnan(a.z));
    ExactSum3 subtracted;
    subtracted.subtract(exact_terms(bad, kUnits.per_force));
    subtracted.add(exact_terms(Vec3{1, 2, 3}, kUnits.per_force));
    EXPECT_TRUE(std::isnan(subtracted.value<float>(kUnits.force).x));
  }
  ExactSum3 edge;  // just below the limit is a number
  const double just_below = std::nextafter(limit, 0.0);
  edge.add(exact_terms(Vec3{just_below, 0, 0}, kUnits.per_force));
  EXPECT_EQ(edge.value<double>(kUnits.force).x, just_below);
}

TEST(ExactUnits, FromTheLightestGrainsWeightAndTheSmallestRadius) {
  // A soil grain of R = 8.5 mm and 1850 kg/m³ weighs 0.0467 N: 2^-40 of it is 4.2 · 10^-14 N,
  // between 2^-45 and 2^-44; 2^-45 N times the radius is 2.4 · 10^-16 N m, between 2^-52 and
  // 2^-51.
  const ExactUnits soil = exact_units_for_grains(0.0467, 0.0085);
  EXPECT_EQ(soil.force, 0x1p-45);
  EXPECT_EQ(soil.torque, 0x1p-52);
  EXPECT_EQ(soil.per_force, 0x1p45);
  EXPECT_EQ(soil.per_torque, 0x1p52);
  // a weight of exactly 2^-4 N: its 2^-40 is the unit itself
  EXPECT_EQ(exact_units_for_grains(0x1p-4, 1.0).force, 0x1p-44);
  EXPECT_EQ(exact_units_for_grains(0x1p-4, 1.0).torque, 0x1p-44);
  // a 10 µm quartz grain, 1.4 · 10^-11 N, and a 0.5 m rock, 1.3 · 10^4 N: the unit follows
  const ExactUnits dust = exact_units_for_grains(1.4e-11, 1e-5);
  EXPECT_LE(dust.force, 1.4e-11 * 0x1p-40);
  EXPECT_GT(dust.force, 1.4e-11 * 0x1p-41);
  const ExactUnits rock = exact_units_for_grains(1.3e4, 0.5);
  EXPECT_LE(rock.force, 1.3e4 * 0x1p-40);
  EXPECT_GT(rock.force, 1.3e4 * 0x1p-41);
}

TEST(ExactSumArrays, SpillsAreReadOnlyOnceOneWasWrittenAndClearedForTheNextSweep) {
  ExactSumStore store;
  store.resize(3);
  ExactSumArrays sums = store.arrays();
  const double u = kUnits.force;
  sums.clear(0);
  sums.clear(1);
  sums.add(0, exact_terms(Vec3{1, 2, 3}, kUnits.per_force));
  sums.subtract(1, exact_terms(Vec3{1, 2, 3}, kUnits.per_force));
  EXPECT_FALSE(sums.spilled->load());
  EXPECT_EQ(sums[0].value<double>(u).z, 3.0);
  const double spilling = 4 * exact_word_limit * u;  // 256 N
  sums.add(1, exact_terms(Vec3{spilling, 0, 0}, kUnits.per_force));
  EXPECT_TRUE(sums.spilled->load());
  EXPECT_EQ(sums[1].value<double>(u).x, spilling - 1);
  EXPECT_EQ(sums[0].value<double>(u).x, 1.0);  // its spill read: zero
  // the next sweep starts from zero spills and an unset flag
  sums = store.arrays();
  EXPECT_FALSE(sums.spilled->load());
  sums.clear(1);
  EXPECT_EQ(sums[1].value<double>(u).x, 0.0);
  sums.add(1, exact_terms(Vec3{-spilling, 0, 0}, kUnits.per_force));
  EXPECT_EQ(sums[1].value<double>(u).x, -spilling);
}

}  // namespace
}  // namespace gpudem::test
