#include "app/Runner.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "app/BedPreparation.hpp"
#include "app/DomainSetup.hpp"
#include "app/LoadBalance.hpp"
#include "app/MemoryReport.hpp"
#include "app/Progress.hpp"
#include "app/Resume.hpp"
#include "app/ThreadCores.hpp"
#include "comm/Checkpoint.hpp"
#include "comm/OutputDirectory.hpp"
#include "comm/SnapshotQueue.hpp"
#include "comm/StartParts.hpp"
#include "comm/StartupShares.hpp"
#include "comm/TimeSeriesWriter.hpp"
#include "core/ExactDecimal.hpp"
#include "core/InputError.hpp"
#include "core/ParticleSources.hpp"
#include "core/RowShare.hpp"
#include "core/SceneLoader.hpp"
#include "core/SceneSetup.hpp"
#include "core/Stopwatch.hpp"
#include "kernels/CudaMemory.hpp"

namespace gpudem {

namespace {

/// Overlap beyond this fraction of the smaller radius stops the run.
constexpr double kOverlapLimit = 0.5;
/// Seconds of wall time between progress lines.
constexpr double kProgressInterval = 2.0;

/// A CUDA engine on this rank's GPU: node-local rank modulo the visible devices, so the ranks
/// of a node spread over its GPUs (several ranks may share one).
std::unique_ptr<StepEngine> make_cuda_engine_on_node(const MpiContext& mpi,
                                                     const EngineSetup& setup) {
  cuda::select_device(mpi.local_rank() % cuda::device_count());
  return make_cuda_engine(setup);
}

/// Whether every rank sees a CUDA device, so that all ranks choose the same backend (they run
/// the same collectives only then). Collective.
bool every_rank_sees_a_device(const MpiContext& mpi) {
  int here = cuda::device_count() > 0 ? 1 : 0, everywhere = 0;
  MPI_Allreduce(&here, &everywhere, 1, MPI_INT, MPI_MIN, mpi.comm());
  return everywhere == 1;
}

/// The engine of the chosen backend; `auto` is CUDA when every rank sees a device. Collective
/// unless the choice is the host (every rank has the same choice).
std::unique_ptr<StepEngine> make_engine(BackendChoice choice, const MpiContext& mpi,
                                        const EngineSetup& setup) {
  if (choice == BackendChoice::Host) return make_host_engine(setup);
  if (choice == BackendChoice::Cuda && !cuda::compiled_in())
    throw InputError("", 0, "--backend", "cuda requested but this build has no CUDA backend");
  const bool devices = every_rank_sees_a_device(mpi);
  if (choice == BackendChoice::Cuda && !devices)
    throw InputError("", 0, "--backend",
                     mpi.size() > 1 ? "cuda requested but no CUDA device is visible on some rank"
                                    : "cuda requested but no CUDA device is visible");
  return devices ? make_cuda_engine_on_node(mpi, setup) : make_host_engine(setup);
}

/// Steps between two events `every` seconds apart (at least 1).
std::uint64_t steps_between(double every, double dt) {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(every / dt)));
}

/// Steps to reach end_time: ⌈end_time / dt⌉.
std::uint64_t step_count(double end_time, double dt) {
  return static_cast<std::uint64_t>(std::ceil(end_time / dt - 1e-9));
}

std::vector<std::string> timeseries_columns(const Scene& scene) {
  std::vector<std::string> c = {"time",
                                "step",
                                "particles",
                                "contacts",
                                "kinetic_translational",
                                "kinetic_rotational",
                                "potential_gravity",
                                "potential_elastic",
                                "max_overlap_ratio",
                                "removed",
                                "imbalance"};
  for (const WallSettings& w : scene.walls)
    for (const char* axis_name : {"fx", "fy", "fz"}) c.push_back(w.name + "_" + axis_name);
  for (const MeshSettings& m : scene.meshes)
    for (const char* axis_name : {"fx", "fy", "fz", "tx", "ty", "tz"})
      c.push_back(m.name + "_" + axis_name);
  return c;
}

