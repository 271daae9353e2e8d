#pragma once
/// Checkpoints: everything a run needs to continue bit-for-bit from a step, in one HDF5 file
/// `<dir>/checkpoint.h5`, written collectively through the MPI-IO driver and replaced
/// atomically (written as `checkpoint.h5.tmp`, synced, then renamed), so the previous
/// checkpoint stays intact until the new one is complete.
///
/// Layout (version kCheckpointFormatVersion). Per-particle datasets are global arrays of N
/// rows, each rank writing its rows at an MPI_Exscan offset, so the layout does not depend on
/// the rank count: position_radius (N×4 f64: x, y, z, radius), velocity_inv_mass (N×4 f64:
/// vx, vy, vz, 1/m), angular_velocity, force, torque (N×3 f64), id (N u64), material (N u32),
/// list_position_radius (N×4 f64: positions at the last neighbour-list build). Contact
/// history, also by rank slices, `history_width` values per contact (the contact law's history
/// size): pair_owner, pair_partner (P u64), pair_history (P×width f64), wall_owner (W u64),
/// wall_index (W u32), wall_history (W×width f64), mesh_owner (M u64), mesh_triangle (M u32),
/// mesh_history (M×width f64). The value datasets exist only when the width is > 0 (a law
/// without history has no values to store) and are 1-D when it is 1. The mesh datasets are
/// optional when read: without them (a checkpoint written before they existed) there are no
/// mesh records.
/// Snapshot table, written by rank 0: snapshot_file (S fixed-length strings), snapshot_time
/// (S f64), snapshot_count (S u64), snapshot_rank_field (S u8: 1 when that snapshot holds the
/// dataset "rank", else 0), snapshot_fields (S u32: the set of kSnapshotFields it holds, bit k
/// for field k), snapshot_precision (S u8: bytes per real value of its particle datasets, 8
/// or 4), snapshot_bond_count (S u64: the bonds in its group /bonds/, 0 without; optional when
/// read: 0). snapshot_rank_field, snapshot_fields and snapshot_precision are always written but
/// optional when read: without them (a
/// checkpoint written before they existed) no snapshot has the rank field, and each holds
/// every field in double precision. material_names (K fixed-length strings, written by rank 0:
/// the writing scene's materials by index; optional when read: without it, a file written
/// before it existed, materials are taken by index). wall_motion (W×3 f64, written by rank 0:
/// per plane wall its displacement, velocity and the particles' push, WallMotion.hpp; optional
/// when read: without it every wall continues from rest at its start). Parallel bonds, by
/// rank slices, only in a run with bonds: bond_owner, bond_partner (B u64), bond_values (B×9
/// f64, core/contact/ParallelBond.hpp's bond_value layout), each end's record of each intact
/// bond; without them there are no bonds.
/// Attributes: format_version, history_width (u32), time, dt, dt_fraction, skin (f64), step,
/// removed, list_build_step (u64; the base step of the last neighbour-list build, optional when
/// read: the step when missing), list_build_substep and list_build_substeps (u32; the substeps
/// it was into the next base step, of how many; optional when read: 0 of 1), substeps (u32;
/// the substeps of the last base step, dt = "adaptive"; optional when read: 1), dt_adaptive
/// (u8: 1 when the run's dt was "adaptive"; optional when read: 0), bonds_made (u64; the bonds
/// made at the run's start, or held by the bed it started from; in a bed, its intact bonds;
/// written with the bond datasets), sum_force_unit and sum_torque_unit (f64, powers of two;
/// optional when read, both or neither: 0).
#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

#include "comm/XdmfDocument.hpp"
#include "core/ContactHistory.hpp"
#include "core/ParticleStore.hpp"
#include "core/RowShare.hpp"
#include "core/Scene.hpp"
#include "core/StepClock.hpp"
#include "core/WallMotion.hpp"

