#pragma once
/// Normal elastic slot: the repulsive spring force F_e(δ), the tangent stiffness S_n = dF_e/dδ
/// that damping laws scale with, and the stored energy. `damping_scale` is the factor c of the
/// restitution dashpot γ = c·|β|·√(S_n m*) that makes its restitution equal e (below).
#include <cmath>

#include "core/ContactParams.hpp"
#include "kernels/contact/ContactPoint.hpp"

namespace gpudem {

template <class S>
struct NormalResponse {
  S force = 0;      ///< F_e > 0, repulsive [N]
  S stiffness = 0;  ///< tangent stiffness S_n = dF_e/dδ [N/m]
  S secant = 0;     ///< F_e / δ [N/m]
};

/// Linear spring (Cundall & Strack 1979): F_e = k_n δ, S_n = k_n, energy ½ k_n δ².
/// With γ = 2|β|√(k_n m*) the damped oscillator rebounds with restitution e exactly.
struct HookeNormal {
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
};

/// Hertz (Johnson 1985, §4.2): F_e = 4/3 E* √R* δ^{3/2}, S_n = 2 E* √(R* δ), energy
/// 8/15 E* √R* δ^{5/2}. The restitution dashpot 2√(5/6)|β|√(S_n m*) is that of EDEM's
/// Hertz–Mindlin and DEM-Engine (Tsuji et al. 1992 scaling γ ∝ δ^{1/4}); it rebounds with e.
struct HertzNormal {
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
};

}  // namespace gpudem
