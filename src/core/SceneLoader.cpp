// Scene loading: parse the TOML file, apply --set overrides, then read and check every table
// of the schema documented in docs/input.md.
#include "core/SceneLoader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <toml.hpp>

#include "core/InputError.hpp"
#include "core/OutputNames.hpp"
#include "core/SceneOverrides.hpp"
#include "core/TomlReader.hpp"

namespace gpudem {
namespace {

/// The parsed tree of `path`; a syntax error keeps toml11's report of line and column.
toml::value parse_scene_file(const std::string& path) {
  std::error_code ignored;
  std::ifstream in;
  if (std::filesystem::is_regular_file(path, ignored)) in.open(path, std::ios::binary);
  if (!in.is_open()) throw InputError(path, 0, "", "cannot open scene file");
  try {
    return toml::parse(in, path);
  } catch (const toml::exception& e) {
    throw InputError(path, static_cast<int>(e.location().line()), "",
                     std::string("TOML syntax error:\n") + e.what());
  }
}

/// "auto" (returned as 0) or a number > 0 in `unit`; absent means "auto".
double auto_or_positive(const TableReader& table, const std::string& key, const std::string& unit) {
  if (!table.has(key)) return 0;
  const toml::value& v = table.value(key);
  if (v.is_string() && v.as_string().str == "auto") return 0;
  const Range range = positive(unit);
  const std::optional<double> x = finite_number(v);
  if (!x || !range.contains(*x)) table.fail_found(key, "\"auto\" or " + range.text("a number"));
  return *x;
}

/// Fails on `key` with "`what`: ..." unless max > min on every axis.
void require_extent(const TableReader& table, const std::string& key, Vec3 min, Vec3 max,
                    const std::string& what) {
  for (int k = 0; k < 3; ++k) {
    if (!(axis(max, k) > axis(min, k))) {
      table.fail(key, what + ": max must exceed min on every axis, got max = " +
                          format_number(axis(max, k)) + " <= min = " + format_number(axis(min, k)) +
                          " on " + "xyz"[k]);
    }
  }
}

SimulationSettings read_simulation(const TableReader& root) {
  const TableReader table = root.table("simulation");
  table.allow_only({"end_time", "dt", "dt_fraction", "integrator", "precision", "seed", "gravity",
                    "impact_speed", "allow_unstable_dt"});
  SimulationSettings s;
  s.end_time = table.number("end_time", positive("s"));
  s.dt = auto_or_positive(table, "dt", "s");
  s.dt_auto = s.dt == 0;
  s.dt_line = table.has("dt") ? table.line("dt") : 0;
  s.dt_fraction = table.number("dt_fraction", interval(0, true, 1, false), s.dt_fraction);
  const std::string integrator =
      table.choice("integrator", {"velocity_verlet", "symplectic_euler"}, "velocity_verlet");
  s.integrator = integrator == "velocity_verlet" ? IntegratorKind::VelocityVerlet
                                                 : IntegratorKind::SymplecticEuler;
  const std::string precision = table.choice("precision", {"double", "mixed", "float"}, "double");
  s.precision = precision == "mixed"   ? Precision::Mixed
                : precision == "float" ? Precision::Float
                                       : Precision::Double;
  s.seed = static_cast<std::uint64_t>(table.integer("seed", non_negative(), 1));
  s.gravity = table.vec3("gravity", "m/s^2", s.gravity);
  s.impact_speed = auto_or_positive(table, "impact_speed", "m/s");
  s.allow_unstable_dt = table.boolean("allow_unstable_dt", s.allow_unstable_dt);
  return s;
}

DomainSettings read_domain(const TableReader& root) {
  const TableReader table = root.table("domain");
  table.allow_only({"min", "max", "periodic"});
  DomainSettings d;
  d.min = table.vec3("min", "m");
  d.max = table.vec3("max", "m");
  d.periodic = table.bool3("periodic", d.periodic);
  require_extent(table, "max", d.min, d.max, "the domain is empty");
  return d;
}

/// A friction coefficient `key` >= 0 that may not exceed the static coefficient `friction`.
double dynamic_friction(const TableReader& table, const std::string& key, double friction) {
  const double dynamic = table.number(key, non_negative(), friction);
  if (dynamic > friction) {
    table.fail_found(key, "a number <= friction = " + format_number(friction) +
                              " (sliding friction cannot exceed static friction)");
  }
  return dynamic;
}

Material read_material(const TableReader& table) {
  table.allow_only({"name", "density", "young", "poisson", "restitution", "friction",
                    "friction_dynamic", "rolling_friction", "rolling_damping", "viscoelastic_time",
                    "cohesion_energy_density"});
  Material m;
  m.name = table.string("name");
  m.density = table.number("density", positive("kg/m^3"));
  m.young = table.number("young", positive("Pa"));
  m.poisson = table.number("poisson", interval(-1, true, 0.5, true), m.poisson);
  m.restitution = table.number("restitution", interval(0, true, 1, false), m.restitution);
  m.friction = table.number("friction", non_negative(), m.friction);
  m.friction_dynamic = dynamic_friction(table, "friction_dynamic", m.friction);
  m.rolling_friction = table.number("rolling_friction", non_negative(), m.rolling_friction);
  m.rolling_damping = table.number("rolling_damping", non_negative(), m.rolling_damping);
  m.viscoelastic_time = table.number("viscoelastic_time", non_negative("s"), m.viscoelastic_time);
  m.cohesion_energy_density =
      table.number("cohesion_energy_density", non_negative("J/m^3"), m.cohesion_energy_density);
  return m;
}

std::vector<Material> read_materials(const TableReader& root) {
  const std::vector<TableReader> tables = root.array_of_tables("material");
  if (tables.empty()) root.fail("material", "expected at least one [[material]] table");
  std::vector<Material> materials;
  for (const TableReader& table : tables) {
    Material m = read_material(table);
    for (std::size_t j = 0; j < materials.size(); ++j) {
      if (materials[j].name == m.name) {
        table.fail("name", "duplicate material name '" + m.name + "' (also used by material[" +
                               std::to_string(j) + "])");
      }
    }
    materials.push_back(std::move(m));
  }
  return materials;
}

/// The enum value whose name (in `names`, enum order) `key` gives, or `fallback` when absent.
template <class Enum>
Enum named_choice(const TableReader& table, const std::string& key,
                  const std::vector<std::string>& names, Enum fallback) {
  const std::string name = table.choice(key, names, names[static_cast<std::size_t>(fallback)]);
  return static_cast<Enum>(std::find(names.begin(), names.end(), name) - names.begin());
}

/// The slots of [contact]; tangential defaults to the normal law's own spring (hooke:
/// linear_history, hertz: mindlin).
ContactModel read_contact_model(const TableReader& table) {
  ContactModel m;
  m.normal = named_choice(table, "normal", normal_law_names(), m.normal);
  m.damping = named_choice(table, "damping", damping_law_names(), m.damping);
  const TangentialLaw own_spring =
      m.normal == NormalLaw::Hertz ? TangentialLaw::Mindlin : TangentialLaw::LinearHistory;
  m.tangential = named_choice(table, "tangential", tangential_law_names(), own_spring);
  m.rolling = named_choice(table, "rolling", rolling_law_names(), m.rolling);
  m.cohesion = named_choice(table, "cohesion", cohesion_law_names(), m.cohesion);
  return m;
}

/// Fails unless `m` is one of valid_contact_models(), naming the slot that does not go with
/// the normal law (damping or tangential; every normal law takes tangential = "none").
void require_valid_model(const TableReader& table, const ContactModel& m) {
  if (is_valid_contact_model(m)) return;
  ContactModel without_tangential = m;
  without_tangential.tangential = TangentialLaw::None;
  const bool damping_wrong = !is_valid_contact_model(without_tangential);
  const std::string key = damping_wrong ? "damping" : "tangential";
  const std::string choice = damping_wrong
                                 ? damping_law_names()[static_cast<std::size_t>(m.damping)]
                                 : tangential_law_names()[static_cast<std::size_t>(m.tangential)];
  const std::string normal = normal_law_names()[static_cast<std::size_t>(m.normal)];
  table.fail(key, "normal = \"" + normal + "\" does not go with " + key + " = \"" + choice + "\"" +
                      (table.has(key) ? "" : " (the default)") + "; valid combinations are " +
                      valid_contact_models_text());
}

ContactSettings read_contact(const TableReader& root) {
  const TableReader table = root.optional_table("contact");
  table.allow_only(
      {"normal", "damping", "tangential", "rolling", "cohesion", "stiffness", "mixing"});
  ContactSettings c;
  c.model = read_contact_model(table);
  c.mixing = named_choice(table, "mixing", mixing_rule_names(), c.mixing);
  require_valid_model(table, c.model);
  if (c.model.normal == NormalLaw::Hooke) {
    c.stiffness = table.number("stiffness", positive("N/m"));
  } else if (table.has("stiffness")) {
    table.fail("stiffness",
               "stiffness belongs to normal = \"hooke\"; normal = \"hertz\" takes its stiffness "
               "from the materials' young and poisson");
  }
  return c;
}

NeighborSettings read_neighbor(const TableReader& root) {
  const TableReader table = root.optional_table("neighbor");
  table.allow_only({"skin"});
  NeighborSettings n;
  n.skin = auto_or_positive(table, "skin", "m");
  return n;
}

/// Index of the material called `name`, given by `key`.
MaterialId material_named(const TableReader& table, const std::string& key, const std::string& name,
                          const std::vector<Material>& materials) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].name == name) return static_cast<MaterialId>(i);
    names.push_back(materials[i].name);
  }
  table.fail(key, "unknown material '" + name + "'; " + suggest(name, names, "materials"));
}

