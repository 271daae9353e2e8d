#pragma once
/// The time loop of a run: steps the engine, checks its health, and writes the time series,
/// snapshots and checkpoints on their schedules; reports the time split at the end.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/AdaptiveStep.hpp"
#include "app/LoadBalance.hpp"
#include "app/Progress.hpp"
#include "app/Runner.hpp"
#include "comm/Checkpoint.hpp"
#include "comm/MpiContext.hpp"
#include "comm/SnapshotQueue.hpp"
#include "comm/TimeSeriesWriter.hpp"
#include "core/ImplementLoads.hpp"
#include "core/Scene.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

struct SettleCheck;

/// Steps to reach end_time: ⌈end_time / dt⌉.
std::uint64_t step_count(double end_time, double dt);

/// Where the time loop starts: step 0 of a new run, or a checkpoint's step with the snapshot
/// series written up to it.
struct LoopStart {
  std::uint64_t step = 0;
  bool resumed = false;
  std::vector<XdmfSnapshot> snapshots;
};

/// The time loop with its output and checkpoint schedule, by base steps of setup.dt. With a
/// settle check (a bed preparation) it stops at the first settled time-series row, after that
/// step's snapshot and checkpoint. With an AdaptiveStep (dt = "adaptive") each base step is
/// split into the substeps it chooses.
class TimeLoop {
 public:
  TimeLoop(const Scene& scene, const MpiContext& mpi, StepEngine& engine, const EngineSetup& setup,
           const LoadBalance& balance, bool quiet, const LoopStart& start,
           const SettleCheck* settle, std::optional<AdaptiveStep> adaptive);

  int run();

  /// The step at which the bed settled; none when it did not or nothing was checked.
  std::optional<std::uint64_t> settled_step() const { return settled_step_; }

  /// Everything the step needs to be continued bit-for-bit (Checkpoint.hpp).
  Checkpoint capture(std::uint64_t step) const;

 private:
  int finish(std::uint64_t step);

  /// One base step: its substeps chosen (dt = "adaptive"), then stepped.
  void advance_base_step();

  /// The step of the last base step: dt / substeps [s].
  double step_dt() const { return adaptive_ ? dt_ / adaptive_->substeps() : dt_; }

  /// The time split of the run, slowest rank per part, and the mean halo bytes a rank sent
  /// per ghost refresh (printed by rank 0 unless quiet); the snapshot writes count in output
  /// when the time loop made them and apart when a writer thread did. Collective.
  void report_times() const;

  /// The time the writer thread spent on snapshots while the run stepped on, for the time split.
  std::string writer_thread_note(double seconds) const;

  /// Writes the step's time-series row when one is due (returning its diagnostics) and its
  /// snapshot when asked; the time it takes counts as output.
  std::optional<Diagnostics> record(std::uint64_t step, bool snapshot);

  /// record, unclocked.
  std::optional<Diagnostics> record_row(std::uint64_t step, bool snapshot);

  /// Stages a snapshot of the particles, written (after checking that no particle was lost or
  /// duplicated between ranks) while the next steps run (SnapshotQueue.hpp).
  void write_snapshot(double time, std::uint64_t step) { snapshots_.write(engine_, time, step); }

  /// Waits until the snapshots are written; the wait counts as output.
  void wait_for_snapshots();

  /// Written after the step's snapshot so that the snapshot table includes it.
  void checkpoint(std::uint64_t step);

  int stop_unstable(std::uint64_t step, const HealthFailure& f);

  static std::string describe(const HealthFailure& f);

  const Scene& scene_;
  const MpiContext& mpi_;
  StepEngine& engine_;
  const LoadBalance& balance_;
  double dt_;
  double skin_;
  ExactUnits sum_units_;  ///< of the host's integer sums, recorded in checkpoints
  std::uint64_t first_step_;
  std::uint64_t first_list_builds_;  ///< the engine's list builds before the first step
  std::uint64_t total_steps_;
  std::uint64_t snapshot_every_;
  std::uint64_t series_every_;
  std::uint64_t checkpoint_every_;  ///< 0: no checkpoints
  SnapshotQueue snapshots_;
  ImplementLoads implement_loads_;
  TimeSeriesWriter series_;
  Progress progress_;
  bool quiet_;
  bool resumed_;
  const SettleCheck* settle_;             ///< null: run to end_time
  std::optional<AdaptiveStep> adaptive_;  ///< none: one step per base step
  std::uint64_t substeps_done_ = 0;       ///< steps of the split base steps so far
  std::optional<std::uint64_t> settled_step_;
  bool removal_reported_ = false;  ///< the first removal was warned of
  double imbalance_ = 1;           ///< at the last time-series row
  double output_seconds_ = 0;      ///< time series, snapshots and checkpoints [s]
};

}  // namespace gpudem
