#pragma once
/// Per-particle force, torque and worst overlap: one thread per particle sums all its
/// contacts from the full neighbour list (no atomics), walls and gravity.
#include "kernels/ContactVisitor.hpp"

namespace gpudem {

struct ForceSum {
  Vec3 force;
  Vec3 torque;
  Real worst_overlap_ratio = 0;
  GPUDEM_HD void operator()(const ContactSample& c) {
    const Vec3 f = linear_contact_force(*c.params, c.kinematics);
    force += f;
    torque += cross(c.arm * c.kinematics.normal, f);
    const Real ratio = c.kinematics.overlap / c.min_radius;
    if (ratio > worst_overlap_ratio) worst_overlap_ratio = ratio;
  }
};

/// F_i = m_i g + Σ contacts, T_i = Σ arm × F (one thread per particle).
struct ComputeForces {
  ParticleView particles;
  ContactScene scene;
  Vec3 gravity;
  Vec3* force;
  Vec3* torque;
  Real* overlap_ratio;
  GPUDEM_HD void operator()(std::size_t i) const {
    ForceSum sum;
    for_each_contact(static_cast<std::uint32_t>(i), particles, scene, sum);
    force[i] = sum.force + (Real(1) / particles.velocity_inv_mass[i].w) * gravity;
    torque[i] = sum.torque;
    overlap_ratio[i] = sum.worst_overlap_ratio;
  }
};

}  // namespace gpudem
