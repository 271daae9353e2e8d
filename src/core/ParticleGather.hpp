#pragma once
/// Every rank's particles on every rank, for the small selections that all ranks must agree on
/// (the particles that decide the time step, tests).
#include "core/ParticleStore.hpp"
#include "core/RankGroup.hpp"

namespace gpudem {

/// Every rank's `share` (all its arrays the same length, or force and torque empty on every
/// rank), concatenated in rank order, on every rank. Collective.
inline ParticleStore gather_particles(const RankGroup& ranks, const ParticleStore& share) {
  ParticleStore all;
  all.position_radius = ranks.gather(share.position_radius);
  all.velocity_inv_mass = ranks.gather(share.velocity_inv_mass);
  all.angular_velocity = ranks.gather(share.angular_velocity);
  all.force = ranks.gather(share.force);
  all.torque = ranks.gather(share.torque);
  all.id = ranks.gather(share.id);
  all.material = ranks.gather(share.material);
  return all;
}

}  // namespace gpudem
