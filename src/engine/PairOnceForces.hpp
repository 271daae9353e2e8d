#pragma once
/// The host backend's force sweep that evaluates each pair contact once. The owned particles
/// are split into one contiguous range per thread (parallel_ranges). Within a range a pair is
/// evaluated at its lower index: that end adds the pair's load to its own sum and subtracts it
/// from the partner's accumulator, whose turn is still to come; a pair across ranges (or with
/// a ghost) is evaluated at both ends, each writing only its own. Loads are summed as integers
/// (ExactSum.hpp), so each particle's force and torque are the same bits as ComputeForces<Law,
/// P, true> gives, on any number of threads or ranks: the two ends of a pair evaluate to exact
/// mirrors (n, v_rel and the history change sign, every other input is symmetric), a term and
/// its negative round to exact negatives, and integer sums do not depend on their order.
/// Only the evaluating end's history advances: MirrorPairHistory copies it to the other end
/// before anything else reads the history. Host code only.
#include <cstdint>

#include "engine/ContactForces.hpp"
#include "engine/ExactSum.hpp"
#include "engine/HostRanges.hpp"

namespace gpudem {

/// The visitor of one particle's pair entries: sums its loads and keeps the last contact's,
/// for the partner.
template <class Law>
struct PairOnceSum {
  using S = typename Law::Scalar;
  HistoryArrays<Law> history;
  Real dt;
  ExactSum3 force;
  ExactSum3 torque;
  Real worst_overlap_ratio;
  bool touched = false;  ///< whether the last entry visited was a contact
  ExactTerm3 force_term{};
  typename Law::Force last{};
  Vec3 normal{};
  Real overlap = 0;
  Real ratio = 0;

  void operator()(ContactSample<Law>& c) {
    last = evaluate_contact(c, c.state.value, dt);
    if constexpr (Law::history_size > 0) history.pair[c.slot] = c.state;
    force_term = exact_terms(last.force);
    force.add(force_term);
    if constexpr (Law::needs_spin) torque.add(exact_terms(contact_torque(c, last)));
    normal = c.point.normal;
    overlap = c.point.overlap;
    ratio = c.point.overlap / c.min_radius;
    if (ratio > worst_overlap_ratio) worst_overlap_ratio = ratio;
    touched = true;
  }
  void separated(std::uint32_t slot) {
    if constexpr (Law::history_size > 0) history.pair[slot] = typename Law::State{};
  }

  /// The torque of the last contact on the partner of radius r_j, as the partner's own sweep
  /// computes it (contact_torque with its arm r_j − δ/2, normal −n and mirrored loads).
  Vec3T<S> partner_torque(Real partner_radius) const {
    Vec3T<S> t = -last.rolling_torque;
    if constexpr (Law::has_tangential_force)
      t += cross(vec_cast<S>((partner_radius - Real(0.5) * overlap) * normal), last.tangential);
    return t;
  }
};

template <class Law, class P>
struct PairOnceForces {
  using S = typename Law::Scalar;
  ParticleView<P> particles;
  ContactScene<Law> scene;
  Vec3 gravity;
  Real dt;
  HistoryArrays<Law> history;
  Vec3T<S>* force;
  Vec3T<S>* torque;
  Real* overlap_ratio;  ///< also the partners' worst ratio so far, within a range
  S* wall_push;
  ExactSum3* pair_force;   ///< per particle: the loads its range's lower partners left
  ExactSum3* pair_torque;  ///< idem, torques

  /// The particles [begin, end) of one range, in order.
  GPUDEM_HOST_FLATTEN void operator()(std::uint32_t begin, std::uint32_t end) const {
    for (std::uint32_t i = begin; i < end; ++i) {
      pair_force[i] = ExactSum3{};
      pair_torque[i] = ExactSum3{};
      overlap_ratio[i] = 0;
    }
    for (std::uint32_t i = begin; i < end; ++i) particle(i, begin, end);
  }

  GPUDEM_HOST_FLATTEN void particle(std::uint32_t i, std::uint32_t begin, std::uint32_t end) const {
    const SweptParticle me = swept_particle<Law>(i, particles);
    PairOnceSum<Law> sum{history, dt, pair_force[i], pair_torque[i], overlap_ratio[i]};
    for (std::uint32_t k = scene.neighbor_offsets[i]; k < scene.neighbor_offsets[i + 1]; ++k) {
      const std::uint32_t j = scene.neighbor_index[k];
      const bool in_range = j >= begin && j < end;
      if (in_range && j < i) continue;  // evaluated at j's turn
      sum.touched = false;
      visit_pair_entry(me, k, particles, scene, sum);
      if (!sum.touched || !in_range) continue;
      pair_force[j].subtract(sum.force_term);
      if constexpr (Law::needs_spin)
        pair_torque[j].add(exact_terms(sum.partner_torque(particles.position(j).w)));
      if (sum.ratio > overlap_ratio[j]) overlap_ratio[j] = sum.ratio;
    }
    ForceSum<Law, true> bodies{history,  dt, Vec3T<S>{}, Vec3T<S>{}, sum.worst_overlap_ratio,
                               wall_push};
    visit_body_contacts(i, me, scene, bodies);
    force[i] =
        (sum.force.template value<S>() + bodies.force) + vec_cast<S>((Real(1) / me.v.w) * gravity);
    if constexpr (Law::needs_spin) torque[i] = sum.torque.template value<S>() + bodies.torque;
    overlap_ratio[i] = bodies.worst_overlap_ratio;
  }
};

/// Copies, for each pair evaluated once in the last PairOnceForces sweep of the same ranges,
/// the evaluating end's history (the lower index) to the other end, mirrored (Law::mirrored).
template <class Law>
struct MirrorPairHistory {
  const std::uint32_t* offsets;
  const std::uint32_t* index;
  typename Law::State* history;

  void operator()(std::uint32_t begin, std::uint32_t end) const {
    for (std::uint32_t i = begin; i < end; ++i)
      for (std::uint32_t k = offsets[i]; k < offsets[i + 1]; ++k) {
        const std::uint32_t j = index[k];
        if (j < begin || j >= i) continue;  // i evaluated this pair itself
        std::uint32_t m = offsets[j];
        while (index[m] != i) ++m;  // j's entry for i (the list is symmetric)
        history[k] = Law::mirrored(history[m]);
      }
  }
};

}  // namespace gpudem
