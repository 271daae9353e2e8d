#pragma once
/// Turns a validated scene and its particles into the engine's plain setup: pair constants,
/// walls, Verlet skin and time step.
#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"
#include "kernels/StepEngine.hpp"

namespace gpudem {

/// Time-step limits of a scene [s].
struct TimeStepLimits {
  double contact_duration = 0;  ///< t_c = π √(m*_min / k_n), lightest particle pair
  double rayleigh =
      0;  ///< T_R = π R_min √(ρ/G) / (0.1631 ν + 0.8766), smallest over materials in use
  double critical() const { return contact_duration < rayleigh ? contact_duration : rayleigh; }
};

/// Limits for the particles present (empty store: +infinity for both).
TimeStepLimits time_step_limits(const Scene& scene, const ParticleStore& particles);

/// The engine setup; dt = dt_fraction × critical step when the scene says "auto".
EngineSetup make_engine_setup(const Scene& scene, const ParticleStore& particles);

}  // namespace gpudem
