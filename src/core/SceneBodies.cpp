// Scene loading: the plane walls ([[wall]]) and triangle-mesh walls ([[mesh]]) with their
// motions.
#include "core/SceneBodies.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/ForceColumns.hpp"
#include "core/InputError.hpp"
#include "core/SceneReading.hpp"

namespace gpudem::scene_reading {
namespace {

WallSettings read_wall(const TableReader& table, std::size_t index,
                       const std::vector<Material>& materials) {
  table.allow_only({"name", "point", "normal", "material", "mass", "load"});
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
  w.mass = table.number("mass", positive("kg"), 0.0);
  w.mass_line = table.line("mass");
  if (table.has("load") && !w.loaded())
    table.fail("load", "a load moves only a wall with a mass: give the wall `mass` too");
  w.load = table.number("load", any_value("N"), 0.0);
  return w;
}

/// A motion table's keyframes: times [s], velocities [m/s] and angular velocities [rad/s]
/// (zero when absent), one per time, times strictly increasing.
std::vector<MotionKeyframe> read_keyframes(const TableReader& motion) {
  const std::vector<double> times = motion.numbers("times", any_value("s"));
  for (std::size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1]))
      motion.fail("times",
                  "keyframe times must increase strictly (index " + std::to_string(k) + ")");
  const std::vector<Vec3> v = motion.vec3s("velocities", "m/s", times.size());
  const std::vector<Vec3> w = motion.has("angular_velocities")
                                  ? motion.vec3s("angular_velocities", "rad/s", times.size())
                                  : std::vector<Vec3>(times.size());
  std::vector<MotionKeyframe> keyframes;
  for (std::size_t k = 0; k < times.size(); ++k) keyframes.push_back({times[k], v[k], w[k]});
  return keyframes;
}

/// [mesh.motion]: its keyframes (read_keyframes) about `centre`, which defaults to `offset`.
void read_motion(const TableReader& mesh, MeshSettings& m) {
  m.centre = m.placement.offset;
  if (!mesh.has("motion")) return;
  const TableReader motion = mesh.table("motion");
  motion.allow_only({"centre", "times", "velocities", "angular_velocities"});
  m.centre = motion.vec3("centre", "m", m.centre);
  m.keyframes = read_keyframes(motion);
  m.own_motion = true;
}

constexpr double kPi = 3.14159265358979323846;

/// The placement's rotation angle [rad]: `rotation_angle` in radians or `rotation_degrees` in
/// degrees, not both.
double rotation_angle(const TableReader& table) {
  if (table.has("rotation_angle") && table.has("rotation_degrees"))
    table.fail("rotation_degrees",
               "give the angle once: rotation_angle in radians or rotation_degrees in degrees");
  if (table.has("rotation_degrees"))
    return table.number("rotation_degrees", any_value("deg"), 0.0) * (kPi / 180);
  return table.number("rotation_angle", any_value("rad"), 0.0);
}

MeshSettings read_mesh(const TableReader& table, std::size_t index, const Scene& scene) {
  table.allow_only({"name", "file", "material", "scale", "offset", "rotation_axis",
                    "rotation_angle", "rotation_degrees", "motion"});
  MeshSettings m;
  m.name = table.string("name", "mesh" + std::to_string(index));
  m.file = path_beside_scene(table, "file", scene);
  m.line = table.line("file");
  m.offset_line = table.line("offset");
  m.scale_line = table.line("scale");
  m.material = table.has("material") ? material_index(table, "material", scene.materials) : 0;
  m.placement.scale = table.number("scale", positive(""), 1.0);
  m.placement.offset = table.vec3("offset", "m", Vec3{});
  m.placement.rotation_axis = table.vec3("rotation_axis", "", Vec3{0, 0, 1});
  if (!(norm(m.placement.rotation_axis) > 0)) table.fail_found("rotation_axis", "a non-zero axis");
  m.placement.rotation_angle = rotation_angle(table);
  read_motion(table, m);
  return m;
}

}  // namespace

