#pragma once
/// Sums of contact loads that are the same bits in any order. Each term x (a force component
/// [N], or a torque's [N m]) is rounded once to integers: y = x · 2^20 (units of 2^-20),
/// whole = round(y), fraction = round((y − whole) · 2^44); the wholes and the fractions are
/// summed modulo 2^64, which is exact and does not depend on the order, so the value,
/// (Σ whole + Σ fraction · 2^-44) · 2^-20, depends on the terms alone. The resolution is 2^-64
/// (5 · 10^-20 N). A term must be below 2^30 (10^9 N) in magnitude, and each sum's net value
/// below 2^43 (8.8 · 10^12 N, e.g. any 8,192 terms at the limit); a term beyond the limit, or
/// not finite, makes its whole sum NaN, as a plain sum of such a term would be. A term and its
/// negative round to exact negatives (rounding to nearest even is symmetric), so the load one
/// end of a pair adds and the other end subtracts cancel exactly. Fixed-point force sums as in
/// AMBER's SPFP (Le Grand, Götz & Walker 2013, Comput. Phys. Commun. 184, 374).
/// Host code: the CUDA backend sums in floating point.
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "core/Config.hpp"
#include "core/Lanes.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// One term, rounded; two's complement in unsigned words, whose sums wrap without overflow.
struct ExactTerm {
  std::uint64_t whole;
  std::uint64_t fraction;
};

inline constexpr double exact_units_per_newton = 1048576.0;           // 2^20
inline constexpr double exact_fractions_per_unit = 17592186044416.0;  // 2^44
inline constexpr double exact_term_limit = 1073741824.0;              // 2^30 N (or N m)

/// The terms of the three components of a vector, and whether all three are within the limit.
struct ExactTerm3 {
  ExactTerm x, y, z;
  bool representable;
};

namespace exact_detail {
inline ExactTerm term(double x) {
  const double y = x * exact_units_per_newton;
  const std::int64_t whole = std::llrint(y);
  const std::int64_t fraction =
      std::llrint((y - static_cast<double>(whole)) * exact_fractions_per_unit);
  return {static_cast<std::uint64_t>(whole), static_cast<std::uint64_t>(fraction)};
}
inline bool within_limit(double x) { return std::fabs(x) < exact_term_limit; }  // NaN: false
}  // namespace exact_detail

template <class S, std::enable_if_t<std::is_arithmetic_v<S>, int> = 0>
ExactTerm3 exact_terms(const Vec3T<S>& v) {
  const double x = v.x, y = v.y, z = v.z;
  using exact_detail::within_limit;
  if (!(within_limit(x) && within_limit(y) && within_limit(z))) return {{}, {}, {}, false};
  using exact_detail::term;
  return {term(x), term(y), term(z), true};
}

/// The terms of W vectors at once (a contact's loads in lanes, core/Lanes.hpp); lane(l) is what
/// exact_terms gives for lane l's vector: llrint is round to nearest even (rint) and the
/// conversion of the integer it gives, which is exact.
template <int W>
struct ExactTermLanes {
  using Integers = Lanes<long long, W>;
  Integers whole[3];
  Integers fraction[3];
  LaneMask<double, W> representable;

  ExactTerm3 lane(int l) const {
    if (!representable[l]) return {{}, {}, {}, false};
    const auto term = [&](int k) {
      return ExactTerm{static_cast<std::uint64_t>(whole[k][l]),
                       static_cast<std::uint64_t>(fraction[k][l])};
    };
    return {term(0), term(1), term(2), true};
  }
};

namespace exact_detail {
/// Lanes rounded to integers: as doubles and as 64-bit integers.
template <int W>
struct RoundedLanes {
  Lanes<double, W> value;
  Lanes<long long, W> integer;
};

/// Per lane y rounded to the nearest integer, ties to even (rint, llrint); |y| < 2^51 (other
/// lanes give unspecified values).
template <int W>
RoundedLanes<W> rounded(const Lanes<double, W>& y) {
  using Integers = Lanes<long long, W>;
#if defined(__AVX512DQ__)
  const Lanes<double, W> value = round_to_integer(y);
  return {value, Integers(value)};  // one instruction per vector with AVX-512 DQ
#else
  // Without AVX-512 DQ a vector of doubles converts to 64-bit integers lane by lane. Instead:
  // y + 1.5 · 2^52 lies in [2^52, 2^53), where the doubles are the integers, so the sum rounds
  // y as rint does (to nearest, ties to the even sum, and 1.5 · 2^52 is even), and the sum's
  // bits less the constant's are that integer in two's complement.
  constexpr double shift = 6755399441055744.0;          // 1.5 · 2^52
  constexpr long long shift_bits = 0x4338000000000000;  // its bits
  const Lanes<double, W> shifted = y + shift;
  const auto bits = (typename Integers::Vector)shifted.v;  // the same bits, as integers
  return {shifted - shift, Integers::from(bits) - Integers(shift_bits)};
#endif
}
}  // namespace exact_detail

template <class S, int W>
ExactTermLanes<W> exact_terms(const Vec3T<Lanes<S, W>>& v) {
  using D = Lanes<double, W>;
  const D x[3] = {D(v.x), D(v.y), D(v.z)};
  ExactTermLanes<W> t;
  t.representable = x[0] < exact_term_limit && x[0] > -exact_term_limit;  // NaN: false
  for (int k = 0; k < 3; ++k) {
    // |y| < 2^50 and |(y − whole) · 2^44| ≤ 2^43 in every representable lane
    const D y = x[k] * exact_units_per_newton;
    const exact_detail::RoundedLanes<W> whole = exact_detail::rounded(y);
    t.whole[k] = whole.integer;
    t.fraction[k] = exact_detail::rounded((y - whole.value) * exact_fractions_per_unit).integer;
    if (k > 0)
      t.representable = t.representable && (x[k] < exact_term_limit && x[k] > -exact_term_limit);
  }
  return t;
}

/// Lane l's terms: the terms themselves for one lane.
inline ExactTerm3 lane_of(const ExactTerm3& t, int) { return t; }
template <int W>
ExactTerm3 lane_of(const ExactTermLanes<W>& t, int l) {
  return t.lane(l);
}

/// A vector summed from rounded terms.
struct ExactSum3 {
  ExactTerm x{0, 0}, y{0, 0}, z{0, 0};
  bool representable = true;  ///< false once a term beyond the limit was added or subtracted

  // The flag is written only when a term is beyond the limit, which is rare: an unconditional
  // read-modify-write of it cost 4–6 % of the host sweep.
  void add(const ExactTerm3& t) {
    add_to(x, t.x);
    add_to(y, t.y);
    add_to(z, t.z);
    if (!t.representable) representable = false;
  }
  void subtract(const ExactTerm3& t) {
    subtract_from(x, t.x);
    subtract_from(y, t.y);
    subtract_from(z, t.z);
    if (!t.representable) representable = false;
  }
  template <class S>
  Vec3T<S> value() const {
    if (!representable) {
      const S nan = std::numeric_limits<S>::quiet_NaN();
      return {nan, nan, nan};
    }
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
    const auto whole = static_cast<std::int64_t>(s.whole);        // two's complement (C++20 rule,
    const auto fraction = static_cast<std::int64_t>(s.fraction);  // what every compiler does)
    return (static_cast<double>(whole) +
            static_cast<double>(fraction) * (1 / exact_fractions_per_unit)) *
           (1 / exact_units_per_newton);
  }
};

}  // namespace gpudem
