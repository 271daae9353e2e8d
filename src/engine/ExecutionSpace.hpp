#pragma once
/// Execution/memory space tags. A buffer lives in exactly one space; kernels run in the space
/// of the buffers they touch (docs/architecture.md, "One source, two backends").
namespace gpudem {

/// Host CPU: serial loops, or OpenMP threads when built with GPUDEM_ENABLE_OPENMP.
struct HostSpace {
  static constexpr const char* name = "host";
};

/// CUDA device: one thread per index, device memory.
struct CudaSpace {
  static constexpr const char* name = "cuda";
};

}  // namespace gpudem