/// Index of the material named by string `key`.
MaterialId material_index(const TableReader& table, const std::string& key,
                          const std::vector<Material>& materials) {
  return material_named(table, key, table.string(key), materials);
}

/// The pair `materials` = ["a", "b"] of a [[pair]] entry, as material indices.
PairOverride read_pair_materials(const TableReader& table, const std::vector<Material>& materials) {
  const std::vector<std::string> names = table.strings("materials", 2);
  PairOverride p;
  p.a = material_named(table, "materials", names[0], materials);
  p.b = material_named(table, "materials", names[1], materials);
  return p;
}

/// μ_s and μ_d of a [[pair]] entry (p.a, p.b set). μ_d defaults to the entry's μ_s when that is
/// given, and may not exceed the pair's μ_s, given or mixed.
void read_pair_friction(const TableReader& table, const std::vector<Material>& materials,
                        MixingRule mixing, PairOverride& p) {
  if (table.has("friction")) p.friction = table.number("friction", non_negative());
  const bool given = p.friction >= 0;
  const double static_friction =
      given ? p.friction : mix(mixing, materials[p.a].friction, materials[p.b].friction);
  if (table.has("friction_dynamic")) {
    p.friction_dynamic = dynamic_friction(table, "friction_dynamic", static_friction);
  } else if (given) {
    p.friction_dynamic = p.friction;
  }
}

