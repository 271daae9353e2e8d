#pragma once
/// The time-step engine: owns the particle state in one memory space and advances it.
/// Host code talks to it through these interfaces only; the implementation is ParticleSystem
/// with a force compute per law (docs/architecture.md, "Particle system and force computes"),
/// made by make_host_engine (StepEngineHost.cpp) and make_cuda_engine (StepEngineCuda.cu). This
/// header includes no CUDA headers.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/BondPairs.hpp"
#include "core/ContactHistory.hpp"
#include "core/ContactModel.hpp"
#include "core/ContactParams.hpp"
#include "core/ParticleStore.hpp"
#include "core/ParticleTally.hpp"
#include "core/Scene.hpp"
#include "core/StepClock.hpp"
#include "engine/DomainLink.hpp"
#include "engine/ExactUnits.hpp"
#include "engine/Integrators.hpp"
#include "engine/MeshWallSetup.hpp"
#include "engine/PeriodicBox.hpp"
#include "engine/PlaneWall.hpp"
#include "engine/WallPistons.hpp"

namespace gpudem {

/// Everything the engine needs, in plain data resolved from the scene on the host.
struct EngineSetup {
  PeriodicBox box;
  Vec3 gravity;
  Real dt = 0;
  IntegratorKind integrator = IntegratorKind::VelocityVerlet;
  Precision precision = Precision::Double;  ///< selects the law's scalar (EngineFactory.hpp)
  Real skin = 0;                            ///< Verlet skin [m]
  ContactModel contact_model;               ///< must be one of valid_contact_models()
  std::uint32_t material_count = 0;
  std::vector<ContactPairParams> pair_params;  ///< material_count² entries, row-major
  std::vector<PlaneWall> walls;
  std::vector<PistonSetup> pistons;       ///< the walls that slide (WallPistons.hpp)
  std::vector<MeshWallSetup> meshes;      ///< triangle-mesh walls (tools)
  std::vector<BondSettings> bonds;        ///< the [[bond]] tables: none, no bonds
  std::vector<std::vector<Real4>> clods;  ///< per [[bond]] table, its clod spheres (BondClods)
  /// Per [[bond]] table, the pairs its CSV file lists (none: it bonds by materials and gap).
  std::vector<std::vector<ListedBond>> bond_pairs;
  /// Per material, whether its particles move at a prescribed velocity, that velocity, and
  /// their drag (Material::fixed, ::velocity, ::drag); empty: every material moves freely.
  std::vector<MaterialMotion> material_motion;
  std::uint64_t start_step = 0;  ///< base step the run starts at (a restart's): the clock
  /// This rank's part of the decomposed domain; null: a run on one rank. Must outlive the
  /// engine.
  DomainLink* domain = nullptr;
  /// Wait for the device at the end of each timed part of a step (StepTimes), so that each
  /// part holds its own kernels' time; a device synchronisation per part on CUDA.
  bool exact_phase_times = false;
  /// The units of the host force sweep's integer sums (exact_units_for_grains); the same on
  /// every rank and after a restart.
  ExactUnits exact_units{};
  /// The most contacts the host's force sweep evaluates at once: eight in AVX-512 lanes or four
  /// in AVX2 lanes where the build and the CPU have them, else one (PairLanesForces.hpp); the
  /// same bits either way.
  int host_lanes = 8;
};

/// Global quantities reduced over all particles; walls' forces are the forces the
/// particles exert on each wall [N].
struct Diagnostics {
  std::uint64_t particle_count = 0;
  std::uint64_t contact_count = 0;      ///< particle–particle plus particle–wall contacts
  double kinetic_translational = 0;     ///< Σ ½ m v² [J]
  double kinetic_rotational = 0;        ///< Σ ½ I ω² [J]
  double potential_gravity = 0;         ///< Σ −m g·x [J]
  double potential_elastic = 0;         ///< Σ contact spring energy [J]
  double max_overlap_ratio = 0;         ///< max over contacts of δ / min(r_i, r_j)
  std::uint64_t bond_count = 0;         ///< intact parallel bonds
  std::uint64_t broken_bond_count = 0;  ///< bonds made at the run's start that broke since
  std::vector<Vec3> wall_force;
  std::vector<Vec3> mesh_force;           ///< force the particles exert on each mesh [N]
  std::vector<Vec3> mesh_torque;          ///< their torque on each mesh about its centre [N m]
  std::vector<WallMotion> piston_motion;  ///< per piston (EngineSetup::pistons)
};

/// One mesh wall at the current time: its surface and the force the particles exert on each
/// of its triangles [N], summed over all ranks.
struct MeshSurface {
  std::vector<Vec3> vertices;                           ///< at the current pose [m]
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< vertex ids of this mesh
  std::vector<Vec3> triangle_force;                     ///< per triangle [N]
};

/// Pressure on each triangle (a, b, c) of `mesh`: p = −(F · n̂) / A [Pa], with F its
/// triangle_force, n̂ the unit normal by the right-hand rule of the corner order (outward on a
/// closed STL) and A the area, so particles pressing on the side n̂ faces give p > 0;
/// n = (b − a) × (c − a) = 2A n̂ gives p = −2 F · n / |n|².
inline std::vector<double> triangle_pressures(const MeshSurface& mesh) {
  std::vector<double> pressure;
  pressure.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3& a = mesh.vertices[mesh.triangles[t][0]];
    const Vec3 n =
        cross(mesh.vertices[mesh.triangles[t][1]] - a, mesh.vertices[mesh.triangles[t][2]] - a);
    pressure.push_back(-2 * dot(mesh.triangle_force[t], n) / norm2(n));
  }
  return pressure;
}

