#pragma once
/// Turns the run-time contact model of a scene into the compile-time law of a step engine:
/// one instantiation of StepEngineImpl per valid combination of slots, selected once at
/// start-up. Each backend instantiates it per normal law and precision policy in its own
/// translation unit (generated from StepEngineInstance.in by kernels.cmake), so the
/// combinations compile in parallel.
#include <memory>
#include <stdexcept>

#include "kernels/StepEngineImpl.hpp"

namespace gpudem::factory {

/// The scalars of a precision policy (Scene.hpp): the contact law's (its arithmetic, history
/// and force sums) and the particle state's (positions, velocities, spins).
template <Precision>
struct PrecisionScalars;
template <>
struct PrecisionScalars<Precision::Double> {
  using Law = double;
  using State = double;
};
template <>
struct PrecisionScalars<Precision::Mixed> {
  using Law = float;
  using State = double;
};
template <>
struct PrecisionScalars<Precision::Float> {
  using Law = float;
  using State = float;
};

template <class Space, Precision Pr, NormalLaw N, DampingLaw D, TangentialLaw T, RollingLaw R,
          CohesionLaw C>
std::unique_ptr<StepEngine> make(const EngineSetup& setup) {
  if constexpr (is_valid_contact_model(ContactModel{N, D, T, R, C})) {
    using Scalars = PrecisionScalars<Pr>;
    using Law = ContactLawOf<N, D, T, R, C, typename Scalars::Law>;
    return std::make_unique<StepEngineImpl<Space, Law, typename Scalars::State>>(setup);
  } else {
    throw std::invalid_argument("no step engine for contact law " +
                                contact_model_name(setup.contact_model));
  }
}

template <class Space, Precision Pr, NormalLaw N, DampingLaw D, TangentialLaw T, RollingLaw R>
std::unique_ptr<StepEngine> make(const EngineSetup& setup) {
  switch (setup.contact_model.cohesion) {
    case CohesionLaw::None:
      return make<Space, Pr, N, D, T, R, CohesionLaw::None>(setup);
    case CohesionLaw::Sjkr:
      return make<Space, Pr, N, D, T, R, CohesionLaw::Sjkr>(setup);
  }
  throw std::invalid_argument("unknown cohesion law");
}

template <class Space, Precision Pr, NormalLaw N, DampingLaw D, TangentialLaw T>
std::unique_ptr<StepEngine> make(const EngineSetup& setup) {
  switch (setup.contact_model.rolling) {
    case RollingLaw::None:
      return make<Space, Pr, N, D, T, RollingLaw::None>(setup);
    case RollingLaw::ConstantTorque:
      return make<Space, Pr, N, D, T, RollingLaw::ConstantTorque>(setup);
    case RollingLaw::Epsd:
      return make<Space, Pr, N, D, T, RollingLaw::Epsd>(setup);
  }
  throw std::invalid_argument("unknown rolling law");
}

template <class Space, Precision Pr, NormalLaw N, DampingLaw D>
std::unique_ptr<StepEngine> make(const EngineSetup& setup) {
  switch (setup.contact_model.tangential) {
    case TangentialLaw::None:
      return make<Space, Pr, N, D, TangentialLaw::None>(setup);
    case TangentialLaw::LinearHistory:
      return make<Space, Pr, N, D, TangentialLaw::LinearHistory>(setup);
    case TangentialLaw::Mindlin:
      return make<Space, Pr, N, D, TangentialLaw::Mindlin>(setup);
  }
  throw std::invalid_argument("unknown tangential law");
}

/// The engine for setup.contact_model, whose normal law must be N, in precision policy Pr.
template <class Space, NormalLaw N, Precision Pr>
std::unique_ptr<StepEngine> make_for_normal_law(const EngineSetup& setup) {
  switch (setup.contact_model.damping) {
    case DampingLaw::None:
      return make<Space, Pr, N, DampingLaw::None>(setup);
    case DampingLaw::Restitution:
      return make<Space, Pr, N, DampingLaw::Restitution>(setup);
    case DampingLaw::Viscoelastic:
      return make<Space, Pr, N, DampingLaw::Viscoelastic>(setup);
  }
  throw std::invalid_argument("unknown damping law");
}

}  // namespace gpudem::factory
