/// CUDA-backend step engine: the particle system with the force compute of the scene's contact
/// law and precision.
#include <stdexcept>

#include "engine/CudaMemory.hpp"
#include "engine/EngineInstances.hpp"

namespace gpudem {

std::unique_ptr<StepEngine> make_cuda_engine(const EngineSetup& setup) {
  if (cuda::device_count() == 0)
    throw std::runtime_error("--backend cuda: no CUDA device is visible on this node");
  require_compiled_contact_model(setup);
  return make_engine_in<CudaSpace>(setup);
}

}  // namespace gpudem