/// The intact bonds whose lower-id end this rank owns, each once: its ends' global ids and
/// centres, its normal force and how much of its strength it uses (snapshots with bonds).
struct BondLines {
  std::vector<ParticleId> ids;        ///< 2 per bond: the lower id, then the higher
  std::vector<Vec3> points;           ///< 2 per bond: the ends' centres, in the order of ids [m]
  std::vector<double> normal_force;   ///< per bond, tension > 0 [N]
  std::vector<double> strength_used;  ///< per bond, max(σ/σ_c, τ/τ_c); 0 without strengths
  std::size_t size() const { return normal_force.size(); }
};

/// Wall time this rank's engine spent in each part of its steps since it was made [s] (host
/// clock: on the CUDA backend a part ends when its last launch has returned, unless
/// EngineSetup::exact_phase_times makes it wait for its kernels), and the ghost bytes its
/// per-step refreshes sent. Waits for other ranks count in the part that waits.
struct StepTimes {
  double integrate = 0;  ///< kicks and drift (velocities, spins, positions), mesh poses
  double forces = 0;     ///< particle, wall and mesh contact forces
  /// The rebuild test and its reduction over ranks, cell sorting, neighbour lists, mesh
  /// candidates, history carry-over
  double neighbors = 0;
  double ghosts = 0;             ///< ghost plans on rebuilds and ghost refreshes on other steps
  double migration = 0;          ///< periodic wrapping, removal, migration between ranks
  std::uint64_t refreshes = 0;   ///< steps that refreshed the ghosts
  std::uint64_t halo_bytes = 0;  ///< bytes those refreshes sent
};

/// Bytes one array, or group of arrays, of an engine holds in its memory space.
struct MemoryUse {
  const char* name;  ///< what the bytes hold
  std::size_t bytes;
};

/// A particle the health check rejected: non-finite state or an overlap beyond the limit.
struct HealthFailure {
  ParticleId id = 0;
  Vec3 position;
  double overlap_ratio = 0;
  bool non_finite = false;
};

/// The owned particles of one step, copied aside so that a snapshot of that step can be written
/// while the engine steps on (SnapshotSource::stage_particles).
class StagedParticles {
 public:
  virtual ~StagedParticles() = default;
  /// Waits until the copies are complete and gives the particles as get_particles gave them at
  /// the staging step. Callable from any thread; once per staging.
  virtual void collect(ParticleStore& particles) = 0;

  /// The particle count and id checksum over all ranks at the staging step, against which the
  /// collected particles of all ranks are checked (ParticleTally.hpp).
  ParticleTally expected_tally;
};

