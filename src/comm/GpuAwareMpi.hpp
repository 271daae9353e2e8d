#pragma once
/// Whether halo and migration buffers may be handed to MPI as device pointers
/// (docs/architecture.md, "Ranks"). Open MPI reports it through MPIX_Query_cuda_support(); other
/// libraries are assumed not to accept device pointers. Without it, buffers are staged through host
/// memory.
namespace gpudem {

enum class GpuAwareChoice { Auto, On, Off };

/// The MPI library's own answer: true only when it was built CUDA-aware and says so at run time.
bool mpi_reports_cuda_support();

/// auto: the library's answer; on: device pointers (the user vouches for the library); off:
/// staging through host memory.
bool use_gpu_aware_mpi(GpuAwareChoice choice);

}  // namespace gpudem
