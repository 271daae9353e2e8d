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

/// Particle i's contact terms, written per particle so that the sums need no law-specific
/// reduction: its share of the contact count and of the elastic energy (a particle pair is
/// seen from both sides, so each side adds ½), and the force it exerts on each wall. The
/// stored history is read, not advanced (dt = 0).
template <class Law>
struct ContactTerms {
  ParticleView particles;
  ContactScene<Law> scene;
  Real* contacts;      ///< per particle
  Real* energy;        ///< per particle [J]
  Vec3* wall_force;    ///< per (particle, wall): i·wall_count + w [N]
  struct Tally : IgnoreSeparated {
    Real contacts = 0;
    Real energy = 0;
    Vec3* wall_force;
    GPUDEM_HD void operator()(ContactSample<Law>& c) {
      const Real share = c.wall < 0 ? Real(0.5) : Real(1);
      contacts += share;
      energy += share * Law::energy(*c.params, c.point, c.state.value);
      if (c.wall >= 0) wall_force[c.wall] = -Law::evaluate(*c.params, c.point, c.state.value, 0).force;
    }
  };
  GPUDEM_HD void operator()(std::size_t i) const {
    Vec3* walls = wall_force + i * scene.wall_count;
    for (std::uint32_t w = 0; w < scene.wall_count; ++w) walls[w] = Vec3{};
    Tally t;
    t.wall_force = walls;
    for_each_contact(static_cast<std::uint32_t>(i), particles, scene, t);
    contacts[i] = t.contacts;
    energy[i] = t.energy;
  }
};

/// Component `component` of the force particle i exerts on wall `wall`, from ContactTerms.
struct WallForceComponent {
  const Vec3* wall_force;
  std::uint32_t wall_count;
  std::uint32_t wall;
  int component;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return axis(wall_force[i * wall_count + wall], component);
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