/// What a snapshot is taken from (SnapshotQueue.hpp): a step engine, or a stand-in in tests.
class SnapshotSource {
 public:
  virtual ~SnapshotSource() = default;
  /// Queues copies of the owned particles as get_particles gives them, ordered after the work
  /// already queued, into a buffer of the source's that later steps leave alone, and returns it.
  /// The buffer is reused: stage again only after the last staging's collect() has returned.
  virtual StagedParticles& stage_particles() = 0;
  /// Each mesh with the load on each of its triangles (StepEngine::mesh_surfaces). Collective.
  virtual std::vector<MeshSurface> mesh_surfaces() const = 0;
  /// This rank's bonds as BondLines (none without bonds).
  virtual BondLines bond_lines() const = 0;
};

/// The particles in and out of an engine: its state set, restored and read back, its contact
/// history, and the copies a snapshot is written from.
class EngineIo : public SnapshotSource {
 public:
  /// Replaces the engine's particles and evaluates the initial forces. Each rank passes a share
  /// of the particles (any subset, all of them on one rank; the ranks' shares hold every particle
  /// once); every particle goes to the rank that owns its position. Collective,
  /// like every call below that changes or reduces the state: all ranks make it at the same
  /// point.
  virtual void set_particles(const ParticleStore& share) = 0;
  /// Copies this rank's owned particles back to the host, in the engine's order, with the
  /// forces and torques of the last evaluation.
  virtual void get_particles(ParticleStore& particles) const = 0;

  /// The history records (Law::history_size values each) of every contact of an owned particle
  /// whose record is not all zero, keyed by global ids.
  virtual void get_contact_history(ContactHistory& history) const = 0;
  /// Gives every contact listed in `history` its record and every other contact a zero
  /// record; call after set_particles or restore_particles. Each rank passes a share of the
  /// records, as for set_particles; every record goes to the rank that owns its owner
  /// particle. Throws std::invalid_argument (on every rank, with the first rank's message) for
  /// a history of another width, an entry naming an unknown particle, a pair that is not in
  /// the neighbour list, or a wall index beyond the walls. Forces are not re-evaluated. Takes
  /// `share` by value: a caller that moves it in lets the records be freed as they are sent.
  virtual void set_contact_history(ContactHistory share) = 0;

  /// Makes the bonds of the [[bond]] tables between the particles present (each pair in the
  /// neighbour list that a table bonds: by materials and gap, within its clods, or listed) and
  /// re-evaluates the forces, the bonds' loads as made; call once when a new run starts, after
  /// the particles and their contact history are set. Throws std::invalid_argument (on every
  /// rank) for a listed pair it could not bond or bonded across more than half the skin.
  virtual void create_bonds() = 0;
  /// The records of the intact bonds of the owned particles (bond_value::width values each,
  /// each end's record, keyed by global ids as pair records) and the number of bonds made at
  /// the run's start.
  virtual void get_bonds(ContactHistory& bonds, std::uint64_t& made) const = 0;
  /// Gives the bonds listed in `bonds` their records (as set_contact_history gives pair
  /// records, with its refusals) and continues the broken count from `made`.
  virtual void set_bonds(ContactHistory bonds, std::uint64_t made) = 0;
  /// A new run's bonds from a bed that holds them (in place of create_bonds): gives them their
  /// records as set_bonds does, `made` the bed's count, and re-evaluates the forces with their
  /// loads as they stand; call once, after the particles and their contact history are set.
  virtual void continue_bonds(ContactHistory bonds, std::uint64_t made) = 0;

  /// Every plane wall's motion (zero for the walls that stand still).
  virtual std::vector<WallMotion> wall_motion() const = 0;
  /// Continues the pistons from a saved motion of every wall: call before restore_particles.
  virtual void set_wall_motion(const std::vector<WallMotion>& motion) = 0;

