#pragma once
// Small programmatic scenes for physics tests (no TOML round trip).
#include "core/Scene.hpp"

namespace gpudem::test {

/// One material, Hooke contact with stiffness k, a box domain and no walls.
inline Scene basic_scene(Vec3 lo, Vec3 hi, double stiffness, double restitution, double friction) {
  Scene s;
  s.file = "<test>";
  s.simulation.end_time = 1;
  s.domain.min = lo;
  s.domain.max = hi;
  Material m;
  m.name = "grain";
  m.density = 2500;
  m.young = 1e7;
  m.poisson = 0.3;
  m.restitution = restitution;
  m.friction = friction;
  s.materials.push_back(m);
  s.contact.stiffness = stiffness;
  return s;
}

/// Adds a floor of material 0: the plane z = height with normal +z.
inline void add_floor(Scene& s, double height = 0) {
  WallSettings floor;
  floor.name = "floor";
  floor.point = {0, 0, height};
  floor.normal = {0, 0, 1};
  s.walls.push_back(floor);
}

/// Adds a box source of `count` spheres of radius mean ± spread, material 0.
inline void add_box_source(Scene& s, Vec3 lo, Vec3 hi, std::uint64_t count, double mean,
                           double spread) {
  ParticleSource source;
  source.region_min = lo;
  source.region_max = hi;
  source.count = count;
  source.radius.mean = mean;
  source.radius.spread = spread;
  s.sources.push_back(source);
}

/// Adds the six faces of the domain as walls of material 0, normals pointing inwards.
inline void add_box_walls(Scene& s) {
  const Vec3 lo = s.domain.min, hi = s.domain.max;
  for (int k = 0; k < 3; ++k) {
    WallSettings low, high;
    axis(low.normal, k) = 1;
    low.point = lo;
    axis(high.normal, k) = -1;
    high.point = hi;
    low.name = "low" + std::to_string(k);
    high.name = "high" + std::to_string(k);
    s.walls.push_back(low);
    s.walls.push_back(high);
  }
}

}  // namespace gpudem::test
