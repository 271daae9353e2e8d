#pragma once
/// Gathering an array into a new order, e.g. particle arrays into cell order after binning.
#include <cstddef>
#include <cstdint>

#include "core/Config.hpp"
#include "kernels/ParallelFor.hpp"

namespace gpudem {

/// out[k] = in[order[k]].
template <class T>
struct GatherByOrder {
  const std::uint32_t* order;
  const T* in;
  T* out;
  GPUDEM_HD void operator()(std::size_t k) const { out[k] = in[order[k]]; }
};

/// Writes out[k] = in[order[k]] for k in [0, n), in the memory of `space`. `in` and `out` must
/// not overlap; `order` must be a permutation of [0, n).
template <class T, class Space>
void permute(Space space, const std::uint32_t* order, const T* in, T* out, std::size_t n) {
  parallel_for(space, n, GatherByOrder<T>{order, in, out});
}

}  // namespace gpudem
