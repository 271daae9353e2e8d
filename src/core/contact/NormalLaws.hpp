#pragma once
/// Normal elastic slot: the repulsive spring force F_e(δ), the tangent stiffness S_n = dF_e/dδ
/// that damping laws scale with, and the stored energy. `damping_scale` is the factor c of the
/// restitution dashpot γ = c·|β|·√(S_n m*) that makes its restitution equal e (below).
#include <algorithm>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/contact/ContactPoint.hpp"
#include "core/contact/JkrRelation.hpp"

namespace gpudem {

template <class S>
struct NormalResponse {
  S force = 0;      ///< F_e > 0, repulsive [N]
  S stiffness = 0;  ///< tangent stiffness S_n = dF_e/dδ [N/m]
  S secant = 0;     ///< F_e / δ [N/m]
};

/// Linear spring (Cundall & Strack 1979): F_e = k_n δ, S_n = k_n, energy ½ k_n δ².
/// With γ = 2|β|√(k_n m*) the damped oscillator rebounds with restitution e exactly.
/// Host: t_c = π √(m*/k_n), the peak overlap of an undamped impact at v δ_max = v √(m*/k_n)
/// (½ m* v² = ½ k_n δ_max²); velocity Verlet is stable for ω dt < 2, ω = √(k_n/m*), i.e.
/// dt < 2 √(m*/k_n) (the linear history spring's tangential mode, k_t = 2/7 k_n on the
/// effective mass 2/7 m*, has the same ω).
struct HookeNormal {
  static constexpr const char* keyword = "hooke";
  static constexpr const char* material_keys = "";
  static constexpr bool needs_effective_radius = false;
  static constexpr Real damping_scale = 2;
  template <class S>
  GPUDEM_HD static NormalResponse<S> respond(const ContactPairParamsT<S>& p,
                                             const ContactPointT<S>& c) {
    return NormalResponse<S>{p.hooke_stiffness * c.overlap, p.hooke_stiffness, p.hooke_stiffness};
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>& p, const ContactPointT<S>& c) {
    return S(0.5) * p.hooke_stiffness * c.overlap * c.overlap;
  }
  static double contact_duration(const ImpactPair& p) {
    return 3.14159265358979323846 * std::sqrt(p.mass / p.stiffness);
  }
  static double peak_overlap(const ImpactPair& p) {
    return p.speed * std::sqrt(p.mass / p.stiffness);
  }
  template <class Tangential>
  static double stable_step(const ImpactPair& p) {
    return 2 * std::sqrt(p.mass / p.stiffness);
  }
};

/// Hertz (Johnson 1985, §4.2): F_e = 4/3 E* √R* δ^{3/2}, S_n = 2 E* √(R* δ), energy
/// 8/15 E* √R* δ^{5/2}. The restitution dashpot 2√(5/6)|β|√(S_n m*) is that of EDEM's
/// Hertz–Mindlin and DEM-Engine (Tsuji et al. 1992 scaling γ ∝ δ^{1/4}); it rebounds with e.
/// Host: the pair modulus 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂; for an impact at v the contact
/// duration t_c = 2.87 (m*² / (R* E*² v))^{1/5} and the peak overlap
/// δ_max = (15 m* v² / (16 E* √R*))^{2/5} (Johnson 1985, ch. 11); the stable step 2/ω of the
/// stiffest moment, ω² the larger of S_n/m* (S_n = 2 E* a, a = √(R* δ_max), or with JKR
/// adhesion the larger JKR contact radius at δ_max, which stays a₀ > 0 as δ_max → 0) and the
/// tangential slot's peak_frequency_squared at that a.
struct HertzNormal {
  static constexpr const char* keyword = "hertz";
  static constexpr const char* material_keys = "";
  static constexpr bool needs_effective_radius = true;
  static constexpr Real damping_scale = Real(1.8257418583505538);  // 2√(5/6)
  template <class S>
  GPUDEM_HD static NormalResponse<S> respond(const ContactPairParamsT<S>& p,
                                             const ContactPointT<S>& c) {
    const S root = square_root(c.effective_radius * c.overlap);  // √(R* δ)
    const S secant = S(4) / 3 * p.effective_young * root;
    return NormalResponse<S>{secant * c.overlap, 2 * p.effective_young * root, secant};
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>& p, const ContactPointT<S>& c) {
    return S(8) / 15 * p.effective_young * square_root(c.effective_radius * c.overlap) * c.overlap *
           c.overlap;
  }
  static double effective_modulus(double young_a, double poisson_a, double young_b,
                                  double poisson_b) {
    return 1 / ((1 - poisson_a * poisson_a) / young_a + (1 - poisson_b * poisson_b) / young_b);
  }
  static double contact_duration(const ImpactPair& p) {
    return 2.87 * std::pow(p.mass * p.mass / (p.radius * p.young * p.young * p.speed), 0.2);
  }
  static double peak_overlap(const ImpactPair& p) {
    return std::pow(15 * p.mass * p.speed * p.speed / (16 * p.young * std::sqrt(p.radius)), 0.4);
  }
  template <class Tangential>
  static double stable_step(const ImpactPair& p) {
    const double root =  // a: √(R* δ_max) without adhesion
        jkr_contact_radius(p.surface_energy, p.young, p.radius, peak_overlap(p));
    const double omega2 =
        std::max(2 * p.young * root / p.mass, Tangential::peak_frequency_squared(p, root));
    return 2 / std::sqrt(omega2);
  }
};

}  // namespace gpudem
