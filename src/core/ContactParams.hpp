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

/// Calls f(field of `to`, field of `from`) for each constant, in order: the one list of the
/// fields for the functions that copy them.
template <class To, class From, class F>
GPUDEM_HD void for_each_param(ContactPairParamsT<To>& to, const ContactPairParamsT<From>& from,
                              F f) {
  f(to.hooke_stiffness, from.hooke_stiffness);
  f(to.hooke_tangential_stiffness, from.hooke_tangential_stiffness);
  f(to.effective_young, from.effective_young);
  f(to.effective_shear, from.effective_shear);
  f(to.restitution_beta, from.restitution_beta);
  f(to.viscoelastic_time, from.viscoelastic_time);
  f(to.friction_static, from.friction_static);
  f(to.friction_dynamic, from.friction_dynamic);
  f(to.rolling_friction, from.rolling_friction);
  f(to.rolling_damping, from.rolling_damping);
  f(to.cohesion_energy_density, from.cohesion_energy_density);
  f(to.surface_energy, from.surface_energy);
}

/// `p` with every constant converted to scalar To.
template <class To>
ContactPairParamsT<To> params_cast(const ContactPairParams& p) {
  ContactPairParamsT<To> out;
  for_each_param(out, p, [](To& to, Real from) { to = static_cast<To>(from); });
  return out;
}

}  // namespace gpudem
