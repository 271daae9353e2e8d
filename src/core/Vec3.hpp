#pragma once
/// Small fixed-size vectors used by host and device code alike, in the precision of their
/// scalar: Vec3 holds Real (particle state), Vec3T<float> the forces and contact geometry of
/// the mixed precision policy (ContactLaw.hpp).
#include <cmath>

#include "core/Config.hpp"

namespace gpudem {

template <class S>
struct Vec3T {
  S x = 0, y = 0, z = 0;
};

using Vec3 = Vec3T<Real>;

/// Position and radius, or velocity and inverse mass, packed for one 32-byte load.
struct Real4 {
  Real x = 0, y = 0, z = 0, w = 0;
};

/// T as written, excluded from template argument deduction: in `s * v` the vector's scalar
/// type decides, and a literal or a wider scalar is converted to it.
template <class T>
struct NonDeduced {
  using type = T;
};
template <class T>
using NonDeducedT = typename NonDeduced<T>::type;

/// √x in the precision of x on host and device (sqrtf for float, not a double round trip).
GPUDEM_HD inline double square_root(double x) { return sqrt(x); }
GPUDEM_HD inline float square_root(float x) { return sqrtf(x); }

/// `a` with its components converted to scalar To.
template <class To, class From>
GPUDEM_HD Vec3T<To> vec_cast(Vec3T<From> a) {
  return {static_cast<To>(a.x), static_cast<To>(a.y), static_cast<To>(a.z)};
}

GPUDEM_HD inline Vec3 make_vec3(Real x, Real y, Real z) { return Vec3{x, y, z}; }
GPUDEM_HD inline Vec3 xyz(const Real4& a) { return Vec3{a.x, a.y, a.z}; }
template <class S>
GPUDEM_HD Vec3T<S> operator+(Vec3T<S> a, Vec3T<S> b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class S>
GPUDEM_HD Vec3T<S> operator-(Vec3T<S> a, Vec3T<S> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class S>
GPUDEM_HD Vec3T<S> operator-(Vec3T<S> a) {
  return {-a.x, -a.y, -a.z};
}
template <class S>
GPUDEM_HD Vec3T<S> operator*(NonDeducedT<S> s, Vec3T<S> a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class S>
GPUDEM_HD Vec3T<S> operator*(Vec3T<S> a, NonDeducedT<S> s) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class S>
GPUDEM_HD Vec3T<S>& operator+=(Vec3T<S>& a, Vec3T<S> b) {
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
template <class S>
GPUDEM_HD Vec3T<S>& operator-=(Vec3T<S>& a, Vec3T<S> b) {
  a.x -= b.x;
  a.y -= b.y;
  a.z -= b.z;
  return a;
}
template <class S>
GPUDEM_HD S dot(Vec3T<S> a, Vec3T<S> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class S>
GPUDEM_HD Vec3T<S> cross(Vec3T<S> a, Vec3T<S> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class S>
GPUDEM_HD S norm2(Vec3T<S> a) {
  return dot(a, a);
}
template <class S>
GPUDEM_HD S norm(Vec3T<S> a) {
  return square_root(dot(a, a));
}

/// Component access by axis index 0..2.
template <class S>
GPUDEM_HD S& axis(Vec3T<S>& a, int k) {
  return k == 0 ? a.x : (k == 1 ? a.y : a.z);
}
template <class S>
GPUDEM_HD S axis(const Vec3T<S>& a, int k) {
  return k == 0 ? a.x : (k == 1 ? a.y : a.z);
}

}  // namespace gpudem
