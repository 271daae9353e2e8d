#pragma once
/// Tangential slot: friction force at the contact point. Both spring laws keep per contact
/// four history values: the spring ξ (3) and a sliding flag (1).
///
/// Coulomb spring (Cundall & Strack 1979; stiffness of Mindlin & Deresiewicz 1953; the
/// sliding rule of LIGGGHTS `tangential history`): each step ξ is rotated into the current
/// tangent plane (length kept) and grows by v_t·dt. A sticking contact starts to slide when
/// the spring force |S_t ξ| exceeds μ_s·F_e; a sliding one keeps |S_t ξ| = μ_d·F_e (ξ cut to
/// length) and sticks again once |S_t ξ| < μ_d·F_e (static/dynamic friction as in EDEM).
/// Sticking: F_t = −S_t ξ − γ_t v_t, capped at μ_s·F_e; sliding: F_t = −S_t ξ, no dashpot.
/// F_e is the elastic normal force: a dashpot's impulse over a whole contact is zero, so in
/// gross sliding the friction impulse is exactly μ_d times the normal impulse (rigid-body
/// theory), and the brief pull of an inelastic dashpot at separation adds no friction.
/// dt = 0 evaluates the force of the stored state (spring and sliding flag) without advancing it.
#include <cmath>

#include "core/contact/DampingLaws.hpp"

