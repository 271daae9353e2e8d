#pragma once
/// The [[wall]] and [[mesh]] tables of a scene (SceneBodies.cpp).
#include <string>
#include <vector>

#include "core/Scene.hpp"
#include "core/TomlReader.hpp"

namespace gpudem::scene_reading {

/// Every [[mesh]] table of `root`: its STL file (beside the scene), placement, material and
/// motion.
std::vector<MeshSettings> read_meshes(const TableReader& root, const Scene& scene);

/// The [[implement]] tables (after the meshes): each names its meshes, which then move with the
/// implement's motion about its reference point (set in `scene.meshes`).
void read_implements(const TableReader& root, Scene& scene);

/// A warning for each [[mesh]] whose rotation_angle exceeds a full turn (2π rad): degrees given
/// in radians' place, most likely; the angle stays as given.
std::vector<std::string> mesh_angle_warnings(const TableReader& root, const std::string& file);

/// Every [[wall]] table of `root`; names must differ (they label the force columns).
std::vector<WallSettings> read_walls(const TableReader& root,
                                     const std::vector<Material>& materials);

}  // namespace gpudem::scene_reading
