#pragma once
/// Damping slot: the normal dashpot force added to F_e, whether the sum may turn attractive,
/// and the tangential dashpot coefficient for a tangential spring of stiffness S_t.
#include <cmath>

#include "kernels/contact/NormalLaws.hpp"

namespace gpudem {

/// No dissipation in the contact.
struct NoDamping {
  static constexpr bool clamps_attraction = false;
  template <class Normal>
  GPUDEM_HD static Real normal_force(const ContactPairParams&, const ContactPoint&,
                                     const NormalResponse&) {
    return 0;
  }
  template <class Normal>
  GPUDEM_HD static Real tangential_coefficient(const ContactPairParams&, const ContactPoint&,
                                               Real) {
    return 0;
  }
};

/// Restitution dashpot, the EDEM / DEM-Engine form: F_d = c·|β|·√(S m*)·δ̇ with
/// β = ln e / √(ln² e + π²), c = Normal::damping_scale (2 for Hooke, 2√(5/6) for Hertz) and S
/// the normal (S_n) or tangential (S_t) stiffness. The sum F_e + F_d is not clamped, as in
/// those codes: it may pull briefly at the end of an inelastic contact, which is what makes
/// the rebound e exact at every e in (0, 1] (clamping would raise e = 0.05 to about 0.21).
struct RestitutionDamping {
  static constexpr bool clamps_attraction = false;
  template <class Normal>
  GPUDEM_HD static Real normal_force(const ContactPairParams& p, const ContactPoint& c,
                                     const NormalResponse& n) {
    return Normal::damping_scale * p.restitution_beta * sqrt(n.stiffness * c.reduced_mass) *
           c.overlap_rate;
  }
  template <class Normal>
  GPUDEM_HD static Real tangential_coefficient(const ContactPairParams& p, const ContactPoint& c,
                                               Real stiffness) {
    return Normal::damping_scale * p.restitution_beta * sqrt(stiffness * c.reduced_mass);
  }
};

/// Viscoelastic Hertz damping of ESyS-Particle (Brilliantov et al. 1996):
/// F_n = max(0, 4/3 E* √R* (δ^{3/2} + A √δ δ̇)), i.e. F_d = 4/3 E* √(R* δ)·A·δ̇ = ⅔ A S_n δ̇,
/// never attractive; no tangential dashpot. Restitution falls with impact speed,
/// 1 − e ∝ v^{1/5}.
struct ViscoelasticDamping {
  static constexpr bool clamps_attraction = true;
  template <class Normal>
  GPUDEM_HD static Real normal_force(const ContactPairParams& p, const ContactPoint& c,
                                     const NormalResponse& n) {
    return Real(2) / 3 * p.viscoelastic_time * n.stiffness * c.overlap_rate;
  }
  template <class Normal>
  GPUDEM_HD static Real tangential_coefficient(const ContactPairParams&, const ContactPoint&,
                                               Real) {
    return 0;
  }
};

}  // namespace gpudem
