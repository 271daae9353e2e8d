#pragma once
/// Turns the run-time contact model of a scene into the compile-time law of a force compute:
/// one instantiation of ContactForceCompute per valid combination of slots, selected once at
/// start-up. Each backend instantiates it per normal law and law scalar in its own
/// translation unit (generated from ForceComputeInstance.in by engine/engine.cmake), so the
/// combinations compile in parallel.
#include <memory>
#include <stdexcept>

#include "engine/ContactForceCompute.hpp"
#include "engine/EngineInstances.hpp"

namespace gpudem::factory {

template <class Space, class S, NormalLaw N, DampingLaw D, TangentialLaw T, RollingLaw R,
          CohesionLaw C>
LawForceCompute<Space, S> make(const EngineSetup& setup) {
  if constexpr (is_compiled_contact_model(ContactModel{N, D, T, R, C})) {
    using Law = ContactLawOf<N, D, T, R, C, S>;
    static_assert(Law::history_size == contact_history_width(ContactModel{N, D, T, R, C}),
                  "the history width the host side declares (ContactModel.hpp) is the law's");
    return std::make_unique<ContactForceCompute<Space, Law, ContactViewScalar<S>>>(
        setup.pair_params, setup.exact_units, setup.host_lanes);
  } else {
    throw std::invalid_argument("no force compute for contact law " +
                                contact_model_name(setup.contact_model));
  }
}

template <class Space, class S, NormalLaw N, DampingLaw D, TangentialLaw T, RollingLaw R>
LawForceCompute<Space, S> make(const EngineSetup& setup) {
  switch (setup.contact_model.cohesion) {
    case CohesionLaw::None:
      return make<Space, S, N, D, T, R, CohesionLaw::None>(setup);
    case CohesionLaw::Sjkr:
      return make<Space, S, N, D, T, R, CohesionLaw::Sjkr>(setup);
    case CohesionLaw::Jkr:
      return make<Space, S, N, D, T, R, CohesionLaw::Jkr>(setup);
  }
  throw std::invalid_argument("unknown cohesion law");
}

template <class Space, class S, NormalLaw N, DampingLaw D, TangentialLaw T>
LawForceCompute<Space, S> make(const EngineSetup& setup) {
  switch (setup.contact_model.rolling) {
    case RollingLaw::None:
      return make<Space, S, N, D, T, RollingLaw::None>(setup);
    case RollingLaw::ConstantTorque:
      return make<Space, S, N, D, T, RollingLaw::ConstantTorque>(setup);
    case RollingLaw::Epsd:
      return make<Space, S, N, D, T, RollingLaw::Epsd>(setup);
  }
  throw std::invalid_argument("unknown rolling law");
}

template <class Space, class S, NormalLaw N, DampingLaw D>
LawForceCompute<Space, S> make(const EngineSetup& setup) {
  switch (setup.contact_model.tangential) {
    case TangentialLaw::None:
      return make<Space, S, N, D, TangentialLaw::None>(setup);
    case TangentialLaw::LinearHistory:
      return make<Space, S, N, D, TangentialLaw::LinearHistory>(setup);
    case TangentialLaw::Mindlin:
      return make<Space, S, N, D, TangentialLaw::Mindlin>(setup);
  }
  throw std::invalid_argument("unknown tangential law");
}

/// The force compute of setup.contact_model, whose normal law must be N, in law scalar S.
template <class Space, NormalLaw N, class S>
LawForceCompute<Space, S> make_for_normal_law(const EngineSetup& setup) {
  switch (setup.contact_model.damping) {
    case DampingLaw::None:
      return make<Space, S, N, DampingLaw::None>(setup);
    case DampingLaw::Restitution:
      return make<Space, S, N, DampingLaw::Restitution>(setup);
    case DampingLaw::Viscoelastic:
      return make<Space, S, N, DampingLaw::Viscoelastic>(setup);
  }
  throw std::invalid_argument("unknown damping law");
}

}  // namespace gpudem::factory
