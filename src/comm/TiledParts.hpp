#pragma once
/// Each rank places its part of a tiled box source (core/TiledInsertion.hpp), passing the
/// spheres of its first and last layers of tiles to the ranks beside it after every phase.
#include <mpi.h>

#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// This rank's part of the particles of a scene whose one source is a tiled box
/// (tiled_box_is_the_only_source): those of its near-equal share of the layers of tiles, in
/// tile order, with global ids (the parts of ranks 0, 1, ... concatenated are the particles
/// the whole region gets on one rank). An input problem any rank finds is thrown on every
/// rank. Collective.
ParticleStore create_tiled_part(MPI_Comm comm, const Scene& scene);

}  // namespace gpudem
