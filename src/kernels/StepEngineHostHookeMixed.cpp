/// Host-backend step engines for the hooke normal law in mixed precision (every valid
/// combination of the other slots).
#include "kernels/ParallelFor.hpp"
// ParallelFor.hpp must come first: the engine template calls the backend's parallel_for.
#include "kernels/EngineFactory.hpp"
#include "kernels/EngineInstances.hpp"

namespace gpudem {

template <>
std::unique_ptr<StepEngine> make_host_engine_for<NormalLaw::Hooke, float>(
    const EngineSetup& setup) {
  return factory::make_for_normal_law<HostSpace, NormalLaw::Hooke, float>(setup);
}

}  // namespace gpudem
