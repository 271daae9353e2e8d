#pragma once
/// The validated scene: plain data filled by SceneLoader from a TOML file (docs/input.md).
/// Units are SI throughout. Every field here is documented in docs/input.md.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/ContactModel.hpp"
#include "core/MixingRule.hpp"
#include "core/OutputNames.hpp"
#include "core/PrescribedMotion.hpp"
#include "core/StlReader.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

enum class IntegratorKind { VelocityVerlet, SymplecticEuler };

/// Precision policy (docs/architecture.md, "Precision"): Double everywhere; Mixed — positions,
/// velocities and the distance that forms each overlap in Real, the contact laws, their history and
/// the force and torque sums in float; Float — as Mixed with the particle state (positions,
/// velocities, spins) held in float too, converted to Real where it is read.
enum class Precision { Double, Mixed, Float };

struct SimulationSettings {
  bool dt_auto = true;  ///< dt = "auto" or "adaptive": dt_fraction of the critical step
  /// dt = "adaptive": the automatic base step without the displacement limit, split into
  /// substeps as the particles' speed requires (AdaptiveStep.hpp)
  bool dt_adaptive = false;
  double dt = 0;             ///< [s] explicit step (when dt_auto is false)
  int dt_line = 0;           ///< line of `dt` in the scene file (0: absent or from --set)
  double dt_fraction = 0.1;  ///< fraction of the critical step used by "auto" [-]
  /// "auto" also keeps v_max dt within this fraction of the smallest radius, and "adaptive"
  /// splits its base steps to keep within it [-]
  double displacement_fraction = 0.1;
  double end_time = 0;  ///< [s] simulated time to reach (required)
  IntegratorKind integrator = IntegratorKind::VelocityVerlet;
  Precision precision = Precision::Double;
  std::uint64_t seed = 1;     ///< random seed for particle insertion
  Vec3 gravity{0, 0, -9.81};  ///< [m/s^2]
  /// [m/s] largest expected impact speed, for the Hertz contact duration; 0 = "auto":
  /// free fall over the domain height plus the fastest inserted particle
  double impact_speed = 0;
  /// accept an explicit dt above the stable limit, and impacts whose peak overlap would pass the
  /// instability limit (warned of instead)
  bool allow_unstable_dt = false;
};

struct DomainSettings {
  Vec3 min;  ///< [m] lower corner
  Vec3 max;  ///< [m] upper corner
  std::array<bool, 3> periodic{false, false, false};
};

struct Material {
  std::string name;
  double density = 0;            ///< [kg/m^3]
  double young = 0;              ///< Young's modulus [Pa]
  double poisson = 0.3;          ///< Poisson ratio [-], in (-1, 0.5)
  double restitution = 0.5;      ///< coefficient of restitution [-], in (0, 1]
  double friction = 0.5;         ///< static Coulomb friction coefficient μ_s [-], >= 0
  double friction_dynamic = -1;  ///< sliding friction μ_d [-], in [0, μ_s]; < 0 = same as μ_s
  double rolling_friction = 0;   ///< rolling friction coefficient μ_r [-], >= 0
  double rolling_damping = 0.3;  ///< EPSD rolling dashpot ratio η_r [-], >= 0
  double viscoelastic_time = 0;  ///< A of the viscoelastic damping law [s], >= 0
  double cohesion_energy_density = 0;  ///< k_c of simplified JKR [J/m^3], >= 0
  double surface_energy = 0;  ///< γ of JKR, work of adhesion per contact area [J/m^2], >= 0
  bool fixed = false;         ///< its particles move at `velocity` (ω = 0), feeling every load
  /// With `fixed`: the constant velocity its particles move at [m/s] (zero: held still), e.g.
  /// the moving grip of a tension test
  Vec3 velocity{0, 0, 0};
  /// c [1/s]: a drag −c m v, −c I ω on its particles that brings quasi-static loading to rest
  /// (a numerical device, not a physical force), >= 0
  double drag = 0;
};

/// An explicit [[pair]] entry: values that replace the mixing rule for one material pair (in
/// both orders). A negative value means "not given, use the mixing rule".
struct PairOverride {
  MaterialId a = 0, b = 0;
  double restitution = -1;
  double friction = -1;
  double friction_dynamic = -1;
  double rolling_friction = -1;
  double cohesion_energy_density = -1;
  double surface_energy = -1;
};

