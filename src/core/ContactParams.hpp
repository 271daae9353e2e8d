#pragma once
/// Per material pair contact constants, resolved once on the host from the materials, the
/// mixing rule and any explicit [[pair]] entry (SceneSetup.cpp), then read by every contact
/// law slot. A slot reads only the fields it needs; the table has material_count² entries.
#include "core/Config.hpp"

namespace gpudem {

struct ContactPairParams {
  Real hooke_stiffness = 0;             ///< k_n of the Hooke law [N/m]
  Real hooke_tangential_stiffness = 0;  ///< k_t = 2/7 k_n of the linear history law [N/m]
  Real effective_young = 0;             ///< E*: 1/E* = (1−ν₁²)/E₁ + (1−ν₂²)/E₂ [Pa]
  Real effective_shear = 0;  ///< G*: 1/G* = (2−ν₁)/G₁ + (2−ν₂)/G₂, G = E/(2(1+ν)) [Pa]
  Real restitution_beta = 0;   ///< |β| = |ln e| / √(ln² e + π²) of the pair restitution e [-]
  Real viscoelastic_time = 0;  ///< A of the viscoelastic law [s]
  Real friction_static = 0;    ///< μ_s, tested before sliding starts [-]
  Real friction_dynamic = 0;   ///< μ_d, applied while sliding [-]
  Real rolling_friction = 0;   ///< μ_r [-]
  Real rolling_damping = 0;    ///< η_r, EPSD rolling dashpot ratio [-]
  Real cohesion_energy_density = 0;  ///< k_c of simplified JKR [J/m³]
};

}  // namespace gpudem
