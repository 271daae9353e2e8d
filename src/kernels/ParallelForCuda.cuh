#pragma once
/// CUDA backend of the portable kernel layer: the same calls as ParallelFor.hpp, one thread
/// per index. Included only by .cu files.
#include <cuda_runtime.h>
#include <thrust/device_ptr.h>
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/Config.hpp"
#include "kernels/ExecutionSpace.hpp"

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

}  // namespace detail

/// Threads per block of the one-thread-per-index launch.
constexpr unsigned kCudaBlockSize = 256;

template <class F>
void parallel_for(CudaSpace, std::size_t n, const F& f) {
  if (n == 0) return;
  const unsigned blocks = static_cast<unsigned>((n + kCudaBlockSize - 1) / kCudaBlockSize);
  detail::parallel_for_kernel<<<blocks, kCudaBlockSize>>>(n, f);
  detail::check_cuda(cudaGetLastError(), "parallel_for launch");
}

template <class F>
Real reduce_max(CudaSpace, std::size_t n, Real identity, const F& f) {
  thrust::counting_iterator<std::size_t> first(0);
  return thrust::transform_reduce(thrust::device, first, first + n, detail::IndexTransform<F>{f},
                                  identity, detail::MaxOp{});
}

template <class F>
Real reduce_sum(CudaSpace, std::size_t n, const F& f) {
  thrust::counting_iterator<std::size_t> first(0);
  return thrust::transform_reduce(thrust::device, first, first + n, detail::IndexTransform<F>{f},
                                  Real(0), thrust::plus<Real>());
}

inline std::uint64_t exclusive_scan(CudaSpace, const std::uint32_t* in, std::uint32_t* out,
                                    std::size_t n) {
  if (n == 0) return 0;
  std::uint32_t last_in = 0;
  detail::check_cuda(cudaMemcpy(&last_in, in + n - 1, sizeof last_in, cudaMemcpyDeviceToHost),
                     "exclusive_scan");
  thrust::exclusive_scan(thrust::device, in, in + n, out);
  std::uint32_t last_out = 0;
  detail::check_cuda(cudaMemcpy(&last_out, out + n - 1, sizeof last_out, cudaMemcpyDeviceToHost),
                     "exclusive_scan");
  return static_cast<std::uint64_t>(last_out) + last_in;
}

inline void sort_by_key(CudaSpace, std::uint64_t* keys, std::uint32_t* values, std::size_t n) {
  thrust::stable_sort_by_key(thrust::device, keys, keys + n, values);
}

}  // namespace gpudem
