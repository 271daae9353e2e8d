#pragma once
/// The JKR relation between overlap, contact radius and force of two elastic spheres that
/// adhere (Johnson, Kendall & Roberts 1971, Proc. R. Soc. Lond. A 324:301):
///   δ = a²/R* − √(2π γ a / E*),      F = 4E* a³/(3R*) − √(8π γ E* a³),
/// γ the pair's work of adhesion [J/m²] (Dupré: γ₁ + γ₂ − γ₁₂, twice the surface energy of
/// like surfaces). With a_c³ = π γ R*²/(8E*) and â = a/a_c, δ̂ = δ R*/a_c², F̂ = F/(π γ R*) it
/// reads δ̂ = â² − 4√â, F̂ = â³/6 − â^{3/2}: the largest pull, F = −3/2 π γ R* (the pull-off
/// force), is at â = 9^{1/3}, δ̂ = −1.443; the contact parts where δ has its minimum, â = 1,
/// δ_c = −3 a_c²/R* = −(3/4)(π² γ² R*/E*²)^{1/3}, pulling with −5/6 π γ R*. It forms at
/// touch, δ = 0, at â₀ = 16^{1/3}, pulling with −4/3 π γ R*.
#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

GPUDEM_HD inline double cube_root(double x) { return cbrt(x); }
GPUDEM_HD inline float cube_root(float x) { return cbrtf(x); }

/// ρ = a/R* of the contact at relative overlap d = δ/R* ≥ δ_c/R*, for k = (a_c/R*)³ =
/// π γ/(8E* R*): the root ρ ≥ k^{1/3} of d = ρ² − 4 √k √ρ (the relation above over R*), in
/// x = √ρ the quartic x⁴ − 4√k x − d = 0. It factors (Ferrari) through the positive root m of the
/// resolvent cubic m³ + d m − 2k = 0 into x = (s + √(8√k/s − s²))/2, s = √(2m). Cardano's root m =
/// u + v, u = ∛(k + √(k² + d³/27)), v = −d/(3u), is taken as 2k/(u² − uv + v²) (u³ + v³ = 2k),
/// which has no cancellation at any d; where d³ > 27·10¹⁸ k² (deep in the Hertz regime), m = 2k/d
/// to within 4k²/d³. Lengths relative to R* keep every power within float's range.
template <class S>
GPUDEM_HD S jkr_relative_radius(S k, S d) {
  S m;
  if (d > 0 && d * d * d > S(27e18) * k * k) {
    m = S(2) * k / d;
  } else {
    const S root = k * k + d * d * d / S(27);
    const S u = cube_root(k + square_root(root > 0 ? root : S(0)));
    const S v = -d / (S(3) * u);
    m = S(2) * k / (u * u - u * v + v * v);
  }
  const S s = square_root(S(2) * m);
  const S rest = S(8) * square_root(k) / s - s * s;
  const S x = S(0.5) * (s + square_root(rest > 0 ? rest : S(0)));
  return x * x;
}

/// a_c² = (π γ R*² / (8E*))^{2/3}, the square of the contact radius at which the contact parts
/// [m²].
template <class S>
GPUDEM_HD S jkr_parting_radius_sq(S work_of_adhesion, S young, S radius) {
  const S a =
      cube_root(S(3.14159265358979323846) * work_of_adhesion * radius * radius / (S(8) * young));
  return a * a;
}

/// |δ_c| = 3 a_c²/R*: how far past touch the contact holds [m].
template <class S>
GPUDEM_HD S jkr_pull_off_gap(S work_of_adhesion, S young, S radius) {
  return S(3) * jkr_parting_radius_sq(work_of_adhesion, young, radius) / radius;
}

/// k = π γ / (8 E* R*), the one material number of jkr_relative_radius.
template <class S>
GPUDEM_HD S jkr_adhesion_number(S work_of_adhesion, S young, S radius) {
  return S(3.14159265358979323846) * work_of_adhesion / (S(8) * young * radius);
}

/// The contact radius a at overlap δ ≥ δ_c on the branch the contact follows [m]; the Hertz
/// radius √(R* δ) (0 apart) when γ = 0.
template <class S>
GPUDEM_HD S jkr_contact_radius(S work_of_adhesion, S young, S radius, S overlap) {
  if (!(work_of_adhesion > 0)) return overlap > 0 ? square_root(radius * overlap) : S(0);
  const S k = jkr_adhesion_number(work_of_adhesion, young, radius);
  return radius * jkr_relative_radius(k, overlap / radius);
}

/// The energy stored by adhesion at contact radius a, ∫₀^δ F dδ' less the Hertz energy
/// 8/15 E* a⁵/R*² of the same a: π γ a_c² (â² − (2/3) â^{7/2} − Û₀), where
/// Û₀ = â₀⁵/15 − (2/3) â₀^{7/2} + â₀² at touch (â₀³ = 16) makes it vanish with the total at
/// δ = 0 [J]. Negative in the well, it gives back the work of adhesion as the contact closes.
template <class S>
GPUDEM_HD S jkr_adhesive_energy(S work_of_adhesion, S young, S radius, S contact_radius) {
  if (!(work_of_adhesion > 0)) return 0;
  constexpr double kTouchEnergy = -3.8097625247236797;  // Û₀ = â₀²·31/15 − (32/3)√â₀
  const S parting_sq = jkr_parting_radius_sq(work_of_adhesion, young, radius);
  const S a = contact_radius / square_root(parting_sq);  // â
  return S(3.14159265358979323846) * work_of_adhesion * parting_sq *
         (a * a - S(2) / S(3) * a * a * a * square_root(a) - S(kTouchEnergy));
}

}  // namespace gpudem
