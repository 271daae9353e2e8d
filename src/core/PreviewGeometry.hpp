#pragma once
/// What `--preview` shows besides the particles, worked out on the host from the scene: each
/// plane wall as the polygon it cuts from the domain box, each mesh at its start and end pose,
/// and the path of each mesh's motion centre over the run.
#include <array>
#include <cstdint>
#include <vector>

#include "core/PrescribedMotion.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// Triangles over shared vertices.
struct PreviewSurface {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// The polygon in which the plane through `point` with unit `normal` cuts the box [lo, hi], as
/// a fan of triangles from its centroid, its corners in turning order about the normal; empty
/// when the plane misses the box or only touches it.
PreviewSurface wall_in_box(Vec3 point, Vec3 normal, Vec3 lo, Vec3 hi);

/// The vertices x₀ of a mesh at t = 0 moved to their pose at time t:
/// R(∫₀ᵗ ω)(x₀ − c₀) + c(t) (docs/input.md, [mesh.motion]).
std::vector<Vec3> vertices_at(const std::vector<Vec3>& start, const PrescribedMotion& motion,
                              double t);

/// The motion's centre c(t) at `samples` ≥ 2 times evenly spread over [0, end_time].
std::vector<Vec3> centre_path(const PrescribedMotion& motion, double end_time, int samples);

}  // namespace gpudem
