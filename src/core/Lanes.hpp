#pragma once
/// W values of one scalar type computed together, lane by lane, with the operations the contact
/// laws use (arithmetic, comparisons, select, square_root), so that a law written once for a
/// scalar S evaluates W contacts at a time as Lanes<S, W>. Built on the compiler's vector types:
/// each operation on eight doubles is one instruction in code compiled for AVX-512
/// (-march=x86-64-v4), and so is each on four doubles in code compiled for AVX2
/// (-march=x86-64-v3); wider vectors than the target's are split by the compiler. Every lane rounds
/// as the scalar operation does (IEEE add, multiply, divide and square root; the build contracts
/// nothing into fused multiply-adds), so a lane's result is the same bits as the scalar law's
/// on the same inputs. Host code only (GCC and Clang).
#include <type_traits>

#include "core/Vec3.hpp"

namespace gpudem {

/// The doubles one vector instruction of this CPU holds, of the widths the host's lanes units
/// are built for: 8 where it runs code built for -march=x86-64-v4 (AVX-512 F, DQ, VL, BW and CD,
/// with AVX2, FMA and BMI2), 4 where it runs -march=x86-64-v3 (AVX2, FMA, BMI2, F16C, MOVBE),
/// else 1.
inline int host_vector_doubles() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  static const int doubles = __builtin_cpu_supports("x86-64-v4")   ? 8
                             : __builtin_cpu_supports("x86-64-v3") ? 4
                                                                   : 1;
  return doubles;
#else
  return 1;
#endif
}

/// Whether this CPU runs code built for -march=x86-64-v4 (AVX-512).
inline bool host_runs_x86_64_v4() { return host_vector_doubles() == 8; }

/// Whether this CPU runs code built for -march=x86-64-v3 (AVX2).
inline bool host_runs_x86_64_v3() { return host_vector_doubles() >= 4; }

template <class S, int W>
struct Lanes;

/// Per lane true or false: all bits set or clear, in the width of S.
template <class S, int W>
struct LaneMask {
  using Bits = std::conditional_t<sizeof(S) == 8, long long, int>;
  typedef Bits Vector __attribute__((vector_size(sizeof(S) * W)));
  Vector bits;
  bool operator[](int lane) const { return bits[lane] != 0; }
};

template <class S, int W>
struct Lanes {
  typedef S Vector __attribute__((vector_size(sizeof(S) * W)));
  Vector v;

  Lanes() : v{} {}
  Lanes(S s) : v(Vector{} + s) {}  // NOLINT: a scalar broadcasts to every lane
  static Lanes from(Vector x) {    // not a constructor: GCC sees Vector as S until instantiation
    Lanes lanes;
    lanes.v = x;
    return lanes;
  }
  template <class T>
  explicit Lanes(const Lanes<T, W>& other) : v(__builtin_convertvector(other.v, Vector)) {}
  S operator[](int lane) const { return v[lane]; }
  void set(int lane, S s) { v[lane] = s; }
};

#define GPUDEM_LANE_ARITHMETIC(op)                                      \
  template <class S, int W>                                             \
  Lanes<S, W> operator op(const Lanes<S, W>& a, const Lanes<S, W>& b) { \
    return Lanes<S, W>::from(a.v op b.v);                               \
  }                                                                     \
  template <class S, int W>                                             \
  Lanes<S, W> operator op(NonDeducedT<S> a, const Lanes<S, W>& b) {     \
    return Lanes<S, W>::from(a op b.v);                                 \
  }                                                                     \
  template <class S, int W>                                             \
  Lanes<S, W> operator op(const Lanes<S, W>& a, NonDeducedT<S> b) {     \
    return Lanes<S, W>::from(a.v op b);                                 \
  }                                                                     \
  template <class S, int W>                                             \
  Lanes<S, W>& operator op##=(Lanes<S, W>& a, const Lanes<S, W>& b) {   \
    a.v = a.v op b.v;                                                   \
    return a;                                                           \
  }
GPUDEM_LANE_ARITHMETIC(+)
GPUDEM_LANE_ARITHMETIC(-)
GPUDEM_LANE_ARITHMETIC(*)
GPUDEM_LANE_ARITHMETIC(/)
#undef GPUDEM_LANE_ARITHMETIC

template <class S, int W>
Lanes<S, W> operator-(const Lanes<S, W>& a) {
  return Lanes<S, W>::from(-a.v);
}

#define GPUDEM_LANE_COMPARISON(op)                                         \
  template <class S, int W>                                                \
  LaneMask<S, W> operator op(const Lanes<S, W>& a, const Lanes<S, W>& b) { \
    return {a.v op b.v};                                                   \
  }                                                                        \
  template <class S, int W>                                                \
  LaneMask<S, W> operator op(const Lanes<S, W>& a, NonDeducedT<S> b) {     \
    return {a.v op b};                                                     \
  }