/// Contact law selection: one choice per slot, validated against valid_contact_models().
struct ContactSettings {
  ContactModel model;
  double stiffness = 0;  ///< Hooke normal stiffness k_n [N/m] (required for hooke)
  /// Turns two materials' restitution, friction, rolling and cohesion values into a pair value
  MixingRule mixing = MixingRule::Mean;
  std::vector<PairOverride> pairs;
};

struct NeighborSettings {
  double skin = 0;  ///< Verlet skin [m]; 0 = "auto": half the smallest particle radius
};

/// An infinite plane; particles live on the side its normal points to. A wall with a mass is a
/// piston: it moves along its normal under its load, its weight and the particles' push.
struct WallSettings {
  std::string name;
  Vec3 point;   ///< [m] any point on the plane at t = 0
  Vec3 normal;  ///< unit normal (normalised by the loader)
  MaterialId material = 0;
  double mass = 0;    ///< [kg] 0: the wall stands still
  double load = 0;    ///< [N] force on a piston along its normal, towards the particles
  int mass_line = 0;  ///< line of `mass` (of the table when absent), for piston errors
  bool loaded() const { return mass > 0; }
};

enum class RadiusDistributionKind { Uniform, TruncatedNormal, Discrete };

struct RadiusDistribution {
  RadiusDistributionKind kind = RadiusDistributionKind::Uniform;
  double mean = 0;              ///< [m] uniform / normal mean
  double spread = 0;            ///< [m] uniform half width (mean ± spread)
  double stddev = 0;            ///< [m] truncated normal standard deviation
  double min = 0, max = 0;      ///< [m] truncated normal bounds
  std::vector<double> values;   ///< [m] discrete radii
  std::vector<double> weights;  ///< discrete weights (by count), normalised by the user of it
};

enum class SourceKind { Box, Csv, Bed };

/// How a box source fills its region: one random sequence over the whole region, or tiles
/// filled in parallel in eight colour phases, the same particles on any number of ranks and
/// threads, each rank creating only its part (core/TiledInsertion.hpp).
enum class Placement { Sequential, Tiled };

/// One [[insert]] entry: random non-overlapping insertion in a box, a CSV file, or the
/// particles of a saved bed.
struct ParticleSource {
  SourceKind kind = SourceKind::Box;
  Vec3 region_min, region_max;  ///< [m] box region
  std::uint64_t count = 0;      ///< number of particles (box; 0 when volume_fraction is used)
  double volume_fraction = 0;   ///< target solid fraction of the region (box)
  RadiusDistribution radius;
  MaterialId material = 0;
  Vec3 velocity;                                ///< [m/s] initial velocity (box)
  Placement placement = Placement::Sequential;  ///< (box)
  std::string csv_file;                         ///< CSV path, resolved relative to the scene file
  std::string bed_file;  ///< bed (checkpoint) path, resolved relative to the scene file
  int bed_line = 0;      ///< line of `bed` in the scene file (0: unknown or from --set)
};

struct OutputSettings {
  std::string dir = "out";      ///< output directory (relative to the working directory)
  double every = 0;             ///< [s] snapshot interval; 0 = first and last only
  double timeseries_every = 0;  ///< [s] time-series interval; 0 = about 200 rows per run
  bool rank_field = false;      ///< snapshots hold each particle's owning MPI rank
  bool asynchronous = true;     ///< snapshots written on a writer thread while the run steps on
  std::uint32_t fields = kAllSnapshotFields;  ///< datasets beside the positions (OutputNames)
  bool single_precision = false;  ///< real-valued particle datasets stored as 32-bit floats
  bool bonds = false;             ///< snapshots hold the bonds (group /bonds/, bonds.xmf)
};

struct CheckpointSettings {
  double every = 0;  ///< [s] checkpoint interval; 0 = no checkpoints
};

enum class DecompositionMethod { Grid, Metis };
enum class BalanceWork { Particles, Contacts };

/// [decomposition]: how the box is split among the ranks (docs/architecture.md, "Ranks").
struct DecompositionSettings {
  DecompositionMethod method = DecompositionMethod::Grid;
  std::array<int, 3> dims{0, 0, 0};  ///< 0,0,0 = "auto"; else each >= 1
  int dims_line = 0;                 ///< line of `dims` in the scene (0: absent)
  double rebalance_every = 0;        ///< [s]; 0 = never
  BalanceWork balance = BalanceWork::Particles;
};

