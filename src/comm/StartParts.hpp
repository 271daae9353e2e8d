#pragma once
/// A new run's particles created by parts (docs/architecture.md, "One time step"): each rank makes
/// and keeps only its part of every [[insert]] source, in scene order, and the parts together are
/// the particles create_particles makes on one rank, with the same ids.
#include "comm/MpiRankGroup.hpp"

#include "core/ParticleSources.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// This rank's part of the particles of every source of `scene`:
/// - a bed: the rows `read_bed_part` reads (this rank's part of the file);
/// - a tiled box: its share of the layers of tiles (comm/TiledParts.hpp), avoiding the earlier
///   sources' spheres that reach them, whichever rank holds them;
/// - a box placed sequentially: placed whole on every rank, avoiding the earlier spheres
///   that reach its region (gathered from every rank), of which the rank keeps its share of the
///   rows;
/// - a CSV file: its part of the rows (every rank reads the file through, parsing only those).
/// Ids as create_particles gives them: a bed's own, the others' consecutive in scene order
/// after the bed's largest. An input problem any rank finds is thrown on every rank, as the
/// lowest rank finding one words it. Collective.
ParticleStore create_start_part(const MpiRankGroup& ranks, const Scene& scene,
                                const BedReader& read_bed_part);

}  // namespace gpudem
