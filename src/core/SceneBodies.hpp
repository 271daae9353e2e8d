#pragma once
/// The [[wall]] and [[mesh]] tables of a scene (SceneBodies.cpp).
#include <vector>

#include "core/Scene.hpp"
#include "core/TomlReader.hpp"

namespace gpudem::scene_reading {

/// Every [[mesh]] table of `root`: its STL file (beside the scene), placement, material and
/// motion.
std::vector<MeshSettings> read_meshes(const TableReader& root, const Scene& scene);

/// Every [[wall]] table of `root`; names must differ (they label the force columns).
std::vector<WallSettings> read_walls(const TableReader& root,
                                     const std::vector<Material>& materials);

}  // namespace gpudem::scene_reading
