#pragma once
/// The time-series columns of the bodies' loads (docs/input.md, timeseries.csv): per wall its
/// force `<wall>_fx` … `_fz`; per piston (a wall with a mass) its displacement along its
/// normal and its velocity, `<wall>_displacement`, `<wall>_velocity`; per mesh its force and torque
/// `<mesh>_fx` … `_tz`; per implement its force and torque `<implement>_fx` … `_tz`, then its loads
/// in its own frame (kFrameColumns), then those of each of its meshes.
#include <string>
#include <vector>

#include "core/Scene.hpp"

namespace gpudem {

inline constexpr const char* kForceColumns[] = {"_fx", "_fy", "_fz"};
inline constexpr const char* kPistonColumns[] = {"_displacement", "_velocity"};
inline constexpr const char* kForceTorqueColumns[] = {"_fx", "_fy", "_fz", "_tx", "_ty", "_tz"};
inline constexpr const char* kFrameColumns[] = {"_draft",     "_vertical",  "_lateral",
                                                "_m_forward", "_m_lateral", "_m_vertical"};

/// The load columns of the scene's walls, meshes and implements, in time-series order.
inline std::vector<std::string> force_columns(const Scene& scene) {
  std::vector<std::string> c;
  for (const WallSettings& w : scene.walls)
    for (const char* suffix : kForceColumns) c.push_back(w.name + suffix);
  for (const WallSettings& w : scene.walls)
    if (w.loaded())
      for (const char* suffix : kPistonColumns) c.push_back(w.name + suffix);
  for (const MeshSettings& m : scene.meshes)
    for (const char* suffix : kForceTorqueColumns) c.push_back(m.name + suffix);
  for (const ImplementSettings& im : scene.implements) {
    for (const char* suffix : kForceTorqueColumns) c.push_back(im.name + suffix);
    for (const char* suffix : kFrameColumns) c.push_back(im.name + suffix);
    for (std::size_t m : im.meshes)
      for (const char* suffix : kFrameColumns) c.push_back(scene.meshes[m].name + suffix);
  }
  return c;
}

}  // namespace gpudem