/// The [[mesh]] tables; names label force columns, so they differ from each other and from
/// the walls' names, and name the mesh's output files (so not "bonds" beside [[bond]] tables).
std::vector<MeshSettings> read_meshes(const TableReader& root, const Scene& scene) {
  std::vector<MeshSettings> meshes;
  const std::vector<TableReader> tables = root.array_of_tables("mesh");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    MeshSettings mesh = read_mesh(tables[i], i, scene);
    if (const char* problem = mesh_output_name_problem(mesh.name, kParticlesBasename))
      tables[i].fail("name", "name '" + mesh.name + "' " + problem +
                                 "; it names the mesh's output file <name>.xmf");
    if (!scene.bonds.empty() && mesh.name == "bonds")
      tables[i].fail("name",
                     "name 'bonds' names the bonds' output file bonds.xmf in a scene "
                     "with [[bond]] tables");
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

namespace {

/// The index of the mesh named `name`, free for an implement with no motion of its own.
std::size_t implement_member(const TableReader& table, const std::string& name,
                             const Scene& scene) {
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    if (scene.meshes[m].name != name) continue;
    for (const ImplementSettings& other : scene.implements)
      for (std::size_t taken : other.meshes)
        if (taken == m)
          table.fail("meshes", "mesh '" + name + "' is already in implement '" + other.name + "'");
    if (scene.meshes[m].own_motion)
      table.fail("meshes", "mesh '" + name +
                               "' has its own [mesh.motion]; an implement's meshes move with "
                               "the implement's [implement.motion], so remove the mesh's");
    return m;
  }
  std::string known;
  for (const MeshSettings& m : scene.meshes) known += (known.empty() ? "'" : ", '") + m.name + "'";
  table.fail("meshes", "no [[mesh]] is named '" + name +
                           "' (meshes: " + (known.empty() ? "none" : known) + ")");
}

/// The implement's frame at t = 0: `up` (default against gravity, +z without it) and
/// `forward` (default the first non-zero velocity of the motion), made normal to up.
void read_frame(const TableReader& table, const Scene& scene, ImplementSettings& im) {
  const Vec3 g = scene.simulation.gravity;
  const Vec3 up = table.vec3("up", "", norm(g) > 0 ? (1 / norm(g)) * (Vec3{} - g) : Vec3{0, 0, 1});
  if (!(norm(up) > 0)) table.fail_found("up", "a non-zero direction");
  im.up = (1 / norm(up)) * up;
  Vec3 forward{};
  for (const MotionKeyframe& k : im.keyframes)
    if (norm(forward) == 0) forward = k.velocity;
  if (!table.has("forward") && norm(forward) == 0)
    table.fail("forward",
               "give the implement's travel direction: its motion has no velocity "
               "to take it from");
  const Vec3 given = table.vec3("forward", "", forward);
  const Vec3 across = given - dot(given, im.up) * im.up;
  if (!(norm(across) > 1e-6 * norm(given)))
    table.fail("forward", std::string("the travel direction (") +
                              (table.has("forward") ? "given" : "the motion's first velocity") +
                              ") must be non-zero and not along up");
  im.forward = (1 / norm(across)) * across;
}

ImplementSettings read_implement(const TableReader& table, std::size_t index, Scene& scene) {
  table.allow_only({"name", "meshes", "reference", "forward", "up", "motion"});
  ImplementSettings im;
  im.name = table.string("name", "implement" + std::to_string(index));
  for (const std::string& name : table.names("meshes"))
    im.meshes.push_back(implement_member(table, name, scene));
  im.reference = table.vec3("reference", "m");
  if (table.has("motion")) {
    const TableReader motion = table.table("motion");
    motion.allow_only({"times", "velocities", "angular_velocities"});
    im.keyframes = read_keyframes(motion);
  }
  read_frame(table, scene, im);
  return im;
}

/// The first load column of the scene named twice, or empty.
std::string repeated_column(const Scene& scene) {
  std::vector<std::string> names = force_columns(scene);
  std::sort(names.begin(), names.end());
  const auto twice = std::adjacent_find(names.begin(), names.end());
  return twice == names.end() ? std::string() : *twice;
}

}  // namespace

void read_implements(const TableReader& root, Scene& scene) {
  const std::vector<TableReader> tables = root.array_of_tables("implement");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    ImplementSettings im = read_implement(tables[i], i, scene);
    bool taken = false;
    for (const WallSettings& w : scene.walls) taken = taken || w.name == im.name;
    for (const MeshSettings& m : scene.meshes) taken = taken || m.name == im.name;
    for (const ImplementSettings& other : scene.implements) taken = taken || other.name == im.name;
    if (taken)
      tables[i].fail("name", "name '" + im.name +
                                 "' is already used by a wall, mesh or implement; names label "
                                 "the force columns");
    for (std::size_t m : im.meshes) {
      scene.meshes[m].centre = im.reference;
      scene.meshes[m].keyframes = im.keyframes;
    }
    scene.implements.push_back(std::move(im));
    if (const std::string twice = repeated_column(scene); !twice.empty())
      tables[i].fail("name", "the time series would have two columns '" + twice +
                                 "'; rename the implement or its meshes");
  }
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

std::vector<std::string> mesh_angle_warnings(const TableReader& root, const std::string& file) {
  std::vector<std::string> warnings;
  for (const TableReader& table : root.array_of_tables("mesh")) {
    if (!table.has("rotation_angle")) continue;
    const double angle = table.number("rotation_angle", any_value("rad"), 0.0);
    if (std::abs(angle) <= 2 * kPi) continue;
    warnings.push_back(InputError::compose(
        file, table.line("rotation_angle"), table.path("rotation_angle"),
        "an angle of " + four_digits(angle) +
            " rad is more than a full turn; for degrees write rotation_degrees instead"));
  }
  return warnings;
}

}  // namespace gpudem::scene_reading
