#pragma once
/// The plane walls that slide (pistons, docs/input.md `[[wall]]`): a wall of mass M moves along
/// its unit normal n, which points into the particles, under its load P (along n), its weight
/// and the particles' push F (the normal force they exert on it, F > 0 pressing it back):
///   M du/dt = P + M g·n − F,   ds/dt = u,   wall point p(t) = p₀ + s n, wall velocity u n,
/// integrated with the particles' scheme (a kick by h: u += h (P + M g·n − F)/M; a drift by dt:
/// s += dt u). The contact law treats a piston like a fixed wall, infinitely heavier than the
/// particle it touches (the scene is refused when the piston is lighter than a layer of the
/// largest particles against it), and sees the wall's velocity.
///
/// The push is summed over the particles in whole multiples of a unit, a power of two near
/// 2^-32 (P + M|g|), rounded per particle: a sum of integers held in doubles is exact in any
/// order, so it is the same on any number of ranks and threads (while the pushes' magnitudes add
/// up to less than 2^53 units, about 2^20 (P + M|g|)).
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "core/WallMotion.hpp"
#include "engine/PlaneWall.hpp"

namespace gpudem {

/// A plane wall that slides: its index among the walls, its mass and its load.
struct PistonSetup {
  std::uint32_t wall = 0;
  double mass = 0;  ///< [kg] > 0
  double load = 0;  ///< [N] along the wall's normal
};

/// The push units of particle i on wall `wall`: its push (per (particle, wall) slot
/// i·wall_count + wall) divided by the unit and rounded to an integer.
template <class S>
struct PushUnits {
  const S* push;
  std::uint32_t wall_count;
  std::uint32_t wall;
  Real unit;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return rint(Real(push[i * wall_count + wall]) / unit);
  }
};

class WallPistons {
 public:
  WallPistons() = default;
  WallPistons(const std::vector<PlaneWall>& walls, const std::vector<PistonSetup>& pistons,
              Vec3 gravity)
      : walls_(walls), start_(walls), pistons_(pistons), motion_(walls.size()) {
    for (const PistonSetup& p : pistons_) {
      const double drive = std::fabs(p.load) + p.mass * norm(gravity);
      unit_.push_back(std::ldexp(1.0, std::ilogb(drive > 0 ? drive : 1.0) - 32));
      drive_.push_back(p.load + p.mass * dot(gravity, walls[p.wall].normal));
    }
  }

  bool empty() const { return pistons_.empty(); }
  std::size_t count() const { return pistons_.size(); }
  const PistonSetup& piston(std::size_t k) const { return pistons_[k]; }
  /// The unit in which piston k's push is summed [N].
  Real push_unit(std::size_t k) const { return unit_[k]; }

  /// Every wall at its current position and velocity.
  const std::vector<PlaneWall>& walls() const { return walls_; }
  /// Every wall's motion (zero for the walls that stand still).
  const std::vector<WallMotion>& motion() const { return motion_; }
  /// Continues from a saved motion of every wall.
  void set_motion(const std::vector<WallMotion>& motion) {
    for (const PistonSetup& p : pistons_) motion_[p.wall] = motion[p.wall];
    place();
  }

  /// The particles' push on piston k, summed over all ranks in its units [N].
  void set_push_units(std::size_t k, Real units) {
    motion_[pistons_[k].wall].push = units * unit_[k];
  }

  /// u += h (P + M g·n − F) / M.
  void kick(Real h) {
    for (std::size_t k = 0; k < pistons_.size(); ++k) {
      WallMotion& m = motion_[pistons_[k].wall];
      m.velocity += h * (drive_[k] - m.push) / pistons_[k].mass;
    }
  }
  /// s += dt u, and the walls moved there.
  void drift(Real dt) {
    for (const PistonSetup& p : pistons_) {
      WallMotion& m = motion_[p.wall];
      m.displacement += dt * m.velocity;
    }
    place();
  }

 private:
  void place() {
    for (const PistonSetup& p : pistons_) {
      const WallMotion& m = motion_[p.wall];
      const Vec3 n = start_[p.wall].normal;
      walls_[p.wall].point = start_[p.wall].point + m.displacement * n;
      walls_[p.wall].velocity = m.velocity * n;
    }
  }

  std::vector<PlaneWall> walls_;
  std::vector<PlaneWall> start_;  ///< at t = 0
  std::vector<PistonSetup> pistons_;
  std::vector<WallMotion> motion_;  ///< per wall
  std::vector<Real> unit_;          ///< per piston [N]
  std::vector<Real> drive_;         ///< per piston: P + M g·n [N]
};

}  // namespace gpudem
