#pragma once
/// Rigid motion prescribed for a tool: velocity v(t) and angular velocity ω(t) piecewise
/// linear between keyframes, zero before the first keyframe and after the last (the tool
/// starts and stops there). Rotation is about a centre that moves with the tool:
/// c(t) = c₀ + ∫₀ᵗ v. A point x of the tool moves with v + ω × (x − c).
#include <string>
#include <vector>

#include "core/Rotation.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

struct MotionKeyframe {
  double time = 0;        ///< [s]
  Vec3 velocity;          ///< [m/s]
  Vec3 angular_velocity;  ///< [rad/s]
};

/// The rigid displacement of one time step: x ↦ rotation·(x − centre) + centre + translation.
struct RigidIncrement {
  Vec3 centre;       ///< rotation centre at the start of the step [m]
  Vec3 translation;  ///< ∫ v over the step [m]
  Rotation rotation;  ///< by the rotation vector ∫ ω over the step (exact for a fixed axis)
  Vec3 move(Vec3 x) const { return rotation.apply(x - centre) + centre + translation; }
};

class PrescribedMotion {
 public:
  PrescribedMotion() = default;
  /// Throws std::invalid_argument unless the keyframe times are finite and strictly
  /// increasing and every vector is finite.
  PrescribedMotion(Vec3 centre, std::vector<MotionKeyframe> keyframes);

  /// No keyframes: the tool never moves.
  bool stands_still() const { return keyframes_.empty(); }
  Vec3 velocity(double t) const;
  Vec3 angular_velocity(double t) const;
  /// ∫ v dt over [t0, t1], exact for the piecewise-linear v [m].
  Vec3 displacement(double t0, double t1) const;
  /// ∫ ω dt over [t0, t1] [rad].
  Vec3 rotation_vector(double t0, double t1) const;
  /// c(t) = c₀ + displacement(0, t) [m].
  Vec3 centre(double t) const;
  /// The motion over [t, t + dt].
  RigidIncrement increment(double t, double dt) const;

 private:
  /// ∫ over [t0, t1] of the piecewise-linear interpolation of `field` of the keyframes.
  Vec3 integral(double t0, double t1, Vec3 MotionKeyframe::*field) const;
  Vec3 value(double t, Vec3 MotionKeyframe::*field) const;

  Vec3 centre_;
  std::vector<MotionKeyframe> keyframes_;
};

}  // namespace gpudem
