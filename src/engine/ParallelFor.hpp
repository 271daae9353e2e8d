#pragma once
/// Host backend of the portable kernel layer: `parallel_for`, reductions, scan and sort over
/// index ranges, with the same signatures as the CUDA backend in ParallelForCuda.cuh. Physics
/// code calls only these, so one functor runs on both backends (docs/architecture.md, "One source,
/// two backends").
#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/ExecutionSpace.hpp"
#include "engine/HostRanges.hpp"
#include "engine/LaunchTuning.hpp"

namespace gpudem {

/// Calls f(i) for every i in [0, n).
template <class F>
void parallel_for(HostSpace, std::size_t n, const F& f) {
  const std::int64_t count = static_cast<std::int64_t>(n);
#if defined(GPUDEM_HAVE_OPENMP) && defined(_OPENMP)
#pragma omp parallel for schedule(static)
#endif
  for (std::int64_t i = 0; i < count; ++i) f(static_cast<std::size_t>(i));
}

/// The same loop: host loops have no block size, so the launch slot changes nothing.
template <class F>
void parallel_for(HostSpace space, std::size_t n, const F& f, LaunchSlot) {
  parallel_for(space, n, f);
}

/// Seconds that work() takes on the host (steady clock).
template <class W>
double seconds_to_run(HostSpace, const W& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// max over i of f(i); `identity` when n == 0.
template <class F>
Real reduce_max(HostSpace, std::size_t n, Real identity, const F& f) {
  const std::int64_t count = static_cast<std::int64_t>(n);
  Real m = identity;
#if defined(GPUDEM_HAVE_OPENMP) && defined(_OPENMP)
#pragma omp parallel for schedule(static) reduction(max : m)
#endif
  for (std::int64_t i = 0; i < count; ++i) m = std::max(m, f(static_cast<std::size_t>(i)));
  return m;
}

/// out[c] = the sum over rows i of values[i·columns + c], for c in [0, columns): one pass over the
/// rows, each thread's contiguous range of rows summed apart (host_numbered_ranges), the ranges'
/// sums then added in order.
inline void sum_columns(HostSpace, const Vec3* values, std::size_t rows, std::size_t columns,
                        Vec3* out) {
  const std::size_t parts = host_thread_count();
  std::vector<Vec3> part_sums(parts * columns);
  host_numbered_ranges(rows, parts, [&](std::size_t part, std::uint32_t begin, std::uint32_t end) {
    Vec3* sum = part_sums.data() + part * columns;
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t c = 0; c < columns; ++c) sum[c] += values[i * columns + c];
  });
  std::fill(out, out + columns, Vec3{});
  for (std::size_t part = 0; part < parts; ++part)
    for (std::size_t c = 0; c < columns; ++c) out[c] += part_sums[part * columns + c];
}

/// sum over i of f(i).
template <class F>
Real reduce_sum(HostSpace, std::size_t n, const F& f) {
  const std::int64_t count = static_cast<std::int64_t>(n);
  Real s = 0;
#if defined(GPUDEM_HAVE_OPENMP) && defined(_OPENMP)
#pragma omp parallel for schedule(static) reduction(+ : s)
#endif
  for (std::int64_t i = 0; i < count; ++i) s += f(static_cast<std::size_t>(i));
  return s;
}

/// out[i] = in[0] + ... + in[i-1]; returns the total. `in` and `out` may alias.
inline std::uint64_t exclusive_scan(HostSpace, const std::uint32_t* in, std::uint32_t* out,
                                    std::size_t n) {
  std::uint64_t running = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t v = in[i];
    out[i] = static_cast<std::uint32_t>(running);
    running += v;
  }
  return running;
}

/// Number of bits a key needs to hold values up to max_key: 0 for 0, 1 for 1, 2 for 2 and 3, ...,
/// 64 for 2^63 and above. sort_by_key looks at only that many low bits of each key.
constexpr int bits_for(std::uint64_t max_key) {
  int bits = 0;
  for (; max_key != 0; max_key >>= 1) ++bits;
  return bits;
}

