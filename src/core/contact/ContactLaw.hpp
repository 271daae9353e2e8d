#pragma once
/// A contact law is one choice per slot (docs/architecture.md, "Contact law"): normal, damping,
/// tangential, rolling and cohesion, each a stateless struct of __host__ __device__ functions with
/// capability flags. ContactLaw<...> composes them and derives the flags the contact sweep uses to
/// load only what the law reads: history values per contact, spins, R*, inertias, contact area. A
/// switched-off slot compiles to nothing. The law's Scalar is the precision of its arithmetic,
/// its history and the forces it returns: Real, or float under the mixed precision policy
/// (positions and velocities stay Real).
#include <cmath>
#include <cstddef>
#include <tuple>

#include "core/ContactModel.hpp"
#include "core/contact/ContactSlots.hpp"

namespace gpudem {

/// The history values of one contact (N > 0); laws with N = 0 store nothing.
template <int N, class S>
struct ContactState {
  S value[N > 0 ? N : 1];
};

/// What one contact exerts on particle i: the force at the contact point, its tangential
/// part and the rolling torque. The torque of the force about i's centre is arm·n × F_t, added
/// by the caller: the normal part has no lever, and leaving it out of the cross product keeps
/// its rounding out of the torque.
template <class S>
struct ContactForce {
  Vec3T<S> force;
  Vec3T<S> tangential;
  Vec3T<S> rolling_torque;
};

template <class NormalSlot, class DampingSlot, class TangentialSlot, class RollingSlot,
          class CohesionSlot, class ScalarType>
struct ContactLaw {
  using Scalar = ScalarType;
  using Normal = NormalSlot;
  using Damping = DampingSlot;
  using Tangential = TangentialSlot;
  using Rolling = RollingSlot;
  using Cohesion = CohesionSlot;

  static constexpr int history_size =
      Tangential::history_size + Rolling::history_size + Cohesion::history_size;
  static constexpr int rolling_offset = Tangential::history_size;
  /// Where the cohesion's history value (1 once the contact has formed) is, when it keeps one.
  static constexpr int formed_offset = Tangential::history_size + Rolling::history_size;
  static constexpr bool needs_spin = Tangential::needs_spin || Rolling::needs_spin;
  static constexpr bool needs_effective_radius =
      Normal::needs_effective_radius || Tangential::needs_effective_radius ||
      Rolling::needs_effective_radius || Cohesion::needs_effective_radius;
  static constexpr bool needs_inertia = Rolling::needs_inertia;
  static constexpr bool needs_contact_area = Cohesion::needs_contact_area;
  static constexpr bool has_tangential_force = Tangential::history_size > 0;
  /// Whether evaluate also runs on Lanes<Scalar, W> (core/Lanes.hpp), W contacts at once: every
  /// slot but JKR's cohesion is written with select instead of branches.
  static constexpr bool evaluates_in_lanes = Cohesion::evaluates_in_lanes;
  /// The slot choices, as a scene names them.
  static constexpr ContactModel model{
      static_cast<NormalLaw>(NormalSlots::index_of<Normal>()),
      static_cast<DampingLaw>(DampingSlots::index_of<Damping>()),
      static_cast<TangentialLaw>(TangentialSlots::index_of<Tangential>()),
      static_cast<RollingLaw>(RollingSlots::index_of<Rolling>()),
      static_cast<CohesionLaw>(CohesionSlots::index_of<Cohesion>())};
  using State = ContactState<history_size, Scalar>;
  using Params = ContactPairParamsT<Scalar>;
  using Point = ContactPointT<Scalar>;
  using Force = ContactForce<Scalar>;

