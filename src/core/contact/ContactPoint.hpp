#pragma once
/// Geometry and kinematics of one contact seen from particle i, as the contact-law slots read
/// them. The sweep (ContactVisitor.hpp) fills only the fields the law's capability flags ask
/// for; the others stay zero. A wall is a partner of infinite mass and radius. The sweep forms
/// them in Real from the particle state; a law evaluated in float reads a converted copy
/// (point_cast).
#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

template <class S>
struct ContactPointT {
  Vec3T<S> normal;         ///< unit vector from i towards its partner
  S overlap = 0;           ///< δ > 0 [m]
  S overlap_rate = 0;      ///< δ̇, positive while approaching [m/s]
  Vec3T<S> velocity;       ///< relative velocity of i w.r.t. the partner at the contact point [m/s]
  S reduced_mass = 0;      ///< m* = m_i m_j/(m_i + m_j), m_i on walls [kg]
  S effective_radius = 0;  ///< R* = r_i r_j/(r_i + r_j), r_i on walls [m]   (radius flag)
  Vec3T<S> relative_spin;  ///< ω_i − ω_j, ω_i on walls [rad/s]                (spin flag)
  S reduced_inertia = 0;   ///< I* = I_i I_j/(I_i + I_j), I_i on walls [kg m²] (inertia flag)
  S rolling_inertia = 0;   ///< I_r: 1/I_r = Σ 1/(I + m r²) over the particles [kg m²]
  S contact_radius_sq = 0;  ///< a², squared radius of the contact circle [m²] (area flag)
};

using ContactPoint = ContactPointT<Real>;

/// `c` with every field converted to scalar To.
template <class To, class From>
GPUDEM_HD ContactPointT<To> point_cast(const ContactPointT<From>& c) {
  ContactPointT<To> out;
  out.normal = vec_cast<To>(c.normal);
  out.overlap = static_cast<To>(c.overlap);
  out.overlap_rate = static_cast<To>(c.overlap_rate);
  out.velocity = vec_cast<To>(c.velocity);
  out.reduced_mass = static_cast<To>(c.reduced_mass);
  out.effective_radius = static_cast<To>(c.effective_radius);
  out.relative_spin = vec_cast<To>(c.relative_spin);
  out.reduced_inertia = static_cast<To>(c.reduced_inertia);
  out.rolling_inertia = static_cast<To>(c.rolling_inertia);
  out.contact_radius_sq = static_cast<To>(c.contact_radius_sq);
  return out;
}

/// Tangential part of the relative velocity, v − (v·n) n [m/s].
template <class S>
GPUDEM_HD Vec3T<S> tangential_velocity(const ContactPointT<S>& c) {
  return c.velocity - dot(c.velocity, c.normal) * c.normal;
}

/// a² of two overlapping spheres at centre distance d: the radius of the lens' rim,
/// a² = (r_i+r_j−d)(d+r_i−r_j)(d−r_i+r_j)(d+r_i+r_j) / (4d²), evaluated with the radii in
/// order of size, so that both ends of a contact get the same bits.
template <class R>
GPUDEM_HD R sphere_contact_radius_sq(R d, R ri, R rj) {
  const R small = select(ri < rj, ri, rj), large = select(ri < rj, rj, ri);
  return (small + large - d) * (d + large - small) * (d - large + small) * (d + small + large) /
         (4 * d * d);
}

/// a² of a sphere of radius r cut by a plane at overlap δ: a² = 2rδ − δ².
GPUDEM_HD inline Real wall_contact_radius_sq(Real r, Real overlap) {
  return 2 * r * overlap - overlap * overlap;
}

}  // namespace gpudem