/// [preparation]: the run settles a bed, trims it and saves it.
struct PreparationSettings {
  bool enabled = false;  ///< a [preparation] table is present
  /// [J] settled when the mean kinetic energy per particle (translational + rotational)
  /// falls below this
  double kinetic_energy = 0;
  /// [s] first time at which settling is checked; < 0 = automatic: √(2H/|g|), H the domain's
  /// extent along gravity (0 without gravity)
  double check_after = -1;
  double remove_above = 0;  ///< [m] particles whose centre is higher along −g are removed
  std::string bed_file;     ///< bed path (relative to the working directory); empty = default
};

/// One [[mesh]] entry: a triangle-mesh wall (a tool) from an STL file, placed and moved.
struct MeshSettings {
  std::string name;
  std::string file;     ///< STL path, resolved relative to the scene file
  int line = 0;         ///< line of `file` in the scene, for mesh errors
  int offset_line = 0;  ///< line of `offset` (of the table when absent), for placement errors
  int scale_line = 0;   ///< line of `scale` (of the table when absent)
  MaterialId material = 0;
  MeshPlacement placement;
  Vec3 centre;  ///< rotation centre at t = 0 [m] (default: the placement offset)
  std::vector<MotionKeyframe> keyframes;  ///< none: the mesh stands still
  bool own_motion = false;                ///< the scene gives it a [mesh.motion]
};

/// One [[implement]]: meshes moved as one rigid body by one motion about one reference point,
/// its loads also given in its own frame (forward, up and lateral = up × forward at t = 0,
/// turned with the implement).
struct ImplementSettings {
  std::string name;
  std::vector<std::size_t> meshes;        ///< indices into Scene::meshes
  Vec3 reference;                         ///< reference point at t = 0, the rotation centre [m]
  Vec3 forward;                           ///< unit travel direction at t = 0
  Vec3 up;                                ///< unit, normal to forward
  std::vector<MotionKeyframe> keyframes;  ///< none: the implement stands still
};

/// The clods of a [[bond]] table: spheres drawn at a new run's start, none overlapping another,
/// within which alone the table bonds particles.
struct ClodSettings {
  std::uint64_t count = 0;      ///< 0: the table bonds anywhere
  RadiusDistribution radius;    ///< of the clod spheres [m]
  Vec3 region_min, region_max;  ///< where their centres lie [m]
};

/// A [[bond]] table: at the start of a new run, a parallel bond (core/contact/ParallelBond.hpp) of
/// this cement joins every two particles of materials a and b whose surfaces are at most `gap`
/// apart (the first table that matches a pair makes its bond), and with clods only pairs whose
/// two centres lie in the same clod; or, given a CSV file of pairs, exactly those pairs.
struct BondSettings {
  MaterialId a = 0, b = 0;
  double gap = 0;                      ///< [m], >= 0
  double young = 0;                    ///< E of the cement [Pa]
  double poisson = 0.25;               ///< ν of the cement, G = E / (2(1 + ν))
  double radius_factor = 1;            ///< λ: bond radius λ min(r_a, r_b)
  double tensile_strength = INFINITY;  ///< σ_c [Pa]; absent: never breaks in tension
  double shear_strength = INFINITY;    ///< τ_c [Pa]; absent: never breaks in shear
  double damping_ratio = 0;            ///< β, fraction of critical damping of each mode
  ClodSettings clods;                  ///< count 0: bonds anywhere
  /// A CSV file of id pairs (path resolved from the scene's folder): the table bonds exactly
  /// those pairs, whatever their materials; empty: it bonds by materials and gap.
  std::string pairs;
};

struct Scene {
  std::string file;  ///< path of the scene file as given
  /// What the loader found suspicious but not wrong (a key the contact law ignores), each
  /// naming its file, line and key; the run goes on.
  std::vector<std::string> warnings;
  SimulationSettings simulation;
  DomainSettings domain;
  std::vector<Material> materials;
  ContactSettings contact;
  std::vector<BondSettings> bonds;
  NeighborSettings neighbor;
  std::vector<WallSettings> walls;
  std::vector<MeshSettings> meshes;
  std::vector<ImplementSettings> implements;
  std::vector<ParticleSource> sources;
  OutputSettings output;
  CheckpointSettings checkpoint;
  PreparationSettings preparation;
  DecompositionSettings decomposition;
};

}  // namespace gpudem
