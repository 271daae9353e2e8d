#pragma once
/// Rank 0's progress line: simulated time, step, steps/s, particle-steps/s, ETA, the particles
/// removed so far (when any were) and, on several ranks, the load imbalance, printed at most
/// once per `interval` seconds of wall time.
#include <chrono>
#include <cstdint>
#include <cstdio>

namespace gpudem {

class Progress {
 public:
  /// `first_step`: the step the run starts from (a restart's checkpoint step).
  Progress(bool enabled, double interval_s, std::uint64_t total_steps, std::uint64_t first_step = 0)
      : enabled_(enabled),
        interval_(interval_s),
        total_(total_steps),
        start_(Clock::now()),
        last_(start_),
        last_step_(first_step) {}

  /// Prints when the interval has passed or `force` is set. removed: particles that left the
  /// domain since the run began (shown when any did); imbalance: max/mean work over the ranks
  /// (shown when above 1).
  void update(double time, std::uint64_t step, std::size_t particles, std::uint64_t removed,
              double imbalance, bool force = false) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (!force && seconds(last_, now) < interval_) return;
    const double since_last = seconds(last_, now);
    const double rate = since_last > 0 ? (step - last_step_) / since_last : 0;
    const double elapsed = seconds(start_, now);
    const double eta = rate > 0 ? (total_ - step) / rate : 0;
    std::printf(
        "t = %.6g s  step %llu/%llu  %.4g steps/s  %.4g particle-steps/s  "
        "elapsed %.1f s  ETA %.1f s",
        time, static_cast<unsigned long long>(step), static_cast<unsigned long long>(total_), rate,
        rate * static_cast<double>(particles), elapsed, eta);
    if (removed > 0) std::printf("  removed %llu", static_cast<unsigned long long>(removed));
    if (imbalance > 1) std::printf("  imbalance %.3f", imbalance);
    std::printf("\n");
    std::fflush(stdout);
    last_ = now;
    last_step_ = step;
  }

  double elapsed() const { return seconds(start_, Clock::now()); }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  }
  bool enabled_;
  double interval_;
  std::uint64_t total_;
  Clock::time_point start_;
  Clock::time_point last_;
  std::uint64_t last_step_;
};

}  // namespace gpudem