/// One [[pair]] entry; values it does not give stay negative ("use the mixing rule").
PairOverride read_pair(const TableReader& table, const std::vector<Material>& materials,
                       MixingRule mixing) {
  table.allow_only({"materials", "restitution", "friction", "friction_dynamic", "rolling_friction",
                    "cohesion_energy_density"});
  PairOverride p = read_pair_materials(table, materials);
  p.restitution = table.number("restitution", interval(0, true, 1, false), p.restitution);
  read_pair_friction(table, materials, mixing, p);
  p.rolling_friction = table.number("rolling_friction", non_negative(), p.rolling_friction);
  p.cohesion_energy_density =
      table.number("cohesion_energy_density", non_negative("J/m^3"), p.cohesion_energy_density);
  return p;
}

/// "'soil'-'steel'", the unordered pair as messages name it.
std::string pair_name(const PairOverride& p, const std::vector<Material>& materials) {
  return "'" + materials[p.a].name + "'-'" + materials[p.b].name + "'";
}

std::vector<PairOverride> read_pairs(const TableReader& root,
                                     const std::vector<Material>& materials, MixingRule mixing) {
  std::vector<PairOverride> pairs;
  const std::vector<TableReader> tables = root.array_of_tables("pair");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const PairOverride pair = read_pair(tables[i], materials, mixing);
    for (std::size_t j = 0; j < pairs.size(); ++j) {
      const bool same = (pairs[j].a == pair.a && pairs[j].b == pair.b) ||
                        (pairs[j].a == pair.b && pairs[j].b == pair.a);
      if (same) {
        tables[i].fail("materials", "duplicate pair " + pair_name(pair, materials) +
                                        " (also given by pair[" + std::to_string(j) + "])");
      }
    }
    pairs.push_back(pair);
  }
  return pairs;
}

