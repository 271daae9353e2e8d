#pragma once
/// The validated scene: plain data filled by SceneLoader from a TOML file (DESIGN §8).
/// Units are SI throughout. Every field here is documented in docs/input.md.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

enum class IntegratorKind { VelocityVerlet, SymplecticEuler };

struct SimulationSettings {
  bool dt_auto = true;       ///< dt = "auto": dt_fraction of the critical time step
  double dt = 0;             ///< [s] explicit step (when dt_auto is false)
  double dt_fraction = 0.1;  ///< fraction of the critical step used by "auto" [-]
  double end_time = 0;       ///< [s] simulated time to reach (required)
  IntegratorKind integrator = IntegratorKind::VelocityVerlet;
  std::uint64_t seed = 1;     ///< random seed for particle insertion
  Vec3 gravity{0, 0, -9.81};  ///< [m/s^2]
};

struct DomainSettings {
  Vec3 min;  ///< [m] lower corner
  Vec3 max;  ///< [m] upper corner
  std::array<bool, 3> periodic{false, false, false};
};

struct Material {
  std::string name;
  double density = 0;           ///< [kg/m^3]
  double young = 0;             ///< Young's modulus [Pa]
  double poisson = 0.3;         ///< Poisson ratio [-], in (-1, 0.5)
  double restitution = 0.5;     ///< coefficient of restitution [-], in (0, 1]
  double friction = 0.5;        ///< Coulomb (sliding) friction coefficient [-], >= 0
  double rolling_friction = 0;  ///< rolling friction coefficient μ_r [-], >= 0
};

/// Contact law selection. The skeleton ships one law: linear spring, restitution-based
/// dashpot and a tangential spring with a Coulomb limit (LinearContact.hpp).
struct ContactSettings {
  std::string normal = "hooke";               ///< normal spring law
  std::string damping = "restitution";        ///< "restitution" | "none"
  std::string tangential = "linear_history";  ///< "linear_history" | "none"
  std::string rolling = "none";               ///< "constant_torque" | "none"
  double stiffness = 0;                       ///< Hooke normal stiffness k_n [N/m] (required)
};

struct NeighborSettings {
  double skin = 0;  ///< Verlet skin [m]; 0 = "auto": half the smallest particle radius
};

/// An infinite plane; particles live on the side its normal points to.
struct WallSettings {
  std::string name;
  Vec3 point;   ///< [m] any point on the plane
  Vec3 normal;  ///< unit normal (normalised by the loader)
  MaterialId material = 0;
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

enum class SourceKind { Box, Csv };

/// One [[insert]] entry: random non-overlapping insertion in a box, or a CSV file.
struct ParticleSource {
  SourceKind kind = SourceKind::Box;
  Vec3 region_min, region_max;  ///< [m] box region
  std::uint64_t count = 0;      ///< number of particles (box; 0 when volume_fraction is used)
  double volume_fraction = 0;   ///< target solid fraction of the region (box)
  RadiusDistribution radius;
  MaterialId material = 0;
  Vec3 velocity;         ///< [m/s] initial velocity (box)
  std::string csv_file;  ///< CSV path, resolved relative to the scene file
};

struct OutputSettings {
  std::string dir = "out";      ///< output directory (relative to the working directory)
  double every = 0;             ///< [s] snapshot interval; 0 = first and last only
  double timeseries_every = 0;  ///< [s] time-series interval; 0 = about 200 rows per run
};

struct CheckpointSettings {
  double every = 0;  ///< [s] checkpoint interval; 0 = no checkpoints
};

struct Scene {
  std::string file;  ///< path of the scene file as given
  SimulationSettings simulation;
  DomainSettings domain;
  std::vector<Material> materials;
  ContactSettings contact;
  NeighborSettings neighbor;
  std::vector<WallSettings> walls;
  std::vector<ParticleSource> sources;
  OutputSettings output;
  CheckpointSettings checkpoint;
};

}  // namespace gpudem
