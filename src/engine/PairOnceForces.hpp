#pragma once
/// The host backend's force sweep, which evaluates each pair contact once. The particles of a
/// sweep (all owned ones, or a subset: the interior or boundary rows of a decomposed run) are
/// split into one contiguous range per thread, and each particle is tagged with its range's
/// group (the selection's number and the range's first particle, written when the sweep's
/// entries are selected: once per list and grouping). A pair whose two ends are in the same
/// group is evaluated at its lower index: that end adds the pair's load to its own sum and
/// subtracts it from the partner's accumulator, whose turn is still to come (a subset lists its
/// particles in ascending order) and which the partner clears when it takes it; any other pair
/// (across ranges or sweeps, or with a ghost) is evaluated at both ends, each writing only its
/// own. The entries each particle evaluates are selected once per list and grouping
/// (SelectEvaluated), so that the sweep walks only those.
/// Loads are summed as integers in the run's units (ExactSum.hpp), so each particle's force and
/// torque are the same bits on any number of threads or ranks: the two ends of a pair evaluate to
/// exact mirrors (n, v_rel and the history change sign, every other input is symmetric), a term and
/// its negative round to exact negatives, and integer sums do not depend on their order. Only the
/// evaluating end's history advances; PairOnceSweep::mirror copies it to the other end before
/// anything reads it. Where the CPU runs AVX-512, PairLanesForces sweeps the same pairs eight
/// contacts at a time. Host code only.
#include <cstddef>
#include <cstdint>
#include <vector>

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
  const ExactUnits& units;
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
    // −0 stored as +0: the same bits whether this end or the partner's mirror writes the record
    if constexpr (Law::history_size > 0)
      history.pair[c.slot] = Law::without_negative_zeros(c.state);
    force_term = exact_terms(last.force, units.per_force);
    force.add(force_term);
    if constexpr (Law::needs_spin)
      torque.add(exact_terms(contact_torque(c, last), units.per_torque));
    normal = c.point.normal;
    overlap = c.point.overlap;
    ratio = c.point.overlap / c.min_radius;
    if (ratio > worst_overlap_ratio) worst_overlap_ratio = ratio;
    touched = true;
  }
  void separated(std::uint32_t slot) {
    if constexpr (Law::history_size > 0) history.pair[slot] = typename Law::State{};
  }

  /// The torque of the last contact on the partner of radius r_j (its arm r_j − δ/2).
  Vec3T<S> partner_torque(Real partner_radius) const {
    return gpudem::partner_torque<Law>(partner_radius - Real(0.5) * overlap, normal, last);
  }
};

/// The owned particles' rows of the full neighbour list a sweep reads.
struct ListRows {
  std::size_t owned;             ///< particles with a row; the others are ghosts
  const std::uint32_t* offsets;  ///< owned + 1
  const std::uint32_t* index;    ///< the partners
  std::uint64_t builds;          ///< the list's build count: a new count, a new list
};

/// The list entries each particle of a sweep evaluates: its row of the full list without the
/// partners of its group at a lower index (they evaluate the pair), those of its group first.
/// Position k of the sweep evaluates entry[h] for h in [begin[k], end[k]), of its group below
/// group_end[k]. Valid for one list and one grouping of one sweep. `entry` and `partner` hold
/// kRowsPadding values past the last row, so that a sweep that reads entries in blocks or ahead
/// (PairLanesForces) reads only what is there.
struct EvaluatedRows {
  std::uint32_t* begin;      ///< per position
  std::uint32_t* group_end;  ///< per position
  std::uint32_t* end;        ///< per position
  std::uint32_t* entry;      ///< list entries; position k's from begin[k], its row's length at most
  std::uint32_t* partner;    ///< the partner on each of them
};

/// Values past the last evaluated row (EvaluatedRows).
inline constexpr std::uint32_t kRowsPadding = 24;

/// Whether owned particle i and its partner j are in one group (GroupRange): then only the lower
/// index evaluates the pair.
inline bool in_one_group(std::uint32_t i, std::uint32_t j, std::size_t owned,
                         const std::uint64_t* group) {
  return j < owned && group[j] == group[i];
}

/// Fills the evaluated rows (EvaluatedRows, `begin` set) of a range of a sweep whose particles
/// carry their groups (GroupRange).
struct SelectEvaluated {
  const std::uint32_t* subset;
  ListRows list;
  const std::uint64_t* group;
  EvaluatedRows rows;

