#pragma once
/// Infinite plane wall: contact geometry for a sphere, the wall acting as infinite mass and
/// infinite radius (m* = m_i, the lever arm on the sphere is r − δ/2). A piston's wall moves
/// (WallPistons.hpp); the others stand still.
#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

struct PlaneWall {
  Vec3 point;   ///< any point of the plane [m]
  Vec3 normal;  ///< unit normal pointing into the particles' side
  MaterialId material = 0;
  Vec3 velocity;  ///< of the plane [m/s] (a piston's; zero for a wall that stands still)
};

/// Overlap of a sphere (centre x, radius r) with the wall: δ = r − (x − p)·n; ≤ 0 means no contact.
GPUDEM_HD inline Real wall_overlap(const PlaneWall& w, Vec3 x, Real r) {
  return r - dot(x - w.point, w.normal);
}

}  // namespace gpudem
