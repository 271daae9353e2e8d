#include "engine/BondClods.hpp"

#include <random>
#include <stdexcept>
#include <string>

#include "core/InputError.hpp"
#include "core/RadiusSampling.hpp"

namespace gpudem {
namespace {

constexpr int kAttempts = 1000;

/// True when a sphere at `centre` of `radius` overlaps none of `placed`.
bool has_room(const std::vector<Real4>& placed, Vec3 centre, double radius) {
  for (const Real4& c : placed) {
    const double reach = c.w + radius;
    if (norm2(xyz(c) - centre) < reach * reach) return false;
  }
  return true;
}

/// The clods of table k.
std::vector<Real4> draw_table(const Scene& scene, std::size_t k) {
  const ClodSettings& clods = scene.bonds[k].clods;
  const std::string key = "bond[" + std::to_string(k) + "].clods";
  std::mt19937_64 rng(scene.simulation.seed * 1000003ull + 7919ull * (k + 1));
  std::vector<double> radii;
  try {
    radii = sample_radii(clods.radius, clods.count, rng);
  } catch (const std::invalid_argument& e) {
    throw InputError(scene.file, 0, key + ".radius", e.what());
  }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Real4> placed;
  for (const double radius : radii) {
    int attempt = 0;
    Vec3 centre;
    do {
      if (++attempt > kAttempts)
        throw InputError(scene.file, 0, key + ".count",
                         "no room for clod " + std::to_string(placed.size() + 1) + " of " +
                             std::to_string(clods.count) + " after " + std::to_string(kAttempts) +
                             " draws (clods may not overlap): give fewer or smaller clods, or a "
                             "larger region");
      for (int a = 0; a < 3; ++a)
        axis(centre, a) = axis(clods.region_min, a) +
                          unit(rng) * (axis(clods.region_max, a) - axis(clods.region_min, a));
    } while (!has_room(placed, centre, radius));
    placed.push_back(Real4{centre.x, centre.y, centre.z, radius});
  }
  return placed;
}

}  // namespace

std::vector<std::vector<Real4>> draw_clods(const Scene& scene) {
  std::vector<std::vector<Real4>> clods;
  for (std::size_t k = 0; k < scene.bonds.size(); ++k)
    clods.push_back(scene.bonds[k].clods.count > 0 ? draw_table(scene, k) : std::vector<Real4>{});
  return clods;
}

}  // namespace gpudem
