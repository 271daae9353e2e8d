#pragma once
/// Small fixed-size vectors used by host and device code alike, in the precision of their
/// scalar: Vec3 and Real4 hold Real (host particle state, and the engine's in the double and
/// mixed policies), Vec3T<float> the forces and contact geometry of the mixed and float
/// policies (ContactLaw.hpp) and Vec4T<float> the engine's particle state in the float policy.
#include <cmath>
#include <type_traits>

#include "core/Config.hpp"

namespace gpudem {

template <class S>
struct Vec3T {
  S x = 0, y = 0, z = 0;
};

using Vec3 = Vec3T<Real>;

/// Position and radius, or velocity and inverse mass, packed for one load: Real4 (32 bytes) in
/// the particle state of the double and mixed policies, Vec4T<float> (16 bytes) in the float
/// policy's (Scene.hpp, Precision).
template <class S>
struct Vec4T {
  S x = 0, y = 0, z = 0, w = 0;
};

using Real4 = Vec4T<Real>;

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

/// The next representable value after x in the direction of `toward`, in the precision of x.
GPUDEM_HD inline double next_toward(double x, double toward) { return nextafter(x, toward); }
GPUDEM_HD inline float next_toward(float x, float toward) { return nextafterf(x, toward); }

/// `a` with its components converted to scalar To.
template <class To, class From>
GPUDEM_HD Vec3T<To> vec_cast(Vec3T<From> a) {
  return {static_cast<To>(a.x), static_cast<To>(a.y), static_cast<To>(a.z)};
}

/// `a` with its components converted to scalar To.
template <class To, class From>
GPUDEM_HD Vec4T<To> vec4_cast(Vec4T<From> a) {
  return {static_cast<To>(a.x), static_cast<To>(a.y), static_cast<To>(a.z), static_cast<To>(a.w)};
}

GPUDEM_HD inline Vec3 make_vec3(Real x, Real y, Real z) { return Vec3{x, y, z}; }
template <class S>
GPUDEM_HD Vec3T<S> xyz(const Vec4T<S>& a) {
  return {a.x, a.y, a.z};
}
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

/// a where `take_a`, else b: how the contact laws choose between cheap values, so that the same
/// law also runs on Lanes (core/Lanes.hpp), where each lane chooses for itself. Both values are
/// computed; choose computes only what is needed.
template <class S, std::enable_if_t<std::is_arithmetic_v<S>, int> = 0>
GPUDEM_HD S select(bool take_a, S a, S b) {
  return take_a ? a : b;
}
template <class Mask, class S>
GPUDEM_HD Vec3T<S> select(const Mask& take_a, const Vec3T<S>& a, const Vec3T<S>& b) {
  return {select(take_a, a.x, b.x), select(take_a, a.y, b.y), select(take_a, a.z, b.z)};
}

/// a() where `take_a`, else b(): how the contact laws choose between outcomes that cost
/// something to compute. On a scalar only the chosen one is computed; on Lanes (core/Lanes.hpp)
/// both are, unless every lane takes the same one, and each lane keeps its own (select).
template <class A, class B>
GPUDEM_HD auto choose(bool take_a, const A& a, const B& b) -> decltype(a()) {
  if (take_a) return a();
  return b();
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
