#pragma once
/// Element-wise array functors for parallel_for, shared by the engine's components.
#include <cstddef>

#include "core/Config.hpp"

namespace gpudem {

template <class T>
struct CopyArray {
  const T* in;
  T* out;
  GPUDEM_HD void operator()(std::size_t k) const { out[k] = in[k]; }
};

template <class T>
struct Fill {
  T* out;
  T value;
  GPUDEM_HD void operator()(std::size_t k) const { out[k] = value; }
};

}  // namespace gpudem
