/// Host-backend instantiation of the step engine.
#include "kernels/ParallelFor.hpp"
#include "kernels/StepEngineImpl.hpp"

namespace gpudem {

std::unique_ptr<StepEngine> make_host_engine(const EngineSetup& setup) {
  return std::make_unique<StepEngineImpl<HostSpace>>(setup);
}

#if !defined(GPUDEM_HAVE_CUDA)
std::unique_ptr<StepEngine> make_cuda_engine(const EngineSetup&) {
  throw std::runtime_error(
      "this gpudem-mpi was built without the CUDA backend "
      "(rebuild with -DGPUDEM_ENABLE_CUDA=ON)");
}
#endif

}  // namespace gpudem
