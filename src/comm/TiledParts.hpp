#pragma once
/// Each rank places its part of a tiled box source (core/TiledInsertion.hpp), passing the
/// spheres of its first and last layers of tiles to the ranks beside it after every phase.
#include <mpi.h>

#include <vector>

#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// This rank's part of the particles of tiled box source `i` (checked here): those of its
/// near-equal share of the layers of tiles, in tile order, with ids from `first_id` on in rank
/// order. The parts of ranks 0, 1, ... concatenated are the particles insert_tiled_box places
/// on one rank avoiding the spheres of every rank's `earlier_part` (its part of the earlier
/// sources' spheres); each rank receives those of every rank that may reach its tiles. An
/// input problem any rank finds is thrown on every rank. Collective.
ParticleStore create_tiled_part(MPI_Comm comm, const Scene& scene, std::size_t i,
                                const std::vector<Real4>& earlier_part, ParticleId first_id);

}  // namespace gpudem
