#pragma once
/// Per-particle terms of the global diagnostics (energies, contacts, wall forces); the engine
/// sums them with reduce_sum / reduce_max.
#include <cmath>

#include "engine/ContactVisitor.hpp"

namespace gpudem {

// The terms read a state held in scalar P and are formed in Real.

/// ½ m v² of particle i [J].
template <class P>
struct TranslationalEnergy {
  ParticleView<P> particles;
  GPUDEM_HD Real operator()(std::size_t i) const {
    const Real4 v = particles.velocity(i);
    return Real(0.5) * (v.x * v.x + v.y * v.y + v.z * v.z) / v.w;
  }
};

/// ½ I ω² of sphere i, I = 2/5 m r² [J].
template <class P>
struct RotationalEnergy {
  ParticleView<P> particles;
  GPUDEM_HD Real operator()(std::size_t i) const {
    const Real inertia = sphere_inertia(particles.position(i).w, particles.velocity(i).w);
    return Real(0.5) * inertia * norm2(particles.spin(i));
  }
};

/// −m g·x of particle i [J] (zero at the origin).
template <class P>
struct GravityEnergy {
  ParticleView<P> particles;
  Vec3 gravity;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return -dot(gravity, xyz(particles.position(i))) / particles.velocity(i).w;
  }
};

/// Particle i's contact terms, written per particle so that the sums need no law-specific
/// reduction: its share of the contact count and of the elastic energy, the force it exerts on
/// each body (plane walls w, then meshes wall_count + m), its torque on each mesh about the
/// mesh's centre, its lever from the periodic image of the particle that the mesh meets, and the
/// force it exerts on the triangle of each of its mesh candidate-list entries (zero for an entry
/// not in contact). A pair of owned particles counts whole at its lower index and is skipped at
/// the other end; a pair with a ghost counts half at the owned end (its owner counts the other
/// half). The lower index of an owned pair holds its history as the last sweep advanced it: the
/// host's pair-once sweep evaluates a pair within one group there and every other pair at both
/// ends (PairOnceForces.hpp), so the terms need no mirrored history. The stored history is read,
/// not advanced (dt = 0). A null output is not written: the mesh loads are asked for alone (one
/// kernel for both: each law's is compiled once per backend).
template <class Law, class P>
struct ContactTerms {
  ParticleView<P> particles;
  ContactScene<Law> scene;
  std::uint32_t owned;  ///< particles [0, owned) are owned, the others ghosts
  Real* contacts;       ///< per particle
  Real* energy;         ///< per particle [J]
  Vec3* body_force;     ///< per (particle, body): i·body_count + body [N]
  Vec3* mesh_torque;    ///< per (particle, mesh): i·mesh_count + m [N m]
  Vec3* entry_load;     ///< per mesh candidate-list entry [N]
  struct Tally {
    Real pair_share = 1;  ///< of the pair being visited: 1, or ½ with a ghost
    Real contacts = 0;
    Real energy = 0;
    Vec3 centre;
    Vec3* body_force;
    Vec3* mesh_torque;
    Vec3* entry_load;
    PeriodicBox box;
    MeshView mesh;
    std::uint32_t wall_count;
    GPUDEM_HD void operator()(ContactSample<Law>& c) {
      const bool pair = c.wall < 0 && c.mesh < 0;
      const Real share = pair ? pair_share : Real(1);
      contacts += share;
      energy += share * contact_energy(c);
      if (pair) return;
      const Vec3 load = -vec_cast<Real>(evaluate_contact(c, c.state.value, 0).force);
      if (c.wall >= 0) {
        if (body_force) body_force[c.wall] += load;
        return;
      }
      if (entry_load) entry_load[c.slot] = load;
      if (!body_force) return;
      body_force[wall_count + c.mesh] += load;
      const auto m = static_cast<std::uint32_t>(c.mesh);
      const Vec3 at = mesh.image_for(box, centre, m) + c.arm * c.point.normal;
      mesh_torque[m] += cross(at - mesh.kinematics[m].centre, load);
    }
    GPUDEM_HD void separated(std::uint32_t) {}
    GPUDEM_HD void separated_from_wall(std::uint32_t) {}
    GPUDEM_HD void separated_from_mesh(std::uint32_t e) {
      if (entry_load) entry_load[e] = Vec3{};
    }
  };
  GPUDEM_HD void operator()(std::size_t i) const {
    const std::uint32_t bodies = scene.wall_count + scene.mesh.mesh_count;
    Tally t;
    t.body_force = body_force ? body_force + i * bodies : nullptr;
    t.mesh_torque = body_force ? mesh_torque + i * scene.mesh.mesh_count : nullptr;
    t.entry_load = entry_load;
    if (body_force) {
      for (std::uint32_t b = 0; b < bodies; ++b) t.body_force[b] = Vec3{};
      for (std::uint32_t m = 0; m < scene.mesh.mesh_count; ++m) t.mesh_torque[m] = Vec3{};
    }
    t.centre = xyz(particles.position(i));
    t.box = scene.box;
    t.mesh = scene.mesh;
    t.wall_count = scene.wall_count;
    const auto me = static_cast<std::uint32_t>(i);
    const SweptParticle swept = swept_particle<Law>(me, particles);
    for (std::uint32_t k = scene.neighbor_offsets[i]; k < scene.neighbor_offsets[i + 1]; ++k) {
      const std::uint32_t j = scene.neighbor_index[k];
      if (j < me) continue;  // the lower index counts it
      t.pair_share = j < owned ? Real(1) : Real(0.5);
      visit_pair_entry(swept, k, j, particles, scene, t);
    }
    visit_body_contacts(me, swept, scene, t);
    if (contacts) contacts[i] = t.contacts;
    if (energy) energy[i] = t.energy;
  }
};

/// The health score of a particle whose position, velocity or overlap is not finite.
constexpr Real kNonFiniteScore = Real(1e300);

/// A number that flags particle i for the health check: its worst overlap ratio, or
/// kNonFiniteScore when its position or velocity is not finite.
template <class P>
struct HealthScore {
  ParticleView<P> particles;
  const Real* overlap_ratio;
  GPUDEM_HD Real operator()(std::size_t i) const {
    const Real4 x = particles.position(i);
    const Real4 v = particles.velocity(i);
    using std::isfinite;
    const bool finite = isfinite(x.x) && isfinite(x.y) && isfinite(x.z) && isfinite(v.x) &&
                        isfinite(v.y) && isfinite(v.z) && isfinite(overlap_ratio[i]);
    return finite ? overlap_ratio[i] : kNonFiniteScore;
  }
};

}  // namespace gpudem
