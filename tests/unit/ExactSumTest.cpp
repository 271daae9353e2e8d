// Integer sums of contact loads: the same bits in any order, exact cancellation of a term and
// its negative, a resolution of 2^-64, exact results through intermediate wrap-around, and NaN
// once a term is beyond the limit or not finite.
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
  for (const Vec3& f : loads) sum.add(exact_terms(f));
  return sum.value<double>();
}

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

TEST(ExactSum, TheSameBitsInAnyOrder) {
  std::vector<Vec3> loads = random_loads(500, 1e3, 7);
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
    sum.add(exact_terms(f));
    sum.subtract(exact_terms(-f));  // subtracting −f adds f once more
    sum.subtract(exact_terms(f));
    sum.add(exact_terms(-f));
  }
  const Vec3 v = sum.value<double>();
  EXPECT_TRUE(same_bits(v, Vec3{0, 0, 0})) << v.x << " " << v.y << " " << v.z;
}

TEST(ExactSum, WithinTheResolutionOfTheTrueSum) {
  const std::vector<Vec3> loads = random_loads(1000, 50, 5);
  __float128 x = 0, y = 0, z = 0;  // 113-bit sums: their own error is below 10^-23 N here
  for (const Vec3& f : loads) {
    x += f.x;
    y += f.y;
    z += f.z;
  }
  const Vec3 v = exact_sum(loads);
  // Each term rounds by at most half a step of 2^-64 N; the value's own rounding to double
  // adds half an ulp.
  const double per_term = std::ldexp(1.0, -65) * static_cast<double>(loads.size());
  const auto error = [](double value, __float128 truth) {
    return static_cast<double>(static_cast<__float128>(value) - truth);
  };
  EXPECT_LE(std::fabs(error(v.x, x)), per_term + std::fabs(v.x) * 0x1p-53);
  EXPECT_LE(std::fabs(error(v.y, y)), per_term + std::fabs(v.y) * 0x1p-53);
  EXPECT_LE(std::fabs(error(v.z, z)), per_term + std::fabs(v.z) * 0x1p-53);
  EXPECT_NE(v.z, 0.0);  // nanonewton terms are resolved, not lost
}

TEST(ExactSum, ExactThroughIntermediateWrapAround) {
  // 20,000 terms of 0.9 · 2^30 N reach 1.9 · 10^13 N, beyond the 2^43 N a 64-bit word holds,
  // before as many negative ones bring the sum back: the result is exact.
  const Vec3 big{0.9 * exact_term_limit, -0.9 * exact_term_limit, 0.25};
  ExactSum3 sum;
  for (int k = 0; k < 20000; ++k) sum.add(exact_terms(big));
  for (int k = 0; k < 20000; ++k) sum.subtract(exact_terms(big));
  sum.add(exact_terms(Vec3{1.5, -2.5, 0.125}));
  const Vec3 v = sum.value<double>();
  EXPECT_EQ(v.x, 1.5);
  EXPECT_EQ(v.y, -2.5);
  EXPECT_EQ(v.z, 0.125);
}

TEST(ExactSum, ATermBeyondTheLimitOrNotFiniteMakesTheSumNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Vec3& bad : {Vec3{exact_term_limit, 0, 0}, Vec3{0, -1.5 * exact_term_limit, 0},
                          Vec3{0, 0, nan}, Vec3{inf, 0, 0}}) {
    ExactSum3 added;
    added.add(exact_terms(Vec3{1, 2, 3}));
    added.add(exact_terms(bad));
    const Vec3 a = added.value<double>();
    EXPECT_TRUE(std::isnan(a.x) && std::isnan(a.y) && std::isnan(a.z));
    ExactSum3 subtracted;
    subtracted.subtract(exact_terms(bad));
    subtracted.add(exact_terms(Vec3{1, 2, 3}));
    EXPECT_TRUE(std::isnan(subtracted.value<float>().x));
  }
  ExactSum3 edge;  // just below the limit is a number
  edge.add(exact_terms(Vec3{std::nextafter(exact_term_limit, 0.0), 0, 0}));
  EXPECT_EQ(edge.value<double>().x, std::nextafter(exact_term_limit, 0.0));
}

}  // namespace
}  // namespace gpudem::test
