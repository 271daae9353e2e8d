/// CUDA-backend step engine: picks the instantiation for the scene's contact law.
#include <stdexcept>

#include "kernels/CudaMemory.hpp"
#include "kernels/EngineInstances.hpp"

namespace gpudem {

std::unique_ptr<StepEngine> make_cuda_engine(const EngineSetup& setup) {
  if (cuda::device_count() == 0)
    throw std::runtime_error("--backend cuda: no CUDA device is visible on this node");
  require_valid_contact_model(setup);
  return setup.contact_model.normal == NormalLaw::Hertz ? make_cuda_hertz_engine(setup)
                                                        : make_cuda_hooke_engine(setup);
}

}  // namespace gpudem
