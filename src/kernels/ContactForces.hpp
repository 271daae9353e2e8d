#pragma once
/// Per-particle force, torque and worst overlap: one thread per particle sums all its
/// contacts from the full neighbour list (no atomics), walls and gravity, and advances the
/// tangential springs it owns (its own neighbour-list entries and wall slots).
#include "kernels/ContactVisitor.hpp"

namespace gpudem {

struct ForceSum {
  Vec3* pair_spring;
  Vec3* wall_spring;
  Real dt;
  Vec3 force;
  Vec3 torque;
  Real worst_overlap_ratio = 0;
  GPUDEM_HD void operator()(const ContactSample& c) {
    const Vec3 spring = advance_tangential_spring(*c.params, c.kinematics, c.spring, dt);
    (c.wall < 0 ? pair_spring : wall_spring)[c.slot] = spring;
    const Vec3 f = linear_contact_force(*c.params, c.kinematics, spring);
    force += f;
    torque += cross(c.arm * c.kinematics.normal, f) +
              rolling_torque(*c.params, c.kinematics, normal_force(*c.params, c.kinematics), dt);
    const Real ratio = c.kinematics.overlap / c.min_radius;
    if (ratio > worst_overlap_ratio) worst_overlap_ratio = ratio;
  }
  /// A contact that opened forgets its spring.
  GPUDEM_HD void separated(std::uint32_t slot) { pair_spring[slot] = Vec3{}; }
  GPUDEM_HD void separated_from_wall(std::uint32_t slot) { wall_spring[slot] = Vec3{}; }
};

/// F_i = m_i g + Σ contacts, T_i = Σ arm × F (one thread per particle).
struct ComputeForces {
  ParticleView particles;
  ContactScene scene;
  Vec3 gravity;
  Real dt;
  Vec3* pair_spring;  ///< the same arrays as scene.pair_spring / wall_spring, writable
  Vec3* wall_spring;
  Vec3* force;
  Vec3* torque;
  Real* overlap_ratio;
  GPUDEM_HD void operator()(std::size_t i) const {
    ForceSum sum{pair_spring, wall_spring, dt, Vec3{}, Vec3{}, Real(0)};
    for_each_contact(static_cast<std::uint32_t>(i), particles, scene, sum);
    force[i] = sum.force + (Real(1) / particles.velocity_inv_mass[i].w) * gravity;
    torque[i] = sum.torque;
    overlap_ratio[i] = sum.worst_overlap_ratio;
  }
};

}  // namespace gpudem
