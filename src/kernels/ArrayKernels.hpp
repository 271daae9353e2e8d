#pragma once
/// Element-wise array functors for parallel_for, shared by the engine's components.
#include <cstddef>
#include <vector>

#include "core/Config.hpp"
#include "kernels/DeviceArray.hpp"
#include "kernels/ParallelFor.hpp"

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

/// Resizes `out` (in Space memory) to n values and copies the n values at `in` (also in Space
/// memory, not in `out`) into it.
template <class Space, class T>
void copy_values(const T* in, std::size_t n, DeviceArray<T, Space>& out) {
  out.resize(n);
  parallel_for(Space{}, n, CopyArray<T>{in, out.data()});
}

/// Host copy of the n values at `data` in Space memory (a part of a larger array).
template <class Space, class T>
std::vector<T> download_values(const T* data, std::size_t n) {
  DeviceArray<T, Space> copy(n);
  parallel_for(Space{}, n, CopyArray<T>{data, copy.data()});
  std::vector<T> host;
  copy.download(host);
  return host;
}

}  // namespace gpudem
