#pragma once
/// Each rank places its part of a tiled box source (core/TiledInsertion.hpp), passing the
/// spheres of its first and last layers of tiles to the ranks beside it after every phase.
#include "comm/MpiRankGroup.hpp"

#include <cstddef>

#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// Appends to `part` this rank's part of the particles of tiled box source `i` (checked here):
/// those of its near-equal share of the layers of tiles, in tile order, with ids from
/// `first_id` on in rank order; returns how many. `part` holds this rank's part of the earlier
/// sources' particles, whose spheres the source avoids, with those of the other ranks' parts
/// that reach its tiles. The parts of ranks 0, 1, ... concatenated are the particles
/// insert_tiled_box places on one rank avoiding all the earlier spheres. An input problem any
/// rank finds is thrown on every rank. Collective.
std::size_t append_tiled_part(const MpiRankGroup& group, const Scene& scene, std::size_t i,
                              ParticleStore& part, ParticleId first_id);

}  // namespace gpudem