WallSettings read_wall(const TableReader& table, std::size_t index,
                       const std::vector<Material>& materials) {
  table.allow_only({"name", "point", "normal", "material"});
  WallSettings w;
  w.name = table.string("name", "wall" + std::to_string(index));
  w.point = table.vec3("point", "m");
  const Vec3 normal = table.vec3("normal", "");
  const double length = norm(normal);
  if (!(length > 0) || !std::isfinite(length)) {
    table.fail_found("normal", "a normal vector of non-zero, finite length");
  }
  w.normal = (1 / length) * normal;
  w.material = material_index(table, "material", materials);
  return w;
}

/// The path string `key` names, resolved relative to the scene file's directory.
std::string path_beside_scene(const TableReader& table, const std::string& key,
                              const Scene& scene) {
  const std::filesystem::path path = table.string(key);
  const std::filesystem::path scene_dir = std::filesystem::path(scene.file).parent_path();
  return path.is_absolute() ? path.string() : (scene_dir / path).lexically_normal().string();
}

/// [mesh.motion]: keyframe times [s], velocities [m/s] and angular velocities [rad/s] (zero
/// when absent), one per time, times strictly increasing; the centre defaults to `offset`.
void read_motion(const TableReader& mesh, MeshSettings& m) {
  m.centre = m.placement.offset;
  if (!mesh.has("motion")) return;
  const TableReader motion = mesh.table("motion");
  motion.allow_only({"centre", "times", "velocities", "angular_velocities"});
  m.centre = motion.vec3("centre", "m", m.centre);
  const std::vector<double> times = motion.numbers("times", any_value("s"));
  for (std::size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1]))
      motion.fail("times",
                  "keyframe times must increase strictly (index " + std::to_string(k) + ")");
  const std::vector<Vec3> v = motion.vec3s("velocities", "m/s", times.size());
  const std::vector<Vec3> w = motion.has("angular_velocities")
                                  ? motion.vec3s("angular_velocities", "rad/s", times.size())
                                  : std::vector<Vec3>(times.size());
  for (std::size_t k = 0; k < times.size(); ++k) m.keyframes.push_back({times[k], v[k], w[k]});
}

