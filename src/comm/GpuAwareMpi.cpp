#include "comm/GpuAwareMpi.hpp"

#include <mpi.h>
#if __has_include(<mpi-ext.h>)
#include <mpi-ext.h>
#endif

namespace gpudem {

bool mpi_reports_cuda_support() {
#if defined(MPIX_CUDA_AWARE_SUPPORT)
  return MPIX_Query_cuda_support() == 1;
#else
  return false;
#endif
}

bool use_gpu_aware_mpi(GpuAwareChoice choice) {
  switch (choice) {
    case GpuAwareChoice::On:
      return true;
    case GpuAwareChoice::Off:
      return false;
    case GpuAwareChoice::Auto:
      break;
  }
  return mpi_reports_cuda_support();
}

}  // namespace gpudem
