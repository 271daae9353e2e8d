#pragma once
/// Particles that a mesh wall overlaps where a new run starts (docs/input.md, "[[mesh]]"): a
/// tool placed in the bed instead of beside it would start with forces far beyond any contact
/// of the run. Checked before the run and with --check, not on a restart (whose meshes are
/// where the saved run left them, in contact with the soil they cut).
#include <cstdint>
#include <string>
#include <vector>

#include "core/ParticleStore.hpp"
#include "core/RankGroup.hpp"
#include "core/Scene.hpp"
#include "core/TriangleMesh.hpp"
#include "engine/MeshWallSetup.hpp"

namespace gpudem {

/// The overlaps δ = r − d > 0 of particles (radius r, centre at distance d from the mesh)
/// with one mesh.
struct MeshStartOverlap {
  std::uint64_t particles = 0;  ///< particles the mesh overlaps
  double deepest_ratio = 0;     ///< largest δ / r
  double deepest = 0;           ///< δ of that particle [m]
  Vec3 deepest_at;              ///< that particle's centre [m]
};

/// The overlaps of `particles` with `mesh` (placed, at t = 0). Only particles whose sphere's
/// box meets the mesh's box are measured, each against the triangles whose boxes its box meets.
MeshStartOverlap mesh_start_overlap(const TriangleMesh& mesh, const ParticleStore& particles);

/// Largest δ / r a mesh may start with: a resting contact's overlap is a small fraction of
/// that (about 1 % or less), a tool placed inside the bed far more.
inline constexpr double kLargestStartOverlap = 0.1;

/// Measures each mesh's overlaps with the particles of all ranks (this rank's `share`) and
/// throws InputError naming `mesh[i].offset` on every rank when the deepest exceeds
/// kLargestStartOverlap of its particle's radius; returns a warning for each mesh that touches
/// particles less deeply. Collective.
std::vector<std::string> check_mesh_start_overlaps(const Scene& scene,
                                                   const std::vector<MeshWallSetup>& meshes,
                                                   const ParticleStore& share,
                                                   const RankGroup& ranks);

}  // namespace gpudem
