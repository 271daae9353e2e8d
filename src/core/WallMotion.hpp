#pragma once
/// The state of a plane wall that slides along its normal (a piston, docs/input.md `[[wall]]`),
/// as a checkpoint keeps it: all zero for a wall that stands still.
namespace gpudem {

struct WallMotion {
  double displacement = 0;  ///< [m] along the normal from the wall's point at t = 0
  double velocity = 0;      ///< [m/s] along the normal
  double push = 0;          ///< [N] the particles' force against the wall at the last step
};

}  // namespace gpudem
