/// The CUDA primitives that do not depend on a functor, declared in ParallelForCuda.cuh and
/// compiled here once for the whole library rather than in every translation unit that calls
/// them: the exclusive scan, the radix sort and the reductions' buffer of partial results.
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/scan.h>
#include <thrust/system/cuda/execution_policy.h>
#include <thrust/transform_reduce.h>

#include <cub/device/device_radix_sort.cuh>
#include <deque>
#include <limits>

#include "engine/DeviceArray.hpp"
#include "engine/ParallelForCuda.cuh"

namespace gpudem {

namespace {

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
auto thrust_on_scratch() {
  static ThrustScratch scratch;
  return thrust::cuda::par(scratch);
}

/// A 32-bit count as 64 bits, for sums that must not wrap.
struct Widen {
  __host__ __device__ std::uint64_t operator()(std::uint32_t v) const { return v; }
};

/// Device memory of sort_by_key kept between calls and only ever grown, so that a sort of no more
/// items than before allocates nothing: the second key and value buffers and CUB's temporary
/// storage.
struct RadixSortScratch {
  DeviceArray<std::uint64_t, CudaSpace> keys;
  DeviceArray<std::uint32_t, CudaSpace> values;
  DeviceArray<unsigned char, CudaSpace> temporary;
};

/// The scratch of this process (one device per rank).
RadixSortScratch& radix_sort_scratch() {
  static RadixSortScratch scratch;
  return scratch;
}

}  // namespace

namespace detail {

Real* reduction_partials() {
  static DeviceArray<Real, CudaSpace> partials(kReduceMaxBlocks);
  return partials.data();
}

void download_partials(Real* host, unsigned count) {
  check_cuda(cudaMemcpy(host, reduction_partials(), count * sizeof(Real), cudaMemcpyDeviceToHost),
             "reduction (partial results)");
}

}  // namespace detail

std::uint64_t exclusive_scan(CudaSpace, const std::uint32_t* in, std::uint32_t* out,
                             std::size_t n) {
  if (n == 0) return 0;
  const std::uint64_t total = thrust::transform_reduce(
      thrust_on_scratch(), in, in + n, Widen{}, std::uint64_t(0), thrust::plus<std::uint64_t>());
  thrust::exclusive_scan(thrust_on_scratch(), in, in + n, out);
  return total;
}

void sort_by_key(CudaSpace, std::uint64_t* keys, std::uint32_t* values, std::size_t n,
                 int key_bits) {
  if (key_bits < 0 || key_bits > 64)
    throw std::invalid_argument("sort_by_key: key_bits must be in [0, 64]");
  if (n > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("sort_by_key: more than 2^32 - 1 items");
  if (n < 2 || key_bits == 0) return;  // already in order
  const auto items = static_cast<std::uint32_t>(n);
  RadixSortScratch& scratch = radix_sort_scratch();
  size_discarding(scratch.keys, n);
  size_discarding(scratch.values, n);
  cub::DoubleBuffer<std::uint64_t> key_buffers(keys, scratch.keys.data());
  cub::DoubleBuffer<std::uint32_t> value_buffers(values, scratch.values.data());
  std::size_t temporary_bytes = 0;
  detail::check_cuda(cub::DeviceRadixSort::SortPairs(nullptr, temporary_bytes, key_buffers,
                                                     value_buffers, items, 0, key_bits),
                     "sort_by_key (temporary storage size)");
  size_discarding(scratch.temporary, temporary_bytes);
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
