/// The [[bond]] tables of a scene (Scene::bonds; docs/input.md, "Bonds").
#include <string>
#include <vector>

#include "core/SceneReading.hpp"

namespace gpudem::scene_reading {

namespace {

/// One [[bond]] table.
BondSettings read_bond(const TableReader& table, const std::vector<Material>& materials) {
  table.allow_only({"materials", "gap", "young", "poisson", "radius_factor", "tensile_strength",
                    "shear_strength", "damping_ratio"});
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
  return b;
}

}  // namespace

std::vector<BondSettings> read_bonds(const TableReader& root,
                                     const std::vector<Material>& materials) {
  std::vector<BondSettings> bonds;
  for (const TableReader& table : root.array_of_tables("bond"))
    bonds.push_back(read_bond(table, materials));
  return bonds;
}

}  // namespace gpudem::scene_reading
