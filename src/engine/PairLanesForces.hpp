#pragma once
/// The host's pair-once force sweep with the law evaluated on several contacts at a time: eight
/// on CPUs with AVX-512, four on CPUs with AVX2 (PairLanesForces); the same pairs, loads and bits
/// as PairOnceForces. Host code only.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/LaneMemory.hpp"
#include "core/Lanes.hpp"
#include "engine/PairOnceForces.hpp"

namespace gpudem {

/// The touching pair entries a sweep in W lanes has found and not yet evaluated, held column by
/// column, so that the entries of one test of W enter packed at once and W waiting ones load
/// straight into the lanes: entries [first, count) wait. Past `count` the columns hold earlier
/// entries' values (or zeros): valid indices, evaluated but not read.
template <int W>
struct TouchingEntries {
  static constexpr int capacity = 8 * W;
  /// Index columns: the contact's particle i, its partner j, its list entry, and 1 where both
  /// ends are in one group (the partner's sums are written here too).
  enum Index : int { i, j, entry, grouped, indices };
  int first = 0;
  int count = 0;
  std::uint32_t index[indices][capacity] = {};
  Real xj[4][capacity] = {};  ///< the partner's position and radius, as the test read them

  int waiting() const { return count - first; }
  /// The waiting entries' index column.
  const std::uint32_t* at(Index column) const { return index[column] + first; }
  /// The first W waiting entries' partner positions and radii.
  Vec4T<Lanes<Real, W>> partner_positions() const {
    const auto c = [this](int k) { return load_lanes<W>(xj[k] + first); };
    return {c(0), c(1), c(2), c(3)};
  }
  /// The first W waiting entries gone, once evaluated.
  void drop_first() { first += W; }
  /// Room for W more entries: fewer than W wait, and they move to the front where the columns
  /// have no room past them.
  void make_room() {
    if (count + W <= capacity) return;
    const int moved = waiting();
    for (auto& column : index) std::memmove(column, column + first, sizeof(column[0]) * moved);
    for (auto& column : xj) std::memmove(column, column + first, sizeof(column[0]) * moved);
    count = moved;
    first = 0;
  }
  void clear() { first = count = 0; }
};

/// The host backend's force sweep over one thread's range of particles, as PairOnceForces
/// (the same pairs, loads and bits) but in lanes of W (core/Lanes.hpp): each particle's entries
/// are tested W at a time, without a branch on the outcome, the touching ones packed into a
/// queue (TouchingEntries) and the law evaluated on W of them at once; then, 64 particles at a
/// time, each particle's walls and meshes, and its loads stored. Built only where one vector
/// instruction holds the W lanes: eight for AVX-512 (sweep_in_avx512_lanes), four for AVX2
/// (sweep_in_avx2_lanes). Split into narrower vectors it is slower than PairOnceForces.
template <class Law, class P, int W>
struct PairLanesForces {
  using S = typename Law::Scalar;
  using R = LaneScalar<Real, W>;
  using L = LaneScalar<S, W>;
  using Index = Lanes<std::uint32_t, W>;
  using Offset = Lanes<std::int64_t, W>;
  using Queue = TouchingEntries<W>;
  static constexpr std::uint32_t chunk = 64;  ///< particles whose pairs share the queue
  /// Entries past a particle's first whose partners' positions it prefetches (eight of them).
  static constexpr std::uint32_t kPrefetchAhead = 16;
  static_assert(kPrefetchAhead + 8 <= kRowsPadding, "the rows' padding holds what is read");
  /// Scalars of one history record.
  static constexpr std::int64_t kRecordSize = sizeof(typename Law::State) / sizeof(S);
  PairOnceForces<Law, P> once;  ///< the sweep, its groups and its integer sums