  /// Force and rolling torque on i; advances `history` by dt (dt = 0: reads the stored state).
  /// The elastic, damping, tangential and rolling slots see the cohesion's point e (adhere).
  /// Normal: F_n = F_e + F_d (clamped at 0 if the damping law says so) minus the cohesion's
  /// pull; the Coulomb and rolling limits scale with the cohesion's friction load (F_e, or
  /// JKR's F_e − pull + 2 F_pull-off; TangentialLaws.hpp).
  /// T is Scalar, or Lanes of it (core/Lanes.hpp) where evaluates_in_lanes.
  template <class T>
  GPUDEM_HD static ContactForce<T> evaluate(const ContactPairParamsT<T>& p,
                                            const ContactPointT<T>& c, T* history,
                                            NonDeducedT<T> dt) {
    const Adhesion<T> adhesion = Cohesion::adhere(p, c);
    const ContactPointT<T>& e = adhesion.point;
    const T pull = adhesion.pull;
    const NormalResponse<T> n = Normal::respond(p, e);
    T fn = n.force + Damping::template normal_force<Normal>(p, e, n);
    if constexpr (Damping::clamps_attraction) fn = select(fn < 0, T(0), fn);
    const T load = Cohesion::friction_load(p, e, n.force, pull);
    ContactForce<T> out;
    out.tangential = Tangential::template force<Damping, Normal>(p, e, load, history, dt);
    out.force = out.tangential - (fn - pull) * c.normal;
    out.rolling_torque = Rolling::torque(p, e, n, load, history + rolling_offset, dt);
    if constexpr (Cohesion::history_size > 0)
      history[formed_offset] = select(dt > 0, T(1), history[formed_offset]);
    return out;
  }

  /// The history of the same contact seen from its other end: each slot's leading
  /// negated_values (its springs) change sign, the rest (flags) are kept. A zero, +0 or −0,
  /// becomes +0, so that a blank record stays blank byte for byte (HistoryCarryOver's is_fresh).
  GPUDEM_HD static State mirrored(const State& s) {
    State m = s;
    negate_leading<Tangential>(m.value);
    negate_leading<Rolling>(m.value + rolling_offset);
    negate_leading<Cohesion>(m.value + formed_offset);
    return m;
  }

  /// The record with every −0 made +0 (x + 0 is x otherwise): what a pair's end stores when the
  /// other end may hold the mirror (ForceCompute::mirror_pair_history), whose zeros are +0.
  GPUDEM_HD static State without_negative_zeros(State s) {
    for (Scalar& v : s.value) v = v + Scalar(0);
    return s;
  }

  /// True when the stored history says the contact has formed (a cohesion that holds contacts
  /// past touch keeps it; false for the others).
  GPUDEM_HD static bool has_formed(const Scalar* history) {
    if constexpr (Cohesion::history_size > 0) return history[formed_offset] != 0;
    return false;
  }

  /// Energy stored in the contact's springs and its adhesion (sjkr's not counted) [J].
  GPUDEM_HD static Scalar energy(const Params& p, const Point& c, const Scalar* history) {
    const Point e = Cohesion::adhere(p, c).point;
    const NormalResponse<Scalar> n = Normal::respond(p, e);
    return Normal::energy(p, e) + Tangential::energy(p, e, history) +
           Rolling::energy(p, e, n, history + rolling_offset) + Cohesion::energy(p, e);
  }

  template <class Slot>
  GPUDEM_HD static void negate_leading(Scalar* values) {
    if constexpr (Slot::history_size > 0)
      for (int k = 0; k < Slot::negated_values; ++k) values[k] = Scalar(0) - values[k];  // 0 → +0
  }

  /// Bytes one contact evaluation reads beyond the partner's position, radius, velocity and
  /// inverse mass (64 B) and its list index (4 B): the history and the partner's spin.
  static constexpr int extra_bytes_per_contact =
      history_size * static_cast<int>(sizeof(Scalar)) + (needs_spin ? 3 * sizeof(Real) : 0);
};

/// The slot type an enum value names in its SlotList (ContactSlots.hpp).
template <class List, auto value>
using SlotOf = typename List::template At<static_cast<std::size_t>(value)>;

/// The law type of a model named by enum values, evaluated in scalar S.
template <NormalLaw N, DampingLaw D, TangentialLaw T, RollingLaw R, CohesionLaw C, class S = Real>
using ContactLawOf =
    ContactLaw<SlotOf<NormalSlots, N>, SlotOf<DampingSlots, D>, SlotOf<TangentialSlots, T>,
               SlotOf<RollingSlots, R>, SlotOf<CohesionSlots, C>, S>;

}  // namespace gpudem
