#pragma once
/// Sums of contact loads that are the same bits in any order. Each term x (a force component
/// [N], or a torque's [N m]) is counted in a unit u of the run (ExactUnits, a power of two):
/// y = x / u is rounded once to the integer round(y) (to nearest, ties to even), and the
/// integers are summed modulo 2^64, which is exact and does not depend on the order, so the
/// value, u · Σ round(y), depends on the terms alone. A term of |y| < 2^50 is one 64-bit word,
/// the part each term writes (ExactWords3); a larger one, which a sound run rarely has, is split
/// into a multiple of 2^50 units, summed in a second word (ExactSpill3), and the rest. A term must
/// be below 2^112 units in magnitude and each sum's words below 2^63 (any 8,192 terms); a term
/// beyond, or not finite, makes its whole sum NaN, as a plain sum of such a term would be. A term
/// and its negative round to exact negatives (rounding to nearest even is symmetric), so the load
/// one end of a pair adds and the other end subtracts cancel exactly. Fixed-point force sums as in
/// AMBER's SPFP (Le Grand, Götz & Walker 2013, Comput. Phys. Commun. 184, 374).
/// Host code: the CUDA backend sums in floating point.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "core/Config.hpp"
#include "core/Lanes.hpp"
#include "core/Vec3.hpp"
#include "engine/ExactUnits.hpp"
#include "engine/HostAllocator.hpp"

namespace gpudem {

inline constexpr double exact_word_limit = 0x1p50;    ///< units a one-word term stays below
inline constexpr double exact_spill_limit = 0x1p112;  ///< units any term stays below

/// The words of a sum that every term writes (24 bytes), or of a term that does not spill.
struct ExactWords3 {
  std::uint64_t word[3] = {0, 0, 0};
};

/// One term of each component of a vector, in two's complement in unsigned words, whose sums
/// wrap without overflow: words.word[k] + spill[k] · 2^50 units.
struct ExactTerm3 {
  ExactWords3 words;
  std::uint64_t spill[3];
  bool spilled;        ///< some spill is not zero, or the term is not representable
  bool representable;  ///< every component below exact_spill_limit units
};

/// The terms of a vector of any magnitude already in units (y = x / u): the spilling path.
ExactTerm3 exact_terms_in_units(double x, double y, double z);

/// The terms of vector v in unit u (1/u is `per_unit`).
template <class S, std::enable_if_t<std::is_arithmetic_v<S>, int> = 0>
ExactTerm3 exact_terms(const Vec3T<S>& v, double per_unit) {
  const double x = v.x * per_unit, y = v.y * per_unit, z = v.z * per_unit;
  const auto within = [](double c) { return std::fabs(c) < exact_word_limit; };  // NaN: false
  if (!(within(x) && within(y) && within(z))) return exact_terms_in_units(x, y, z);
  return {{{static_cast<std::uint64_t>(std::llrint(x)), static_cast<std::uint64_t>(std::llrint(y)),
            static_cast<std::uint64_t>(std::llrint(z))}},
          {0, 0, 0},
          false,
          true};
}

/// The terms of W vectors at once (a contact's loads in lanes, core/Lanes.hpp); lane(l) is what
/// exact_terms gives for lane l's vector (the same integers: rint, ties to even).
template <int W>
struct ExactTermLanes {
  Lanes<long long, W> word[3];  ///< the rounded components, where no lane spills
  Lanes<double, W> units[3];    ///< the components in units, where some lane spills
  bool spills;                  ///< some lane has a component of 2^50 units or more, or NaN

