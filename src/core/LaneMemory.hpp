#pragma once
/// Lanes (core/Lanes.hpp) read from and written to memory: loads and stores of W consecutive
/// values, gathers by index, stores of only the lanes a bit mask selects, packed to the front,
/// and the bit mask of a lane mask. In code compiled for AVX-512 (eight doubles) or AVX2 (four
/// doubles) a gather of doubles is one instruction, and so are a mask's bits and a packed store
/// (with AVX2, a permute by a table); elsewhere they go lane by lane, without branches. Host code
/// only (GCC and Clang).
#include <cstdint>
#include <cstring>
#include <type_traits>
#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "core/Lanes.hpp"

namespace gpudem {

/// Lane l's bit of a lane bit mask: bit l.
using LaneBits = unsigned;

/// The bits of lanes [0, n), of all W where n ≥ W.
template <int W>
LaneBits first_lanes(unsigned n) {
  static_assert(W < 32, "a lane bit mask holds at most 31 lanes");
  return n >= W ? (1u << W) - 1 : (1u << n) - 1;
}

/// W values from p[0, W).
template <int W, class S>
Lanes<S, W> load_lanes(const S* p) {
  Lanes<S, W> v;
  std::memcpy(&v.v, p, sizeof(v.v));
  return v;
}

/// v's W values to p[0, W).
template <class S, int W>
void store_lanes(S* p, const Lanes<S, W>& v) {
  std::memcpy(p, &v.v, sizeof(v.v));
}

/// 0, 1, …, W − 1.
template <int W>
Lanes<std::uint32_t, W> lane_numbers() {
  Lanes<std::uint32_t, W> n;
  for (int l = 0; l < W; ++l) n.v[l] = static_cast<std::uint32_t>(l);
  return n;
}

/// The lane bit mask of a lane mask.
template <class S, int W>
LaneBits bits_of(const LaneMask<S, W>& m) {
#if defined(__AVX512DQ__)
  if constexpr (sizeof(m.bits) == 64 && sizeof(S) == 8)
    return _mm512_movepi64_mask(reinterpret_cast<__m512i>(m.bits));
#endif
#if defined(__AVX2__)
  if constexpr (sizeof(m.bits) == 32 && sizeof(S) == 8)
    return static_cast<LaneBits>(_mm256_movemask_pd(reinterpret_cast<__m256d>(m.bits)));
#endif
  LaneBits b = 0;
  for (int l = 0; l < W; ++l) b |= LaneBits(m.bits[l] != 0) << l;
  return b;
}

/// base[at[l]] in each lane l (at: element offsets from base).
template <class S, int W>
Lanes<S, W> gather(const S* base, const Lanes<std::int64_t, W>& at) {
#if defined(__AVX512F__)
  if constexpr (std::is_same_v<S, double> && W == 8)
    return Lanes<S, W>::from(_mm512_mask_i64gather_pd(_mm512_setzero_pd(), 0xff,
                                                      reinterpret_cast<__m512i>(at.v), base, 8));
#endif
#if defined(__AVX2__)
  if constexpr (std::is_same_v<S, double> && W == 4)
    return Lanes<S, W>::from(
        _mm256_mask_i64gather_pd(_mm256_setzero_pd(), base, reinterpret_cast<__m256i>(at.v),
                                 _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), 8));
#endif
  Lanes<S, W> v;
  for (int l = 0; l < W; ++l) v.v[l] = base[at.v[l]];
  return v;
}

/// v's lanes whose bit is set in `which` to base[at[l]] (at: element offsets from base, distinct
/// among those lanes).
template <class S, int W>
void scatter(S* base, const Lanes<std::int64_t, W>& at, const Lanes<S, W>& v, LaneBits which) {
#if defined(__AVX512F__)
  if constexpr (std::is_same_v<S, double> && W == 8) {
    _mm512_mask_i64scatter_pd(base, static_cast<__mmask8>(which), reinterpret_cast<__m512i>(at.v),
                              reinterpret_cast<__m512d>(v.v), 8);
    return;
  }
#endif
  for (; which != 0; which &= which - 1) {
    const int l = __builtin_ctz(which);
    base[at.v[l]] = v.v[l];
  }
}

namespace lane_detail {
/// For each bit mask of four lanes, the 32-bit elements that pack its lanes to the front, for an
/// AVX2 permute: of four 8-byte lanes (two elements each) and of four 4-byte lanes.
struct PackedOrders {
  alignas(32) int of_doubles[16][8];
  alignas(16) int of_words[16][4];
};
constexpr PackedOrders packed_orders() {
  PackedOrders t{};
  for (unsigned m = 0; m < 16; ++m) {
    int n = 0;
    for (int l = 0; l < 4; ++l)
      if (m >> l & 1u) {
        t.of_doubles[m][2 * n] = 2 * l;
        t.of_doubles[m][2 * n + 1] = 2 * l + 1;
        t.of_words[m][n++] = l;
      }
  }
  return t;
}
// internal linkage: no unit built for wider vectors defines a symbol the others could share
static constexpr PackedOrders kPackedOrders = packed_orders();
}  // namespace lane_detail

/// The lanes of v whose bit is set in `take`, in order, to p[0, popcount(take)); p[0, W) may be
/// written.
template <class S, int W>
void store_packed(S* p, const Lanes<S, W>& v, LaneBits take) {
#if defined(__AVX512F__)
  if constexpr (std::is_same_v<S, double> && W == 8) {
    _mm512_storeu_pd(
        p, _mm512_maskz_compress_pd(static_cast<__mmask8>(take), reinterpret_cast<__m512d>(v.v)));
    return;
  }
#endif
#if defined(__AVX512F__) && defined(__AVX512VL__)
  if constexpr (sizeof(S) == 4 && W == 8) {
    _mm256_storeu_si256(
        reinterpret_cast<__m256i*>(p),
        _mm256_maskz_compress_epi32(static_cast<__mmask8>(take), reinterpret_cast<__m256i>(v.v)));
    return;
  }
#endif
#if defined(__AVX2__)
  if constexpr (sizeof(S) == 8 && W == 4) {
    const __m256i order = _mm256_load_si256(
        reinterpret_cast<const __m256i*>(lane_detail::kPackedOrders.of_doubles[take & 15u]));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p),
                        _mm256_permutevar8x32_epi32(reinterpret_cast<__m256i>(v.v), order));
    return;
  }
  if constexpr (sizeof(S) == 4 && W == 4) {
    const __m128i order = _mm_load_si128(
        reinterpret_cast<const __m128i*>(lane_detail::kPackedOrders.of_words[take & 15u]));
    _mm_storeu_ps(reinterpret_cast<float*>(p),
                  _mm_permutevar_ps(reinterpret_cast<__m128>(v.v), order));
    return;
  }
#endif
  unsigned n = 0;
  for (int l = 0; l < W; ++l) {
    p[n] = v.v[l];
    n += take >> l & 1u;
  }
}

}  // namespace gpudem
