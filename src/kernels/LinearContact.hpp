#pragma once
/// Linear spring–dashpot contact with a velocity-regularised Coulomb tangential force.
///
///   normal:      F_n = max(0, k_n·δ + γ_n·δ̇)          (never attractive)
///   damping:     γ_n = 2·|β|·√(m*·k_n),  β = ln e / √(ln² e + π²)
///                (gives restitution e exactly for the linear spring–dashpot oscillator
///                 before the no-attraction clamp; Cundall & Strack 1979, Tsuji et al. 1992)
///   tangential:  F_t = −min(γ_t·|v_t|, μ·|F_n|)·t̂,   γ_t = γ_n,   t̂ = v_t/|v_t|
///                (no tangential spring: the regularised Coulomb law of LAMMPS gran/hooke)
///
/// δ is the overlap, δ̇ its rate (positive when approaching), v_t the tangential relative
/// velocity at the contact point (spin included), m* = m_i m_j/(m_i + m_j) (m* = m_i on walls).
#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// Per material pair constants, precomputed on the host.
struct LinearPairParams {
  Real stiffness;     ///< k_n [N/m]
  Real damping_beta;  ///< |β| from the pair restitution (0 when damping is off)
  Real friction;      ///< μ (0 when the tangential force is off)
};

/// Geometry and kinematics of one contact, seen from particle i.
struct ContactKinematics {
  Vec3 normal;        ///< unit vector from i towards its partner
  Real overlap;       ///< δ > 0 [m]
  Vec3 velocity;      ///< relative velocity of i w.r.t. partner at the contact point [m/s]
  Real reduced_mass;  ///< m* [kg]
};

/// β = ln e / √(ln² e + π²) as a magnitude; 0 for e = 1.
inline Real restitution_beta(Real e) {
  const Real pi = Real(3.14159265358979323846);
  const Real l = log(e);
  return fabs(l) / sqrt(l * l + pi * pi);
}

/// Force on particle i from one contact [N].
GPUDEM_HD inline Vec3 linear_contact_force(const LinearPairParams& p, const ContactKinematics& c) {
  const Real approach = dot(c.velocity, c.normal);  // δ̇ > 0 when closing
  const Real gamma = 2 * p.damping_beta * sqrt(c.reduced_mass * p.stiffness);
  Real fn = p.stiffness * c.overlap + gamma * approach;
  if (fn < 0) fn = 0;
  Vec3 force = -fn * c.normal;
  const Vec3 vt = c.velocity - approach * c.normal;
  const Real vt_mag = norm(vt);
  if (vt_mag > 0 && p.friction > 0) {
    const Real ft = fmin(gamma * vt_mag, p.friction * fn);
    force -= (ft / vt_mag) * vt;
  }
  return force;
}

/// Elastic energy stored in one linear contact: ½·k_n·δ² [J].
GPUDEM_HD inline Real linear_contact_energy(const LinearPairParams& p, Real overlap) {
  return Real(0.5) * p.stiffness * overlap * overlap;
}

}  // namespace gpudem