  ExactTerm3 lane(int l) const {
    if (spills) return exact_terms_in_units(units[0][l], units[1][l], units[2][l]);
    return {words(l), {0, 0, 0}, false, true};
  }
  /// Lane l's terms, one word each, where no lane spills.
  ExactWords3 words(int l) const {
    return {{static_cast<std::uint64_t>(word[0][l]), static_cast<std::uint64_t>(word[1][l]),
             static_cast<std::uint64_t>(word[2][l])}};
  }
};

namespace exact_detail {
/// Per lane y rounded to the nearest integer, ties to even (llrint); |y| < 2^51 (other lanes
/// give unspecified values).
template <int W>
Lanes<long long, W> rounded(const Lanes<double, W>& y) {
  using Integers = Lanes<long long, W>;
#if defined(__AVX512DQ__)
  return Integers(round_to_integer(y));  // one instruction per vector with AVX-512 DQ
#else
  // Without AVX-512 DQ a vector of doubles converts to 64-bit integers lane by lane. Instead:
  // y + 1.5 · 2^52 lies in [2^52, 2^53), where the doubles are the integers, so the sum rounds
  // y as rint does (to nearest, ties to the even sum, and 1.5 · 2^52 is even), and the sum's
  // bits less the constant's are that integer in two's complement.
  constexpr double shift = 6755399441055744.0;          // 1.5 · 2^52
  constexpr long long shift_bits = 0x4338000000000000;  // its bits
  const Lanes<double, W> shifted = y + shift;
  const auto bits = (typename Integers::Vector)shifted.v;  // the same bits, as integers
  return Integers::from(bits) - Integers(shift_bits);
#endif
}
}  // namespace exact_detail

template <class S, int W>
ExactTermLanes<W> exact_terms(const Vec3T<Lanes<S, W>>& v, double per_unit) {
  using D = Lanes<double, W>;
  const D units[3] = {D(v.x) * per_unit, D(v.y) * per_unit, D(v.z) * per_unit};
  const auto within = [](const D& c) { return c < exact_word_limit && c > -exact_word_limit; };
  ExactTermLanes<W> t;
  t.spills = any(!(within(units[0]) && within(units[1]) && within(units[2])));
  for (int k = 0; k < 3; ++k) {
    if (t.spills)
      t.units[k] = units[k];
    else
      t.word[k] = exact_detail::rounded(units[k]);
  }
  return t;
}

/// The spilled multiples of 2^50 units of a sum, and whether its terms were representable:
/// written only by a term that spills.
struct ExactSpill3 {
  std::uint64_t spill[3] = {0, 0, 0};
  bool representable = true;
};

namespace exact_detail {
inline void add(ExactWords3& w, const ExactWords3& t) {
  for (int k = 0; k < 3; ++k) w.word[k] += t.word[k];
}
inline void subtract(ExactWords3& w, const ExactWords3& t) {
  for (int k = 0; k < 3; ++k) w.word[k] -= t.word[k];
}
inline void add(ExactSpill3& s, const ExactTerm3& t) {
  for (int k = 0; k < 3; ++k) s.spill[k] += t.spill[k];
  if (!t.representable) s.representable = false;
}
inline void subtract(ExactSpill3& s, const ExactTerm3& t) {
  for (int k = 0; k < 3; ++k) s.spill[k] -= t.spill[k];
  if (!t.representable) s.representable = false;
}
/// The exact integer word + spill · 2^50 (two's complement words), rounded once to double,
/// times the unit: where some term spilled.
double spilled_component(std::uint64_t word, std::uint64_t spill, double unit);
/// The same for any sum: without a spill the word alone, whose rounding is the same.
inline double component(std::uint64_t word, std::uint64_t spill, double unit) {
  if (spill != 0) return spilled_component(word, spill, unit);
  return static_cast<double>(static_cast<std::int64_t>(word)) * unit;
}
}  // namespace exact_detail

/// A vector summed from rounded terms, in unit u.
struct ExactSum3 {
  ExactWords3 words;
  ExactSpill3 spill;

  void add(const ExactTerm3& t) {
    exact_detail::add(words, t.words);
    if (t.spilled) exact_detail::add(spill, t);
  }
  void subtract(const ExactTerm3& t) {
    exact_detail::subtract(words, t.words);
    if (t.spilled) exact_detail::subtract(spill, t);
  }
  template <class S>
  Vec3T<S> value(double unit) const {
    if (!spill.representable) {
      const S nan = std::numeric_limits<S>::quiet_NaN();
      return {nan, nan, nan};
    }
    const auto c = [&](int k) {
      return static_cast<S>(exact_detail::component(words.word[k], spill.spill[k], unit));
    };
    return {c(0), c(1), c(2)};
  }
};

/// Sums of many particles: their words, and their spills, which only a term that spills writes.
/// While `spilled` is false every spill is zero and is not read. A particle's sum is written by
/// one thread only, which sets `spilled` before it reads the sum.
struct ExactSumArrays {
  ExactWords3* words = nullptr;
  ExactSpill3* spills = nullptr;
  std::atomic<bool>* spilled = nullptr;

  explicit operator bool() const { return words != nullptr; }
  void add(std::uint32_t i, const ExactTerm3& t) const {
    exact_detail::add(words[i], t.words);
    if (t.spilled) {
      exact_detail::add(spills[i], t);
      spilled->store(true, std::memory_order_relaxed);
    }
  }
  void subtract(std::uint32_t i, const ExactTerm3& t) const {
    exact_detail::subtract(words[i], t.words);
    if (t.spilled) {
      exact_detail::subtract(spills[i], t);
      spilled->store(true, std::memory_order_relaxed);
    }
  }
  /// The same for a term that does not spill.
  void add(std::uint32_t i, const ExactWords3& t) const { exact_detail::add(words[i], t); }
  void subtract(std::uint32_t i, const ExactWords3& t) const {
    exact_detail::subtract(words[i], t);
  }
  /// Particle i's words set to zero (its spill is zero at the start of a sweep).
  void clear(std::uint32_t i) const { words[i] = ExactWords3{}; }
  ExactSum3 operator[](std::uint32_t i) const {
    ExactSum3 sum{words[i], {}};
    if (spilled->load(std::memory_order_relaxed)) sum.spill = spills[i];
    return sum;
  }
};

/// The arrays of ExactSumArrays, owned.
class ExactSumStore {
 public:
  void resize(std::size_t n) {
    words_.resize(n);
    spills_.resize(n);
  }
  /// The arrays for a sweep, the spills a sweep before left set to zero.
  ExactSumArrays arrays() {
    if (spilled_.load(std::memory_order_relaxed)) {
      std::fill(spills_.begin(), spills_.end(), ExactSpill3{});
      spilled_.store(false, std::memory_order_relaxed);
    }
    return {words_.data(), spills_.data(), &spilled_};
  }
  std::size_t bytes() const {
    return words_.capacity() * sizeof(ExactWords3) + spills_.capacity() * sizeof(ExactSpill3);
  }

 private:
  HostVector<ExactWords3> words_;
  HostVector<ExactSpill3> spills_;
  std::atomic<bool> spilled_{false};
};

}  // namespace gpudem
