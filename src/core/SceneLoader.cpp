// Scene loading: parse the TOML file, apply --set overrides, then read and check every table
// of the schema documented in docs/input.md.
#include "core/SceneLoader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <toml.hpp>

#include "core/InputError.hpp"
#include "core/OutputNames.hpp"
#include "core/SceneBodies.hpp"
#include "core/SceneOverrides.hpp"
#include "core/SceneReading.hpp"
#include "core/SceneSources.hpp"
#include "core/TomlReader.hpp"
#include "core/Utf8.hpp"

namespace gpudem {

using scene_reading::material_named;
using scene_reading::mesh_angle_warnings;
using scene_reading::named_choice;
using scene_reading::read_bonds;
using scene_reading::read_implements;
using scene_reading::read_meshes;
using scene_reading::read_sources;
using scene_reading::read_walls;
using scene_reading::require_extent;

namespace {

/// The parsed tree of `path`; a syntax error keeps toml11's report of line and column. Text
/// that is not UTF-8 is refused with the line of its first bad byte before it is parsed.
toml::value parse_scene_file(const std::string& path) {
  std::error_code ignored;
  std::ifstream in;
  if (std::filesystem::is_regular_file(path, ignored)) in.open(path, std::ios::binary);
  if (!in.is_open()) throw InputError(path, 0, "", "cannot open scene file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (const std::optional<std::size_t> bad = first_invalid_utf8(text)) {
    const auto line = 1 + std::count(text.begin(), text.begin() + *bad, '\n');
    throw InputError(path, static_cast<int>(line), "",
                     "byte " + std::to_string(*bad + 1) +
                         " of the file is not UTF-8 text: a scene file must be UTF-8");
  }
  std::istringstream text_stream(text);
  try {
    return toml::parse(text_stream, path);
  } catch (const toml::exception& e) {
    throw InputError(path, static_cast<int>(e.location().line()), "",
                     std::string("TOML syntax error:\n") + e.what());
  }
}

/// "auto" (returned as 0) or a number > 0 in `unit`; absent means "auto". `words`: the strings
/// the key takes, for the message.
double auto_or_positive(const TableReader& table, const std::string& key, const std::string& unit,
                        const std::string& words = "\"auto\"") {
  if (!table.has(key)) return 0;
  const toml::value& v = table.value(key);
  if (v.is_string() && v.as_string().str == "auto") return 0;
  const Range range = positive(unit);
  const std::optional<double> x = finite_number(v);
  if (!x || !range.contains(*x)) table.fail_found(key, words + " or " + range.text("a number"));
  return *x;
}

SimulationSettings read_simulation(const TableReader& root) {
  const TableReader table = root.table("simulation");
  table.allow_only({"end_time", "dt", "dt_fraction", "displacement_fraction", "integrator",
                    "precision", "seed", "gravity", "impact_speed", "allow_unstable_dt"});
  SimulationSettings s;
  s.end_time = table.number("end_time", positive("s"));
  s.dt_adaptive = table.has("dt") && table.value("dt").is_string() &&
                  table.value("dt").as_string().str == "adaptive";
  s.dt = s.dt_adaptive ? 0 : auto_or_positive(table, "dt", "s", "\"auto\", \"adaptive\"");
  s.dt_auto = s.dt == 0;
  s.dt_line = table.has("dt") ? table.line("dt") : 0;
  s.dt_fraction = table.number("dt_fraction", interval(0, true, 1, false), s.dt_fraction);
  s.displacement_fraction =
      table.number("displacement_fraction", interval(0, true, 1, false), s.displacement_fraction);
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
                    "cohesion_energy_density", "surface_energy", "fixed", "velocity", "drag"});
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
  m.surface_energy = table.number("surface_energy", non_negative("J/m^2"), m.surface_energy);
  m.fixed = table.boolean("fixed", m.fixed);
  m.velocity = table.vec3("velocity", "m/s", m.velocity);
  if (!m.fixed && table.has("velocity"))
    table.fail("velocity", "is given only with fixed = true (the velocity of held particles)");
  m.drag = table.number("drag", non_negative("1/s"), m.drag);
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

/// The slot of `m` that does not go with its normal law, as (key, choice): damping, else
/// tangential, else cohesion (every normal law takes tangential and cohesion "none").
std::pair<std::string, std::string> misfit_slot(const ContactModel& m) {
  ContactModel bare = m;
  bare.tangential = TangentialLaw::None;
  bare.cohesion = CohesionLaw::None;
  if (!is_valid_contact_model(bare))
    return {"damping", damping_law_names()[static_cast<std::size_t>(m.damping)]};
  bare.tangential = m.tangential;
  if (!is_valid_contact_model(bare))
    return {"tangential", tangential_law_names()[static_cast<std::size_t>(m.tangential)]};
  return {"cohesion", cohesion_law_names()[static_cast<std::size_t>(m.cohesion)]};
}

/// Fails unless `m` is one of valid_contact_models(), naming the slot that does not go with
/// the normal law.
void require_valid_model(const TableReader& table, const ContactModel& m) {
  if (is_valid_contact_model(m)) return;
  const auto [key, choice] = misfit_slot(m);
  const std::string normal = normal_law_names()[static_cast<std::size_t>(m.normal)];
  table.fail(key, "normal = \"" + normal + "\" does not go with " + key + " = \"" + choice + "\"" +
                      (table.has(key) ? "" : " (the default)") + "; valid combinations are " +
                      valid_contact_models_text());
}

/// Fails unless this build compiles the valid law `m` (is_compiled_contact_model).
void require_compiled_model(const TableReader& table, const ContactModel& m) {
  if (is_compiled_contact_model(m)) return;
  table.fail("normal", "the contact law " + contact_model_name(m) +
                           " is not compiled into this build, which has " +
                           compiled_contact_models_text());
}

ContactSettings read_contact(const TableReader& root) {
  const TableReader table = root.optional_table("contact");
  table.allow_only(
      {"normal", "damping", "tangential", "rolling", "cohesion", "stiffness", "mixing"});
  ContactSettings c;
  c.model = read_contact_model(table);
  c.mixing = named_choice(table, "mixing", mixing_rule_names(), c.mixing);
  require_valid_model(table, c.model);
  require_compiled_model(table, c.model);
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
                    "cohesion_energy_density", "surface_energy"});
  PairOverride p = read_pair_materials(table, materials);
  p.restitution = table.number("restitution", interval(0, true, 1, false), p.restitution);
  read_pair_friction(table, materials, mixing, p);
  p.rolling_friction = table.number("rolling_friction", non_negative(), p.rolling_friction);
  p.cohesion_energy_density =
      table.number("cohesion_energy_density", non_negative("J/m^3"), p.cohesion_energy_density);
  p.surface_energy = table.number("surface_energy", non_negative("J/m^2"), p.surface_energy);
  return p;
}