GPUDEM_LANE_COMPARISON(<)
GPUDEM_LANE_COMPARISON(>)
GPUDEM_LANE_COMPARISON(<=)
GPUDEM_LANE_COMPARISON(>=)
GPUDEM_LANE_COMPARISON(==)
GPUDEM_LANE_COMPARISON(!=)
#undef GPUDEM_LANE_COMPARISON

template <class S, int W>
LaneMask<S, W> operator||(const LaneMask<S, W>& a, const LaneMask<S, W>& b) {
  return {a.bits | b.bits};
}
template <class S, int W>
LaneMask<S, W> operator&&(const LaneMask<S, W>& a, const LaneMask<S, W>& b) {
  return {a.bits & b.bits};
}
template <class S, int W>
LaneMask<S, W> operator!(const LaneMask<S, W>& a) {
  return {~a.bits};
}

/// Per lane: a where `take_a`, else b.
template <class S, int W>
Lanes<S, W> select(const LaneMask<S, W>& take_a, const Lanes<S, W>& a, const Lanes<S, W>& b) {
  return Lanes<S, W>::from(take_a.bits ? a.v : b.v);
}
template <class S, int W>
LaneMask<S, W> select(const LaneMask<S, W>& take_a, const LaneMask<S, W>& a,
                      const LaneMask<S, W>& b) {
  return {take_a.bits ? a.bits : b.bits};
}

/// Whether any lane is true: one test instruction where the mask fills an AVX or an SSE 4.1
/// register and the target has them, else lane by lane.
template <class S, int W>
bool any(const LaneMask<S, W>& m) {
#if defined(__AVX__)
  if constexpr (sizeof(m.bits) == 32) {
    typedef long long Quads __attribute__((vector_size(32)));
    const Quads bits = (Quads)m.bits;
    return !__builtin_ia32_ptestz256(bits, bits);
  }
#endif
#if defined(__SSE4_1__)
  if constexpr (sizeof(m.bits) == 16) {
    typedef long long Pairs __attribute__((vector_size(16)));
    const Pairs bits = (Pairs)m.bits;
    return !__builtin_ia32_ptestz128(bits, bits);
  }
#endif
  bool found = false;
  for (int lane = 0; lane < W; ++lane) found = found || m.bits[lane] != 0;
  return found;
}

/// Per lane a() where `take_a`, else b() (choose on a scalar, core/Vec3.hpp): both computed and
/// selected, or only the one every lane takes.
template <class S, int W, class A, class B>
auto choose(const LaneMask<S, W>& take_a, const A& a, const B& b) -> decltype(a()) {
  if (!any(take_a)) return b();
  if (!any(!take_a)) return a();
  return select(take_a, a(), b());
}

/// Per lane √x, correctly rounded as the scalar square_root.
template <class S, int W>
Lanes<S, W> square_root(const Lanes<S, W>& x) {
  Lanes<S, W> r;
  for (int lane = 0; lane < W; ++lane) r.v[lane] = square_root(x.v[lane]);
  return r;
}

/// Per lane the nearest integer, ties to even (rint in the default rounding mode).
template <int W>
Lanes<double, W> round_to_integer(const Lanes<double, W>& x) {
  Lanes<double, W> r;
  for (int lane = 0; lane < W; ++lane) r.v[lane] = __builtin_rint(x.v[lane]);
  return r;
}

/// S itself for one lane, else Lanes<S, W>: code written for both runs one contact or W.
template <class S, int W>
using LaneScalar = std::conditional_t<W == 1, S, Lanes<S, W>>;

/// Sets lane `lane` of a scalar (the one lane), of lanes, or of a vector of either.
template <class S>
void set_lane(S& to, int, S value) {
  to = value;
}
template <class S, int W>
void set_lane(Lanes<S, W>& to, int lane, S value) {
  to.set(lane, value);
}
template <class S, int W>
void set_lane(Vec3T<LaneScalar<S, W>>& to, int lane, const Vec3T<S>& value) {
  set_lane(to.x, lane, value.x);
  set_lane(to.y, lane, value.y);
  set_lane(to.z, lane, value.z);
}
template <class S, int W>
void set_lane(Vec4T<LaneScalar<S, W>>& to, int lane, const Vec4T<S>& value) {
  set_lane(to.x, lane, value.x);
  set_lane(to.y, lane, value.y);
  set_lane(to.z, lane, value.z);
  set_lane(to.w, lane, value.w);
}
/// Lane `lane` of a scalar (the one lane), of lanes, or of a vector of either.
template <class S, std::enable_if_t<std::is_arithmetic_v<S>, int> = 0>
S lane_of(S value, int) {
  return value;
}
template <class S, int W>
S lane_of(const Lanes<S, W>& values, int lane) {
  return values[lane];
}
template <class L>
auto lane_of(const Vec3T<L>& v, int lane) {
  return Vec3T<decltype(lane_of(v.x, lane))>{lane_of(v.x, lane), lane_of(v.y, lane),
                                             lane_of(v.z, lane)};
}

}  // namespace gpudem