namespace gpudem {

constexpr std::uint32_t kCheckpointFormatVersion = 2;

/// The state of a run at the end of one step.
struct Checkpoint {
  ParticleStore particles;                  ///< in the engine's order, with the step's forces
  std::vector<Real4> list_position_radius;  ///< positions at the last neighbour-list build
  ContactHistory history;
  /// Each end's record of each intact bond (pair records only; width 0 without bonds).
  ContactHistory bonds;
  std::uint64_t bonds_made = 0;         ///< bonds the run started with (made or from a bed)
  std::vector<XdmfSnapshot> snapshots;  ///< snapshots written so far (SnapshotWriter::table)
  /// The names of the writing scene's materials, by index (none in files written before the
  /// names were recorded): a scene that lists its materials otherwise reads them by name.
  std::vector<std::string> material_names;
  std::vector<WallMotion> wall_motion;  ///< per plane wall (none in files written before)
  double time = 0;                      ///< [s]
  std::uint64_t step = 0;
  StepClock list_build;        ///< where the last neighbour-list build was
  std::uint32_t substeps = 1;  ///< substeps of the last base step
  std::uint64_t removed = 0;   ///< particles removed so far for leaving the domain
  double dt = 0;               ///< [s] time step of the run
  double dt_fraction = 0;      ///< fraction of the critical step when dt was "auto", else 0
  bool dt_adaptive = false;    ///< dt was "adaptive": dt is the base step
  double skin = 0;             ///< [m] Verlet skin of the run
  /// The units of the host's integer force and torque sums (engine/ExactUnits.hpp) [N, N m];
  /// 0 in files written before they were recorded.
  double sum_force_unit = 0;
  double sum_torque_unit = 0;
};

/// `<dir>/checkpoint.h5`.
std::string checkpoint_path(const std::string& dir);

/// Writes this rank's part of `checkpoint` (particles and history; the snapshot table and
/// attributes from rank 0's values) to `<dir>/checkpoint.h5.tmp`, replacing any stale file
/// there, then rank 0 syncs it and renames it to `<dir>/checkpoint.h5`. Collective; throws
/// std::runtime_error naming the file when a step fails, leaving the previous checkpoint as
/// it was, and std::logic_error on every rank when the ranks' histories differ in width.
void write_checkpoint(MPI_Comm comm, const std::string& dir, const Checkpoint& checkpoint);

/// Reads part `part` of a checkpoint: the particle rows part.rows_of(N) and, of each kind of
/// contact-history record, the records part.rows_of(count); the snapshot table and the
/// attributes whole. The default part is the whole file; a run on P ranks reads part
/// {rank, P} on each, so that no rank holds more than its share. Throws InputError naming
/// `path` and what is wrong: a missing file, a file that is not
/// HDF5, another format version, a missing or mistyped dataset or attribute, a history
/// dataset without history_width columns, datasets of one group with different lengths, a
/// radius, inverse mass or time step that is not finite and > 0, a snapshot_rank_field
/// value other than 0 and 1, a snapshot_fields value with a bit beyond the fields or a
/// snapshot_precision other than 4 and 8. Particle values are checked in the part read.
Checkpoint read_checkpoint(const std::string& path, FilePart part = {});

/// Renumbers the particles' materials of `checkpoint` (read from `path`) to the materials of
/// the same names in `scene` when the file records names (material_names); throws InputError
/// naming `path` and the scene's file when the scene lacks one of the particles' materials, or
/// a particle's index has no recorded name.
void map_materials_by_name(Checkpoint& checkpoint, const std::string& path, const Scene& scene);

/// Throws InputError naming `path` when `checkpoint` holds bonds that the [[bond]] tables of
/// `scene` cannot continue: bonds (bonds_made > 0, or bond records) without tables, or a bond
/// of a table the scene lacks.
void require_bond_tables(const Checkpoint& checkpoint, const std::string& path, const Scene& scene);

/// map_materials_by_name, then throws InputError naming `path` when `checkpoint` refers to a
/// material or a wall that `scene` does not define, holds the motion of another number of
/// walls than the scene defines, or holds another number of history values
/// per contact than the scene's contact law keeps (contact_history_width): it was written with
/// another law.
void fit_checkpoint_to_scene(Checkpoint& checkpoint, const std::string& path, const Scene& scene);

}  // namespace gpudem
