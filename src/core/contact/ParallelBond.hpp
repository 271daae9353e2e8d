#pragma once
/// The parallel bond of Potyondy & Cundall (2004, "A bonded-particle model for rock", Int. J.
/// Rock Mech. Min. Sci. 41, 1329–1364): a cylinder of cement of radius r_b = λ min(r_a, r_b)
/// joining two spheres, acting as a short beam between their centres.
///
/// Stiffness per unit area from the bond's Young's modulus E and shear modulus G over its rest
/// length L₀ (the centre distance when it formed): k̄_n = E / L₀, k̄_s = G / L₀; its section
/// A = π r_b², I = π r_b⁴ / 4, J = 2I. With n the unit vector from the lower-id end a to the
/// higher-id end b at distance L, and the relative motion of b w.r.t. a at the bond's contact
/// point c = x_a + L_a n (L_a = L r_a / (r_a + r_b)):
///   F_n = k̄_n A (L − L₀)                    (normal force on a along +n; tension > 0)
///   F_s ← R(F_s) + k̄_s A v_t Δt              (shear force on a)
///   M_t ← M_t + k̄_s J (ω_rel·n) Δt           (twisting moment on a, along n)
///   M_b ← R(M_b) + k̄_n I ω_rel,t Δt          (bending moment on a)
/// where v_t is the tangential part of the relative velocity at c, ω_rel = ω_b − ω_a, and R
/// rotates a stored vector into the plane normal to the current n, its length kept (the
/// incremental update of the paper, rotated with the bond). b receives −F and −(M_t n + M_b), and
/// each end the moment of the shear force about its centre (L_a n × F_s on a, L_b n × F_s on b),
/// so that momentum and angular momentum are conserved exactly. Viscous damping adds
/// 2β√(m* k) times each relative rate (k the stiffness of that mode, m* or I* the reduced mass
/// or moment of inertia). The bond breaks when the largest tensile stress of its section,
/// σ = F_n / A + |M_b| r_b / I, reaches the tensile strength σ_c, or the largest shear stress,
/// τ = |F_s| / A + |M_t| r_b / J, reaches the shear strength τ_c; it then carries nothing and the
/// pair meets through the contact law. Both ends evaluate the bond in this one orientation (a
/// to b) from the same particle state, so both hold the same state bit for bit.
#include <cstdint>
#include <utility>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "core/contact/TangentialLaws.hpp"

