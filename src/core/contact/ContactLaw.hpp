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

  static constexpr int history_size = Tangential::history_size + Rolling::history_size;
  static constexpr int rolling_offset = Tangential::history_size;
  static constexpr bool needs_spin = Tangential::needs_spin || Rolling::needs_spin;
  static constexpr bool needs_effective_radius = Normal::needs_effective_radius ||
                                                 Tangential::needs_effective_radius ||
                                                 Rolling::needs_effective_radius;
  static constexpr bool needs_inertia = Rolling::needs_inertia;
  static constexpr bool needs_contact_area = Cohesion::needs_contact_area;
  static constexpr bool has_tangential_force = Tangential::history_size > 0;
  using State = ContactState<history_size, Scalar>;
  using Params = ContactPairParamsT<Scalar>;
  using Point = ContactPointT<Scalar>;
  using Force = ContactForce<Scalar>;

  /// Force and rolling torque on i; advances `history` by dt (dt = 0: reads the stored state).
  /// Normal: F_n = F_e + F_d (clamped at 0 if the damping law says so) minus cohesion; the
  /// Coulomb and rolling limits scale with the elastic force F_e (TangentialLaws.hpp).
  GPUDEM_HD static Force evaluate(const Params& p, const Point& c, Scalar* history, Scalar dt) {
    const NormalResponse<Scalar> n = Normal::respond(p, c);
    Scalar fn = n.force + Damping::template normal_force<Normal>(p, c, n);
    if (Damping::clamps_attraction && fn < 0) fn = 0;
    Force out;
    out.tangential = Tangential::template force<Damping, Normal>(p, c, n.force, history, dt);
    out.force = out.tangential - (fn - Cohesion::force(p, c)) * c.normal;
    out.rolling_torque = Rolling::torque(p, c, n, n.force, history + rolling_offset, dt);
    return out;
  }

  /// Elastic energy stored in the contact's springs (cohesion not included) [J].
  GPUDEM_HD static Scalar energy(const Params& p, const Point& c, const Scalar* history) {
    const NormalResponse<Scalar> n = Normal::respond(p, c);
    return Normal::energy(p, c) + Tangential::energy(p, c, history) +
           Rolling::energy(p, c, n, history + rolling_offset);
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
