#pragma once
// Scenes, sources and checks for the tests of particle insertion: a unit-cube domain with two
// materials, radius distributions and box sources, and the checks that inserted spheres lie
// inside their region and do not overlap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"

namespace gpudem::test {

inline constexpr double kPi = 3.14159265358979323846;

inline double ball_volume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

/// The unit cube [0, 1]^3 with materials "soil" (2000 kg/m³) and "steel" (7800 kg/m³).
inline Scene insertion_scene(std::uint64_t seed = 7) {
  Scene scene;
  scene.file = "scene.toml";
  scene.simulation.seed = seed;
  scene.domain.min = {0, 0, 0};
  scene.domain.max = {1, 1, 1};
  scene.materials.push_back({"soil", 2000.0});
  scene.materials.push_back({"steel", 7800.0});
  return scene;
}

inline RadiusDistribution uniform(double mean, double spread) {
  RadiusDistribution d;
  d.kind = RadiusDistributionKind::Uniform;
  d.mean = mean;
  d.spread = spread;
  return d;
}

inline RadiusDistribution discrete(std::vector<double> values, std::vector<double> weights) {
  RadiusDistribution d;
  d.kind = RadiusDistributionKind::Discrete;
  d.values = std::move(values);
  d.weights = std::move(weights);
  return d;
}

/// A box source of `count` spheres (0: give volume_fraction), material 0, placed sequentially.
inline ParticleSource box(Vec3 lo, Vec3 hi, std::uint64_t count, RadiusDistribution radius) {
  ParticleSource s;
  s.kind = SourceKind::Box;
  s.region_min = lo;
  s.region_max = hi;
  s.count = count;
  s.radius = std::move(radius);
  return s;
}

/// Every pair of particles with at least one in [first, size): no overlap, i.e.
/// |x_i - x_j| >= (r_i + r_j)(1 - 1e-12), the factor allowing for rounding of touching spheres.
/// A sweep along x: only pairs closer in x than r_i + the largest radius are compared.
inline void expect_no_overlaps(const ParticleStore& store, std::size_t first = 0) {
  std::vector<std::size_t> order(store.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto& p = store.position_radius;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return p[a].x < p[b].x; });
  double r_max = 0;
  for (const Real4& q : p) r_max = std::max(r_max, double(q.w));
  std::size_t overlaps = 0;
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a + 1;
         b < order.size() && p[order[b]].x - p[order[a]].x < p[order[a]].w + r_max; ++b) {
      const std::size_t i = order[a], j = order[b];
      if (i < first && j < first) continue;
      const double contact = (p[i].w + p[j].w) * (1 - 1e-12);
      if (norm2(xyz(p[i]) - xyz(p[j])) < contact * contact) ++overlaps;
    }
  EXPECT_EQ(overlaps, 0u);
}

/// Particles [first, last) lie wholly inside [lo, hi] (to 1e-12 m of rounding).
inline void expect_inside(const ParticleStore& store, std::size_t first, std::size_t last, Vec3 lo,
                          Vec3 hi) {
  std::size_t outside = 0;
  for (std::size_t n = first; n < last; ++n) {
    const Real4& p = store.position_radius[n];
    for (int k = 0; k < 3; ++k)
      if (axis(xyz(p), k) - p.w < axis(lo, k) - 1e-12 ||
          axis(xyz(p), k) + p.w > axis(hi, k) + 1e-12)
        ++outside;
  }
  EXPECT_EQ(outside, 0u);
}

}  // namespace gpudem::test