/// "'soil'-'steel'", the unordered pair as messages name it.
std::string pair_name(const PairOverride& p, const std::vector<Material>& materials) {
  return "'" + materials[p.a].name + "'-'" + materials[p.b].name + "'";
}

/// A warning for each [[material]] and [[pair]] key that the contact law does not read.
std::vector<std::string> ignored_key_warnings(const TableReader& root, const std::string& file,
                                              const ContactModel& model) {
  std::vector<std::string> warnings;
  const std::vector<IgnoredLawKey> ignored = ignored_law_keys(model);
  for (const char* kind : {"material", "pair"})
    for (const TableReader& table : root.array_of_tables(kind))
      for (const IgnoredLawKey& k : ignored) {
        if (!table.has(k.key)) continue;
        warnings.push_back(InputError::compose(file, table.line(k.key), table.path(k.key),
                                               "ignored: contact." + k.slot + " = \"" + k.chosen +
                                                   "\" does not read it (" + k.slot + " = \"" +
                                                   k.readers + "\" would)"));
      }
  return warnings;
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

OutputSettings read_output(const TableReader& root) {
  const TableReader table = root.optional_table("output");
  table.allow_only({"dir", "every", "timeseries_every", "rank_field", "asynchronous", "fields",
                    "precision", "bonds"});
  OutputSettings o;
  o.dir = table.string("dir", o.dir);
  o.every = table.number("every", non_negative("s"), o.every);
  o.timeseries_every = table.number("timeseries_every", non_negative("s"), o.timeseries_every);
  o.rank_field = table.boolean("rank_field", o.rank_field);
  o.asynchronous = table.boolean("asynchronous", o.asynchronous);
  if (table.has("fields"))
    o.fields = table.subset("fields", {kSnapshotFields.begin(), kSnapshotFields.end()});
  o.single_precision = table.choice("precision", {"double", "float"}, "double") == "float";
  o.bonds = table.boolean("bonds", o.bonds);
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

namespace scene_reading {

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

/// The path string `key` names, resolved relative to the scene file's directory.
std::string path_beside_scene(const TableReader& table, const std::string& key,
                              const Scene& scene) {
  const std::filesystem::path path = table.string(key);
  const std::filesystem::path scene_dir = std::filesystem::path(scene.file).parent_path();
  return path.is_absolute() ? path.string() : (scene_dir / path).lexically_normal().string();
}

}  // namespace scene_reading

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  toml::value tree = parse_scene_file(path);
  apply_overrides(tree, overrides);
  const TableReader root(tree, path, "", "");
  root.allow_only({"simulation", "domain", "material", "contact", "pair", "bond", "neighbor",
                   "wall", "mesh", "implement", "insert", "output", "checkpoint", "preparation",
                   "decomposition"});
  Scene scene;
  scene.file = path;
  scene.simulation = read_simulation(root);
  scene.domain = read_domain(root);
  scene.materials = read_materials(root);
  scene.contact = read_contact(root);
  scene.contact.pairs = read_pairs(root, scene.materials, scene.contact.mixing);
  scene.bonds = read_bonds(root, scene);
  scene.warnings = ignored_key_warnings(root, path, scene.contact.model);
  scene.neighbor = read_neighbor(root);
  scene.walls = read_walls(root, scene.materials);
  scene.meshes = read_meshes(root, scene);
  read_implements(root, scene);
  for (std::string& warning : mesh_angle_warnings(root, path))
    scene.warnings.push_back(std::move(warning));
  scene.sources = read_sources(root, scene);
  scene.output = read_output(root);
  if (scene.output.bonds && scene.bonds.empty())
    root.optional_table("output").fail("bonds", "the scene defines no [[bond]] table to write");
  scene.checkpoint = read_checkpoint(root);
  scene.preparation = read_preparation(root, scene.simulation.gravity);
  scene.decomposition = read_decomposition(root);
  return scene;
}

}  // namespace gpudem
