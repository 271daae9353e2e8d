#pragma once
/// Geometry and kinematics of one contact seen from particle i, as the contact-law slots read
/// them. The sweep (ContactVisitor.hpp) fills only the fields the law's capability flags ask
/// for; the others stay zero. A wall is a partner of infinite mass and radius.
#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

struct ContactPoint {
  Vec3 normal;            ///< unit vector from i towards its partner
  Real overlap = 0;       ///< δ > 0 [m]
  Real overlap_rate = 0;  ///< δ̇, positive while approaching [m/s]
  Vec3 velocity;  ///< relative velocity of i w.r.t. the partner at the contact point [m/s]
  Real reduced_mass = 0;      ///< m* = m_i m_j/(m_i + m_j), m_i on walls [kg]
  Real effective_radius = 0;  ///< R* = r_i r_j/(r_i + r_j), r_i on walls [m]   (radius flag)
  Vec3 relative_spin;         ///< ω_i − ω_j, ω_i on walls [rad/s]                (spin flag)
  Real reduced_inertia = 0;   ///< I* = I_i I_j/(I_i + I_j), I_i on walls [kg m²] (inertia flag)
  Real rolling_inertia = 0;   ///< I_r: 1/I_r = Σ 1/(I + m r²) over the particles [kg m²]
  Real contact_radius_sq = 0;  ///< a², squared radius of the contact circle [m²] (area flag)
};

/// Tangential part of the relative velocity, v − (v·n) n [m/s].
GPUDEM_HD inline Vec3 tangential_velocity(const ContactPoint& c) {
  return c.velocity - dot(c.velocity, c.normal) * c.normal;
}

/// a² of two overlapping spheres at centre distance d: the radius of the lens' rim,
/// a² = (r_i+r_j−d)(d+r_i−r_j)(d−r_i+r_j)(d+r_i+r_j) / (4d²).
GPUDEM_HD inline Real sphere_contact_radius_sq(Real d, Real ri, Real rj) {
  return (ri + rj - d) * (d + ri - rj) * (d - ri + rj) * (d + ri + rj) / (4 * d * d);
}

/// a² of a sphere of radius r cut by a plane at overlap δ: a² = 2rδ − δ².
GPUDEM_HD inline Real wall_contact_radius_sq(Real r, Real overlap) {
  return 2 * r * overlap - overlap * overlap;
}

}  // namespace gpudem
