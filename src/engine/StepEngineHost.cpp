/// Host-backend step engine: the particle system with the force compute of the scene's contact
/// law and precision.
#include <stdexcept>

#include "engine/EngineInstances.hpp"

namespace gpudem {

void require_compiled_contact_model(const EngineSetup& setup) {
  if (!is_compiled_contact_model(setup.contact_model))
    throw std::invalid_argument("contact law " + contact_model_name(setup.contact_model) +
                                " is not one of the combinations this build compiles (" +
                                compiled_contact_models_text() + ")");
}

std::unique_ptr<StepEngine> make_host_engine(const EngineSetup& setup) {
  require_compiled_contact_model(setup);
  return make_engine_in<HostSpace>(setup);
}

#if !defined(GPUDEM_HAVE_CUDA)
std::unique_ptr<StepEngine> make_cuda_engine(const EngineSetup&) {
  throw std::runtime_error(
      "this gpudem-mpi was built without the CUDA backend "
      "(rebuild with -DGPUDEM_ENABLE_CUDA=ON)");
}
#endif

}  // namespace gpudem
