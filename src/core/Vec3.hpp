#pragma once
/// Small fixed-size vectors used by host and device code alike.
#include <cmath>

#include "core/Config.hpp"

namespace gpudem {

struct Vec3 {
  Real x = 0, y = 0, z = 0;
};

/// Position and radius, or velocity and inverse mass, packed for one 32-byte load.
struct Real4 {
  Real x = 0, y = 0, z = 0, w = 0;
};

GPUDEM_HD inline Vec3 make_vec3(Real x, Real y, Real z) { return Vec3{x, y, z}; }
GPUDEM_HD inline Vec3 xyz(const Real4& a) { return Vec3{a.x, a.y, a.z}; }
GPUDEM_HD inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
GPUDEM_HD inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
GPUDEM_HD inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
GPUDEM_HD inline Vec3 operator*(Real s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
GPUDEM_HD inline Vec3 operator*(Vec3 a, Real s) { return {s * a.x, s * a.y, s * a.z}; }
GPUDEM_HD inline Vec3& operator+=(Vec3& a, Vec3 b) {
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
GPUDEM_HD inline Vec3& operator-=(Vec3& a, Vec3 b) {
  a.x -= b.x;
  a.y -= b.y;
  a.z -= b.z;
  return a;
}
GPUDEM_HD inline Real dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
GPUDEM_HD inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
GPUDEM_HD inline Real norm2(Vec3 a) { return dot(a, a); }
GPUDEM_HD inline Real norm(Vec3 a) { return sqrt(dot(a, a)); }

/// Component access by axis index 0..2.
GPUDEM_HD inline Real& axis(Vec3& a, int k) { return k == 0 ? a.x : (k == 1 ? a.y : a.z); }
GPUDEM_HD inline Real axis(const Vec3& a, int k) { return k == 0 ? a.x : (k == 1 ? a.y : a.z); }

}  // namespace gpudem
