/// Host-backend step engine: picks the instantiation for the scene's contact law and precision.
#include <stdexcept>

#include "kernels/EngineInstances.hpp"

namespace gpudem {

void require_valid_contact_model(const EngineSetup& setup) {
  if (!is_valid_contact_model(setup.contact_model))
    throw std::invalid_argument("contact law " + contact_model_name(setup.contact_model) +
                                " is not one of the combinations the engine is built for");
}

std::unique_ptr<StepEngine> make_host_engine(const EngineSetup& setup) {
  require_valid_contact_model(setup);
  return make_for_law_and_precision(setup, [&setup](auto law, auto policy) {
    return make_host_engine_for<decltype(law)::value, decltype(policy)::value>(setup);
  });
}

#if !defined(GPUDEM_HAVE_CUDA)
std::unique_ptr<StepEngine> make_cuda_engine(const EngineSetup&) {
  throw std::runtime_error(
      "this gpudem-mpi was built without the CUDA backend "
      "(rebuild with -DGPUDEM_ENABLE_CUDA=ON)");
}
#endif

}  // namespace gpudem
