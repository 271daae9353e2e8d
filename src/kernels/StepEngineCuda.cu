/// CUDA-backend step engine: picks the instantiation for the scene's contact law and precision.
#include <stdexcept>

#include "kernels/CudaMemory.hpp"
#include "kernels/EngineInstances.hpp"

namespace gpudem {

std::unique_ptr<StepEngine> make_cuda_engine(const EngineSetup& setup) {
  if (cuda::device_count() == 0)
    throw std::runtime_error("--backend cuda: no CUDA device is visible on this node");
  require_valid_contact_model(setup);
  return make_for_law_and_precision(setup, [&setup](auto law, auto policy) {
    return make_cuda_engine_for<decltype(law)::value, decltype(policy)::value>(setup);
  });
}

}  // namespace gpudem
