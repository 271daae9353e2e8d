#pragma once
/// The host's pair-once force sweep with the law evaluated on several contacts at a time: eight
/// on CPUs with AVX-512, four on CPUs with AVX2 (PairLanesForces); the same pairs, loads and bits
/// as PairOnceForces. Host code only.
#include <cstdint>
#include <type_traits>

#include "core/Lanes.hpp"
#include "engine/PairOnceForces.hpp"

namespace gpudem {

/// Up to W touching pair entries, gathered lane by lane for one evaluation of the law. Lanes at
/// and past `count` hold an earlier batch's inputs (or zeros) and are evaluated but not read.
template <class Law, int W>
struct PairContactLanes {
  using S = typename Law::Scalar;
  using R = LaneScalar<Real, W>;
  using L = LaneScalar<S, W>;
  int count = 0;
  // Which contact each lane holds.
  std::uint32_t i[W];
  std::uint32_t j[W];
  std::uint32_t entry[W];
  bool grouped[W];  ///< both ends in one group: the partner's sums are written here too
  // The contact's inputs.
  Vec3T<R> d;
  R dist2;
  R min_radius;  ///< the smaller radius of the pair
  Vec4T<R> xi, vi, xj, vj;
  Vec3T<R> wi, wj;
  ContactPairParamsT<L> params;
  bool one_pair_type = false;  ///< a scene of one material: params are set once, for every lane
  L history[Law::history_size > 0 ? Law::history_size : 1];

  template <class P>
  void add(std::uint32_t me_index, const SweptParticle& me, const PairEntry& e, std::uint32_t k,
           bool both_in_group, const ParticleView<P>& p, const ContactScene<Law>& s) {
    const int l = count++;
    i[l] = me_index;
    j[l] = e.j;
    entry[l] = k;
    grouped[l] = both_in_group;
    set_lane(min_radius, l, me.x.w < e.xj.w ? me.x.w : e.xj.w);
    set_lane<Real, W>(d, l, e.d);
    set_lane(dist2, l, e.dist2);
    set_lane<Real, W>(xi, l, me.x);
    set_lane<Real, W>(vi, l, me.v);
    set_lane<Real, W>(xj, l, e.xj);
    set_lane<Real, W>(vj, l, p.velocity(e.j));
    if constexpr (Law::needs_spin) {
      set_lane<Real, W>(wi, l, me.w);
      set_lane<Real, W>(wj, l, p.spin(e.j));
    }
    if (!one_pair_type)
      for_each_param(params, s.pair_params[me.material * s.material_count + p.material[e.j]],
                     [l](L& to, S from) { set_lane(to, l, from); });
    for (int v = 0; v < Law::history_size; ++v) set_lane(history[v], l, s.pair_history[k].value[v]);
  }
};

/// The host backend's force sweep over one thread's range of particles, as PairOnceForces
/// (the same pairs, loads and bits) but with the touching entries of 64 particles at a time
/// gathered into lanes of W contacts (core/Lanes.hpp) and the law evaluated on the W at once;
/// then each particle's walls and meshes, and its loads stored. Built only where one vector
/// instruction holds the W lanes: eight for AVX-512 (sweep_in_avx512_lanes), four for AVX2
/// (sweep_in_avx2_lanes). Split into narrower vectors it is slower than PairOnceForces.
template <class Law, class P, int W>
struct PairLanesForces {
  using S = typename Law::Scalar;
  static constexpr std::uint32_t chunk = 64;  ///< particles whose pairs share the lanes
  PairOnceForces<Law, P> once;                ///< the sweep, its groups and its integer sums

  /// The particles at positions [begin, end) of the sweep.
  void sweep_range(std::uint32_t begin, std::uint32_t end) const {
    const ForceSweep<Law, P>& s = once.sweep;
    PairContactLanes<Law, W> lanes{};
    if (s.scene.material_count == 1) {
      lanes.one_pair_type = true;
      for_each_param(lanes.params, s.scene.pair_params[0], [](auto& to, S from) { to = from; });
    }
    for (std::uint32_t first = begin; first < end; first += chunk) {
      const std::uint32_t last = end - first < chunk ? end : first + chunk;
      for (std::uint32_t k = first; k < last; ++k) gather_pairs(k, lanes);
      evaluate(lanes);
      for (std::uint32_t k = first; k < last; ++k) finish(swept_index(s.subset, k));
    }
  }

  /// The touching pair entries of the particle at position k (each pair in its group once) into
  /// the lanes, evaluated whenever they are full; a separated entry forgets its history.
  void gather_pairs(std::uint32_t position, PairContactLanes<Law, W>& lanes) const {
    const ForceSweep<Law, P>& s = once.sweep;
    const std::uint32_t i = swept_index(s.subset, position);
    const SweptParticle me = swept_particle<Law>(i, s.particles);
    const EvaluatedRows& rows = once.evaluated;
    const std::uint32_t group_end = rows.group_end[position];
    for (std::uint32_t h = rows.begin[position]; h < rows.end[position]; ++h) {
      const std::uint32_t k = rows.entry[h];
      const bool grouped = h < group_end;
      const PairEntry e = pair_entry(me, k, rows.partner[h], s.particles, s.scene);
      if (!e.touching) {
        if constexpr (Law::history_size > 0) s.history.pair[k] = typename Law::State{};
        continue;
      }
      lanes.add(i, me, e, k, grouped, s.particles, s.scene);
      if (lanes.count == W) evaluate(lanes);
    }
  }