namespace detail {

constexpr int kRadixDigitBits = 8;
constexpr std::size_t kRadixBuckets = std::size_t(1) << kRadixDigitBits;
constexpr std::uint64_t kRadixDigitMask = kRadixBuckets - 1;
using RadixHistogram = std::array<std::size_t, kRadixBuckets>;

/// Throws std::invalid_argument unless 0 <= key_bits <= 64 and every key is below 2^key_bits.
inline void check_key_bits(const std::uint64_t* keys, std::size_t n, int key_bits) {
  if (key_bits < 0 || key_bits > 64)
    throw std::invalid_argument("sort_by_key: key_bits must be in [0, 64]");
  std::uint64_t all = 0;
  for (std::size_t i = 0; i < n; ++i) all |= keys[i];
  if (key_bits < 64 && (all >> key_bits) != 0)
    throw std::invalid_argument("sort_by_key: a key needs more than key_bits bits");
}

/// One histogram of digit values per radix pass, from a single sweep over the keys.
inline std::vector<RadixHistogram> digit_histograms(const std::uint64_t* keys, std::size_t n,
                                                    int passes) {
  std::vector<RadixHistogram> counts(static_cast<std::size_t>(passes), RadixHistogram{});
  for (std::size_t i = 0; i < n; ++i)
    for (int p = 0; p < passes; ++p)
      ++counts[p][(keys[i] >> (p * kRadixDigitBits)) & kRadixDigitMask];
  return counts;
}

/// Stable counting-sort pass on the digit at `shift`: (keys, values) in -> out, with `count` the
/// digit histogram of the keys.
inline void radix_pass(const std::uint64_t* keys_in, const std::uint32_t* values_in,
                       std::uint64_t* keys_out, std::uint32_t* values_out, std::size_t n, int shift,
                       const RadixHistogram& count) {
  RadixHistogram next{};
  std::size_t running = 0;
  for (std::size_t d = 0; d < kRadixBuckets; ++d) {
    next[d] = running;
    running += count[d];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t slot = next[(keys_in[i] >> shift) & kRadixDigitMask]++;
    keys_out[slot] = keys_in[i];
    values_out[slot] = values_in[i];
  }
}

}  // namespace detail

/// Sorts `values` by `keys` (stable, ascending); both arrays are reordered. Every key must be
/// below 2^key_bits (bits_for of the largest key); std::invalid_argument otherwise. A least
/// significant digit radix sort over the low key_bits bits, 8 bits a pass; passes whose digit is
/// the same in every key are skipped.
inline void sort_by_key(HostSpace, std::uint64_t* keys, std::uint32_t* values, std::size_t n,
                        int key_bits) {
  detail::check_key_bits(keys, n, key_bits);
  const int passes = (key_bits + detail::kRadixDigitBits - 1) / detail::kRadixDigitBits;
  const std::vector<detail::RadixHistogram> counts = detail::digit_histograms(keys, n, passes);
  std::vector<std::uint64_t> other_keys(n);
  std::vector<std::uint32_t> other_values(n);
  std::uint64_t *key_in = keys, *key_out = other_keys.data();
  std::uint32_t *value_in = values, *value_out = other_values.data();
  for (int p = 0; p < passes; ++p) {
    const auto& count = counts[p];
    if (std::find(count.begin(), count.end(), n) != count.end()) continue;  // one digit value
    detail::radix_pass(key_in, value_in, key_out, value_out, n, p * detail::kRadixDigitBits, count);
    std::swap(key_in, key_out);
    std::swap(value_in, value_out);
  }
  if (key_in != keys) {
    std::copy(key_in, key_in + n, keys);
    std::copy(value_in, value_in + n, values);
  }
}

}  // namespace gpudem
