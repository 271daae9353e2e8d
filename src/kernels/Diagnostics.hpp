#pragma once
/// Per-particle terms of the global diagnostics (energies, contacts, wall forces); the engine
/// sums them with reduce_sum / reduce_max.
#include <cmath>

#include "kernels/ContactVisitor.hpp"

namespace gpudem {

/// ½ m v² of particle i [J].
struct TranslationalEnergy {
  const Real4* velocity_inv_mass;
  GPUDEM_HD Real operator()(std::size_t i) const {
    const Real4 v = velocity_inv_mass[i];
    return Real(0.5) * (v.x * v.x + v.y * v.y + v.z * v.z) / v.w;
  }
};

/// ½ I ω² of sphere i, I = 2/5 m r² [J].
struct RotationalEnergy {
  const Real4* velocity_inv_mass;
  const Real4* position_radius;
  const Vec3* angular_velocity;
  GPUDEM_HD Real operator()(std::size_t i) const {
    const Real inertia = sphere_inertia(position_radius[i].w, velocity_inv_mass[i].w);
    return Real(0.5) * inertia * norm2(angular_velocity[i]);
  }
};

/// −m g·x of particle i [J] (zero at the origin).
struct GravityEnergy {
  const Real4* velocity_inv_mass;
  const Real4* position_radius;
  Vec3 gravity;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return -dot(gravity, xyz(position_radius[i])) / velocity_inv_mass[i].w;
  }
};

/// Contact count and elastic energy; a particle pair is seen from both sides, so it adds ½.
struct ContactTally : IgnoreSeparated {
  Real contacts = 0;
  Real elastic_energy = 0;
  GPUDEM_HD void operator()(const ContactSample& c) {
    const Real share = c.wall < 0 ? Real(0.5) : Real(1);
    contacts += share;
    elastic_energy += share * linear_contact_energy(*c.params, c.kinematics.overlap, c.spring);
  }
};

/// Particle i's share of the contact count, or of the elastic energy when `energy` is set.
struct ContactShare {
  ParticleView particles;
  ContactScene scene;
  bool energy;
  GPUDEM_HD Real operator()(std::size_t i) const {
    ContactTally t;
    for_each_contact(static_cast<std::uint32_t>(i), particles, scene, t);
    return energy ? t.elastic_energy : t.contacts;
  }
};

/// Component `axis` of the force particle i exerts on wall `wall` [N].
struct WallForceComponent {
  ParticleView particles;
  ContactScene scene;
  std::int32_t wall;
  int component;
  struct Pick : IgnoreSeparated {
    std::int32_t wall = -1;
    Vec3 force;
    GPUDEM_HD void operator()(const ContactSample& c) {
      if (c.wall == wall) force -= linear_contact_force(*c.params, c.kinematics, c.spring);
    }
  };
  GPUDEM_HD Real operator()(std::size_t i) const {
    Pick pick;
    pick.wall = wall;
    for_each_contact(static_cast<std::uint32_t>(i), particles, scene, pick);
    return axis(pick.force, component);
  }
};

/// The health score of a particle whose position, velocity or overlap is not finite.
constexpr Real kNonFiniteScore = Real(1e300);

/// A number that flags particle i for the health check: its worst overlap ratio, or
/// kNonFiniteScore when its position or velocity is not finite.
struct HealthScore {
  const Real4* position_radius;
  const Real4* velocity_inv_mass;
  const Real* overlap_ratio;
  GPUDEM_HD Real operator()(std::size_t i) const {
    const Real4 x = position_radius[i];
    const Real4 v = velocity_inv_mass[i];
    using std::isfinite;
    const bool finite = isfinite(x.x) && isfinite(x.y) && isfinite(x.z) && isfinite(v.x) &&
                        isfinite(v.y) && isfinite(v.z) && isfinite(overlap_ratio[i]);
    return finite ? overlap_ratio[i] : kNonFiniteScore;
  }
};

}  // namespace gpudem
