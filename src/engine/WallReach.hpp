#pragma once
/// The plane walls each particle may touch before the next list build, found at each build, so
/// that a force sweep tests only those walls and a particle far from every wall costs one load.
///
/// Wall w is in the reach of particle i when it is a piston (a wall that moves) or when the
/// centre of i lies nearer to its plane than r_i + skin at the build: between builds a particle
/// moves at most skin / 2 (ParticleSystem::needs_rebuild), so a standing wall out of reach stays
/// more than skin / 2 away. The rule is the mesh candidates' (MeshCandidateList.hpp); as there, a
/// contact held past touch by cohesion stays in reach, since the scene's skin covers the largest
/// pull-off gap (SceneSetup.cpp). The build blanks the history of the walls out of reach: the
/// sweep would have found them separated and blanked it at the next step.
#include <cstddef>
#include <cstdint>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/PlaneWall.hpp"

namespace gpudem {

/// A set of plane walls as 32 bits: bit w mod 32 stands for wall w (beyond 32 walls, a bit
/// stands for every wall of its residue, so a set may hold more walls than were added).
struct WallReachBits {
  std::uint32_t bits = 0;

  GPUDEM_HD bool none() const { return bits == 0; }
  GPUDEM_HD bool holds(std::uint32_t wall) const { return ((bits >> (wall & 31u)) & 1u) != 0; }
  GPUDEM_HD void add(std::uint32_t wall) { bits |= 1u << (wall & 31u); }
};

/// reach[i]: the walls in particle i's reach at its current position (the list build's).
template <class P>
struct FindWallReach {
  const Vec4T<P>* position_radius;
  const PlaneWall* walls;
  std::uint32_t wall_count;
  WallReachBits moving;  ///< the pistons, always in reach
  Real skin;             ///< [m]
  std::uint32_t* reach;

  GPUDEM_HD void operator()(std::size_t i) const {
    const Real4 x = vec4_cast<Real>(position_radius[i]);
    WallReachBits found = moving;
    for (std::uint32_t w = 0; w < wall_count; ++w)
      if (wall_overlap(walls[w], xyz(x), x.w) > -skin) found.add(w);
    reach[i] = found.bits;
  }
};

/// Blanks particle i's history with the walls out of its reach: `width` values per (particle,
/// wall) slot i·wall_count + w.
template <class S>
struct BlankWallsOutOfReach {
  const std::uint32_t* reach;
  std::uint32_t wall_count;
  std::uint32_t width;
  S* wall_history;

  GPUDEM_HD void operator()(std::size_t i) const {
    const WallReachBits in_reach{reach[i]};
    for (std::uint32_t w = 0; w < wall_count; ++w) {
      if (in_reach.holds(w)) continue;
      S* slot = wall_history + (i * wall_count + w) * width;
      for (std::uint32_t k = 0; k < width; ++k) slot[k] = S{};
    }
  }
};

}  // namespace gpudem