namespace gpudem {

/// A bond's material, as a [[bond]] table of the scene gives it.
template <class S>
struct BondParamsT {
  S young = 0;             ///< E of the cement [Pa]
  S shear = 0;             ///< G = E / (2(1 + ν)) [Pa]
  S radius_factor = 1;     ///< λ: r_b = λ min(r_a, r_b)
  S tensile_strength = 0;  ///< σ_c [Pa] (+inf: never breaks in tension)
  S shear_strength = 0;    ///< τ_c [Pa] (+inf: never breaks in shear)
  S damping_ratio = 0;     ///< β, a fraction of critical damping of each mode
};

using BondParams = BondParamsT<Real>;

template <class To>
BondParamsT<To> bond_params_cast(const BondParams& p) {
  return {static_cast<To>(p.young),          static_cast<To>(p.shear),
          static_cast<To>(p.radius_factor),  static_cast<To>(p.tensile_strength),
          static_cast<To>(p.shear_strength), static_cast<To>(p.damping_ratio)};
}

/// The three values at `v` as a vector, and back.
template <class S>
GPUDEM_HD Vec3T<S> load_vec(const S* v) {
  return Vec3T<S>{v[0], v[1], v[2]};
}
template <class S>
GPUDEM_HD void store_vec(S* v, const Vec3T<S>& a) {
  v[0] = a.x;
  v[1] = a.y;
  v[2] = a.z;
}

/// The values one end stores per bond: rest length L₀ (0: no bond), bond type (the index of
/// its [[bond]] table), shear force F_s (3), bending moment M_b (3), twisting moment M_t, the
/// loads being those on end a. They are in the law's scalar: in float L₀ is rounded, which
/// leaves a bond a residual strain of at most 6e-8 when it forms.
namespace bond_value {
inline constexpr int rest_length = 0, type = 1, shear = 2, bending = 5, twist = 8;
inline constexpr std::uint32_t width = 9;
}  // namespace bond_value

/// A bond's geometry and relative motion, from end a to end b, in the law's scalar.
template <class S>
struct BondGeometry {
  Vec3T<S> normal;         ///< n, unit, from a to b
  S stretch = 0;           ///< L − L₀, formed in Real from the stored L₀ [m]
  S arm_a = 0, arm_b = 0;  ///< L_a, L_b: distances of the contact point from a and b [m]
  S min_radius = 0;        ///< min(r_a, r_b) [m]
  Vec3T<S> velocity;       ///< of b w.r.t. a at the contact point [m/s]
  Vec3T<S> spin;           ///< ω_b − ω_a [rad/s]
  S reduced_mass = 0;      ///< m* [kg]
  S reduced_inertia = 0;   ///< I* [kg m²]
};

/// The loads of a bond this step: on a the force and torque, on b −force and torque_b.
template <class S>
struct BondLoad {
  Vec3T<S> force;
  Vec3T<S> torque_a;
  Vec3T<S> torque_b;
  bool broken = false;
};

/// The section of a bond: radius r_b, area A, second moment I and polar moment J.
template <class S>
struct BondSection {
  S radius, area, inertia, polar;
  GPUDEM_HD static BondSection of(const BondParamsT<S>& p, S min_radius) {
    const S r = p.radius_factor * min_radius, pi = S(3.14159265358979323846);
    const S area = pi * r * r, inertia = S(0.25) * pi * r * r * r * r;
    return {r, area, inertia, 2 * inertia};
  }
};

/// The stiffnesses of the four modes: k_n = k̄_n A, k_s = k̄_s A [N/m], k_t = k̄_s J,
/// k_b = k̄_n I [N m/rad].
template <class S>
struct BondStiffness {
  S normal, shear, twist, bending;
  GPUDEM_HD static BondStiffness of(const BondParamsT<S>& p, const BondSection<S>& a,
                                    S rest_length) {
    const S kn = p.young / rest_length, ks = p.shear / rest_length;
    return {kn * a.area, ks * a.area, ks * a.polar, kn * a.inertia};
  }
};

/// 2β√(m k): the viscous coefficient of a mode of stiffness k and inertia m.
template <class S>
GPUDEM_HD S bond_damping(S ratio, S inertia, S stiffness) {
  return 2 * ratio * square_root(inertia * stiffness);
}

/// The largest tensile and shear stresses of the section [Pa]: σ = F_n/A + |M_b| r_b/I and
/// τ = |F_s|/A + |M_t| r_b/J.
template <class S>
struct BondStress {
  S tension, shear;
  GPUDEM_HD static BondStress of(const BondSection<S>& a, S normal_force, const Vec3T<S>& shear,
                                 const Vec3T<S>& bending, S twist) {
    return {normal_force / a.area + norm(bending) * a.radius / a.inertia,
            norm(shear) / a.area + (twist < 0 ? -twist : twist) * a.radius / a.polar};
  }
  /// The larger of σ/σ_c and τ/τ_c: 1 breaks the bond (0 without strengths).
  GPUDEM_HD S strength_used(const BondParamsT<S>& p) const {
    const S t = tension / p.tensile_strength, s = shear / p.shear_strength;
    return t > s ? t : s;
  }
};

/// True when the section's stresses reach either strength (the criterion above).
template <class S>
GPUDEM_HD bool bond_fails(const BondParamsT<S>& p, const BondSection<S>& a, S normal_force,
                          const Vec3T<S>& shear, const Vec3T<S>& bending, S twist) {
  const BondStress<S> stress = BondStress<S>::of(a, normal_force, shear, bending, twist);
  return stress.tension >= p.tensile_strength || stress.shear >= p.shear_strength;
}

/// Advances the bond whose stored values are `state` (bond_value layout) by dt and returns its
/// loads; a bond that fails is marked broken, its state left for the caller to clear.
template <class S>
GPUDEM_HD BondLoad<S> evaluate_bond(const BondParamsT<S>& p, const BondGeometry<S>& g, S* state,
                                    S dt) {
  namespace v = bond_value;
  const BondSection<S> a = BondSection<S>::of(p, g.min_radius);
  const BondStiffness<S> k = BondStiffness<S>::of(p, a, state[v::rest_length]);
  const Vec3T<S> n = g.normal;
  const S normal_force = k.normal * g.stretch;
  const S normal_rate = dot(g.velocity, n), twist_rate = dot(g.spin, n);
  const Vec3T<S> vt = g.velocity - normal_rate * n, wt = g.spin - twist_rate * n;
  const Vec3T<S> shear = rotate_into_plane(load_vec(state + v::shear), n) + (k.shear * dt) * vt;
  const Vec3T<S> bending =
      rotate_into_plane(load_vec(state + v::bending), n) + (k.bending * dt) * wt;
  const S twist = state[v::twist] + k.twist * dt * twist_rate;
  BondLoad<S> load;
  if (bond_fails(p, a, normal_force, shear, bending, twist)) {
    load.broken = true;
    return load;
  }
  store_vec(state + v::shear, shear);
  store_vec(state + v::bending, bending);
  state[v::twist] = twist;
  const S beta = p.damping_ratio;
  const Vec3T<S> shear_total = shear + bond_damping(beta, g.reduced_mass, k.shear) * vt;
  const Vec3T<S> moment =
      (twist + bond_damping(beta, g.reduced_inertia, k.twist) * twist_rate) * n + bending +
      bond_damping(beta, g.reduced_inertia, k.bending) * wt;
  load.force =
      (normal_force + bond_damping(beta, g.reduced_mass, k.normal) * normal_rate) * n + shear_total;
  load.torque_a = moment + cross(g.arm_a * n, shear_total);
  load.torque_b = cross(g.arm_b * n, shear_total) - moment;
  return load;
}

/// What a snapshot shows of a bond: its normal force and stresses.
struct BondReading {
  double normal_force = 0;  ///< [N], tension > 0
  BondStress<double> stress;
};

/// The reading of the bond whose stored values are `state`, at stretch L − L₀.
inline BondReading read_bond(const BondParams& p, double min_radius, double stretch,
                             const double* state) {
  namespace v = bond_value;
  const BondSection<double> a = BondSection<double>::of(p, min_radius);
  const BondStiffness<double> k = BondStiffness<double>::of(p, a, state[v::rest_length]);
  const double normal_force = k.normal * stretch;
  return {normal_force, BondStress<double>::of(a, normal_force, load_vec(state + v::shear),
                                               load_vec(state + v::bending), state[v::twist])};
}

/// ω² bounding the fastest vibration of two spheres (radii r_a, r_b, masses m_a, m_b) joined
/// by a bond of rest length r_a + r_b (a pair bonded while overlapping is stiffer) [1/s²]: the
/// trace of M⁻¹K of the pair's twelve degrees of freedom, which no eigenvalue exceeds, Σ over the
/// ends of (k_n + 2k_s)/m + (k_t + 2k_b + 2k_s L_p²)/I, with I = 2/5 m r² and L_p the end's
/// distance from the contact point.
inline double bond_frequency_squared(const BondParams& p, double ra, double ma, double rb,
                                     double mb) {
  const BondSection<double> a = BondSection<double>::of(p, ra < rb ? ra : rb);
  const BondStiffness<double> k = BondStiffness<double>::of(p, a, ra + rb);
  double sum = 0;
  for (const auto& [r, m] : {std::pair<double, double>{ra, ma}, {rb, mb}}) {
    const double inertia = 0.4 * m * r * r;
    sum += (k.normal + 2 * k.shear) / m + (k.twist + 2 * k.bending + 2 * k.shear * r * r) / inertia;
  }
  return sum;
}

/// Elastic energy the bond stores [J]: F_n²/(2k_n) + |F_s|²/(2k_s) + M_t²/(2k_t) + |M_b|²/(2k_b).
template <class S>
GPUDEM_HD S bond_energy(const BondParamsT<S>& p, const BondGeometry<S>& g, const S* state) {
  namespace v = bond_value;
  const BondSection<S> a = BondSection<S>::of(p, g.min_radius);
  const BondStiffness<S> k = BondStiffness<S>::of(p, a, state[v::rest_length]);
  const S normal_force = k.normal * g.stretch;
  const S twist = state[v::twist];
  return normal_force * normal_force / (2 * k.normal) +
         norm2(load_vec(state + v::shear)) / (2 * k.shear) + twist * twist / (2 * k.twist) +
         norm2(load_vec(state + v::bending)) / (2 * k.bending);
}

}  // namespace gpudem
