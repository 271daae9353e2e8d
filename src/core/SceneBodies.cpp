// Scene loading: the plane walls ([[wall]]) and triangle-mesh walls ([[mesh]]) with their
// motions.
#include "core/SceneBodies.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/InputError.hpp"
#include "core/SceneReading.hpp"

namespace gpudem::scene_reading {
namespace {

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