std::vector<double> timeseries_row(double time, std::uint64_t step, const Diagnostics& d,
                                   std::uint64_t removed, double imbalance) {
  std::vector<double> row = {time,
                             static_cast<double>(step),
                             static_cast<double>(d.particle_count),
                             static_cast<double>(d.contact_count),
                             d.kinetic_translational,
                             d.kinetic_rotational,
                             d.potential_gravity,
                             d.potential_elastic,
                             d.max_overlap_ratio,
                             static_cast<double>(removed),
                             imbalance};
  const auto append = [&row](Vec3 v) { row.insert(row.end(), {v.x, v.y, v.z}); };
  for (const Vec3& f : d.wall_force) append(f);
  for (std::size_t m = 0; m < d.mesh_force.size(); ++m) {
    append(d.mesh_force[m]);
    append(d.mesh_torque[m]);
  }
  return row;
}

/// The snapshots of the time loop: the particles' fields and precision the scene asks for,
/// with the rank field when asked, and every mesh of the scene with the counts of its setup.
SnapshotOptions snapshot_options(const Scene& scene, const EngineSetup& setup) {
  SnapshotOptions options;
  options.layout = {scene.output.rank_field, scene.output.fields, scene.output.single_precision};
  for (std::size_t m = 0; m < setup.meshes.size(); ++m)
    options.meshes.push_back({scene.meshes[m].name, setup.meshes[m].mesh.vertices.size(),
                              setup.meshes[m].mesh.triangles.size()});
  return options;
}

/// Whether snapshots are written on a writer thread while the run steps on, and if not why.
void print_output_mode(const Scene& scene) {
  if (!scene.output.asynchronous)
    std::printf("snapshots: written in the time loop (output.asynchronous = false)\n");
  else if (!mpi_thread_multiple())
    std::printf("snapshots: written in the time loop (MPI offers no MPI_THREAD_MULTIPLE)\n");
  else
    std::printf("snapshots: written on a writer thread while the run steps on\n");
}