  /// The particles at positions [begin, end) of the sweep.
  void sweep_range(std::uint32_t begin, std::uint32_t end) const {
    const ForceSweep<Law, P>& s = once.sweep;
    ContactPairParamsT<L> one_pair{};  // a scene of one material: its pair's constants
    if (s.scene.material_count == 1)
      for_each_param(one_pair, s.scene.pair_params[0], [](auto& to, S from) { to = from; });
    Queue queue;
    for (std::uint32_t first = begin; first < end; first += chunk) {
      const std::uint32_t last = end - first < chunk ? end : first + chunk;
      for (std::uint32_t k = first; k < last; ++k) test_pairs(k, queue, one_pair);
      if (queue.waiting() > 0) evaluate(queue, one_pair);
      queue.clear();
      for (std::uint32_t k = first; k < last; ++k) finish(swept_index(s.subset, k));
    }
  }

  /// The pair entries of the particle at position k (each pair in its group once), W at a time;
  /// the law is evaluated whenever W touching ones wait.
  void test_pairs(std::uint32_t position, Queue& queue,
                  const ContactPairParamsT<L>& one_pair) const {
    const ForceSweep<Law, P>& s = once.sweep;
    const EvaluatedRows& rows = once.evaluated;
    const std::uint32_t i = swept_index(s.subset, position);
    const std::uint32_t end = rows.end[position];
    if (rows.begin[position] == end) return;
    const Me me = lanes_of_particle(i);
    if (const ParticleView<Real>* p = state_in_double()) {  // partners a few particles ahead
      const std::uint32_t* ahead = rows.partner + rows.begin[position] + kPrefetchAhead;
      for (int l = 0; l < 8; ++l) __builtin_prefetch(&p->position_radius[ahead[l]]);
    }
    for (std::uint32_t h = rows.begin[position]; h < end; h += W) {
      test_entries(me, h, end - h, rows.group_end[position], queue);
      if (queue.waiting() >= W) {
        evaluate(queue, one_pair);
        queue.drop_first();
      }
      queue.make_room();
    }
  }

  /// Particle i, its position and radius in every lane.
  struct Me {
    std::uint32_t i;
    Vec4T<R> x;
  };
  Me lanes_of_particle(std::uint32_t i) const {
    const Real4 x = once.sweep.particles.position(i);
    return {i, {R(x.x), R(x.y), R(x.z), R(x.w)}};
  }

  /// Tests the evaluated entries [h, h + n) of particle `me` (at most W of them) at once: the
  /// touching ones join the queue, packed; a separated one forgets its history. A lane past n
  /// repeats the first entry, so that every read is of a real particle.
  void test_entries(const Me& me, std::uint32_t h, std::uint32_t n, std::uint32_t group_end,
                    Queue& q) const {
    const ForceSweep<Law, P>& s = once.sweep;
    const EvaluatedRows& rows = once.evaluated;
    const Index lane = lane_numbers<W>();
    const auto valid = lane < n;
    const Index j = select(valid, load_lanes<W>(rows.partner + h), Index(rows.partner[h]));
    const Index k = select(valid, load_lanes<W>(rows.entry + h), Index(rows.entry[h]));
    const Vec4T<R> xj = positions(j);
    const Vec3T<R> d = minimum_image(xyz(xj) - xyz(me.x));
    const R dist2 = norm2(d);
    const R reach = me.x.w + xj.w;
    // NaN: touching, so that it spreads, as pair_entry
    LaneBits touching = first_lanes<W>(n) & ~bits_of(dist2 >= reach * reach || dist2 == Real(0));
    if (s.scene.bond_records)
      for (int l = 0; l < W; ++l) touching &= ~(LaneBits(s.scene.bonded(k[l])) << l);
    forget_history(k, first_lanes<W>(n) & ~touching);
    const int at = q.count;
    store_packed(q.index[Queue::j] + at, j, touching);
    store_packed(q.index[Queue::entry] + at, k, touching);
    store_packed(q.index[Queue::grouped] + at, select(h + lane < group_end, Index(1u), Index(0u)),
                 touching);
    store_lanes(q.index[Queue::i] + at, Index(me.i));
    store_packed(q.xj[0] + at, xj.x, touching);
    store_packed(q.xj[1] + at, xj.y, touching);
    store_packed(q.xj[2] + at, xj.z, touching);
    store_packed(q.xj[3] + at, xj.w, touching);
    q.count += __builtin_popcount(touching);
  }

