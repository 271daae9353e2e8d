#pragma once
/// Where a mesh wall is over a run (docs/input.md, "[[mesh]]"): the box of its placed triangles
/// at t = 0 and a box that holds it at every moment of the run, for the start-up report and the
/// checks that refuse a mesh that never meets the domain or is smaller than one particle.
#include <vector>

#include "core/PrescribedMotion.hpp"
#include "core/Scene.hpp"
#include "core/TriangleMesh.hpp"
#include "engine/MeshWallSetup.hpp"

namespace gpudem {

struct MeshReach {
  Vec3 start_lo, start_hi;  ///< bounding box of the placed mesh at t = 0 [m]
  Vec3 swept_lo, swept_hi;  ///< a box holding the mesh at every t in [0, end_time] [m]
};

/// The reach of `wall` (placed, at t = 0) moved by its motion (keyframes `keyframes`, rotation
/// centre c₀ = `centre`) until `end_time`. The centre's displacement d(t) is piecewise quadratic
/// (v is piecewise linear), so its range over [0, end_time] comes from d at the ends, at the
/// keyframes and where a velocity component crosses zero. A mesh that never turns sweeps its
/// start box moved by that range (exact); one that turns, the ball of radius max |x − c₀| over
/// its vertices moved by it (a bound).
MeshReach mesh_reach(const MeshWallSetup& wall, const std::vector<MotionKeyframe>& keyframes,
                     Vec3 centre, double end_time);

/// Throws InputError naming `mesh[i].offset` when mesh i's swept box misses the domain along a
/// non-periodic axis (it never meets a particle), and naming `mesh[i].scale` when its largest
/// extent is below `smallest_diameter` (a particle could not rest against it; an STL in
/// millimetres placed with scale 1 is a thousand times too large instead, which the first check
/// catches in a bin of ordinary size).
void require_meshes_meet_the_domain(const Scene& scene, const std::vector<MeshWallSetup>& meshes,
                                    double smallest_diameter);

}  // namespace gpudem