/// "1 wall", "2 walls": a count and its noun, plural unless the count is 1.
std::string counted(std::size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

/// The start-up summary; engine_bytes < 0 when no engine was made (--check).
/// `deciding`: the particles that set the time step (setup_deciding_particles over all ranks);
/// `count`: the particles on all ranks.
void print_summary(const Scene& scene, const ParticleStore& deciding, std::uint64_t count,
                   const EngineSetup& setup, const StepEngine* engine, double engine_bytes,
                   std::uint64_t steps) {
  const TimeStepLimits limits = time_step_limits(scene, deciding);
  std::printf(
      "scene %s: %llu particles, %s, %s, contact law %s\n", scene.file.c_str(),
      static_cast<unsigned long long>(count), counted(scene.materials.size(), "material").c_str(),
      counted(scene.walls.size(), "wall").c_str(), contact_model_name(setup.contact_model).c_str());
  std::printf(
      "dt = %.4g s (%s; contact duration %.4g s, Rayleigh time %.4g s, stable limit %.4g s), "
      "%llu steps to t = %.4g s, skin %.4g m\n",
      setup.dt, scene.simulation.dt_auto ? "auto" : "explicit", limits.contact_duration,
      limits.rayleigh, limits.stable, static_cast<unsigned long long>(steps),
      scene.simulation.end_time, setup.skin);
  for (std::size_t m = 0; m < setup.meshes.size(); ++m) {
    const TriangleMesh& mesh = setup.meshes[m].mesh;
    std::printf("mesh %s: %zu triangles, %zu vertices", scene.meshes[m].name.c_str(),
                mesh.triangles.size(), mesh.vertices.size());
    if (mesh.skipped_degenerate > 0)
      std::printf(" (%zu zero-area triangles skipped)", mesh.skipped_degenerate);
    std::printf("\n");
  }
  if (engine) {
    const std::string device =
        engine->backend_name() == "cuda" ? " (" + cuda::device_description() + ")" : "";
    std::printf("backend %s%s, %.1f bytes per particle\n", engine->backend_name().c_str(),
                device.c_str(), count ? engine_bytes / static_cast<double>(count) : 0.0);
  }
  std::fflush(stdout);
}

/// Where the time loop starts: step 0 of a new run, or a checkpoint's step with the snapshot
/// series written up to it.
struct LoopStart {
  std::uint64_t step = 0;
  bool resumed = false;
  std::vector<XdmfSnapshot> snapshots;
};

/// A restarted run keeps the time-series rows up to its checkpoint's step.
std::optional<SeriesResume> series_resume(const LoopStart& start) {
  if (!start.resumed) return std::nullopt;
  return SeriesResume{"step", static_cast<double>(start.step)};
}

/// The time loop with its output and checkpoint schedule. With a settle check (a bed
/// preparation) it stops at the first settled time-series row, after that step's snapshot and
/// checkpoint.
class TimeLoop {
 public:
  TimeLoop(const Scene& scene, const MpiContext& mpi, StepEngine& engine, const EngineSetup& setup,
           const LoadBalance& balance, bool quiet, const LoopStart& start,
           const SettleCheck* settle)
      : scene_(scene),
        mpi_(mpi),
        engine_(engine),
        balance_(balance),
        dt_(setup.dt),
        skin_(setup.skin),
        first_step_(start.step),
        total_steps_(step_count(scene.simulation.end_time, setup.dt)),
        snapshot_every_(scene.output.every > 0 ? steps_between(scene.output.every, dt_)
                                               : total_steps_),
        series_every_(scene.output.timeseries_every > 0
                          ? steps_between(scene.output.timeseries_every, dt_)
                          : std::max<std::uint64_t>(1, total_steps_ / 200)),
        checkpoint_every_(scene.checkpoint.every > 0 ? steps_between(scene.checkpoint.every, dt_)
                                                     : 0),
        snapshots_(mpi.comm(), scene.output.dir, snapshot_options(scene, setup),
                   scene.output.asynchronous),
        series_(scene.output.dir + "/timeseries.csv", timeseries_columns(scene), mpi.is_root(),
                series_resume(start)),
        progress_(!quiet && mpi.is_root(), kProgressInterval, total_steps_, start.step),
        quiet_(quiet),
        resumed_(start.resumed),
        settle_(settle) {
    if (resumed_) snapshots_.resume(start.snapshots);
  }

  int run() {
    if (!resumed_) record(first_step_, true);
    for (std::uint64_t step = first_step_ + 1; step <= total_steps_; ++step) {
      engine_.step();
      HealthFailure failure;
      if (engine_.find_unhealthy(kOverlapLimit, failure)) return stop_unstable(step, failure);
      balance_.maybe_rebalance(step, engine_);
      const bool last = step == total_steps_;
      const bool snapshot = last || step % snapshot_every_ == 0;
      const std::optional<Diagnostics> row = record(step, snapshot);
      const bool settled = settle_ && row && settle_->settled(step, *row);
      if (settled && !snapshot) write_snapshot(step * dt_, step);
      if (checkpoint_every_ > 0 && (last || settled || step % checkpoint_every_ == 0))
        checkpoint(step);
      progress_.update(step * dt_, step, engine_.particle_count(), engine_.removed_count(),
                       imbalance_, last || settled);
      if (settled) {
        settled_step_ = step;
        return finish(step);
      }
    }
    return finish(total_steps_);
  }

  /// The step at which the bed settled; none when it did not or nothing was checked.
  std::optional<std::uint64_t> settled_step() const { return settled_step_; }

  /// Everything the step needs to be continued bit-for-bit (Checkpoint.hpp).
  Checkpoint capture(std::uint64_t step) const {
    Checkpoint c;
    engine_.get_particles(c.particles);
    engine_.get_list_positions(c.list_position_radius);
    c.list_build_step = engine_.list_build_step();
    engine_.get_contact_history(c.history);
    c.snapshots = snapshots_.writer().table();
    c.time = step * dt_;
    c.step = step;
    c.removed = engine_.removed_count();
    c.dt = dt_;
    c.dt_fraction = scene_.simulation.dt_auto ? scene_.simulation.dt_fraction : 0.0;
    c.skin = skin_;
    return c;
  }

 private:
  int finish(std::uint64_t step) {
    wait_for_snapshots();
    report_times();
    if (mpi_.is_root())
      std::printf(
          "done: %llu steps in %.2f s; %llu particles removed (left the domain); output "
          "in %s (open %s in ParaView)\n",
          static_cast<unsigned long long>(step - first_step_), progress_.elapsed(),
          static_cast<unsigned long long>(engine_.removed_count()), scene_.output.dir.c_str(),
          snapshots_.writer().xmf_path().c_str());
    return kExitOk;
  }

  /// The time split of the run, slowest rank per part, and the mean halo bytes a rank sent
  /// per ghost refresh (printed by rank 0 unless quiet); the snapshot writes count in output
  /// when the time loop made them and apart when a writer thread did. Collective.
  void report_times() const {
    const StepTimes t = engine_.step_times();
    double slowest[7] = {t.integrate,
                         t.forces,
                         t.neighbors,
                         t.ghosts,
                         t.migration,
                         output_seconds_,
                         snapshots_.write_seconds()};
    MPI_Allreduce(MPI_IN_PLACE, slowest, 7, MPI_DOUBLE, MPI_MAX, mpi_.comm());
    double halo[2] = {static_cast<double>(t.halo_bytes), static_cast<double>(t.refreshes)};
    MPI_Allreduce(MPI_IN_PLACE, halo, 2, MPI_DOUBLE, MPI_SUM, mpi_.comm());
    if (quiet_ || !mpi_.is_root()) return;
    std::printf(
        "time split (slowest rank): integration %.3g s, forces %.3g s, neighbour lists %.3g s, "
        "ghost exchange %.3g s, migration %.3g s, output %.3g s%s; halo %.4g bytes per rank per "
        "step\n",
        slowest[0], slowest[1], slowest[2], slowest[3], slowest[4], slowest[5],
        writer_thread_note(slowest[6]).c_str(), halo[1] > 0 ? halo[0] / halo[1] : 0.0);
  }

  /// The time the writer thread spent on snapshots while the run stepped on, for the time split.
  std::string writer_thread_note(double seconds) const {
    if (!snapshots_.asynchronous()) return {};
    char note[64];
    std::snprintf(note, sizeof(note), " (snapshots %.3g s on the writer thread)", seconds);
    return note;
  }

  /// Writes the step's time-series row when one is due (returning its diagnostics) and its
  /// snapshot when asked; the time it takes counts as output.
  std::optional<Diagnostics> record(std::uint64_t step, bool snapshot) {
    Stopwatch watch;
    const std::optional<Diagnostics> row = record_row(step, snapshot);
    output_seconds_ += watch.lap();
    return row;
  }

  /// record, unclocked.
  std::optional<Diagnostics> record_row(std::uint64_t step, bool snapshot) {
    const double time = step * dt_;
    std::optional<Diagnostics> row;
    if (step % series_every_ == 0 || snapshot) {
      const std::uint64_t removed = engine_.removed_count();
      if (removed > 0 && !removal_reported_ && mpi_.is_root())
        std::printf(
            "warning: %llu particle(s) left the domain and were removed; later removals are "
            "counted in the progress lines and in timeseries.csv (column removed)\n",
            static_cast<unsigned long long>(removed));
      removal_reported_ = removal_reported_ || removed > 0;
      row = engine_.diagnostics();
      imbalance_ = balance_.imbalance(engine_);
      series_.append(timeseries_row(time, step, *row, removed, imbalance_));
    }
    if (snapshot) write_snapshot(time, step);
    return row;
  }

  /// Stages a snapshot of the particles, written (after checking that no particle was lost or
  /// duplicated between ranks) while the next steps run (SnapshotQueue.hpp).
  void write_snapshot(double time, std::uint64_t step) { snapshots_.write(engine_, time, step); }

  /// Waits until the snapshots are written; the wait counts as output.
  void wait_for_snapshots() {
    Stopwatch watch;
    snapshots_.wait();
    output_seconds_ += watch.lap();
  }

  /// Written after the step's snapshot so that the snapshot table includes it.
  void checkpoint(std::uint64_t step) {
    wait_for_snapshots();
    Stopwatch watch;
    write_checkpoint(mpi_.comm(), scene_.output.dir, capture(step));
    output_seconds_ += watch.lap();
  }

  int stop_unstable(std::uint64_t step, const HealthFailure& f) {
    write_snapshot(step * dt_, step);
    wait_for_snapshots();
    if (mpi_.is_root())
      std::fprintf(stderr,
                   "gpudem-mpi: error: unstable at step %llu (t = %.6g s): particle id %llu at "
                   "(%.6g, %.6g, %.6g) %s; last state written to %s. Reduce dt or check "
                   "stiffness and initial overlaps.\n",
                   static_cast<unsigned long long>(step), step * dt_,
                   static_cast<unsigned long long>(f.id), f.position.x, f.position.y, f.position.z,
                   describe(f).c_str(), snapshots_.writer().files().back().c_str());
    return kExitUnstable;
  }

  static std::string describe(const HealthFailure& f) {
    if (f.non_finite) return "has a non-finite position or velocity";
    if (f.mesh_overflow) return "touches more mesh triangles at once than the engine holds (16)";
    return "overlaps by " + std::to_string(f.overlap_ratio * 100) + " % of its radius";
  }

  const Scene& scene_;
  const MpiContext& mpi_;
  StepEngine& engine_;
  const LoadBalance& balance_;
  double dt_;
  double skin_;
  std::uint64_t first_step_;
  std::uint64_t total_steps_;
  std::uint64_t snapshot_every_;
  std::uint64_t series_every_;
  std::uint64_t checkpoint_every_;  ///< 0: no checkpoints
  SnapshotQueue snapshots_;
  TimeSeriesWriter series_;
  Progress progress_;
  bool quiet_;
  bool resumed_;
  const SettleCheck* settle_;  ///< null: run to end_time
  std::optional<std::uint64_t> settled_step_;
  bool removal_reported_ = false;  ///< the first removal was warned of
  double imbalance_ = 1;           ///< at the last time-series row
  double output_seconds_ = 0;      ///< time series, snapshots and checkpoints [s]
};

/// A restart continues with the checkpoint's time step and skin (DESIGN §8): an explicit
/// simulation.dt must equal the stored step; with dt = "auto" the stored step is used (it was
/// computed from the particles the run started with) provided dt_fraction is unchanged. An
/// automatic skin is the stored one. The checkpoint must lie before end_time.
void adopt_checkpoint_step(EngineSetup& setup, const Scene& scene, const Checkpoint& c,
                           const std::string& path) {
  const SimulationSettings& sim = scene.simulation;
  const std::string written = "checkpoint '" + path + "' was written with ";
  const std::string fix =
      "; a restart continues with the same time step: set simulation.dt = " + exact_decimal(c.dt);
  if (!sim.dt_auto && sim.dt != c.dt)
    throw InputError(scene.file, 0, "simulation.dt",
                     written + "dt = " + exact_decimal(c.dt) + " s but the scene gives " +
                         exact_decimal(sim.dt) + " s" + fix);
  if (sim.dt_auto && c.dt_fraction == 0)
    throw InputError(scene.file, 0, "simulation.dt",
                     written + "an explicit dt = " + exact_decimal(c.dt) + " s" + fix);
  if (sim.dt_auto && sim.dt_fraction != c.dt_fraction)
    throw InputError(scene.file, 0, "simulation.dt_fraction",
                     written + "dt_fraction = " + exact_decimal(c.dt_fraction) +
                         " but the scene gives " + exact_decimal(sim.dt_fraction) + fix);
  setup.dt = c.dt;
  setup.start_step = c.step;
  if (scene.neighbor.skin <= 0) setup.skin = c.skin;
  if (c.step >= step_count(sim.end_time, c.dt))
    throw InputError(scene.file, 0, "simulation.end_time",
                     "checkpoint '" + path + "' is at t = " + exact_decimal(c.time) +
                         " s, not before end_time = " + exact_decimal(sim.end_time) +
                         " s: nothing to continue");
}

/// This rank's share of the particles a run starts with: the rows of its part of the
/// checkpoint it restarts from (read by parts, so that no rank holds the whole file), or its
/// part of a new run's particles (comm/StartParts.hpp).
struct StartShare {
  std::optional<Checkpoint> checkpoint;  ///< this rank's part of it, on a restart
  ParticleStore created;                 ///< this rank's share of a new run's particles

  const ParticleStore& particles() const { return checkpoint ? checkpoint->particles : created; }

  /// Frees the rows once the engine holds them; the checkpoint's step, time and snapshot table
  /// stay.
  void release_rows() {
    created = ParticleStore{};
    if (!checkpoint) return;
    checkpoint->particles = ParticleStore{};
    checkpoint->list_position_radius = std::vector<Real4>{};
    checkpoint->history = ContactHistory{};
  }
};

/// Reads or creates this rank's StartShare. A problem with the input that any rank finds in its
/// part is thrown on every rank. Collective.
StartShare load_start_share(const Scene& scene, const RunOptions& options, const MpiContext& mpi,
                            BedLoader& bed) {
  StartShare start;
  const int rank = mpi.rank(), ranks = mpi.size();
  if (!options.restart_file.empty()) {
    const std::string& path = options.restart_file;
    start.checkpoint = agree_on_input(mpi.comm(), [&] {
      Checkpoint part = read_checkpoint(path, FilePart{rank, ranks});
      check_checkpoint_fits_scene(part, path, scene);
      return part;
    });
  } else {
    start.created = create_start_part(mpi.comm(), scene, bed.reader(FilePart{rank, ranks}));
  }
  return start;
}

/// Hands this rank's share of the particles to the engine, then frees it: a new run's evaluate
/// their forces; a checkpoint's are restored with their forces, neighbour list order and
/// contact history (the particle rows freed before the history is routed).
void start_engine(StepEngine& engine, StartShare& share, const std::string& path) {
  if (!share.checkpoint) {
    engine.set_particles(share.created);
    share.release_rows();
    return;
  }
  Checkpoint& c = *share.checkpoint;
  try {
    engine.restore_particles(c.particles, c.list_position_radius, c.removed, c.list_build_step);
    c.particles = ParticleStore{};
    c.list_position_radius = std::vector<Real4>{};
    engine.set_contact_history(std::move(c.history));
  } catch (const std::invalid_argument& e) {
    throw InputError(path, 0, "", e.what());
  }
  share.release_rows();
}

/// Ends a bed preparation: saves the trimmed bed when it settled, else reports why not.
int finish_preparation(const Scene& scene, const MpiContext& mpi, const StepEngine& engine,
                       const TimeLoop& loop, double dt) {
  const std::optional<std::uint64_t> settled = loop.settled_step();
  if (!settled) {
    report_unsettled(scene, mpi, step_count(scene.simulation.end_time, dt) * dt,
                     engine.diagnostics());
    return kExitFailure;
  }
  save_bed(scene, mpi, loop.capture(*settled));
  return kExitOk;
}

/// --resume: makes the output folder's checkpoint, if any, the restart file. False, with a
/// line saying so, when a bed preparation's bed is already written (nothing left to do).
bool resume_from_output(const Scene& scene, const MpiContext& mpi, RunOptions& options) {
  const ResumePoint point = find_resume_point(scene, mpi);
  if (!point.bed.empty()) {
    if (mpi.is_root())
      std::printf("run complete: the bed %s is written; nothing to do\n", point.bed.c_str());
    return false;
  }
  options.restart_file = point.checkpoint;
  return true;
}

/// Whether a resumed run's checkpoint has reached end_time; prints a line saying so if it has.
bool reached_end(const Scene& scene, const MpiContext& mpi, const Checkpoint& checkpoint,
                 const std::string& path) {
  if (checkpoint.step < step_count(scene.simulation.end_time, checkpoint.dt)) return false;
  if (mpi.is_root())
    std::printf("run complete: %s is at t = %.6g s, end_time = %.6g s; nothing to do\n",
                path.c_str(), checkpoint.time, scene.simulation.end_time);
  return true;
}

}  // namespace

