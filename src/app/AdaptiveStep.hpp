#pragma once
/// dt = "adaptive" (docs/input.md, "Time step"): each base step dt₀ is split into k = 2^j
/// substeps so that the fastest thing in the scene moves at most the reach per substep,
///   (v + v_tool) dt₀ / k ≤ reach,   reach = displacement_fraction × r_min,
/// with v the fastest particle or piston at the start of the base step and v_tool the fastest
/// point of any mesh over the run. k grows as soon as that requires; it shrinks only as far as
/// keeps the move within half the reach, so it does not flip between two values from one base
/// step to the next. k depends only on the state and the previous k, so a restart that
/// continues with the saved k chooses as the straight run does.
#include <cstdint>

#include "core/StepClock.hpp"

namespace gpudem {

class AdaptiveStep {
 public:
  /// `base_dt` dt₀ [s], `reach` [m], `tool_speed` v_tool [m/s]; `substeps` k of the last base
  /// step (1 for a new run, the checkpoint's on a restart).
  AdaptiveStep(double base_dt, double reach, double tool_speed, std::uint32_t substeps)
      : base_dt_(base_dt), reach_(reach), tool_speed_(tool_speed), substeps_(substeps) {}

  /// The substeps of the next base step, the fastest particle or piston moving at `speed`.
  std::uint32_t next(double speed) {
    const double travel = (speed + tool_speed_) * base_dt_;
    const std::uint32_t needed = within(travel, reach_);
    if (needed > substeps_) {
      substeps_ = needed;
    } else {
      const std::uint32_t relaxed = within(travel, 0.5 * reach_);
      if (relaxed < substeps_) substeps_ = relaxed;
    }
    return substeps_;
  }

  std::uint32_t substeps() const { return substeps_; }

 private:
  /// The least power of two k with travel / k ≤ reach, at most kMaxSubsteps.
  static std::uint32_t within(double travel, double reach) {
    std::uint32_t k = 1;
    while (k < kMaxSubsteps && travel > reach * k) k *= 2;
    return k;
  }

  double base_dt_;
  double reach_;
  double tool_speed_;
  std::uint32_t substeps_;
};

}  // namespace gpudem
