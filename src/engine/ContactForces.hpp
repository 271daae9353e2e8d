#pragma once
/// Per-particle force, torque and worst overlap: one thread per particle sums all its
/// contacts from the full neighbour list (no atomics), walls and gravity, and advances the
/// contact history it owns (its own neighbour-list entries and wall slots). Forces and torques
/// are summed in the law's scalar.
#include "engine/ContactVisitor.hpp"

namespace gpudem {

/// Torque about a particle's centre of a contact's loads f on it, with lever arm `arm` along
/// the contact normal n: arm·n × F_t plus the law's rolling torque. R is Real and L the law's
/// scalar, or lanes of both (core/Lanes.hpp).
template <class Law, class R, class L>
GPUDEM_HD Vec3T<L> lever_torque(R arm, const Vec3T<R>& normal, const ContactForce<L>& f) {
  Vec3T<L> torque = f.rolling_torque;
  if constexpr (Law::has_tangential_force) torque += cross(vec_cast<L>(arm * normal), f.tangential);
  return torque;
}

/// The torque on i's partner of the loads f on i (normal n from i to the partner), as the
/// partner's own evaluation computes it: lever_torque with its arm, normal −n and mirrored
/// loads, which is −M_r + (arm·n) × F_t exactly.
template <class Law, class R, class L>
GPUDEM_HD Vec3T<L> partner_torque(R partner_arm, const Vec3T<R>& normal, const ContactForce<L>& f) {
  Vec3T<L> torque = -f.rolling_torque;
  if constexpr (Law::has_tangential_force)
    torque += cross(vec_cast<L>(partner_arm * normal), f.tangential);
  return torque;
}

/// Torque of a contact force about i's centre (lever_torque).
template <class Law>
GPUDEM_HD Vec3T<typename Law::Scalar> contact_torque(const ContactSample<Law>& c,
                                                     const typename Law::Force& f) {
  return lever_torque<Law>(c.arm, c.point.normal, f);
}

/// Writable history arrays of one particle's contacts.
template <class Law>
struct HistoryArrays {
  typename Law::State* pair;
  typename Law::State* wall;
  typename Law::State* mesh;
  GPUDEM_HD typename Law::State* of(const ContactSample<Law>& c) const {
    return c.mesh >= 0 ? mesh : (c.wall >= 0 ? wall : pair);
  }
};

template <class Law>
struct ForceSum {
  using S = typename Law::Scalar;
  HistoryArrays<Law> history;
  Real dt;
  Vec3T<S> force;
  Vec3T<S> torque;
  Real worst_overlap_ratio = 0;
  /// Per (particle, plane wall) slot: the push −F·n_c of the particle on the wall along the
  /// contact normal n_c (towards the wall) [N]; null: not wanted.
  S* wall_push = nullptr;
  GPUDEM_HD void operator()(ContactSample<Law>& c) {
    const typename Law::Force f = evaluate_contact(c, c.state.value, dt);
    if constexpr (Law::history_size > 0) history.of(c)[c.slot] = c.state;
    if (wall_push && c.wall >= 0) wall_push[c.slot] = -dot(f.force, vec_cast<S>(c.point.normal));
    force += f.force;
    if constexpr (Law::needs_spin) torque += contact_torque(c, f);
    if (c.point.overlap > worst_overlap_ratio * c.min_radius)  // divides only for a new worst
      worst_overlap_ratio = c.point.overlap / c.min_radius;
  }
  /// A contact that opened forgets its history.
  GPUDEM_HD void separated(std::uint32_t slot) {
    if constexpr (Law::history_size > 0) history.pair[slot] = typename Law::State{};
  }
  GPUDEM_HD void separated_from_wall(std::uint32_t slot) {
    if constexpr (Law::history_size > 0) history.wall[slot] = typename Law::State{};
    if (wall_push) wall_push[slot] = S{};
  }
  GPUDEM_HD void separated_from_mesh(std::uint32_t slot) {
    if constexpr (Law::history_size > 0) history.mesh[slot] = typename Law::State{};
  }
};

/// The particle a sweep visits at position k: subset[k], or k without a subset.
GPUDEM_HD inline std::uint32_t swept_index(const std::uint32_t* subset, std::size_t k) {
  return subset ? subset[k] : static_cast<std::uint32_t>(k);
}

/// What a force sweep reads and writes, on either backend: the particles (in scalar P), the
/// scene, and per particle the force, torque and worst overlap ratio it computes.
template <class Law, class P>
struct ForceSweep {
  using S = typename Law::Scalar;
  ParticleView<P> particles;
  ContactScene<Law> scene;
  Vec3 gravity;
  Real dt;
  HistoryArrays<Law> history;  ///< scene's history arrays, writable
  Vec3T<S>* force;
  Vec3T<S>* torque;
  Real* overlap_ratio;
  S* wall_push;                           ///< per (particle, plane wall) slot, or null (ForceSum)
  const std::uint32_t* subset = nullptr;  ///< the particles swept; null: 0..count

  /// Stores particle i's results: F_i = m_i g + the contacts' force, T_i, the worst ratio.
  GPUDEM_HD void store(std::uint32_t i, Real inv_mass, const Vec3T<S>& contact_force,
                       const Vec3T<S>& contact_torque, Real worst_overlap_ratio) const {
    force[i] = contact_force + vec_cast<S>((Real(1) / inv_mass) * gravity);
    if constexpr (Law::needs_spin) torque[i] = contact_torque;
    overlap_ratio[i] = worst_overlap_ratio;
  }
};

/// F_i = m_i g + Σ contacts, T_i = Σ (arm × F + rolling torque) (one thread per particle), from
/// a state held in scalar P; thread k computes particle swept_index(subset, k) (one kernel for
/// both launches: each law's force kernel is compiled once per backend).
template <class Law, class P>
struct ComputeForces {
  ForceSweep<Law, P> sweep;
  GPUDEM_HD GPUDEM_HOST_FLATTEN void operator()(std::size_t k) const {
    const ForceSweep<Law, P>& s = sweep;
    const std::uint32_t i = swept_index(s.subset, k);
    ForceSum<Law> sum{s.history, s.dt, {}, {}, Real(0), s.wall_push};
    for_each_contact(i, s.particles, s.scene, sum);
    s.store(i, s.particles.velocity(i).w, sum.force, sum.torque, sum.worst_overlap_ratio);
  }
};

}  // namespace gpudem
