#pragma once
/// Host description of one triangle-mesh wall (a tool) for the engine: its mesh at t = 0, its
/// material and its prescribed motion. Plain data; the engine copies it to its memory space.
#include <vector>

#include "core/PrescribedMotion.hpp"
#include "core/TriangleMesh.hpp"

namespace gpudem {

struct MeshWallSetup {
  TriangleMesh mesh;
  MaterialId material = 0;
  PrescribedMotion motion;  ///< no keyframes: the mesh stands still
};

}  // namespace gpudem
