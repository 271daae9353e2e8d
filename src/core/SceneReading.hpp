#pragma once
/// Readers the scene loader (SceneLoader.cpp) and its [[source]] reader (SceneSources.cpp)
/// share.
#include <algorithm>
#include <string>
#include <vector>

#include "core/Scene.hpp"
#include "core/TomlReader.hpp"

namespace gpudem::scene_reading {

/// Fails on `key` with "`what`: ..." unless max > min on every axis.
void require_extent(const TableReader& table, const std::string& key, Vec3 min, Vec3 max,
                    const std::string& what);

/// Index of the material called `name`, given by `key`.
MaterialId material_named(const TableReader& table, const std::string& key, const std::string& name,
                          const std::vector<Material>& materials);

/// Index of the material named by string `key`.
MaterialId material_index(const TableReader& table, const std::string& key,
                          const std::vector<Material>& materials);

/// The path string `key` names, resolved relative to the scene file's directory.
std::string path_beside_scene(const TableReader& table, const std::string& key, const Scene& scene);

/// `radius` of `table`: a number (every particle the same) or a distribution table
/// (SceneSources.cpp).
RadiusDistribution read_radius(const TableReader& table);

/// The [[bond]] tables (SceneBonds.cpp).
std::vector<BondSettings> read_bonds(const TableReader& root, const Scene& scene);

/// The enum value whose name (in `names`, enum order) `key` gives, or `fallback` when absent.
template <class Enum>
Enum named_choice(const TableReader& table, const std::string& key,
                  const std::vector<std::string>& names, Enum fallback) {
  const std::string name = table.choice(key, names, names[static_cast<std::size_t>(fallback)]);
  return static_cast<Enum>(std::find(names.begin(), names.end(), name) - names.begin());
}

}  // namespace gpudem::scene_reading
