#pragma once
/// Rolling-resistance slot: a torque on particle i opposing the relative spin ω_rel = ω_i − ω_j.
#include <cmath>

#include "core/contact/NormalLaws.hpp"
#include "core/contact/TangentialLaws.hpp"

namespace gpudem {

struct NoRolling {
  static constexpr const char* keyword = "none";
  static constexpr const char* material_keys = "";
  static constexpr int history_size = 0;
  static constexpr bool needs_spin = false;
  static constexpr bool needs_effective_radius = false;
  static constexpr bool needs_inertia = false;
  template <class S>
  GPUDEM_HD static Vec3T<S> torque(const ContactPairParamsT<S>&, const ContactPointT<S>&,
                                   const NormalResponse<S>&, S, S*, S) {
    return Vec3T<S>{};
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>&, const ContactPointT<S>&,
                            const NormalResponse<S>&, const S*) {
    return 0;
  }
};

/// Constant directional torque, EDEM rolling model type A (Ai et al. 2011, model A):
/// M = −μ_r F_e R* ω̂_rel (F_e the elastic normal force). So that it cannot chatter as ω_rel → 0,
/// its magnitude is capped at I*|ω_rel|/dt, the torque that stops the relative spin in one step. A
/// sphere rolling on a plane then stops after d = v₀² / (2·(5/7)·μ_r·g).
struct ConstantTorqueRolling {
  static constexpr const char* keyword = "constant_torque";
  static constexpr const char* material_keys = "rolling_friction";
  static constexpr int history_size = 0;
  static constexpr bool needs_spin = true;
  static constexpr bool needs_effective_radius = true;
  static constexpr bool needs_inertia = true;
  template <class S>
  GPUDEM_HD static Vec3T<S> torque(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                                   const NormalResponse<S>&, S elastic_force, S*, S dt) {
    const S spin = norm(c.relative_spin);
    const S limit = p.rolling_friction * elastic_force * c.effective_radius;
    const S stopping = c.reduced_inertia * spin / dt;
    const S magnitude = select(dt > 0 && stopping < limit, stopping, limit);
    return select(spin == 0, Vec3T<S>{}, (-magnitude / spin) * c.relative_spin);
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>&, const ContactPointT<S>&,
                            const NormalResponse<S>&, const S*) {
    return 0;
  }
};

/// Elastic–plastic spring–dashpot, EDEM/Rocky type C and LIGGGHTS epsd (Ai et al. 2011,
/// model C; Iwashita & Oda 1998). History: the spring torque M_k (3 values).
///   M_k ← rotate_into_plane(M_k) − k_r ω_roll dt,  |M_k| ≤ M_m = μ_r F_e R*
///   M_d = −η_r · 2√(I_r k_r) · ω_roll  while |M_k| < M_m, else 0
///   k_r = 2.25 · k_n · μ_r² · R*²  (k_n = F_e/δ, the secant normal stiffness)
/// ω_roll is ω_rel without its component along the normal (twisting is not resisted).
struct EpsdRolling {
  static constexpr const char* keyword = "epsd";
  static constexpr const char* material_keys = "rolling_friction rolling_damping";
  static constexpr int history_size = 3;
  /// The spring torque changes sign seen from the other end.
  static constexpr int negated_values = 3;
  static constexpr bool needs_spin = true;
  static constexpr bool needs_effective_radius = true;
  static constexpr bool needs_inertia = true;
  template <class S>
  GPUDEM_HD static S stiffness(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                               const NormalResponse<S>& n) {
    const S arm = p.rolling_friction * c.effective_radius;
    return S(2.25) * n.secant * arm * arm;
  }
  template <class S>
  GPUDEM_HD static Vec3T<S> torque(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                                   const NormalResponse<S>& n, S elastic_force, S* history, S dt) {
    const Vec3T<S> roll = c.relative_spin - dot(c.relative_spin, c.normal) * c.normal;
    const S k_r = stiffness(p, c, n);
    Vec3T<S> spring = rotate_into_plane(Vec3T<S>{history[0], history[1], history[2]}, c.normal) -
                      (k_r * dt) * roll;
    const S limit = p.rolling_friction * elastic_force * c.effective_radius;
    const S magnitude = norm(spring);
    const auto at_limit = magnitude >= limit;
    spring = select(at_limit, select(magnitude > 0, limit / magnitude, S(0)) * spring, spring);
    history[0] = spring.x;
    history[1] = spring.y;
    history[2] = spring.z;
    return choose(
        at_limit, [&] { return spring; },
        [&] {
          return spring - (p.rolling_damping * 2 * square_root(c.rolling_inertia * k_r)) * roll;
        });
  }
  /// ½ |M_k|² / k_r [J].
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                            const NormalResponse<S>& n, const S* history) {
    const S k_r = stiffness(p, c, n);
    if (k_r == 0) return 0;
    return S(0.5) * (history[0] * history[0] + history[1] * history[1] + history[2] * history[2]) /
           k_r;
  }
};

}  // namespace gpudem