MeshSettings read_mesh(const TableReader& table, std::size_t index, const Scene& scene) {
  table.allow_only(
      {"name", "file", "material", "scale", "offset", "rotation_axis", "rotation_angle", "motion"});
  MeshSettings m;
  m.name = table.string("name", "mesh" + std::to_string(index));
  m.file = path_beside_scene(table, "file", scene);
  m.line = table.line("file");
  m.material = table.has("material") ? material_index(table, "material", scene.materials) : 0;
  m.placement.scale = table.number("scale", positive(""), 1.0);
  m.placement.offset = table.vec3("offset", "m", Vec3{});
  m.placement.rotation_axis = table.vec3("rotation_axis", "", Vec3{0, 0, 1});
  if (!(norm(m.placement.rotation_axis) > 0)) table.fail_found("rotation_axis", "a non-zero axis");
  m.placement.rotation_angle = table.number("rotation_angle", any_value("rad"), 0.0);
  read_motion(table, m);
  return m;
}

/// The [[mesh]] tables; names label force columns, so they differ from each other and from
/// the walls' names, and name the mesh's output files.
std::vector<MeshSettings> read_meshes(const TableReader& root, const Scene& scene) {
  std::vector<MeshSettings> meshes;
  const std::vector<TableReader> tables = root.array_of_tables("mesh");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    MeshSettings mesh = read_mesh(tables[i], i, scene);
    if (const char* problem = mesh_output_name_problem(mesh.name, kParticlesBasename))
      tables[i].fail("name", "name '" + mesh.name + "' " + problem +
                                 "; it names the mesh's output file <name>.xmf");
    bool taken = false;
    for (const WallSettings& w : scene.walls) taken = taken || w.name == mesh.name;
    for (const MeshSettings& m : meshes) taken = taken || m.name == mesh.name;
    if (taken)
      tables[i].fail("name", "name '" + mesh.name +
                                 "' is already used by a wall or mesh; names label the force "
                                 "columns");
    meshes.push_back(std::move(mesh));
  }
  return meshes;
}

std::vector<WallSettings> read_walls(const TableReader& root,
                                     const std::vector<Material>& materials) {
  std::vector<WallSettings> walls;
  const std::vector<TableReader> tables = root.array_of_tables("wall");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    WallSettings wall = read_wall(tables[i], i, materials);
    for (std::size_t j = 0; j < walls.size(); ++j) {
      if (walls[j].name == wall.name) {
        tables[i].fail("name", "duplicate wall name '" + wall.name + "' (also used by wall[" +
                                   std::to_string(j) + "]); names label the force columns");
      }
    }
    walls.push_back(std::move(wall));
  }
  return walls;
}

/// radius = {distribution = "uniform", mean, spread}: radii in mean ± spread.
RadiusDistribution read_uniform_radius(const TableReader& table) {
  table.allow_only({"distribution", "mean", "spread"});
  RadiusDistribution r;
  r.kind = RadiusDistributionKind::Uniform;
  r.mean = table.number("mean", positive("m"));
  r.spread = table.number("spread", non_negative("m"), 0);
  if (!(r.spread < r.mean)) {
    table.fail_found("spread", "a number < mean = " + format_number(r.mean) +
                                   " [m] so that every radius is > 0");
  }
  return r;
}

/// radius = {distribution = "normal", mean, stddev, min, max}: truncated normal.
RadiusDistribution read_normal_radius(const TableReader& table) {
  table.allow_only({"distribution", "mean", "stddev", "min", "max"});
  RadiusDistribution r;
  r.kind = RadiusDistributionKind::TruncatedNormal;
  r.mean = table.number("mean", positive("m"));
  r.stddev = table.number("stddev", positive("m"));
  r.min = table.number("min", positive("m"));
  r.max = table.number("max", positive("m"));
  const std::string mean = format_number(r.mean);
  if (r.min > r.mean) table.fail_found("min", "a number <= mean = " + mean + " [m]");
  if (r.max < r.mean) table.fail_found("max", "a number >= mean = " + mean + " [m]");
  return r;
}

