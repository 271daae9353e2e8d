#include "engine/MeshReach.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/InputError.hpp"

namespace gpudem {
namespace {

/// The times in [0, end] at which a component of the centre's displacement may be extreme:
/// the ends, the keyframes, and where a velocity component changes sign within a segment.
std::vector<double> extreme_times(const std::vector<MotionKeyframe>& keyframes, double end) {
  std::vector<double> times{0, end};
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    times.push_back(keyframes[k].time);
    if (k + 1 == keyframes.size()) break;
    const MotionKeyframe& a = keyframes[k];
    const MotionKeyframe& b = keyframes[k + 1];
    for (int c = 0; c < 3; ++c) {
      const double va = axis(a.velocity, c), vb = axis(b.velocity, c);
      if ((va < 0 && vb > 0) || (va > 0 && vb < 0))
        times.push_back(a.time + va / (va - vb) * (b.time - a.time));
    }
  }
  std::vector<double> inside;
  for (const double t : times)
    if (t >= 0 && t <= end) inside.push_back(t);
  return inside;
}

bool turns(const std::vector<MotionKeyframe>& keyframes) {
  for (const MotionKeyframe& k : keyframes)
    if (norm2(k.angular_velocity) > 0) return true;
  return false;
}

/// x with four significant digits.
std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

/// "[a, b]" with four significant digits.
std::string range(double a, double b) { return "[" + number(a) + ", " + number(b) + "]"; }

const char* const kAxisName[3] = {"x", "y", "z"};

}  // namespace

MeshReach mesh_reach(const MeshWallSetup& wall, const std::vector<MotionKeyframe>& keyframes,
                     Vec3 centre, double end_time) {
  MeshReach reach;
  const std::vector<Vec3>& vertices = wall.mesh.vertices;
  if (vertices.empty()) return reach;
  reach.start_lo = reach.start_hi = vertices.front();
  double radius = 0;  // max |x − c₀|
  for (const Vec3& v : vertices) {
    for (int k = 0; k < 3; ++k) {
      axis(reach.start_lo, k) = std::min(axis(reach.start_lo, k), axis(v, k));
      axis(reach.start_hi, k) = std::max(axis(reach.start_hi, k), axis(v, k));
    }
    radius = std::max(radius, norm(v - centre));
  }
  Vec3 d_lo, d_hi;  // range of the centre's displacement
  for (const double t : extreme_times(keyframes, end_time)) {
    const Vec3 d = wall.motion.displacement(0, t);
    for (int k = 0; k < 3; ++k) {
      axis(d_lo, k) = std::min(axis(d_lo, k), axis(d, k));
      axis(d_hi, k) = std::max(axis(d_hi, k), axis(d, k));
    }
  }
  const bool turning = turns(keyframes);
  const Vec3 ball{radius, radius, radius};
  reach.swept_lo = (turning ? centre - ball : reach.start_lo) + d_lo;
  reach.swept_hi = (turning ? centre + ball : reach.start_hi) + d_hi;
  return reach;
}

void require_meshes_meet_the_domain(const Scene& scene, const std::vector<MeshWallSetup>& meshes,
                                    double smallest_diameter) {
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const MeshSettings& settings = scene.meshes[i];
    const std::string key = "mesh[" + std::to_string(i) + "].";
    const MeshReach r =
        mesh_reach(meshes[i], settings.keyframes, settings.centre, scene.simulation.end_time);
    for (int k = 0; k < 3; ++k) {
      const double lo = axis(scene.domain.min, k), hi = axis(scene.domain.max, k);
      if (scene.domain.periodic[k] || (axis(r.swept_hi, k) >= lo && axis(r.swept_lo, k) <= hi))
        continue;
      throw InputError(scene.file, settings.offset_line, key + "offset",
                       "mesh '" + settings.name + "' never meets the domain: at t = 0 it spans " +
                           kAxisName[k] + " " + range(axis(r.start_lo, k), axis(r.start_hi, k)) +
                           " m and until the end of the run " +
                           range(axis(r.swept_lo, k), axis(r.swept_hi, k)) +
                           " m, outside the domain's " + range(lo, hi) +
                           " m; check its offset, scale, rotation and motion");
    }
    const Vec3 extent = r.start_hi - r.start_lo;
    const double largest = std::max({extent.x, extent.y, extent.z});
    if (largest < smallest_diameter)
      throw InputError(scene.file, settings.scale_line, key + "scale",
                       "mesh '" + settings.name + "' spans only " + number(largest) +
                           " m at scale " + number(settings.placement.scale) +
                           ", less than the smallest particle's diameter (" +
                           number(smallest_diameter) +
                           " m); an STL in millimetres needs scale = 0.001, one in metres "
                           "scale = 1");
  }
}

}  // namespace gpudem