  /// The law on the lanes' contacts; each contact's loads go to its own end and, for a pair in
  /// one group, to the partner (the loads mirrored, its torque with its own arm).
  void evaluate(PairContactLanes<Law, W>& c) const {
    using L = LaneScalar<S, W>;
    if (c.count == 0) return;
    ContactPointT<typename PairContactLanes<Law, W>::R> point;
    typename PairContactLanes<Law, W>::R arm;
    describe_pair<Law>(point, arm, c.d, c.dist2, c.xi, c.vi, c.wi, c.xj, c.vj, c.wj);
    const ContactForce<L> f =
        Law::evaluate(c.params, point_cast<L>(point), c.history, L(static_cast<S>(once.sweep.dt)));
    const ExactUnits& units = once.units;
    LoadTerms terms{exact_terms(f.force, units.per_force), {}, {}};
    if constexpr (Law::needs_spin) {
      terms.torque = exact_terms(lever_torque<Law>(arm, point.normal, f), units.per_torque);
      terms.partner_torque =
          exact_terms(partner_torque<Law>(c.xj.w - Real(0.5) * point.overlap, point.normal, f),
                      units.per_torque);
    }
    if (terms.force.spills || terms.torque.spills || terms.partner_torque.spills)
      store_loads<true>(c, terms, point.overlap / c.min_radius);
    else
      store_loads<false>(c, terms, point.overlap / c.min_radius);
    c.count = 0;
  }

  /// The integer terms of the lanes' loads.
  struct LoadTerms {
    ExactTermLanes<W> force, torque, partner_torque;
  };

  /// Each lane's history written back and its loads added to its ends' sums (in one word each
  /// unless some lane `Spills`), with its overlap ratio.
  template <bool Spills, class Ratio>
  void store_loads(const PairContactLanes<Law, W>& c, const LoadTerms& t,
                   const Ratio& ratio) const {
    const auto term = [](const ExactTermLanes<W>& terms, int l) {
      if constexpr (Spills)
        return terms.lane(l);
      else
        return terms.words(l);
    };
    for (int l = 0; l < c.count; ++l) {
      if constexpr (Law::history_size > 0) {
        typename Law::State state;
        for (int v = 0; v < Law::history_size; ++v) state.value[v] = lane_of(c.history[v], l);
        // −0 stored as +0: the same bits whether this end or the partner's mirror writes it
        once.sweep.history.pair[c.entry[l]] = Law::without_negative_zeros(state);
      }
      const std::uint32_t i = c.i[l], j = c.j[l];
      const auto force_term = term(t.force, l);
      once.pair_force.add(i, force_term);
      if (c.grouped[l]) once.pair_force.subtract(j, force_term);
      if constexpr (Law::needs_spin) {
        once.pair_torque.add(i, term(t.torque, l));
        if (c.grouped[l]) once.pair_torque.add(j, term(t.partner_torque, l));
      }
      const Real lane_ratio = lane_of(ratio, l);
      Real* worst = once.pair_ratio;
      if (lane_ratio > worst[i]) worst[i] = lane_ratio;
      if (c.grouped[l] && lane_ratio > worst[j]) worst[j] = lane_ratio;
    }
  }

  /// Particle i's walls and meshes, then its force, torque and worst ratio stored; its sums
  /// cleared for the next sweep.
  void finish(std::uint32_t i) const {
    const ForceSweep<Law, P>& s = once.sweep;
    const SweptParticle me = swept_particle<Law>(i, s.particles);
    ForceSum<Law> bodies{s.history, s.dt, {}, {}, take(once.pair_ratio, i), s.wall_push};
    visit_body_contacts(i, me, s.scene, bodies);
    Vec3T<S> torque{};  // summed only for a law with torques
    const ExactUnits& units = once.units;
    if constexpr (Law::needs_spin)
      torque = take(once.pair_torque, i).template value<S>(units.torque) + bodies.torque;
    s.store(i, me.v.w, take(once.pair_force, i).template value<S>(units.force) + bodies.force,
            torque, bodies.worst_overlap_ratio);
  }
};

#if GPUDEM_HOST_LANES
/// PairLanesForces::sweep_range in eight lanes compiled for -march=x86-64-v4 (AVX-512), with
/// everything it calls inlined, in translation units of its own (engine/PairLanesInstance.in);
/// call it only where host_vector_doubles() is 8.
template <class Law, class P>
void sweep_in_avx512_lanes(const PairLanesForces<Law, P, 8>& kernel, std::uint32_t begin,
                           std::uint32_t end);
/// The same in four lanes compiled for -march=x86-64-v3 (AVX2); call it only where
/// host_vector_doubles() is at least 4.
template <class Law, class P>
void sweep_in_avx2_lanes(const PairLanesForces<Law, P, 4>& kernel, std::uint32_t begin,
                         std::uint32_t end);

/// One thread's range of the sweep in W lanes, run by the units built for them.
template <class Law, class P, int W>
struct PairLanesInVectors {
  static_assert(W == 8 || W == 4, "lanes units are built for eight and four doubles");
  PairLanesForces<Law, P, W> kernel;
  void operator()(std::uint32_t begin, std::uint32_t end) const {
    if constexpr (W == 8)
      sweep_in_avx512_lanes(kernel, begin, end);
    else
      sweep_in_avx2_lanes(kernel, begin, end);
  }
};
#endif

}  // namespace gpudem
