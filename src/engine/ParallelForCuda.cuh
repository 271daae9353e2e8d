#pragma once
/// CUDA backend of the portable kernel layer: the same calls as ParallelFor.hpp, one thread
/// per index. Included only by .cu files.
#include <cuda_runtime.h>
#include <thrust/device_ptr.h>
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/scan.h>
#include <thrust/system/cuda/execution_policy.h>
#include <thrust/transform_reduce.h>
#include <cub/device/device_radix_sort.cuh>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/Config.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/ExecutionSpace.hpp"
#include "engine/LaunchTuning.hpp"

namespace gpudem {

namespace detail {

inline void check_cuda(cudaError_t status, const char* what) {
  if (status != cudaSuccess)
    throw std::runtime_error(std::string("CUDA error in ") + what + ": " +
                             cudaGetErrorString(status));
}

template <class F>
__global__ void parallel_for_kernel(std::size_t n, F f) {
  const std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n) f(i);
}

/// Adapts f(i) -> Real to a thrust unary functor on the index.
template <class F>
struct IndexTransform {
  F f;
  __host__ __device__ Real operator()(std::size_t i) const { return f(i); }
};

struct MaxOp {
  __host__ __device__ Real operator()(Real a, Real b) const { return a > b ? a : b; }
};

/// The most threads per block parallel_for_kernel<F> can launch with on the current device (its
/// registers per thread bound it), rounded down to whole warps; read once per functor type.
template <class F>
unsigned max_block_size() {
  static const unsigned limit = [] {
    cudaFuncAttributes attributes{};
    check_cuda(cudaFuncGetAttributes(&attributes, parallel_for_kernel<F>), "cudaFuncGetAttributes");
    return static_cast<unsigned>(attributes.maxThreadsPerBlock) / 32 * 32;
  }();
  return limit;
}

/// One thread per index in [0, n), `block` threads per block, or fewer where the kernel cannot
/// launch so many (a slot's tuned block size is timed on one kernel and used by others, such
/// as the forces of a subset of the particles).
template <class F>
void launch_per_index(std::size_t n, const F& f, unsigned block) {
  if (n == 0) return;
  block = std::min(block, max_block_size<F>());
  const unsigned blocks = static_cast<unsigned>((n + block - 1) / block);
  parallel_for_kernel<<<blocks, block>>>(n, f);
  check_cuda(cudaGetLastError(), "parallel_for launch");
}

/// A 32-bit count as 64 bits, for sums that must not wrap.
struct Widen {
  __host__ __device__ std::uint64_t operator()(std::uint32_t v) const { return v; }
};

/// A CUDA event, destroyed with its scope.
struct ScopedEvent {
  cudaEvent_t event = nullptr;
  ScopedEvent() { check_cuda(cudaEventCreate(&event), "cudaEventCreate"); }
  ~ScopedEvent() { cudaEventDestroy(event); }
  ScopedEvent(const ScopedEvent&) = delete;
  ScopedEvent& operator=(const ScopedEvent&) = delete;
};

}  // namespace detail

/// Calls f(i) for every i in [0, n), kDefaultBlockSize threads per block.
template <class F>
void parallel_for(CudaSpace, std::size_t n, const F& f) {
  detail::launch_per_index(n, f, kDefaultBlockSize);
}

/// Calls f(i) for every i in [0, n) with the block size launch_tuning() holds for `slot`.
template <class F>
void parallel_for(CudaSpace, std::size_t n, const F& f, LaunchSlot slot) {
  detail::launch_per_index(n, f, launch_tuning().block_size(slot));
}

/// Seconds that the device work queued by work() takes, between two events on the default
/// stream; waits for it to finish.
template <class W>
double seconds_to_run(CudaSpace, const W& work) {
  const detail::ScopedEvent start, stop;
  detail::check_cuda(cudaEventRecord(start.event), "seconds_to_run (start)");
  work();
  detail::check_cuda(cudaEventRecord(stop.event), "seconds_to_run (stop)");
  detail::check_cuda(cudaEventSynchronize(stop.event), "seconds_to_run (wait)");
  float milliseconds = 0;
  detail::check_cuda(cudaEventElapsedTime(&milliseconds, start.event, stop.event),
                     "seconds_to_run (elapsed)");
  return 1e-3 * milliseconds;
}

namespace detail {

/// Gives `a` n elements without keeping its contents: allocates only when n exceeds its capacity
/// (from size 0, DeviceArray::resize has nothing to copy).
template <class T>
void size_discarding(DeviceArray<T, CudaSpace>& a, std::size_t n) {
  a.resize(0);
  a.resize(n);
}

/// Device memory for the temporary storage of thrust's reductions and scans, kept between calls
/// and only ever grown: once warm, a reduction allocates nothing (a cudaMalloc and a cudaFree,
/// which waits for the device, would each cost a round trip to the driver every step). One pool
/// per process (one device per rank); blocks are reused while free.
class ThrustScratch {
 public:
  using value_type = char;

