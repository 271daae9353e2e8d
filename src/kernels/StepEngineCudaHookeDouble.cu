/// CUDA-backend step engines for the hooke normal law in double precision: the same template as
/// the host backend.
#include "kernels/ParallelForCuda.cuh"
// ParallelForCuda.cuh must come first: the engine template calls the backend's parallel_for.
#include "kernels/EngineFactory.hpp"
#include "kernels/EngineInstances.hpp"

namespace gpudem {

template <>
std::unique_ptr<StepEngine> make_cuda_engine_for<NormalLaw::Hooke, double>(
    const EngineSetup& setup) {
  return factory::make_for_normal_law<CudaSpace, NormalLaw::Hooke, double>(setup);
}

}  // namespace gpudem
