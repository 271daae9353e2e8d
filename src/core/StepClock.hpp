#pragma once
/// A point of a run's time grid. The run advances by base steps of dt; with dt = "adaptive" a
/// base step may be split into `substeps` equal steps of dt / substeps (docs/input.md, "Time
/// step"), so a point is a base step plus a count of substeps into the next one. Its time is
/// always computed by the one expression of time(), so that a restart poses the meshes at the
/// same time, bit for bit, as the run that saved it.
#include <cstdint>

namespace gpudem {

/// The most substeps a base step is split into.
constexpr std::uint32_t kMaxSubsteps = 1024;

struct StepClock {
  std::uint64_t step = 0;      ///< base steps done
  std::uint32_t substep = 0;   ///< substeps done of the base step in progress, < substeps
  std::uint32_t substeps = 1;  ///< substeps of the base step in progress

  /// step·dt + substep·(dt / substeps) [s]: exactly step·dt between base steps.
  double time(double dt) const {
    return substep == 0 ? double(step) * dt : double(step) * dt + substep * (dt / substeps);
  }
  /// One substep on; a base step ends after `substeps` of them.
  void advance() {
    if (++substep < substeps) return;
    substep = 0;
    ++step;
  }
};

}  // namespace gpudem