  char* allocate(std::ptrdiff_t bytes) {
    const auto n = std::max<std::size_t>(static_cast<std::size_t>(bytes), 1);
    Block* chosen = nullptr;  // the largest free block
    for (Block& b : blocks_)
      if (!b.in_use && (!chosen || b.memory.bytes() > chosen->memory.bytes())) chosen = &b;
    if (!chosen) chosen = &blocks_.emplace_back();
    if (chosen->memory.bytes() < n) size_discarding(chosen->memory, n);
    chosen->in_use = true;
    return reinterpret_cast<char*>(chosen->memory.data());
  }

  void deallocate(char* p, std::size_t) {
    for (Block& b : blocks_)
      if (reinterpret_cast<char*>(b.memory.data()) == p) b.in_use = false;
  }

 private:
  struct Block {
    DeviceArray<unsigned char, CudaSpace> memory;
    bool in_use = false;
  };
  std::deque<Block> blocks_;  // stable addresses as blocks are added
};

/// thrust's execution policy on the default stream with the process's ThrustScratch.
inline auto thrust_on_scratch() {
  static ThrustScratch scratch;
  return thrust::cuda::par(scratch);
}

}  // namespace detail

template <class F>
Real reduce_max(CudaSpace, std::size_t n, Real identity, const F& f) {
  thrust::counting_iterator<std::size_t> first(0);
  return thrust::transform_reduce(detail::thrust_on_scratch(), first, first + n,
                                  detail::IndexTransform<F>{f}, identity, detail::MaxOp{});
}

template <class F>
Real reduce_sum(CudaSpace, std::size_t n, const F& f) {
  thrust::counting_iterator<std::size_t> first(0);
  return thrust::transform_reduce(detail::thrust_on_scratch(), first, first + n,
                                  detail::IndexTransform<F>{f}, Real(0), thrust::plus<Real>());
}

/// out[i] = in[0] + ... + in[i-1] (modulo 2^32); returns the total in 64 bits, so that the caller
/// sees a sum beyond 2^32 - 1 (thrust adds in the input's 32 bits). `in` and `out` may alias.
inline std::uint64_t exclusive_scan(CudaSpace, const std::uint32_t* in, std::uint32_t* out,
                                    std::size_t n) {
  if (n == 0) return 0;
  const std::uint64_t total =
      thrust::transform_reduce(detail::thrust_on_scratch(), in, in + n, detail::Widen{},
                               std::uint64_t(0), thrust::plus<std::uint64_t>());
  thrust::exclusive_scan(detail::thrust_on_scratch(), in, in + n, out);
  return total;
}

namespace detail {

/// Device memory of sort_by_key kept between calls and only ever grown, so that a sort of no more
/// items than before allocates nothing: the second key and value buffers and CUB's temporary
/// storage.
struct RadixSortScratch {
  DeviceArray<std::uint64_t, CudaSpace> keys;
  DeviceArray<std::uint32_t, CudaSpace> values;
  DeviceArray<unsigned char, CudaSpace> temporary;
};

/// The scratch of this process (one device per rank).
inline RadixSortScratch& radix_sort_scratch() {
  static RadixSortScratch scratch;
  return scratch;
}

}  // namespace detail

/// Sorts `values` by `keys` (stable, ascending) with cub::DeviceRadixSort over the low key_bits
/// bits; both arrays are reordered. Every key must be below 2^key_bits (bits_for of the largest
/// key): higher bits are not looked at. Same order as the host backend.
inline void sort_by_key(CudaSpace, std::uint64_t* keys, std::uint32_t* values, std::size_t n,
                        int key_bits) {
  if (key_bits < 0 || key_bits > 64)
    throw std::invalid_argument("sort_by_key: key_bits must be in [0, 64]");
  if (n > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("sort_by_key: more than 2^32 - 1 items");
  if (n < 2 || key_bits == 0) return;  // already in order
  const auto items = static_cast<std::uint32_t>(n);
  detail::RadixSortScratch& scratch = detail::radix_sort_scratch();
  detail::size_discarding(scratch.keys, n);
  detail::size_discarding(scratch.values, n);
  cub::DoubleBuffer<std::uint64_t> key_buffers(keys, scratch.keys.data());
  cub::DoubleBuffer<std::uint32_t> value_buffers(values, scratch.values.data());
  std::size_t temporary_bytes = 0;
  detail::check_cuda(cub::DeviceRadixSort::SortPairs(nullptr, temporary_bytes, key_buffers,
                                                     value_buffers, items, 0, key_bits),
                     "sort_by_key (temporary storage size)");
  detail::size_discarding(scratch.temporary, temporary_bytes);
  detail::check_cuda(
      cub::DeviceRadixSort::SortPairs(scratch.temporary.data(), temporary_bytes, key_buffers,
                                      value_buffers, items, 0, key_bits),
      "sort_by_key");
  if (key_buffers.Current() != keys)
    detail::check_cuda(
        cudaMemcpyAsync(keys, key_buffers.Current(), n * sizeof *keys, cudaMemcpyDeviceToDevice),
        "sort_by_key (keys back)");
  if (value_buffers.Current() != values)
    detail::check_cuda(cudaMemcpyAsync(values, value_buffers.Current(), n * sizeof *values,
                                       cudaMemcpyDeviceToDevice),
                       "sort_by_key (values back)");
}

}  // namespace gpudem
