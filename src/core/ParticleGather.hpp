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
  for_each_particle_field([&](auto field) { field.of(all) = ranks.gather(field.of(share)); });
  return all;
}

}  // namespace gpudem
