#pragma once
/// Per material pair contact constants, resolved once on the host from the materials, the
/// mixing rule and any explicit [[pair]] entry (SceneSetup.cpp), then read by every contact
/// law slot. A slot reads only the fields it needs; the table has material_count² entries. The
/// host resolves them in Real; a law evaluated in float reads a converted copy (params_cast).
#include "core/Config.hpp"

namespace gpudem {

template <class S>
struct ContactPairParamsT {
  S hooke_stiffness = 0;             ///< k_n of the Hooke law [N/m]
  S hooke_tangential_stiffness = 0;  ///< k_t = 2/7 k_n of the linear history law [N/m]
  S effective_young = 0;             ///< E*: 1/E* = (1−ν₁²)/E₁ + (1−ν₂²)/E₂ [Pa]
  S effective_shear = 0;   ///< G*: 1/G* = (2−ν₁)/G₁ + (2−ν₂)/G₂, G = E/(2(1+ν)) [Pa]
  S restitution_beta = 0;  ///< |β| = |ln e| / √(ln² e + π²) of the pair restitution e [-]
  S viscoelastic_time = 0;        ///< A of the viscoelastic law [s]
  S friction_static = 0;          ///< μ_s, tested before sliding starts [-]
  S friction_dynamic = 0;         ///< μ_d, applied while sliding [-]
  S rolling_friction = 0;         ///< μ_r [-]
  S rolling_damping = 0;          ///< η_r, EPSD rolling dashpot ratio [-]
  S cohesion_energy_density = 0;  ///< k_c of simplified JKR [J/m³]
  S surface_energy = 0;           ///< γ of JKR, the pair's work of adhesion [J/m²]
};

using ContactPairParams = ContactPairParamsT<Real>;

/// One contact that bounds the time step, as the host sees it: the laws' host functions
/// (contact_duration, stable_step, peak_frequency_squared) take it.
struct ImpactPair {
  double radius = 0;          ///< R* [m]
  double mass = 0;            ///< m* [kg]
  double young = 0;           ///< E* [Pa]
  double shear = 0;           ///< G* [Pa]
  double stiffness = 0;       ///< k_n of the Hooke law [N/m]
  double speed = 0;           ///< impact speed v [m/s]
  double surface_energy = 0;  ///< γ of JKR adhesion, 0 without [J/m²]
};

/// G = E / (2(1 + ν)) [Pa] of a material of Young's modulus E and Poisson ratio ν.
inline double shear_modulus(double young, double poisson) { return young / (2 * (1 + poisson)); }

/// `p` with every constant converted to scalar To.
template <class To>
ContactPairParamsT<To> params_cast(const ContactPairParams& p) {
  ContactPairParamsT<To> out;
  out.hooke_stiffness = static_cast<To>(p.hooke_stiffness);
  out.hooke_tangential_stiffness = static_cast<To>(p.hooke_tangential_stiffness);
  out.effective_young = static_cast<To>(p.effective_young);
  out.effective_shear = static_cast<To>(p.effective_shear);
  out.restitution_beta = static_cast<To>(p.restitution_beta);
  out.viscoelastic_time = static_cast<To>(p.viscoelastic_time);
  out.friction_static = static_cast<To>(p.friction_static);
  out.friction_dynamic = static_cast<To>(p.friction_dynamic);
  out.rolling_friction = static_cast<To>(p.rolling_friction);
  out.rolling_damping = static_cast<To>(p.rolling_damping);
  out.cohesion_energy_density = static_cast<To>(p.cohesion_energy_density);
  out.surface_energy = static_cast<To>(p.surface_energy);
  return out;
}

}  // namespace gpudem
