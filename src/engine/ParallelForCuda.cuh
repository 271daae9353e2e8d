#pragma once
/// CUDA backend of the portable kernel layer: the same calls as ParallelFor.hpp, one thread
/// per index. Included only by .cu files.
#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
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

/// Threads per block of the reductions, and the most blocks one launches: a grid of at most
/// kReduceMaxBlocks blocks whose threads stride over the indices, so that the partial results
/// fit one small buffer and the order of the additions depends only on n.
constexpr unsigned kReduceBlockSize = 256;
constexpr unsigned kReduceMaxBlocks = 1024;

struct SumOp {
  __host__ __device__ Real operator()(Real a, Real b) const { return a + b; }
};

/// Block b folds op over f(i) of its threads' indices (i = b·blockDim + thread, striding by the
/// whole grid), then over its threads in a tree, and writes partial[b].
template <class F, class Op>
__global__ void __launch_bounds__(kReduceBlockSize)
    reduce_blocks_kernel(std::size_t n, F f, Op op, Real identity, Real* partial) {
  __shared__ Real folded[kReduceBlockSize];
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  Real value = identity;
  for (std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; i < n;
       i += stride)
    value = op(value, f(i));
  folded[threadIdx.x] = value;
  __syncthreads();
  for (unsigned half = blockDim.x / 2; half > 0; half /= 2) {
    if (threadIdx.x < half)
      folded[threadIdx.x] = op(folded[threadIdx.x], folded[threadIdx.x + half]);
    __syncthreads();
  }
  if (threadIdx.x == 0) partial[blockIdx.x] = folded[0];
}

/// The device buffer of kReduceMaxBlocks partial results, allocated once per process.
Real* reduction_partials();

/// Copies the first `count` partial results to `host` (waits for the device).
void download_partials(Real* host, unsigned count);

/// op folded over f(i), i in [0, n), starting from `identity`: one kernel of per-block partial
/// results, folded in block order on the host. The law-independent parts are compiled once
/// (CudaPrimitives.cu); only this small kernel is instantiated per functor.
template <class F, class Op>
Real reduce(std::size_t n, const F& f, Op op, Real identity) {
  if (n == 0) return identity;
  const auto blocks = static_cast<unsigned>(
      std::min<std::size_t>((n + kReduceBlockSize - 1) / kReduceBlockSize, kReduceMaxBlocks));
  reduce_blocks_kernel<<<blocks, kReduceBlockSize>>>(n, f, op, identity, reduction_partials());
  check_cuda(cudaGetLastError(), "reduction launch");
  Real partial[kReduceMaxBlocks];
  download_partials(partial, blocks);
  Real result = identity;
  for (unsigned b = 0; b < blocks; ++b) result = op(result, partial[b]);
  return result;
}

}  // namespace detail

template <class F>
Real reduce_max(CudaSpace, std::size_t n, Real identity, const F& f) {
  return detail::reduce(n, f, detail::MaxOp{}, identity);
}

template <class F>
Real reduce_sum(CudaSpace, std::size_t n, const F& f) {
  return detail::reduce(n, f, detail::SumOp{}, Real(0));
}

namespace detail {

/// Component k of column c of a per-(row, column) Vec3 array, row i.
struct ColumnComponent {
  const Vec3* values;
  std::size_t columns;
  std::size_t column;
  int component;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return axis(values[i * columns + column], component);
  }
};

}  // namespace detail

/// out[c] = the sum over rows i of values[i·columns + c], for c in [0, columns): three
/// reductions per column (`values` in device memory, `out` on the host).
inline void sum_columns(CudaSpace, const Vec3* values, std::size_t rows, std::size_t columns,
                        Vec3* out) {
  for (std::size_t c = 0; c < columns; ++c)
    for (int k = 0; k < 3; ++k)
      axis(out[c], k) =
          reduce_sum(CudaSpace{}, rows, detail::ColumnComponent{values, columns, c, k});
}

/// out[i] = in[0] + ... + in[i-1] (modulo 2^32); returns the total in 64 bits, so that the caller
/// sees a sum beyond 2^32 - 1. `in` and `out` may alias. Compiled once (CudaPrimitives.cu).
std::uint64_t exclusive_scan(CudaSpace, const std::uint32_t* in, std::uint32_t* out, std::size_t n);

/// Sorts `values` by `keys` (stable, ascending) with cub::DeviceRadixSort over the low key_bits
/// bits; both arrays are reordered. Every key must be below 2^key_bits (bits_for of the largest
/// key): higher bits are not looked at. Same order as the host backend. Compiled once
/// (CudaPrimitives.cu).
void sort_by_key(CudaSpace, std::uint64_t* keys, std::uint32_t* values, std::size_t n,
                 int key_bits);

}  // namespace gpudem
