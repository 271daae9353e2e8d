#pragma once
/// Particle snapshots: one HDF5 file per snapshot written collectively through the MPI-IO
/// driver (each rank writes its slice at an MPI_Exscan offset), plus one XDMF temporal
/// collection (`<basename>.xmf`) rewritten after every snapshot so ParaView can open the run
/// at any time. Mesh walls go into the same files, each with its own XDMF collection
/// (`<mesh name>.xmf`). A restarted run resumes the series where its checkpoint left it.
#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

#include "comm/XdmfDocument.hpp"
#include "core/OutputNames.hpp"
#include "core/ParticleStore.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

/// What the snapshots of one writer hold beside "position", in what precision, and their names.
struct SnapshotOptions {
  SnapshotLayout layout;  ///< the datasets beside "position" and their precision
  std::string basename = kParticlesBasename;  ///< files `<basename>_<index>.h5`, `<basename>.xmf`
  /// The mesh walls every snapshot holds, in the order write() gets them: names unique,
  /// non-empty, without '/', neither "." nor ".." and not `basename`.
  std::vector<XdmfMesh> meshes = {};
  /// Every snapshot holds the bonds (group `/bonds/`, `bonds.xmf`); no mesh may then be
  /// named "bonds".
  bool bonds = false;
};

class SnapshotWriter {
 public:
  /// `dir` must exist. Files are `<dir>/<basename>_<index, 6 digits>.h5`,
  /// `<dir>/<basename>.xmf` and `<dir>/<mesh name>.xmf` per mesh. Throws
  /// std::invalid_argument for a mesh name SnapshotOptions does not allow.
  SnapshotWriter(MPI_Comm comm, std::string dir, SnapshotOptions options = {});

  /// Writes this rank's particles [0, particles.size()) as the next snapshot: datasets
  /// position (N×3), and those of radius (N), velocity (N×3), angular_velocity (N×3),
  /// force (N×3), material (N, uint32) and id (N, uint64) in the options' field set (real
  /// values in float64, or float32 in single precision), connectivity, and with the rank field
  /// rank (N, uint32: each rank's rows hold its rank in `comm`); attributes time and step. For each
  /// mesh m of the options, group `/mesh/<name>/` holds meshes[m] as rank 0 has it: vertices (V×3),
  /// triangles (T×3, uint32), force (T×3) and pressure (T): (F · n̂) / A with n̂ the unit
  /// normal of the triangle's corner order and A its area [Pa]. Throws
  /// std::invalid_argument when `meshes` does not match the options' counts. Collective.
  void write(const ParticleStore& particles, const std::vector<MeshSurface>& meshes, double time,
             std::uint64_t step);
  /// write() with this rank's `bonds`, which a writer with SnapshotOptions::bonds puts in group
  /// `/bonds/`, each rank its rows at an MPI_Exscan offset: ids (B×2, uint64), points (2B×3:
  /// the two ends of each bond), connectivity (B×2, uint64: rows of points), normal_force (B)
  /// and strength_used (B) (BondLines). Collective.
  void write(const ParticleStore& particles, const std::vector<MeshSurface>& meshes,
             const BondLines& bonds, double time, std::uint64_t step);
  /// write() of a writer without meshes.
  void write(const ParticleStore& particles, double time, std::uint64_t step);

  const std::string& xmf_path() const { return xmf_path_; }
  bool writes_bonds() const { return options_.bonds; }
  /// Paths of the snapshot files written so far.
  const std::vector<std::string>& files() const { return files_; }
  /// The snapshots written so far as the .xmf lists them (file names relative to the folder).
  std::vector<XdmfSnapshot> table() const;

  /// Continues the series of an earlier writer whose table() was `table`: numbering goes on
  /// after its last snapshot and the .xmf is rewritten to list exactly these snapshots (any
  /// written after them are dropped from it, and overwritten as numbering reaches them). Each
  /// keeps the datasets and precision it was written with; new snapshots follow this writer's
  /// options.
  /// Collective.
  void resume(const std::vector<XdmfSnapshot>& table);

 private:
  /// Rank 0 rewrites the .xmf of the particles and of each mesh (temporary file, then rename)
  /// listing every snapshot so far; every rank throws if that failed. Collective.
  void publish_xmf() const;
  std::string mesh_xmf_path(const XdmfMesh& mesh) const;

  MPI_Comm comm_;
  std::string dir_;
  SnapshotOptions options_;
  std::string xmf_path_;
  std::vector<std::string> files_;
  std::vector<XdmfSnapshot> written_;  ///< the snapshots so far, as table() returns them
};

}  // namespace gpudem