  void operator()(std::uint32_t begin, std::uint32_t end) const {
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t i = swept_index(subset, k);
      std::uint32_t h = rows.begin[k];
      for (int pass = 0; pass < 2; ++pass) {  // the group's partners, then the others
        for (std::uint32_t e = list.offsets[i]; e < list.offsets[i + 1]; ++e) {
          const std::uint32_t j = list.index[e];
          const bool grouped = in_one_group(i, j, list.owned, group);
          if (grouped == (pass == 0) && !(grouped && j < i)) {
            rows.entry[h] = e;
            rows.partner[h++] = j;
          }
        }
        if (pass == 0) rows.group_end[k] = h;
      }
      rows.end[k] = h;
    }
  }
};

/// Tags each particle of a range with the range's group: the selection's number and the range's
/// first particle.
struct GroupRange {
  const std::uint32_t* subset;
  std::uint64_t selection;
  std::uint64_t* group;

  void operator()(std::uint32_t begin, std::uint32_t end) const {
    if (begin == end) return;
    const std::uint64_t tag = selection << 32 | swept_index(subset, begin);
    for (std::uint32_t k = begin; k < end; ++k) group[swept_index(subset, k)] = tag;
  }
};

/// What particle i's lower partners left in `sums`, which is cleared for the next sweep.
inline ExactSum3 take(const ExactSumArrays& sums, std::uint32_t i) {
  const ExactSum3 sum = sums[i];
  sums.clear(i);
  return sum;
}

/// The worst overlap ratio particle i's lower partners left, cleared for the next sweep.
inline Real take(Real* worst, std::uint32_t i) {
  const Real ratio = worst[i];
  worst[i] = 0;
  return ratio;
}

template <class Law, class P>
struct PairOnceForces {
  using S = typename Law::Scalar;
  ForceSweep<Law, P> sweep;
  // Filled in by PairOnceSweep::run.
  EvaluatedRows evaluated{};     ///< the entries each particle evaluates
  ExactUnits units{};            ///< of the integer sums
  ExactSumArrays pair_force{};   ///< per particle: what its group's lower partners left
  ExactSumArrays pair_torque{};  ///< idem, torques; empty for a law without torques
  Real* pair_ratio = nullptr;    ///< idem, the worst overlap ratio

  /// The particles at positions [begin, end) of the sweep, in order.
  GPUDEM_HOST_FLATTEN void operator()(std::uint32_t begin, std::uint32_t end) const {
    for (std::uint32_t k = begin; k < end; ++k) particle(k);
  }

  /// The particle at position k: its pairs (each in its group once), then its walls and meshes.
  /// It starts from what its lower partners in its group left, and clears that for the next
  /// sweep.
  GPUDEM_HOST_FLATTEN void particle(std::uint32_t position) const {
    const std::uint32_t i = swept_index(sweep.subset, position);
    const ForceSweep<Law, P>& s = sweep;
    const SweptParticle me = swept_particle<Law>(i, s.particles);
    ExactSum3 torque_so_far{};
    if constexpr (Law::needs_spin) torque_so_far = take(pair_torque, i);
    PairOnceSum<Law> sum{s.history,           s.dt,          units,
                         take(pair_force, i), torque_so_far, take(pair_ratio, i)};
    const std::uint32_t group_end = evaluated.group_end[position];
    for (std::uint32_t h = evaluated.begin[position]; h < evaluated.end[position]; ++h) {
      const std::uint32_t k = evaluated.entry[h];
      const std::uint32_t j = evaluated.partner[h];
      const bool grouped = h < group_end;
      sum.touched = false;
      visit_pair_entry(me, k, j, s.particles, s.scene, sum);
      if (!sum.touched || !grouped) continue;
      pair_force.subtract(j, sum.force_term);
      if constexpr (Law::needs_spin)
        pair_torque.add(
            j, exact_terms(sum.partner_torque(s.particles.position(j).w), units.per_torque));
      if (sum.ratio > pair_ratio[j]) pair_ratio[j] = sum.ratio;
    }
    ForceSum<Law> bodies{s.history, s.dt, {}, {}, sum.worst_overlap_ratio, s.wall_push};
    visit_body_contacts(i, me, s.scene, bodies);
    Vec3T<S> torque{};  // summed only for a law with torques
    if constexpr (Law::needs_spin)
      torque = sum.torque.template value<S>(units.torque) + bodies.torque;
    s.store(i, me.v.w, sum.force.template value<S>(units.force) + bodies.force, torque,
            bodies.worst_overlap_ratio);
  }
};

}  // namespace gpudem
