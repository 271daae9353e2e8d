// Checkpoint and scene: the checks that a checkpoint fits the scene that continues it.
#include <cmath>
#include <string>
#include <vector>

#include "comm/Checkpoint.hpp"
#include "core/ContactModel.hpp"
#include "core/ExactDecimal.hpp"
#include "core/InputError.hpp"
#include "core/contact/ParallelBond.hpp"

namespace gpudem {
namespace {

/// The index of the scene's material named `name`; the material count when there is none.
std::size_t material_index_by_name(const Scene& scene, const std::string& name) {
  std::size_t k = 0;
  while (k < scene.materials.size() && scene.materials[k].name != name) ++k;
  return k;
}

/// The scene's material names, quoted and separated by commas.
std::string material_list(const Scene& scene) {
  std::string list;
  for (const Material& m : scene.materials) list += (list.empty() ? "'" : ", '") + m.name + "'";
  return list;
}

/// Refuses bonds the scene's [[bond]] tables cannot continue (require_bond_tables), and
/// tables without bonds, which make bonds only when a run starts.
void check_bonds_fit(const Checkpoint& c, const std::string& path, const Scene& scene) {
  require_bond_tables(c, path, scene);
  if (c.bonds.width == 0 && !scene.bonds.empty())
    throw InputError(path, 0, "",
                     "holds no bonds but the scene defines [[bond]] tables, which make bonds only "
                     "when a run starts from its sources: restart without them, or start anew");
}

}  // namespace

void require_bond_tables(const Checkpoint& c, const std::string& path, const Scene& scene) {
  const bool bonded = c.bonds.width > 0 && (c.bonds_made > 0 || !c.bonds.pair_owner.empty());
  if (bonded && scene.bonds.empty())
    throw InputError(path, 0, "",
                     "holds parallel bonds but the scene defines no [[bond]] table: a run "
                     "continues with the bonds it was saved with");
  for (std::size_t k = 0; k < c.bonds.pair_owner.size(); ++k) {
    const Real type = c.bonds.pair_values[k * c.bonds.width + bond_value::type];
    if (!(type >= 0 && type < Real(scene.bonds.size()) && type == std::floor(type)))
      throw InputError(path, 0, "",
                       "the bond of particles " + std::to_string(c.bonds.pair_owner[k]) + " and " +
                           std::to_string(c.bonds.pair_partner[k]) + " is of [[bond]] table " +
                           exact_decimal(type) + " but the scene defines " +
                           std::to_string(scene.bonds.size()));
  }
}

void map_materials_by_name(Checkpoint& c, const std::string& path, const Scene& scene) {
  if (c.material_names.empty()) return;  // a file from before the names: by index
  std::vector<MaterialId> to_scene(c.material_names.size());
  for (std::size_t k = 0; k < to_scene.size(); ++k)
    to_scene[k] = static_cast<MaterialId>(material_index_by_name(scene, c.material_names[k]));
  ParticleStore& p = c.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const MaterialId m = p.material[i];
    if (m >= to_scene.size())
      throw InputError(path, 0, "",
                       "particle id " + std::to_string(p.id[i]) + " has material index " +
                           std::to_string(m) + " but the file names " +
                           std::to_string(to_scene.size()) + " material(s)");
    if (to_scene[m] == scene.materials.size())
      throw InputError(path, 0, "",
                       "its particles are of material '" + c.material_names[m] +
                           "', which the scene " + scene.file + " does not define (it defines " +
                           material_list(scene) + "); add a [[material]] of that name");
    p.material[i] = to_scene[m];
  }
}

void fit_checkpoint_to_scene(Checkpoint& c, const std::string& path, const Scene& scene) {
  map_materials_by_name(c, path, scene);
  const ParticleStore& p = c.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.material[i] >= scene.materials.size())
      throw InputError(path, 0, "",
                       "particle id " + std::to_string(p.id[i]) + " has material index " +
                           std::to_string(p.material[i]) + " but the scene defines " +
                           std::to_string(scene.materials.size()) + " material(s)");
  for (const std::uint32_t wall : c.history.wall_index)
    if (wall >= scene.walls.size())
      throw InputError(path, 0, "",
                       "contact history names wall index " + std::to_string(wall) +
                           " but the scene defines " + std::to_string(scene.walls.size()) +
                           " wall(s)");
  if (!c.wall_motion.empty() && c.wall_motion.size() != scene.walls.size())
    throw InputError(path, 0, "",
                     "holds the motion of " + std::to_string(c.wall_motion.size()) +
                         " wall(s) but the scene defines " + std::to_string(scene.walls.size()) +
                         " wall(s): a run continues with the walls it was saved with");
  if (!c.history.mesh_owner.empty() && scene.meshes.empty())
    throw InputError(path, 0, "",
                     "contact history holds particle-mesh contacts (particle id " +
                         std::to_string(c.history.mesh_owner.front()) + " with triangle " +
                         std::to_string(c.history.mesh_triangle.front()) +
                         ") but the scene defines no mesh");
  check_bonds_fit(c, path, scene);
  const std::uint32_t width = contact_history_width(scene.contact.model);
  if (c.history.width != width)
    throw InputError(path, 0, "",
                     "contact history of " + std::to_string(c.history.width) +
                         " values per contact, but the scene's contact law keeps " +
                         std::to_string(width) +
                         " (tangential linear_history or mindlin: 4, rolling epsd: 3): the "
                         "checkpoint was written with another contact law");
}

}  // namespace gpudem