/// radius = {distribution = "discrete", values, weights}: radii drawn from a list.
RadiusDistribution read_discrete_radius(const TableReader& table) {
  table.allow_only({"distribution", "values", "weights"});
  RadiusDistribution r;
  r.kind = RadiusDistributionKind::Discrete;
  r.values = table.numbers("values", positive("m"));
  r.weights = table.has("weights") ? table.numbers("weights", positive())
                                   : std::vector<double>(r.values.size(), 1.0);
  if (r.weights.size() != r.values.size()) {
    table.fail("weights", "expected as many weights as values (" + std::to_string(r.values.size()) +
                              "), got " + std::to_string(r.weights.size()));
  }
  return r;
}

/// `radius`: a number (every particle the same) or a distribution table.
RadiusDistribution read_radius(const TableReader& source) {
  if (source.has("radius") && source.value("radius").is_table()) {
    const TableReader table = source.table("radius");
    const std::string kind =
        table.choice("distribution", {"uniform", "normal", "discrete"}, "uniform");
    if (kind == "normal") return read_normal_radius(table);
    if (kind == "discrete") return read_discrete_radius(table);
    return read_uniform_radius(table);
  }
  RadiusDistribution r;
  r.mean = source.number("radius", positive("m"));
  return r;
}

/// The box `region` of a source, which must lie inside the domain (touching it is allowed).
void read_region(const TableReader& source, const DomainSettings& domain, ParticleSource& s) {
  const TableReader region = source.table("region");
  region.allow_only({"min", "max"});
  s.region_min = region.vec3("min", "m");
  s.region_max = region.vec3("max", "m");
  require_extent(region, "max", s.region_min, s.region_max, "the source region is empty");
  for (int k = 0; k < 3; ++k) {
    const double lo = axis(s.region_min, k), hi = axis(s.region_max, k);
    if (lo < axis(domain.min, k) || hi > axis(domain.max, k)) {
      source.fail("region", std::string("source region lies outside the domain on ") + "xyz"[k] +
                                ": [" + format_number(lo) + ", " + format_number(hi) +
                                "] is not inside [" + format_number(axis(domain.min, k)) + ", " +
                                format_number(axis(domain.max, k)) + "]");
    }
  }
}

/// Keys that only box (region) sources take.
const std::vector<std::string> kBoxOnlyKeys = {"region", "count", "volume_fraction", "radius",
                                               "velocity", "placement"};

ParticleSource read_box_source(const TableReader& table, const Scene& scene) {
  ParticleSource s;
  s.kind = SourceKind::Box;
  read_region(table, scene.domain, s);
  if (table.has("count") && table.has("volume_fraction")) {
    table.fail("volume_fraction", "give either count or volume_fraction, not both");
  }
  if (table.has("volume_fraction")) {
    s.volume_fraction = table.number("volume_fraction", interval(0, true, 0.6, false));
  } else if (table.has("count")) {
    s.count = static_cast<std::uint64_t>(table.integer("count", positive()));
  } else {
    table.fail("count", "missing 'count' or 'volume_fraction' in [[insert]] (give exactly one)");
  }
  s.radius = read_radius(table);
  s.material = material_index(table, "material", scene.materials);
  s.velocity = table.vec3("velocity", "m/s", s.velocity);
  s.placement = named_choice(table, "placement", {"sequential", "tiled"}, s.placement);
  return s;
}

/// Fails on the first of `keys` the table holds, saying why it does not belong there.
void refuse_keys(const TableReader& table, const std::vector<std::string>& keys,
                 const std::string& why) {
  for (const std::string& key : keys)
    if (table.has(key)) table.fail(key, "'" + key + "' " + why);
}

/// A CSV source; its file is resolved relative to the scene file's directory, not opened.
ParticleSource read_csv_source(const TableReader& table, const Scene& scene) {
  refuse_keys(table, kBoxOnlyKeys,
              "belongs to region sources; a csv source takes only csv and material");
  ParticleSource s;
  s.kind = SourceKind::Csv;
  s.csv_file = path_beside_scene(table, "csv", scene);
  s.material = table.has("material") ? material_index(table, "material", scene.materials) : 0;
  return s;
}

