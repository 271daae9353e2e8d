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

/// One [[bond]] table.
BondSettings read_bond(const TableReader& table, const std::vector<Material>& materials,
                       const DomainSettings& domain) {
  table.allow_only({"materials", "gap", "young", "poisson", "radius_factor", "tensile_strength",
                    "shear_strength", "damping_ratio", "clods"});
  BondSettings b;
  const std::vector<std::string> names = table.strings("materials", 2);
  b.a = material_named(table, "materials", names[0], materials);
  b.b = material_named(table, "materials", names[1], materials);
  b.gap = table.number("gap", non_negative("m"), b.gap);
  b.young = table.number("young", positive("Pa"));
  b.poisson = table.number("poisson", interval(-1, true, 0.5, true), b.poisson);
  b.radius_factor = table.number("radius_factor", positive(), b.radius_factor);
  b.tensile_strength = table.number("tensile_strength", positive("Pa"), b.tensile_strength);
  b.shear_strength = table.number("shear_strength", positive("Pa"), b.shear_strength);
  b.damping_ratio = table.number("damping_ratio", non_negative(), b.damping_ratio);
  b.clods = read_clods(table, domain);
  return b;
}

}  // namespace

std::vector<BondSettings> read_bonds(const TableReader& root, const Scene& scene) {
  std::vector<BondSettings> bonds;
  for (const TableReader& table : root.array_of_tables("bond"))
    bonds.push_back(read_bond(table, scene.materials, scene.domain));
  return bonds;
}

}  // namespace gpudem::scene_reading
