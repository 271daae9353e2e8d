#pragma once
/// Rigid rotations as 3×3 matrices (rows), built by Rodrigues' formula.
#include <cmath>

#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

struct Rotation {
  Vec3 rows[3] = {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  GPUDEM_HD Vec3 apply(Vec3 v) const {
    return Vec3{dot(rows[0], v), dot(rows[1], v), dot(rows[2], v)};
  }
};

/// R = cos θ I + sin θ [k]× + (1 − cos θ) k kᵀ: the right-handed rotation by `angle` [rad] about
/// the direction of the non-zero `axis` (Rodrigues' rotation formula).
inline Rotation rotation_about(Vec3 axis, double angle) {
  const Vec3 k = (1.0 / norm(axis)) * axis;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  Rotation r;
  r.rows[0] = Vec3{c + t * k.x * k.x, t * k.x * k.y - s * k.z, t * k.x * k.z + s * k.y};
  r.rows[1] = Vec3{t * k.y * k.x + s * k.z, c + t * k.y * k.y, t * k.y * k.z - s * k.x};
  r.rows[2] = Vec3{t * k.z * k.x - s * k.y, t * k.z * k.y + s * k.x, c + t * k.z * k.z};
  return r;
}

/// The rotation by the rotation vector θ: angle |θ| about θ/|θ|; the identity for θ = 0.
inline Rotation rotation_by_vector(Vec3 theta) {
  const double angle = norm(theta);
  return angle > 0 ? rotation_about(theta, angle) : Rotation{};
}

}  // namespace gpudem
