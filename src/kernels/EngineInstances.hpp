#pragma once
/// The step-engine factories of each backend, normal law and law scalar (the precision policy),
/// one translation unit each (EngineFactory.hpp); make_host_engine / make_cuda_engine pick one
/// by the scene's law and precision.
#include <memory>
#include <type_traits>

#include "kernels/StepEngine.hpp"

namespace gpudem {

/// The host engine for setup.contact_model, whose normal law must be N, in law scalar S.
template <NormalLaw N, class S>
std::unique_ptr<StepEngine> make_host_engine_for(const EngineSetup& setup);
/// The CUDA engine for setup.contact_model, whose normal law must be N, in law scalar S.
template <NormalLaw N, class S>
std::unique_ptr<StepEngine> make_cuda_engine_for(const EngineSetup& setup);

template <>
std::unique_ptr<StepEngine> make_host_engine_for<NormalLaw::Hooke, double>(const EngineSetup&);
template <>
std::unique_ptr<StepEngine> make_host_engine_for<NormalLaw::Hertz, double>(const EngineSetup&);
template <>
std::unique_ptr<StepEngine> make_host_engine_for<NormalLaw::Hooke, float>(const EngineSetup&);
template <>
std::unique_ptr<StepEngine> make_host_engine_for<NormalLaw::Hertz, float>(const EngineSetup&);
template <>
std::unique_ptr<StepEngine> make_cuda_engine_for<NormalLaw::Hooke, double>(const EngineSetup&);
template <>
std::unique_ptr<StepEngine> make_cuda_engine_for<NormalLaw::Hertz, double>(const EngineSetup&);
template <>
std::unique_ptr<StepEngine> make_cuda_engine_for<NormalLaw::Hooke, float>(const EngineSetup&);
template <>
std::unique_ptr<StepEngine> make_cuda_engine_for<NormalLaw::Hertz, float>(const EngineSetup&);

/// make(law, scalar) for the normal law of `setup` (law: std::integral_constant<NormalLaw, N>)
/// and the law scalar of its precision (scalar: a value of type double or float).
template <class Make>
std::unique_ptr<StepEngine> make_for_law_and_precision(const EngineSetup& setup, Make make) {
  using Hooke = std::integral_constant<NormalLaw, NormalLaw::Hooke>;
  using Hertz = std::integral_constant<NormalLaw, NormalLaw::Hertz>;
  const bool hertz = setup.contact_model.normal == NormalLaw::Hertz;
  if (setup.precision == Precision::Mixed)
    return hertz ? make(Hertz{}, float{}) : make(Hooke{}, float{});
  return hertz ? make(Hertz{}, double{}) : make(Hooke{}, double{});
}

/// Throws std::invalid_argument naming the law when it is not one of valid_contact_models().
void require_valid_contact_model(const EngineSetup& setup);

}  // namespace gpudem
