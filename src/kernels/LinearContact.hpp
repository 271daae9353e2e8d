#pragma once
/// Linear spring–dashpot contact with a history-dependent tangential spring and Coulomb limit
/// (Cundall & Strack 1979; the `hooke/history` model of LAMMPS GRANULAR).
///
///   normal:      F_n = max(0, k_n·δ + γ_n·δ̇)          (never attractive)
///   damping:     γ_n = 2·|β|·√(m*·k_n),  β = ln e / √(ln² e + π²)
///                (gives restitution e exactly for the linear spring–dashpot oscillator
///                 before the no-attraction clamp; Tsuji et al. 1992)
///   tangential:  F_t = −k_t·ξ − γ_t·v_t,  |F_t| ≤ μ·F_n,  k_t = 2/7·k_n,  γ_t = 2·|β|·√(m*·k_t)
///                ξ, the tangential spring, is kept per contact: each step it is rotated into
///                the current tangent plane (length kept) and grows by v_t·dt; on sliding it
///                is reset so that −k_t·ξ − γ_t·v_t equals the Coulomb force μ·F_n.
///   rolling:     M_r = −min(μ_r·F_n·R*, I*·|ω_rel|/dt)·ω̂_rel   (EDEM rolling model type A;
///                the cap keeps the torque from reversing the relative spin within one step)
///
/// δ is the overlap, δ̇ its rate (positive when approaching), v_t the tangential relative
/// velocity at the contact point (spin included), m* = m_i m_j/(m_i + m_j) (m* = m_i on walls).
#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// Per material pair constants, precomputed on the host.
struct LinearPairParams {
  Real stiffness;             ///< k_n [N/m]
  Real tangential_stiffness;  ///< k_t [N/m] (0 when the tangential force is off)
  Real damping_beta;          ///< |β| from the pair restitution (0 when damping is off)
  Real friction;              ///< μ (0 when the tangential force is off)
  Real rolling_friction;      ///< μ_r (0 when rolling resistance is off)
};

/// k_t / k_n: equal normal and tangential oscillation periods for a solid sphere.
constexpr double kTangentialStiffnessRatio = 2.0 / 7.0;

/// Geometry and kinematics of one contact, seen from particle i.
struct ContactKinematics {
  Vec3 normal;           ///< unit vector from i towards its partner
  Real overlap;          ///< δ > 0 [m]
  Vec3 velocity;         ///< relative velocity of i w.r.t. partner at the contact point [m/s]
  Real reduced_mass;     ///< m* [kg]
  Vec3 relative_spin;    ///< ω_i − ω_j (ω_i on walls) [rad/s]
  Real rolling_radius;   ///< R* = r_i r_j / (r_i + r_j) (r_i on walls) [m]
  Real reduced_inertia;  ///< I* = I_i I_j / (I_i + I_j) (I_i on walls) [kg m²]
};

/// β = ln e / √(ln² e + π²) as a magnitude; 0 for e = 1.
inline Real restitution_beta(Real e) {
  const Real pi = Real(3.14159265358979323846);
  const Real l = log(e);
  return fabs(l) / sqrt(l * l + pi * pi);
}

/// Dashpot coefficient 2|β|√(m* k) for a spring of stiffness k [kg/s].
GPUDEM_HD inline Real damping_coefficient(const LinearPairParams& p, const ContactKinematics& c,
                                          Real stiffness) {
  return 2 * p.damping_beta * sqrt(c.reduced_mass * stiffness);
}

/// F_n = max(0, k_n δ + γ_n δ̇) [N].
GPUDEM_HD inline Real normal_force(const LinearPairParams& p, const ContactKinematics& c) {
  const Real fn =
      p.stiffness * c.overlap + damping_coefficient(p, c, p.stiffness) * dot(c.velocity, c.normal);
  return fn > 0 ? fn : Real(0);
}

/// Tangential relative velocity v_t = v − (v·n) n [m/s].
GPUDEM_HD inline Vec3 tangential_velocity(const ContactKinematics& c) {
  return c.velocity - dot(c.velocity, c.normal) * c.normal;
}

/// F_t = −k_t ξ − γ_t v_t, limited to μ F_n [N].
GPUDEM_HD inline Vec3 tangential_force(const LinearPairParams& p, const ContactKinematics& c,
                                       Vec3 spring, Real fn) {
  if (p.tangential_stiffness == 0) return Vec3{};
  const Real gamma = damping_coefficient(p, c, p.tangential_stiffness);
  Vec3 ft = -p.tangential_stiffness * spring - gamma * tangential_velocity(c);
  const Real limit = p.friction * fn;
  const Real magnitude = norm(ft);
  if (magnitude > limit) ft = (magnitude > 0 ? limit / magnitude : Real(0)) * ft;
  return ft;
}

/// The spring after one step dt: ξ rotated into the current tangent plane (length kept),
/// plus v_t·dt, then shortened so that the trial force respects the Coulomb limit.
GPUDEM_HD inline Vec3 advance_tangential_spring(const LinearPairParams& p,
                                                const ContactKinematics& c, Vec3 spring, Real dt) {
  if (p.tangential_stiffness == 0) return Vec3{};
  const Real length = norm(spring);
  spring -= dot(spring, c.normal) * c.normal;
  const Real projected = norm(spring);
  if (projected > 0) spring = (length / projected) * spring;
  const Vec3 vt = tangential_velocity(c);
  spring += dt * vt;
  const Real gamma = damping_coefficient(p, c, p.tangential_stiffness);
  const Vec3 trial = -p.tangential_stiffness * spring - gamma * vt;
  const Real limit = p.friction * normal_force(p, c);
  const Real magnitude = norm(trial);
  if (magnitude > limit) {  // sliding: the spring holds only what friction allows
    const Vec3 ft = (magnitude > 0 ? limit / magnitude : Real(0)) * trial;
    spring = (Real(-1) / p.tangential_stiffness) * (ft + gamma * vt);
  }
  return spring;
}

/// Force on particle i from one contact with tangential spring ξ [N].
GPUDEM_HD inline Vec3 linear_contact_force(const LinearPairParams& p, const ContactKinematics& c,
                                           Vec3 spring) {
  const Real fn = normal_force(p, c);
  return tangential_force(p, c, spring, fn) - fn * c.normal;
}

/// Rolling resistance torque on particle i [N m].
GPUDEM_HD inline Vec3 rolling_torque(const LinearPairParams& p, const ContactKinematics& c, Real fn,
                                     Real dt) {
  const Real spin = norm(c.relative_spin);
  if (p.rolling_friction == 0 || spin == 0) return Vec3{};
  const Real full = p.rolling_friction * fn * c.rolling_radius;
  const Real stopping = c.reduced_inertia * spin / dt;
  return (-(full < stopping ? full : stopping) / spin) * c.relative_spin;
}

/// Elastic energy stored in one contact: ½ k_n δ² + ½ k_t |ξ|² [J].
GPUDEM_HD inline Real linear_contact_energy(const LinearPairParams& p, Real overlap, Vec3 spring) {
  return Real(0.5) * (p.stiffness * overlap * overlap + p.tangential_stiffness * norm2(spring));
}

}  // namespace gpudem
