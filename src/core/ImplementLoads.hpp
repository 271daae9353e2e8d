#pragma once
/// The values of the implements' time-series columns (ForceColumns.hpp): each implement's force
/// and its torque about its reference point in the global frame, and both in the implement's
/// own frame, as for each of its meshes. The frame is forward f, up u and lateral l = u × f
/// (to the left of the travel) at t = 0, turned with the implement by R(t), the rotation by
/// ∫₀ᵗ ω of its motion; the reference point moves with the motion's centre c(t). For a force F
/// and a torque M about c(t) the frame components are
///   draft = −F·R f (positive when the soil resists the travel), vertical = F·R u,
///   lateral = F·R l, and the moments M·R f, M·R l, M·R u about the forward, lateral and up
///   axes.
/// The meshes of an implement turn about its reference point, so the diagnostics give their
/// torques about that point, and the implement's torque is their sum.
#include <vector>

#include "core/PrescribedMotion.hpp"
#include "core/Scene.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// A force and a torque in an implement's frame.
struct FrameLoads {
  double draft = 0, vertical = 0, lateral = 0;
  double moment_forward = 0, moment_lateral = 0, moment_vertical = 0;
};

/// The components of force F and torque M in the frame (forward, up) at t = 0 turned by R.
FrameLoads frame_loads(Vec3 force, Vec3 torque, const Rotation& turned, Vec3 forward, Vec3 up);

class ImplementLoads {
 public:
  explicit ImplementLoads(const Scene& scene);

  /// The values of the implements' columns of force_columns (ForceColumns.hpp) at time t from
  /// each mesh's force and torque about its centre.
  std::vector<double> row(double t, const std::vector<Vec3>& mesh_force,
                          const std::vector<Vec3>& mesh_torque) const;

 private:
  struct Implement {
    const ImplementSettings* settings;
    PrescribedMotion motion;
  };
  std::vector<Implement> implements_;
};

}  // namespace gpudem
