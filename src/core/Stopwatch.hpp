#pragma once
/// Wall-clock laps on the steady clock, for the time split of a run.
#include <chrono>

namespace gpudem {

class Stopwatch {
 public:
  /// Seconds since the last lap (or since construction).
  double lap() {
    const Clock::time_point now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_ = Clock::now();
};

}  // namespace gpudem
