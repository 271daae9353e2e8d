/// The [[bond]] tables of a scene (Scene::bonds; docs/input.md, "Bonds").
#include <string>
#include <vector>

#include "core/SceneReading.hpp"

namespace gpudem::scene_reading {

namespace {

/// `clods` of a [[bond]] table: their count, radius and the region of their centres (the
/// domain when absent).
ClodSettings read_clods(const TableReader& bond, const DomainSettings& domain) {
  ClodSettings c;
  if (!bond.has("clods")) return c;
  const TableReader table = bond.table("clods");
  table.allow_only({"count", "radius", "region"});
  c.count = static_cast<std::uint64_t>(table.integer("count", positive()));
  c.radius = read_radius(table);
  c.region_min = domain.min;
  c.region_max = domain.max;
  if (table.has("region")) {
    const TableReader region = table.table("region");
    region.allow_only({"min", "max"});
    c.region_min = region.vec3("min", "m");
    c.region_max = region.vec3("max", "m");
    require_extent(region, "max", c.region_min, c.region_max, "the clods' region is empty");
  }
  return c;
}

/// The materials of a [[bond]] table; a table with `pairs` takes none (nor gap or clods).
void read_bond_members(const TableReader& table, const Scene& scene, BondSettings& b) {
  if (table.has("pairs")) {
    for (const char* key : {"materials", "gap", "clods"})
      if (table.has(key))
        table.fail(key, std::string("a [[bond]] table with pairs bonds exactly the listed pairs "
                                    "and takes no ") +
                            key);
    b.pairs = path_beside_scene(table, "pairs", scene);
    return;
  }
  const std::vector<std::string> names = table.strings("materials", 2);
  b.a = material_named(table, "materials", names[0], scene.materials);
  b.b = material_named(table, "materials", names[1], scene.materials);
  b.gap = table.number("gap", non_negative("m"), b.gap);
  b.clods = read_clods(table, scene.domain);
}

/// One [[bond]] table.
BondSettings read_bond(const TableReader& table, const Scene& scene) {
  table.allow_only({"materials", "gap", "young", "poisson", "radius_factor", "tensile_strength",
                    "shear_strength", "damping_ratio", "clods", "pairs"});
  BondSettings b;
  read_bond_members(table, scene, b);
  b.young = table.number("young", positive("Pa"));
  b.poisson = table.number("poisson", interval(-1, true, 0.5, true), b.poisson);
  b.radius_factor = table.number("radius_factor", positive(), b.radius_factor);
  b.tensile_strength = table.number("tensile_strength", positive("Pa"), b.tensile_strength);
  b.shear_strength = table.number("shear_strength", positive("Pa"), b.shear_strength);
  b.damping_ratio = table.number("damping_ratio", non_negative(), b.damping_ratio);
  return b;
}

}  // namespace

std::vector<BondSettings> read_bonds(const TableReader& root, const Scene& scene) {
  std::vector<BondSettings> bonds;
  for (const TableReader& table : root.array_of_tables("bond"))
    bonds.push_back(read_bond(table, scene));
  return bonds;
}

}  // namespace gpudem::scene_reading
