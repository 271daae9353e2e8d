#pragma once
/// Gathering an array into a new order, e.g. particle arrays into cell order after binning.
#include <cstddef>
#include <cstdint>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/ParallelFor.hpp"

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

/// out[k] = in[order[k]] converted to Real (positions in the state scalar P for a search that
/// reads Real).
template <class P>
struct GatherInReal {
  const std::uint32_t* order;
  const Vec4T<P>* in;
  Real4* out;
  GPUDEM_HD void operator()(std::size_t k) const { out[k] = vec4_cast<Real>(in[order[k]]); }
};

/// permute() of values held in scalar P into Real values.
template <class P, class Space>
void permute_into_real(Space space, const std::uint32_t* order, const Vec4T<P>* in, Real4* out,
                       std::size_t n) {
  parallel_for(space, n, GatherInReal<P>{order, in, out});
}

}  // namespace gpudem
