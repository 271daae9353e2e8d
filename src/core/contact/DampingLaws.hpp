#pragma once
/// Damping slot: the normal dashpot force added to F_e, whether the sum may turn attractive,
/// and the tangential dashpot coefficient for a tangential spring of stiffness S_t.
#include <cmath>

#include "core/contact/NormalLaws.hpp"

namespace gpudem {

/// No dissipation in the contact.
struct NoDamping {
  static constexpr const char* keyword = "none";
  static constexpr const char* material_keys = "";
  static constexpr bool clamps_attraction = false;
  template <class Normal, class S>
  GPUDEM_HD static S normal_force(const ContactPairParamsT<S>&, const ContactPointT<S>&,
                                  const NormalResponse<S>&) {
    return 0;
  }
  template <class Normal, class S>
  GPUDEM_HD static S tangential_coefficient(const ContactPairParamsT<S>&, const ContactPointT<S>&,
                                            S) {
    return 0;
  }
};

/// Restitution dashpot, the EDEM / DEM-Engine form: F_d = c·|β|·√(S m*)·δ̇ with
/// β = ln e / √(ln² e + π²), c = Normal::damping_scale (2 for Hooke, 2√(5/6) for Hertz) and S
/// the normal (S_n) or tangential (S_t) stiffness. The sum F_e + F_d is not clamped, as in
/// those codes: it may pull briefly at the end of an inelastic contact, which is what makes
/// the rebound e exact at every e in (0, 1] (clamping would raise e = 0.05 to about 0.21).
/// Host: |β| = |ln e| / √(ln² e + π²), the damping ratio of a linear spring–dashpot whose
/// coefficient of restitution is e (Tsuji et al. 1992); 0 for e = 1.
struct RestitutionDamping {
  static constexpr const char* keyword = "restitution";
  static constexpr const char* material_keys = "restitution";
  static double damping_ratio(double e) {
    const double log_e = std::log(e);
    return std::abs(log_e) /
           std::sqrt(log_e * log_e + 3.14159265358979323846 * 3.14159265358979323846);
  }
  static constexpr bool clamps_attraction = false;
  template <class Normal, class S>
  GPUDEM_HD static S normal_force(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                                  const NormalResponse<S>& n) {
    return S(Normal::damping_scale) * p.restitution_beta *
           square_root(n.stiffness * c.reduced_mass) * c.overlap_rate;
  }
  template <class Normal, class S>
  GPUDEM_HD static S tangential_coefficient(const ContactPairParamsT<S>& p,
                                            const ContactPointT<S>& c, S stiffness) {
    return S(Normal::damping_scale) * p.restitution_beta * square_root(stiffness * c.reduced_mass);
  }
};

/// Viscoelastic Hertz damping of ESyS-Particle (Brilliantov et al. 1996):
/// F_n = max(0, 4/3 E* √R* (δ^{3/2} + A √δ δ̇)), i.e. F_d = 4/3 E* √(R* δ)·A·δ̇ = ⅔ A S_n δ̇,
/// never attractive; no tangential dashpot. Restitution falls with impact speed,
/// 1 − e ∝ v^{1/5}.
struct ViscoelasticDamping {
  static constexpr const char* keyword = "viscoelastic";
  static constexpr const char* material_keys = "viscoelastic_time";
  static constexpr bool clamps_attraction = true;
  template <class Normal, class S>
  GPUDEM_HD static S normal_force(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                                  const NormalResponse<S>& n) {
    return S(2) / 3 * p.viscoelastic_time * n.stiffness * c.overlap_rate;
  }
  template <class Normal, class S>
  GPUDEM_HD static S tangential_coefficient(const ContactPairParamsT<S>&, const ContactPointT<S>&,
                                            S) {
    return 0;
  }
};

}  // namespace gpudem