/// A bed source: the particles of a saved bed file (resolved like a CSV file, not opened).
ParticleSource read_bed_source(const TableReader& table, const Scene& scene) {
  std::vector<std::string> other_keys = kBoxOnlyKeys;
  other_keys.push_back("material");
  refuse_keys(table, other_keys,
              "does not apply to a bed source, whose particles keep their own values; a bed "
              "source takes only bed");
  ParticleSource s;
  s.kind = SourceKind::Bed;
  s.bed_file = path_beside_scene(table, "bed", scene);
  s.bed_line = table.line("bed");
  return s;
}

/// The one source kind an [[insert]] entry names by its `region`, `csv` or `bed` key.
SourceKind source_kind(const TableReader& table) {
  const std::pair<std::string, SourceKind> kinds[] = {
      {"region", SourceKind::Box}, {"csv", SourceKind::Csv}, {"bed", SourceKind::Bed}};
  const std::pair<std::string, SourceKind>* chosen = nullptr;
  for (const auto& kind : kinds) {
    if (!table.has(kind.first)) continue;
    if (chosen) {
      table.fail(kind.first, "an [[insert]] takes either " + kind.first + " or " + chosen->first +
                                 ", not both");
    }
    chosen = &kind;
  }
  if (!chosen) {
    table.fail("region",
               "missing 'region' (random insertion in a box), 'csv' (particles from a file) or "
               "'bed' (the particles of a saved bed) in [[insert]]");
  }
  return chosen->second;
}

ParticleSource read_source(const TableReader& table, const Scene& scene) {
  table.allow_only(
      {"csv", "region", "bed", "count", "volume_fraction", "radius", "material", "velocity",
       "placement"});
  switch (source_kind(table)) {
    case SourceKind::Csv:
      return read_csv_source(table, scene);
    case SourceKind::Bed:
      return read_bed_source(table, scene);
    case SourceKind::Box:
      break;
  }
  return read_box_source(table, scene);
}

std::vector<ParticleSource> read_sources(const TableReader& root, const Scene& scene) {
  std::vector<ParticleSource> sources;
  const std::vector<TableReader> tables = root.array_of_tables("insert");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    sources.push_back(read_source(tables[i], scene));
    for (std::size_t j = 0; j < i; ++j) {
      if (sources[i].kind == SourceKind::Bed && sources[j].kind == SourceKind::Bed) {
        tables[i].fail("bed", "a scene takes at most one bed source (also given by insert[" +
                                  std::to_string(j) + "])");
      }
    }
  }
  return sources;
}

OutputSettings read_output(const TableReader& root) {
  const TableReader table = root.optional_table("output");
  table.allow_only(
      {"dir", "every", "timeseries_every", "rank_field", "asynchronous", "fields", "precision"});
  OutputSettings o;
  o.dir = table.string("dir", o.dir);
  o.every = table.number("every", non_negative("s"), o.every);
  o.timeseries_every = table.number("timeseries_every", non_negative("s"), o.timeseries_every);
  o.rank_field = table.boolean("rank_field", o.rank_field);
  o.asynchronous = table.boolean("asynchronous", o.asynchronous);
  if (table.has("fields"))
    o.fields = table.subset("fields", {kSnapshotFields.begin(), kSnapshotFields.end()});
  o.single_precision = table.choice("precision", {"double", "float"}, "double") == "float";
  return o;
}