namespace gpudem {

struct NoTangential {
  static constexpr const char* keyword = "none";
  static constexpr const char* material_keys = "";
  static double peak_frequency_squared(const ImpactPair&, double) { return 0; }
  static constexpr int history_size = 0;
  static constexpr bool needs_spin = false;
  static constexpr bool needs_effective_radius = false;
  template <class Damping, class Normal, class S>
  GPUDEM_HD static Vec3T<S> force(const ContactPairParamsT<S>&, const ContactPointT<S>&, S, S*, S) {
    return Vec3T<S>{};
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>&, const ContactPointT<S>&, const S*) {
    return 0;
  }
};

/// ξ rotated into the tangent plane of `normal`, its length kept: the projection scaled by
/// √(|ξ|² / |ξ_t|²), one root instead of two.
template <class S>
GPUDEM_HD Vec3T<S> rotate_into_plane(Vec3T<S> v, Vec3T<S> normal) {
  const S length_sq = norm2(v);
  v -= dot(v, normal) * normal;
  const S projected_sq = norm2(v);
  return select(projected_sq > 0, square_root(length_sq / projected_sq) * v, v);
}

/// |v| > limit, from |v|² without a root (true for any v when the limit is negative).
template <class S>
GPUDEM_HD auto longer_than(const Vec3T<S>& v, S limit) {
  return limit < 0 || norm2(v) > limit * limit;
}

/// |v| ≥ limit, from |v|² without a root (true for any v when the limit is negative).
template <class S>
GPUDEM_HD auto at_least(const Vec3T<S>& v, S limit) {
  return limit < 0 || norm2(v) >= limit * limit;
}

/// `v` scaled to length `length` (unchanged when it is zero).
template <class S>
GPUDEM_HD Vec3T<S> with_length(Vec3T<S> v, S length) {
  const S current = norm(v);
  return select(current > 0, (length / current) * v, v);
}

/// The spring ξ a Coulomb contact keeps and the force it exerts.
template <class S>
struct SpringForce {
  Vec3T<S> spring;
  Vec3T<S> force;
};
template <class Mask, class S>
GPUDEM_HD SpringForce<S> select(const Mask& take_a, const SpringForce<S>& a,
                                const SpringForce<S>& b) {
  return {select(take_a, a.spring, b.spring), select(take_a, a.force, b.force)};
}

/// The Coulomb spring above for stiffness S_t and elastic normal force F_e; `history` holds ξ
/// and the sliding flag. The branches choose (core/Vec3.hpp), so that the law runs on lanes too.
template <class Damping, class Normal, class S>
GPUDEM_HD Vec3T<S> coulomb_spring_force(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                                        S stiffness, S elastic_force, S* history, S dt) {
  const Vec3T<S> vt = tangential_velocity(c);
  const Vec3T<S> spring =
      rotate_into_plane(Vec3T<S>{history[0], history[1], history[2]}, c.normal) + dt * vt;
  const Vec3T<S> spring_force = stiffness * spring;
  const auto was_sliding = history[3] != 0;
  const auto still_sliding = [&] {
    return at_least(spring_force, p.friction_dynamic * elastic_force);
  };
  const auto starts_sliding = [&] {
    return longer_than(spring_force, p.friction_static * elastic_force);
  };
  const auto sliding = select(dt == 0, was_sliding,  // reading the stored state
                              choose(was_sliding, still_sliding, starts_sliding));
  const SpringForce<S> out = choose(
      sliding,
      [&] {  // the spring shrinks to the dynamic limit and pulls back
        const Vec3T<S> slid = with_length(spring, p.friction_dynamic * elastic_force / stiffness);
        return SpringForce<S>{slid, -stiffness * slid};
      },
      [&] {  // the spring and the dashpot, capped at the static limit
        const S gamma = Damping::template tangential_coefficient<Normal>(p, c, stiffness);
        const Vec3T<S> stuck = -spring_force - gamma * vt;
        const S limit = p.friction_static * elastic_force;
        return SpringForce<S>{
            spring, choose(
                        longer_than(stuck, limit), [&] { return with_length(stuck, limit); },
                        [&] { return stuck; })};
      });
  history[0] = out.spring.x;
  history[1] = out.spring.y;
  history[2] = out.spring.z;
  history[3] = select(sliding, S(1), S(0));
  return out.force;
}

/// ½ S_t |ξ|² [J].
template <class S>
GPUDEM_HD S coulomb_spring_energy(S stiffness, const S* history) {
  return S(0.5) * stiffness *
         (history[0] * history[0] + history[1] * history[1] + history[2] * history[2]);
}

/// Linear history spring of LAMMPS `hooke/history`: S_t = k_t = 2/7 k_n (equal normal and
/// tangential periods for a solid sphere). Host: its mode ω² = k_t / (2/7 m*) = k_n/m*, the
/// contact point of a free sphere also moving by rotation (effective mass 2/7 m*).
struct LinearHistoryTangential {
  static constexpr const char* keyword = "linear_history";
  static constexpr const char* material_keys = "friction friction_dynamic";
  static constexpr double stiffness_ratio = 2.0 / 7.0;  ///< k_t / k_n
  static double peak_frequency_squared(const ImpactPair& p, double) { return p.stiffness / p.mass; }
  static constexpr int history_size = 4;
  /// The spring (history 0–2) changes sign seen from the other end; the sliding flag does not.
  static constexpr int negated_values = 3;
  static constexpr bool needs_spin = true;
  static constexpr bool needs_effective_radius = false;
  template <class Damping, class Normal, class S>
  GPUDEM_HD static Vec3T<S> force(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                                  S elastic_force, S* history, S dt) {
    return coulomb_spring_force<Damping, Normal>(p, c, p.hooke_tangential_stiffness, elastic_force,
                                                 history, dt);
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>& p, const ContactPointT<S>&,
                            const S* history) {
    return coulomb_spring_energy(p.hooke_tangential_stiffness, history);
  }
};

/// Mindlin no-slip spring of Hertz–Mindlin (EDEM; Di Renzo & Di Maio 2004):
/// S_t = 8 G* √(R* δ), 1/G* = (2 − ν₁)/G₁ + (2 − ν₂)/G₂ (Mindlin 1949). Host: at the peak of an
/// impact its mode ω² = S_t / (2/7 m*), the contact point of a free sphere also moving by
/// rotation (effective mass 2/7 m*).
struct MindlinTangential {
  static constexpr const char* keyword = "mindlin";
  static constexpr const char* material_keys = "friction friction_dynamic";
  static double effective_shear_modulus(double young_a, double poisson_a, double young_b,
                                        double poisson_b) {
    return 1 / ((2 - poisson_a) / shear_modulus(young_a, poisson_a) +
                (2 - poisson_b) / shear_modulus(young_b, poisson_b));
  }
  /// `root`: the contact radius at the peak, √(R* δ_max) without adhesion.
  static double peak_frequency_squared(const ImpactPair& p, double root) {
    return 8 * p.shear * root / (2.0 / 7.0 * p.mass);
  }
  static constexpr int history_size = 4;
  /// The spring (history 0–2) changes sign seen from the other end; the sliding flag does not.
  static constexpr int negated_values = 3;
  static constexpr bool needs_spin = true;
  static constexpr bool needs_effective_radius = true;
  template <class S>
  GPUDEM_HD static S stiffness(const ContactPairParamsT<S>& p, const ContactPointT<S>& c) {
    return 8 * p.effective_shear * square_root(c.effective_radius * c.overlap);
  }
  template <class Damping, class Normal, class S>
  GPUDEM_HD static Vec3T<S> force(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                                  S elastic_force, S* history, S dt) {
    return coulomb_spring_force<Damping, Normal>(p, c, stiffness(p, c), elastic_force, history, dt);
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>& p, const ContactPointT<S>& c,
                            const S* history) {
    return coulomb_spring_energy(stiffness(p, c), history);
  }
};

}  // namespace gpudem
