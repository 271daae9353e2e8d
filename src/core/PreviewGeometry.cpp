#include "core/PreviewGeometry.hpp"

#include <algorithm>
#include <cmath>

#include "core/Rotation.hpp"

namespace gpudem {

namespace {

/// The points where the plane meets the box's twelve edges (an edge lying in the plane gives
/// both its ends).
std::vector<Vec3> plane_box_points(Vec3 point, Vec3 normal, Vec3 lo, Vec3 hi) {
  std::vector<Vec3> points;
  const Vec3 corner[2] = {lo, hi};
  for (int axis = 0; axis < 3; ++axis)
    for (int k = 0; k < 4; ++k) {  // the edge along `axis` at the other two axes' ends k
      Vec3 a{}, b{};
      for (int other = 0, bit = 0; other < 3; ++other) {
        if (other == axis) continue;
        gpudem::axis(a, other) = gpudem::axis(corner[(k >> bit) & 1], other);
        ++bit;
      }
      b = a;
      gpudem::axis(a, axis) = gpudem::axis(lo, axis);
      gpudem::axis(b, axis) = gpudem::axis(hi, axis);
      const double da = dot(a - point, normal), db = dot(b - point, normal);
      if (da == 0) points.push_back(a);
      if (db == 0) points.push_back(b);
      if ((da < 0 && db > 0) || (da > 0 && db < 0))
        points.push_back(a + (da / (da - db)) * (b - a));
    }
  return points;
}

}  // namespace

PreviewSurface wall_in_box(Vec3 point, Vec3 normal, Vec3 lo, Vec3 hi) {
  std::vector<Vec3> points;  // each once: a plane through a box corner meets three edges there
  for (const Vec3& p : plane_box_points(point, normal, lo, hi))
    if (std::none_of(points.begin(), points.end(), [&](Vec3 q) { return norm2(q - p) == 0; }))
      points.push_back(p);
  PreviewSurface wall;
  if (points.size() < 3) return wall;
  Vec3 centre{};
  for (const Vec3& p : points) centre += p;
  centre = (1.0 / points.size()) * centre;
  const Vec3 helper = std::abs(normal.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 u = cross(normal, helper), v = cross(normal, u);
  const auto angle = [&](Vec3 p) { return std::atan2(dot(p - centre, v), dot(p - centre, u)); };
  std::sort(points.begin(), points.end(), [&](Vec3 a, Vec3 b) { return angle(a) < angle(b); });
  wall.vertices.push_back(centre);
  for (const Vec3& p : points) wall.vertices.push_back(p);
  const auto n = static_cast<std::uint32_t>(points.size());
  for (std::uint32_t k = 0; k < n; ++k) wall.triangles.push_back({0, 1 + k, 1 + (k + 1) % n});
  return wall;
}

std::vector<Vec3> vertices_at(const std::vector<Vec3>& start, const PrescribedMotion& motion,
                              double t) {
  const Rotation turned = rotation_by_vector(motion.rotation_vector(0, t));
  const Vec3 c0 = motion.centre(0), c = motion.centre(t);
  std::vector<Vec3> moved;
  moved.reserve(start.size());
  for (const Vec3& x : start) moved.push_back(turned.apply(x - c0) + c);
  return moved;
}

std::vector<Vec3> centre_path(const PrescribedMotion& motion, double end_time, int samples) {
  std::vector<Vec3> path;
  for (int k = 0; k < samples; ++k) path.push_back(motion.centre(end_time * k / (samples - 1)));
  return path;
}

}  // namespace gpudem
