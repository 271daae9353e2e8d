#pragma once
/// The domain decomposition of a run on several ranks (docs/architecture.md, "Ranks"), made once at
/// start-up from the scene's [decomposition] table and the particles the run starts with.
#include <cstdint>
#include <memory>

#include "comm/MpiContext.hpp"
#include "comm/MpiDomain.hpp"
#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

/// This rank's part of the domain on mpi.size() ranks, or null on one rank, from every rank's
/// `share` of the particles, `count` over all ranks (collective). Coarse cells of edge at least the
/// ghost width 2 r_max + skin (r_max over all particles) are weighted by the particles they hold;
/// "grid" cuts the particle bed into blocks of equal particle counts along each axis ("auto" dims
/// judge the bed as it will settle under gravity), "metis" partitions the cell graph. Throws
/// InputError for dims that do not multiply to the rank count or more ranks than coarse cells.
/// gpu_aware: MPI accepts device buffers (GpuAwareMpi.hpp).
std::unique_ptr<MpiDomain> make_domain(const Scene& scene, const MpiContext& mpi,
                                       const ParticleStore& share, std::uint64_t count,
                                       const EngineSetup& setup, bool gpu_aware);

/// One line describing the decomposition (rank 0 prints it).
void print_decomposition(const MpiDomain& domain);

}  // namespace gpudem
