#pragma once
/// Host loops over contiguous ranges of particles, one range per thread: the pair-once force
/// sweep and its history mirror (PairOnceSweep.hpp) split the particles the same way, and the
/// host's neighbour search (NeighborList.hpp) its rows.
#include <cstddef>
#include <cstdint>

#if defined(GPUDEM_HAVE_OPENMP) && defined(_OPENMP)
#include <omp.h>
#endif

namespace gpudem {

/// Threads a host loop runs on.
inline std::size_t host_thread_count() {
#if defined(GPUDEM_HAVE_OPENMP) && defined(_OPENMP)
  return static_cast<std::size_t>(omp_get_max_threads());
#else
  return 1;
#endif
}

/// Calls f(r, begin, end) for each of `parts` contiguous ranges that split [0, n) in order, range
/// r being [begin, end) = [n·r/parts, n·(r+1)/parts), the ranges on the threads side by side.
template <class F>
void host_numbered_ranges(std::size_t n, std::size_t parts, const F& f) {
  const std::int64_t count = static_cast<std::int64_t>(parts);
#if defined(GPUDEM_HAVE_OPENMP) && defined(_OPENMP)
#pragma omp parallel for schedule(static, 1)
#endif
  for (std::int64_t r = 0; r < count; ++r)
    f(static_cast<std::size_t>(r), static_cast<std::uint32_t>(n * r / parts),
      static_cast<std::uint32_t>(n * (r + 1) / parts));
}

/// Calls f(begin, end) for each range of host_numbered_ranges.
template <class F>
void host_ranges(std::size_t n, std::size_t parts, const F& f) {
  host_numbered_ranges(
      n, parts, [&f](std::size_t, std::uint32_t begin, std::uint32_t end) { f(begin, end); });
}

}  // namespace gpudem