int run_scene(const RunOptions& command_line, const MpiContext& mpi) {
  Scene scene = load_scene(command_line.scene_file, command_line.overrides);
  if (!command_line.output_dir.empty()) scene.output.dir = command_line.output_dir;
  RunOptions options = command_line;
  if (options.resume && !resume_from_output(scene, mpi, options)) return kExitOk;
  BedLoader bed;
  StartShare share = load_start_share(scene, options, mpi, bed);
  const Checkpoint* checkpoint = share.checkpoint ? &*share.checkpoint : nullptr;
  if (options.resume && checkpoint && reached_end(scene, mpi, *checkpoint, options.restart_file))
    return kExitOk;
  const ParticleStore deciding =
      gather_particles(mpi.comm(), setup_deciding_particles(scene, share.particles()));
  const std::uint64_t particle_count = sum_over_ranks(mpi.comm(), share.particles().size());
  EngineSetup setup = make_engine_setup(scene, deciding);
  if (checkpoint) adopt_checkpoint_step(setup, scene, *checkpoint, options.restart_file);
  const std::unique_ptr<MpiDomain> domain =
      make_domain(scene, mpi, share.particles(), particle_count, setup,
                  use_gpu_aware_mpi(options.gpu_aware_mpi));
  setup.domain = domain.get();
  setup.exact_phase_times = options.exact_time_split;
  const std::uint64_t steps = step_count(scene.simulation.end_time, setup.dt);
  std::optional<SettleCheck> settle;
  if (scene.preparation.enabled) settle.emplace(scene, setup.dt);
  const bool banner = !options.quiet && mpi.is_root();
  if (checkpoint && mpi.is_root() && (banner || options.check_only))
    std::printf("restart from %s at t = %.6g s (step %llu)\n", options.restart_file.c_str(),
                checkpoint->time, static_cast<unsigned long long>(checkpoint->step));
  if (options.check_only) {
    if (mpi.is_root()) {
      print_summary(scene, deciding, particle_count, setup, nullptr, -1, steps);
      if (domain) print_decomposition(*domain);
      if (settle) print_preparation(scene, *settle, setup.dt);
      std::printf("scene is valid\n");
    }
    return kExitOk;
  }
  std::unique_ptr<StepEngine> engine = make_engine(options.backend, mpi, setup);
  start_engine(*engine, share, options.restart_file);
  if (!checkpoint) bed.apply_history(scene, mpi, *engine);
  const std::string tuning = engine->tune_launches();
  prepare_output_directory(scene.output.dir);
  const std::vector<MemoryUse> memory = memory_over_ranks(mpi, *engine);
  if (banner)
    print_summary(scene, deciding, particle_count, setup, engine.get(), total_bytes(memory), steps);
  if (!options.quiet && engine->backend_name() == "host") {
    const std::string crowded = crowded_threads_warning(mpi);
    if (!crowded.empty()) std::printf("%s\n", crowded.c_str());
  }
  if (banner && options.verbose) {
    print_memory_report(memory, engine->particle_count());
    std::printf("%s\n", tuning.c_str());
  }
  if (banner) print_output_mode(scene);
  if (banner && domain) print_decomposition(*domain);
  if (banner && settle) print_preparation(scene, *settle, setup.dt);
  LoopStart start;
  if (checkpoint) start = {checkpoint->step, true, checkpoint->snapshots};
  const LoadBalance balance(scene, mpi, domain.get(), setup.dt);
  TimeLoop loop(scene, mpi, *engine, setup, balance, options.quiet, start,
                settle ? &*settle : nullptr);
  const int code = loop.run();
  if (code != kExitOk || !settle) return code;
  return finish_preparation(scene, mpi, *engine, loop, setup.dt);
}

}  // namespace gpudem
