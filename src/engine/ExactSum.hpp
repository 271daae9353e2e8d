#pragma once
/// Sums of contact loads that are the same bits in any order. Each term x (a force component
/// [N], or a torque's [N m]) is rounded once to integers: y = x · 2^20 (units of 2^-20),
/// whole = round(y), fraction = round((y − whole) · 2^54); the sum of the wholes and the sum of
/// the fractions are exact in 64-bit integers, so the value, (Σ whole + Σ fraction · 2^-54) ·
/// 2^-20, depends on the terms alone and not on their order. The resolution is 2^-74 (5 · 10^-23 N)
/// and the range 2^42 (4 · 10^12 N) per term; up to 2^9 terms fit in the fractions' sum. A term
/// and its negative round to exact negatives (rounding to nearest even is symmetric), so the
/// load one end of a pair adds and the other end subtracts cancel exactly. Fixed-point force
/// sums as in AMBER's SPFP (Le Grand, Götz & Walker 2013, Comput. Phys. Commun. 184, 374).
/// Host code: the CUDA backend sums in floating point.
#include <cmath>
#include <cstdint>

#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// One term, rounded.
struct ExactTerm {
  std::int64_t whole;
  std::int64_t fraction;
};

inline constexpr double exact_units_per_newton = 1048576.0;              // 2^20
inline constexpr double exact_fractions_per_unit = 18014398509481984.0;  // 2^54

inline ExactTerm exact_term(double x) {
  const double y = x * exact_units_per_newton;
  const std::int64_t whole = std::llrint(y);
  return {whole, std::llrint((y - static_cast<double>(whole)) * exact_fractions_per_unit)};
}

/// The terms of the three components of a vector.
struct ExactTerm3 {
  ExactTerm x, y, z;
};

template <class S>
ExactTerm3 exact_terms(const Vec3T<S>& v) {
  return {exact_term(v.x), exact_term(v.y), exact_term(v.z)};
}

/// A vector summed from rounded terms.
struct ExactSum3 {
  ExactTerm x{0, 0}, y{0, 0}, z{0, 0};

  void add(const ExactTerm3& t) {
    add_to(x, t.x);
    add_to(y, t.y);
    add_to(z, t.z);
  }
  void subtract(const ExactTerm3& t) {
    subtract_from(x, t.x);
    subtract_from(y, t.y);
    subtract_from(z, t.z);
  }
  template <class S>
  Vec3T<S> value() const {
    return {static_cast<S>(component(x)), static_cast<S>(component(y)),
            static_cast<S>(component(z))};
  }

 private:
  static void add_to(ExactTerm& sum, const ExactTerm& t) {
    sum.whole += t.whole;
    sum.fraction += t.fraction;
  }
  static void subtract_from(ExactTerm& sum, const ExactTerm& t) {
    sum.whole -= t.whole;
    sum.fraction -= t.fraction;
  }
  static double component(const ExactTerm& s) {
    return (static_cast<double>(s.whole) +
            static_cast<double>(s.fraction) * (1 / exact_fractions_per_unit)) *
           (1 / exact_units_per_newton);
  }
};

}  // namespace gpudem
