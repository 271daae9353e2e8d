// The periodic images of a sphere that reach into the domain (core/PeriodicImages.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/PeriodicImages.hpp"

namespace gpudem {
namespace {

/// [0, 2] × [0, 1] × [0, 1], periodic along x and y.
DomainSettings periodic_xy() {
  DomainSettings d;
  d.min = {0, 0, 0};
  d.max = {2, 1, 1};
  d.periodic = {true, true, false};
  return d;
}

/// The images visited, sorted by x, then y, then z.
std::vector<std::array<double, 4>> images(const DomainSettings& d, Real4 p) {
  std::vector<std::array<double, 4>> out;
  for_each_image_in_domain(d, p, [&](const Real4& q) { out.push_back({q.x, q.y, q.z, q.w}); });
  std::sort(out.begin(), out.end());
  return out;
}

TEST(PeriodicImages, ASphereClearOfEveryFaceIsItsOnlyImage) {
  using V = std::vector<std::array<double, 4>>;
  EXPECT_EQ(images(periodic_xy(), {1.0, 0.5, 0.5, 0.1}), (V{{1.0, 0.5, 0.5, 0.1}}));
}

TEST(PeriodicImages, ASphereAcrossAPeriodicFaceAlsoLiesAcrossTheOpposite) {
  using V = std::vector<std::array<double, 4>>;
  EXPECT_EQ(images(periodic_xy(), {1.95, 0.5, 0.5, 0.1}),
            (V{{1.95 - 2, 0.5, 0.5, 0.1}, {1.95, 0.5, 0.5, 0.1}}));
}

TEST(PeriodicImages, ASphereAcrossACornerHasFourImages) {
  const auto v = images(periodic_xy(), {0.05, 0.97, 0.5, 0.1});
  ASSERT_EQ(v.size(), 4u);
  EXPECT_DOUBLE_EQ(v[0][0], 0.05);
  EXPECT_DOUBLE_EQ(v[0][1], 0.97 - 1);
  EXPECT_DOUBLE_EQ(v[1][1], 0.97);
  EXPECT_DOUBLE_EQ(v[2][0], 2.05);
  EXPECT_DOUBLE_EQ(v[3][1], 0.97);
}

TEST(PeriodicImages, ACentreOutsideAPeriodicAxisIsBroughtIn) {
  const auto v = images(periodic_xy(), {-3.5, 0.5, 0.5, 0.1});  // 2 periods below x = 0.5
  ASSERT_EQ(v.size(), 1u);
  EXPECT_DOUBLE_EQ(v[0][0], 0.5);
}

TEST(PeriodicImages, NoImageAlongAnAxisThatIsNotPeriodic) {
  const auto v = images(periodic_xy(), {1.0, 0.5, 0.98, 0.1});  // across z = 1
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0][2], 0.98);
}

}  // namespace
}  // namespace gpudem