  /// Positions and radii at the last neighbour-list build, in the order of get_particles.
  virtual void get_list_positions(std::vector<Real4>& position_radius) const = 0;
  /// Where the run was at the last neighbour-list build (the meshes' pose it was built with).
  virtual StepClock list_build_clock() const = 0;
  /// Replaces the particles to continue a saved run bit-for-bit, on any number of ranks:
  /// `share` and `list_positions` a share (as for set_particles) of what get_particles and
  /// get_list_positions gave on all ranks of the saved run; each particle goes to the rank
  /// that owns its list position. Unlike
  /// set_particles it keeps the forces and torques of `share` (evaluated from half-step
  /// velocities that the saved state no longer holds) and builds the neighbour list at the
  /// positions of the saved engine's last build, so that the list and the next rebuild follow
  /// the saved run (the sums do not depend on the particle order), with the
  /// meshes at their pose of `list_build`. Springs are zero until set_contact_history;
  /// removed_count() continues from `removed`.
  virtual void restore_particles(const ParticleStore& share,
                                 const std::vector<Real4>& list_positions, std::uint64_t removed,
                                 StepClock list_build) = 0;
  /// Particles on all ranks.
  virtual std::size_t particle_count() const = 0;
  /// Particles this rank owns.
  virtual std::size_t owned_count() const = 0;
  /// Neighbour-list entries of each owned particle, in the order of get_particles.
  virtual void get_list_lengths(std::vector<std::uint32_t>& lengths) const = 0;

  /// SnapshotSource::stage_particles. The copies are host memory (pinned on the CUDA backend),
  /// not counted in memory_use().
  StagedParticles& stage_particles() override = 0;

  /// Each mesh (in the order of EngineSetup::meshes) with the load on each of its triangles;
  /// the triangle forces of a mesh add up to its Diagnostics::mesh_force. Collective.
  std::vector<MeshSurface> mesh_surfaces() const override = 0;
};

/// What an engine reports of its state and its work: health, global diagnostics, counts,
/// times and memory.
class EngineDiagnostics {
 public:
  virtual ~EngineDiagnostics() = default;
  /// Checks every particle for non-finite state and for an overlap above `max_overlap_ratio`
  /// of the smaller radius; returns the first offender's details (false when healthy).
  virtual bool find_unhealthy(double max_overlap_ratio, HealthFailure& failure) const = 0;

  virtual Diagnostics diagnostics() const = 0;
  /// Particles removed so far for leaving the non-periodic domain.
  virtual std::uint64_t removed_count() const = 0;
  virtual std::uint64_t rebuild_count() const = 0;
  virtual StepTimes step_times() const = 0;
  /// Bytes held in the engine's memory space on this rank, by array (or group of arrays).
  virtual std::vector<MemoryUse> memory_use() const = 0;
  /// Σ memory_use() [bytes].
  std::size_t memory_bytes() const {
    std::size_t total = 0;
    for (const MemoryUse& use : memory_use()) total += use.bytes;
    return total;
  }
  virtual std::string backend_name() const = 0;
  /// Contacts one thread evaluates at once (ForceCompute::contact_lanes).
  virtual int contact_lanes() const = 0;
};

/// The one-off choice of an engine's launch parameters.
class EngineTuning {
 public:
  virtual ~EngineTuning() = default;
  /// Chooses the block size of the tunable launches once per run, the same on every rank, and
  /// returns the --verbose line that reports it (LaunchTuning.hpp). Collective.
  virtual std::string tune_launches() = 0;
};

/// A time-step engine: advances its particles (below), and is read and written (EngineIo),
/// reported on (EngineDiagnostics) and tuned (EngineTuning). Callers take the narrowest of them
/// that serves.
class StepEngine : public EngineIo, public EngineDiagnostics, public EngineTuning {
 public:
  /// Advances one step: dt / substeps of the base step in progress.
  virtual void step() = 0;
  /// Splits the next base steps into `substeps` steps each (dt = "adaptive"; 1 otherwise). Only
  /// between base steps; throws std::logic_error otherwise or for 0.
  virtual void set_substeps(std::uint32_t substeps) = 0;
  /// The largest speed of a particle on any rank and of a piston [m/s]. Collective.
  virtual double fastest_speed() const = 0;

  /// Rebuilds the neighbour list now (re-sorting particles by cell and carrying contact
  /// history over) and re-evaluates the forces, without advancing time.
  virtual void rebuild_neighbors() = 0;
};

std::unique_ptr<StepEngine> make_host_engine(const EngineSetup& setup);
/// Throws std::runtime_error when the CUDA backend is not compiled in or no device exists.
std::unique_ptr<StepEngine> make_cuda_engine(const EngineSetup& setup);

}  // namespace gpudem