  /// The separated entries' histories cleared.
  void forget_history(const Index& k, LaneBits separated) const {
    if constexpr (Law::history_size > 0) {
      const Offset first = Offset(k) * kRecordSize;
      for (std::int64_t v = 0; v < kRecordSize; ++v)
        scatter(&once.sweep.history.pair[0].value[0], first + v, L(S(0)), separated);
    }
  }

  /// d reduced to its nearest periodic image on each periodic axis, as PeriodicBox does.
  Vec3T<R> minimum_image(Vec3T<R> d) const {
    const PeriodicBox& box = once.sweep.scene.box;
    for (int a = 0; a < 3; ++a)
      if (box.periodic[a]) {
        const Real length = axis(box.length, a);
        R& c = axis(d, a);
        for (int l = 0; l < W; ++l) c.v[l] -= length * floor(c.v[l] / length + Real(0.5));
      }
    return d;
  }

  /// Components [0, N) of records of N doubles at `base`, of the lanes' records.
  template <int N>
  static std::array<R, N> gather_records(const Real* base, const Index& at) {
    const Offset first = Offset(at) * std::int64_t(N);
    std::array<R, N> v;
    for (int c = 0; c < N; ++c) v[c] = gather(base, first + std::int64_t(c));
    return v;
  }

  /// The particle arrays where the state is held in double (every policy but "float"), else
  /// null.
  const ParticleView<Real>* state_in_double() const {
    if constexpr (std::is_same_v<P, Real>)
      return &once.sweep.particles;
    else
      return once.sweep.particles.is_float ? nullptr : &once.sweep.particles.in_double;
  }

  /// The lanes' particles' positions (and radii), velocities (and inverse masses) and spins:
  /// gathered from a state held in double, else read lane by lane.
  Vec4T<R> positions(const Index& at) const {
    if (const ParticleView<Real>* p = state_in_double())
      return vec4(gather_records<4>(&p->position_radius[0].x, at));
    Vec4T<R> v;
    for (int l = 0; l < W; ++l) set_lane<Real, W>(v, l, once.sweep.particles.position(at[l]));
    return v;
  }
  Vec4T<R> velocities(const Index& at) const {
    if (const ParticleView<Real>* p = state_in_double())
      return vec4(gather_records<4>(&p->velocity_inv_mass[0].x, at));
    Vec4T<R> v;
    for (int l = 0; l < W; ++l) set_lane<Real, W>(v, l, once.sweep.particles.velocity(at[l]));
    return v;
  }
  Vec3T<R> spins(const Index& at) const {
    if (const ParticleView<Real>* p = state_in_double()) {
      const std::array<R, 3> w = gather_records<3>(&p->angular_velocity[0].x, at);
      return {w[0], w[1], w[2]};
    }
    Vec3T<R> v;
    for (int l = 0; l < W; ++l) set_lane<Real, W>(v, l, once.sweep.particles.spin(at[l]));
    return v;
  }
  static Vec4T<R> vec4(const std::array<R, 4>& c) { return {c[0], c[1], c[2], c[3]}; }

