#pragma once
/// The step-engine factories of each backend, normal law and precision policy, one translation
/// unit each, generated from StepEngineInstance.in (kernels.cmake, EngineFactory.hpp);
/// make_host_engine / make_cuda_engine pick one by the scene's law and precision.
#include <memory>
#include <stdexcept>
#include <type_traits>

#include "kernels/StepEngine.hpp"

namespace gpudem {

/// The host engine for setup.contact_model, whose normal law must be N, in precision policy Pr.
template <NormalLaw N, Precision Pr>
std::unique_ptr<StepEngine> make_host_engine_for(const EngineSetup& setup);
/// The CUDA engine for setup.contact_model, whose normal law must be N, in precision policy Pr.
template <NormalLaw N, Precision Pr>
std::unique_ptr<StepEngine> make_cuda_engine_for(const EngineSetup& setup);

#define GPUDEM_DECLARE_ENGINES(Law, Policy)                                            \
  template <>                                                                          \
  std::unique_ptr<StepEngine> make_host_engine_for<NormalLaw::Law, Precision::Policy>( \
      const EngineSetup&);                                                             \
  template <>                                                                          \
  std::unique_ptr<StepEngine> make_cuda_engine_for<NormalLaw::Law, Precision::Policy>( \
      const EngineSetup&);
GPUDEM_DECLARE_ENGINES(Hooke, Double)
GPUDEM_DECLARE_ENGINES(Hertz, Double)
GPUDEM_DECLARE_ENGINES(Hooke, Mixed)
GPUDEM_DECLARE_ENGINES(Hertz, Mixed)
GPUDEM_DECLARE_ENGINES(Hooke, Float)
GPUDEM_DECLARE_ENGINES(Hertz, Float)
#undef GPUDEM_DECLARE_ENGINES

/// make(law, policy) for the normal law and the precision policy of `setup` (law:
/// std::integral_constant<NormalLaw, N>, policy: std::integral_constant<Precision, Pr>).
template <class Make>
std::unique_ptr<StepEngine> make_for_law_and_precision(const EngineSetup& setup, Make make) {
  const auto with_law = [&](auto policy) {
    using Hooke = std::integral_constant<NormalLaw, NormalLaw::Hooke>;
    using Hertz = std::integral_constant<NormalLaw, NormalLaw::Hertz>;
    if (setup.contact_model.normal == NormalLaw::Hertz) return make(Hertz{}, policy);
    return make(Hooke{}, policy);
  };
  switch (setup.precision) {
    case Precision::Double:
      return with_law(std::integral_constant<Precision, Precision::Double>{});
    case Precision::Mixed:
      return with_law(std::integral_constant<Precision, Precision::Mixed>{});
    case Precision::Float:
      return with_law(std::integral_constant<Precision, Precision::Float>{});
  }
  throw std::invalid_argument("unknown precision policy");
}

/// Throws std::invalid_argument naming the law when it is not one of valid_contact_models().
void require_valid_contact_model(const EngineSetup& setup);

}  // namespace gpudem
