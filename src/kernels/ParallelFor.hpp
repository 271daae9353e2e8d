#pragma once
/// Host backend of the portable kernel layer: `parallel_for`, reductions, scan and sort over
/// index ranges, with the same signatures as the CUDA backend in ParallelForCuda.cuh. Physics
/// code calls only these, so one functor runs on both backends (DESIGN §2).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/Config.hpp"
#include "kernels/ExecutionSpace.hpp"

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

/// Sorts `values` by `keys` (stable, ascending); both arrays are reordered.
inline void sort_by_key(HostSpace, std::uint64_t* keys, std::uint32_t* values, std::size_t n) {
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [keys](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  std::vector<std::uint64_t> k(n);
  std::vector<std::uint32_t> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    k[i] = keys[order[i]];
    v[i] = values[order[i]];
  }
  std::copy(k.begin(), k.end(), keys);
  std::copy(v.begin(), v.end(), values);
}

}  // namespace gpudem