  /// The law on the queue's first W entries (its first `count`, where fewer wait); each
  /// contact's loads go to its own end and, for a pair in one group, to the partner (the loads
  /// mirrored, its torque with its own arm).
  void evaluate(const Queue& q, const ContactPairParamsT<L>& one_pair) const {
    const Index j = load_lanes<W>(q.at(Queue::j));
    const Index i = load_lanes<W>(q.at(Queue::i));
    const Vec4T<R> xi = positions(i), vi = velocities(i), xj = q.partner_positions();
    Vec3T<R> wi{}, wj{};
    if constexpr (Law::needs_spin) wi = spins(i), wj = spins(j);
    ContactPointT<R> point;
    R arm;
    const Vec3T<R> d = minimum_image(xyz(xj) - xyz(xi));
    describe_pair<Law>(point, arm, d, norm2(d), xi, vi, wi, xj, velocities(j), wj);
    L history[Law::history_size > 0 ? Law::history_size : 1];
    if constexpr (Law::history_size > 0) {
      const Offset first = Offset(load_lanes<W>(q.at(Queue::entry))) * kRecordSize;
      for (int v = 0; v < Law::history_size; ++v)
        history[v] = gather(&once.sweep.history.pair[0].value[0], first + std::int64_t(v));
    }
    const ContactForce<L> f = Law::evaluate(pair_params(q, one_pair), point_cast<L>(point), history,
                                            L(static_cast<S>(once.sweep.dt)));
    const ExactUnits& units = once.units;
    LoadTerms terms{exact_terms(f.force, units.per_force), {}, {}};
    if constexpr (Law::needs_spin) {
      terms.torque = exact_terms(lever_torque<Law>(arm, point.normal, f), units.per_torque);
      terms.partner_torque = exact_terms(
          partner_torque<Law>(xj.w - Real(0.5) * point.overlap, point.normal, f), units.per_torque);
    }
    const R ratio = point.overlap / select(xi.w < xj.w, xi.w, xj.w);
    const int count = q.waiting() < W ? q.waiting() : W;
    if (terms.force.spills || terms.torque.spills || terms.partner_torque.spills)
      store_loads<true>(q, count, terms, ratio, history);
    else
      store_loads<false>(q, count, terms, ratio, history);
  }

  /// The lanes' pair constants: the one pair's in a scene of one material.
  ContactPairParamsT<L> pair_params(const Queue& q, const ContactPairParamsT<L>& one_pair) const {
    const ContactScene<Law>& s = once.sweep.scene;
    if (s.material_count == 1) return one_pair;
    const MaterialId* material = once.sweep.particles.material;
    ContactPairParamsT<L> params;
    for (int l = 0; l < W; ++l)
      for_each_param(params,
                     s.pair_params[material[q.at(Queue::i)[l]] * s.material_count +
                                   material[q.at(Queue::j)[l]]],
                     [l](L& to, S from) { set_lane(to, l, from); });
    return params;
  }

  /// The integer terms of the lanes' loads.
  struct LoadTerms {
    ExactTermLanes<W> force, torque, partner_torque;
  };

  /// Each of the first `count` lanes' history written back and its loads added to its ends'
  /// sums (in one word each unless some lane `Spills`), with its overlap ratio.
  template <bool Spills>
  void store_loads(const Queue& q, int count, const LoadTerms& t, const R& ratio,
                   const L* history) const {
    const auto term = [](const ExactTermLanes<W>& terms, int l) {
      if constexpr (Spills)
        return terms.lane(l);
      else
        return terms.words(l);
    };
    for (int l = 0; l < count; ++l) {
      if constexpr (Law::history_size > 0) {
        typename Law::State state;
        for (int v = 0; v < Law::history_size; ++v) state.value[v] = lane_of(history[v], l);
        // −0 stored as +0: the same bits whether this end or the partner's mirror writes it
        once.sweep.history.pair[q.at(Queue::entry)[l]] = Law::without_negative_zeros(state);
      }
      const std::uint32_t i = q.at(Queue::i)[l], j = q.at(Queue::j)[l];
      const bool grouped = q.at(Queue::grouped)[l] != 0;
      const auto force_term = term(t.force, l);
      once.pair_force.add(i, force_term);
      if (grouped) once.pair_force.subtract(j, force_term);
      if constexpr (Law::needs_spin) {
        once.pair_torque.add(i, term(t.torque, l));
        if (grouped) once.pair_torque.add(j, term(t.partner_torque, l));
      }
      const Real lane_ratio = lane_of(ratio, l);
      Real* worst = once.pair_ratio;
      worst[i] = lane_ratio > worst[i] ? lane_ratio : worst[i];
      if (grouped) worst[j] = lane_ratio > worst[j] ? lane_ratio : worst[j];
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