/// `dims`: "auto" (returned as 0, 0, 0) or 3 integers >= 1; absent means "auto". Their product
/// is checked against the rank count by the run.
std::array<int, 3> read_dims(const TableReader& table) {
  const std::array<int, 3> automatic{0, 0, 0};
  if (!table.has("dims")) return automatic;
  const toml::value& v = table.value("dims");
  if (v.is_string() && v.as_string().str == "auto") return automatic;
  const std::string expected = "\"auto\" or an array of 3 integers >= 1";
  if (!v.is_array() || v.as_array().size() != 3) table.fail_found("dims", expected);
  std::array<int, 3> dims{};
  for (std::size_t k = 0; k < 3; ++k) {
    const toml::value& e = v.as_array()[k];
    if (!e.is_integer() || e.as_integer() < 1 || e.as_integer() > std::numeric_limits<int>::max())
      table.fail_found("dims", expected);
    dims[k] = static_cast<int>(e.as_integer());
  }
  return dims;
}

/// [decomposition]: grid (dims given or "auto") or METIS, and the load balancing schedule.
DecompositionSettings read_decomposition(const TableReader& root) {
  const TableReader table = root.optional_table("decomposition");
  table.allow_only({"method", "dims", "rebalance_every", "balance"});
  DecompositionSettings d;
  d.method = named_choice(table, "method", {"grid", "metis"}, d.method);
  if (d.method == DecompositionMethod::Metis && table.has("dims")) {
    table.fail("dims",
               "dims belongs to method = \"grid\"; method = \"metis\" chooses its own parts");
  }
  d.dims = read_dims(table);
  d.dims_line = table.has("dims") ? table.line("dims") : 0;
  d.rebalance_every = table.number("rebalance_every", non_negative("s"), d.rebalance_every);
  d.balance = named_choice(table, "balance", {"particles", "contacts"}, d.balance);
  return d;
}

CheckpointSettings read_checkpoint(const TableReader& root) {
  const TableReader table = root.optional_table("checkpoint");
  table.allow_only({"every"});
  CheckpointSettings c;
  c.every = table.number("every", non_negative("s"), c.every);
  return c;
}

/// [preparation]: settle, trim and save a bed. The bed file is left empty for the runner to
/// default to <output.dir>/bed.h5 once --output-dir has been applied. Heights are measured
/// against gravity, which must therefore be non-zero.
PreparationSettings read_preparation(const TableReader& root, Vec3 gravity) {
  PreparationSettings p;
  if (!root.has("preparation")) return p;
  const TableReader table = root.table("preparation");
  table.allow_only({"kinetic_energy", "remove_above", "bed_file", "check_after"});
  p.enabled = true;
  p.kinetic_energy = table.number("kinetic_energy", positive("J"));
  p.remove_above = table.number("remove_above", any_value("m"));
  if (!(norm(gravity) > 0)) {
    table.fail("remove_above",
               "heights are measured against gravity, but simulation.gravity is zero");
  }
  p.bed_file = table.string("bed_file", p.bed_file);
  p.check_after = table.number("check_after", non_negative("s"), p.check_after);
  return p;
}

}  // namespace

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  toml::value tree = parse_scene_file(path);
  apply_overrides(tree, overrides);
  const TableReader root(tree, path, "", "");
  root.allow_only({"simulation", "domain", "material", "contact", "pair", "neighbor", "wall",
                   "mesh", "insert", "output", "checkpoint", "preparation", "decomposition"});
  Scene scene;
  scene.file = path;
  scene.simulation = read_simulation(root);
  scene.domain = read_domain(root);
  scene.materials = read_materials(root);
  scene.contact = read_contact(root);
  scene.contact.pairs = read_pairs(root, scene.materials, scene.contact.mixing);
  scene.neighbor = read_neighbor(root);
  scene.walls = read_walls(root, scene.materials);
  scene.meshes = read_meshes(root, scene);
  scene.sources = read_sources(root, scene);
  scene.output = read_output(root);
  scene.checkpoint = read_checkpoint(root);
  scene.preparation = read_preparation(root, scene.simulation.gravity);
  scene.decomposition = read_decomposition(root);
  return scene;
}

}  // namespace gpudem
