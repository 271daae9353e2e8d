/// CUDA-backend instantiation of the step engine: the same template as the host backend.
#include "kernels/CudaMemory.hpp"
#include "kernels/ParallelForCuda.cuh"
#include "kernels/StepEngineImpl.hpp"

namespace gpudem {

std::unique_ptr<StepEngine> make_cuda_engine(const EngineSetup& setup) {
  if (cuda::device_count() == 0)
    throw std::runtime_error("--backend cuda: no CUDA device is visible on this node");
  return std::make_unique<StepEngineImpl<CudaSpace>>(setup);
}

}  // namespace gpudem
