#pragma once
/// Element-wise array functors for parallel_for, shared by the engine's components.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/Config.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/ParallelFor.hpp"

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

/// value[i], for reductions.
struct ReadValue {
  const Real* value;
  GPUDEM_HD Real operator()(std::size_t i) const { return value[i]; }
};

/// out[k] = k.
struct Iota {
  std::uint32_t* out;
  GPUDEM_HD void operator()(std::size_t k) const { out[k] = static_cast<std::uint32_t>(k); }
};

/// out[k] = first + k.
struct IotaFrom {
  std::uint32_t* out;
  std::uint32_t first;
  GPUDEM_HD void operator()(std::size_t k) const { out[k] = first + static_cast<std::uint32_t>(k); }
};

/// out row k = in row order[k], rows of `width` values (per-particle wall histories).
template <class T>
struct GatherRows {
  const std::uint32_t* order;
  const T* in;
  T* out;
  std::uint32_t width;
  GPUDEM_HD void operator()(std::size_t k) const {
    for (std::uint32_t w = 0; w < width; ++w) out[k * width + w] = in[order[k] * width + w];
  }
};

/// Swaps the first n values of two arrays.
template <class T>
struct SwapValues {
  T* a;
  T* b;
  GPUDEM_HD void operator()(std::size_t k) const {
    const T t = a[k];
    a[k] = b[k];
    b[k] = t;
  }
};

/// Resizes `out` (in Space memory) to n values and copies the n values at `in` (also in Space
/// memory, not in `out`) into it.
template <class Space, class T>
void copy_values(const T* in, std::size_t n, DeviceArray<T, Space>& out) {
  out.resize(n);
  parallel_for(Space{}, n, CopyArray<T>{in, out.data()});
}

/// Turns the n counts at offsets[0, n) into CSR offsets in place (offsets holds n + 1 values in
/// Space memory): offsets[i] = counts[0] + ... + counts[i - 1], offsets[n] = the total, which it
/// returns. Throws std::overflow_error(`overflow`) when the total does not fit 32 bits.
template <class Space>
std::uint64_t counts_to_offsets(std::uint32_t* offsets, std::size_t n, const char* overflow) {
  const std::uint64_t total = exclusive_scan(Space{}, offsets, offsets, n);
  if (total > std::numeric_limits<std::uint32_t>::max()) throw std::overflow_error(overflow);
  parallel_for(Space{}, 1, Fill<std::uint32_t>{offsets + n, static_cast<std::uint32_t>(total)});
  return total;
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

/// Copies the host values `host` into the host.size() values at `data` in Space memory (a part
/// of a larger array).
template <class Space, class T>
void upload_values(const std::vector<T>& host, T* data) {
  DeviceArray<T, Space> copy;
  copy.upload(host);
  parallel_for(Space{}, host.size(), CopyArray<T>{copy.data(), data});
}

}  // namespace gpudem
