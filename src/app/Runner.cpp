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
#include "app/Preview.hpp"
#include "app/Progress.hpp"
#include "app/Resume.hpp"
#include "app/ThreadCores.hpp"
#include "app/TimeLoop.hpp"
#include "comm/Checkpoint.hpp"
#include "comm/MpiWait.hpp"
#include "comm/OutputDirectory.hpp"
#include "comm/SnapshotQueue.hpp"
#include "comm/StartParts.hpp"
#include "comm/TimeSeriesWriter.hpp"
#include "core/ExactDecimal.hpp"
#include "core/InputError.hpp"
#include "core/ParticleGather.hpp"
#include "core/ParticleSources.hpp"
#include "core/RowShare.hpp"
#include "core/SceneLoader.hpp"
#include "core/Stopwatch.hpp"
#include "engine/CudaMemory.hpp"
#include "engine/MeshReach.hpp"
#include "engine/MeshStartOverlap.hpp"
#include "engine/SceneSetup.hpp"

namespace gpudem {

namespace {

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
  return mpi.group().first_rank_with(cuda::device_count() == 0) == mpi.size();
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

/// Each mesh's triangles and where it is: its box at t = 0 and the box it sweeps until the end.
void print_mesh_summary(const Scene& scene, const EngineSetup& setup) {
  const auto box = [](Vec3 lo, Vec3 hi) {
    char text[160];
    std::snprintf(text, sizeof text, "x [%.4g, %.4g], y [%.4g, %.4g], z [%.4g, %.4g] m", lo.x, hi.x,
                  lo.y, hi.y, lo.z, hi.z);
    return std::string(text);
  };
  for (std::size_t m = 0; m < setup.meshes.size(); ++m) {
    const TriangleMesh& mesh = setup.meshes[m].mesh;
    const MeshSettings& settings = scene.meshes[m];
    std::printf("mesh %s: %zu triangles, %zu vertices", settings.name.c_str(),
                mesh.triangles.size(), mesh.vertices.size());
    if (mesh.skipped_degenerate > 0)
      std::printf(" (%zu zero-area triangles skipped)", mesh.skipped_degenerate);
    const MeshReach r =
        mesh_reach(setup.meshes[m], settings.keyframes, settings.centre, scene.simulation.end_time);
    std::printf("; at t = 0 within %s", box(r.start_lo, r.start_hi).c_str());
    if (!settings.keyframes.empty())
      std::printf("; until t = %.4g s within %s", scene.simulation.end_time,
                  box(r.swept_lo, r.swept_hi).c_str());
    std::printf("\n");
  }
  for (const ImplementSettings& im : scene.implements) {
    std::string names;
    for (std::size_t m : im.meshes) names += (names.empty() ? "" : ", ") + scene.meshes[m].name;
    std::printf(
        "implement %s: meshes %s; reference point (%.4g, %.4g, %.4g) m; forward (%.3g, %.3g, "
        "%.3g), up (%.3g, %.3g, %.3g)\n",
        im.name.c_str(), names.c_str(), im.reference.x, im.reference.y, im.reference.z,
        im.forward.x, im.forward.y, im.forward.z, im.up.x, im.up.y, im.up.z);
  }
}

/// How the scene sets dt, for the summary.
const char* dt_kind(const SimulationSettings& sim) {
  if (sim.dt_adaptive) return "adaptive base step, split while particles move fast";
  return sim.dt_auto ? "auto" : "explicit";
}

/// The start-up summary; engine_bytes < 0 when no engine was made (--check).
/// `deciding`: the particles that set the time step (setup_deciding_particles over all ranks);
/// `count`: the particles on all ranks.
void print_summary(const Scene& scene, const ParticleStore& deciding, std::uint64_t count,
                   const EngineSetup& setup, const StepEngine* engine, double engine_bytes,
                   std::uint64_t steps) {
  const TimeStepLimits limits = time_step_limits(scene, deciding, setup.meshes);
  std::printf(
      "scene %s: %llu particles, %s, %s, contact law %s\n", scene.file.c_str(),
      static_cast<unsigned long long>(count), counted(scene.materials.size(), "material").c_str(),
      counted(scene.walls.size(), "wall").c_str(), contact_model_name(setup.contact_model).c_str());
  std::printf(
      "dt = %.4g s (%s; contact duration %.4g s, Rayleigh time %.4g s, stable limit %.4g s, "
      "displacement limit %.4g s at v_max %.4g m/s), %llu steps to t = %.4g s, skin %.4g m\n",
      setup.dt, dt_kind(scene.simulation), limits.contact_duration, limits.rayleigh, limits.stable,
      limits.displacement, limits.max_speed, static_cast<unsigned long long>(steps),
      scene.simulation.end_time, setup.skin);
  const PeakOverlap impact = peak_overlap(scene, deciding, impact_speed(scene, deciding));
  if (impact.ratio > 0)
    std::printf(
        "impacts at v = %.4g m/s overlap by at most %.3g %% of the radius (instability at %.3g %%, "
        "reached at %.4g m/s)\n",
        impact.speed, 100 * impact.ratio, 100 * kUnstableOverlapRatio, impact.unstable_speed);
  if (std::isfinite(limits.bond))
    std::printf("bonds: %zu [[bond]] table(s); the stiffest bond vibrates with pi/omega = %.4g s\n",
                scene.bonds.size(), limits.bond);
  print_mesh_summary(scene, setup);
  if (engine) {
    const std::string device =
        engine->backend_name() == "cuda" ? " (" + cuda::device_description() + ")" : "";
    const std::string lanes = engine->contact_lanes() > 1
                                  ? ", " + std::to_string(engine->contact_lanes()) +
                                        " contacts at once (" +
                                        (engine->contact_lanes() == 8 ? "AVX-512" : "AVX2") + ")"
                                  : "";
    std::printf("backend %s%s%s, %.1f bytes per particle\n", engine->backend_name().c_str(),
                device.c_str(), lanes.c_str(),
                count ? engine_bytes / static_cast<double>(count) : 0.0);
  }
  std::fflush(stdout);
}

/// A restart continues with the checkpoint's time step and skin (docs/architecture.md, "Checkpoints
/// and restart"): an explicit simulation.dt must equal the stored step; with dt = "auto" the stored
/// step is used (it was computed from the particles the run started with) provided dt_fraction is
/// unchanged. An automatic skin is the stored one, and so are the units of the host's integer
/// sums where the checkpoint records them. The checkpoint must lie before end_time.
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
  if (sim.dt_adaptive != c.dt_adaptive)
    throw InputError(scene.file, 0, "simulation.dt",
                     written + (c.dt_adaptive ? "dt = \"adaptive\"" : "a fixed dt") +
                         "; a restart continues with the same kind of time step");
  if (sim.dt_auto && sim.dt_fraction != c.dt_fraction)
    throw InputError(scene.file, 0, "simulation.dt_fraction",
                     written + "dt_fraction = " + exact_decimal(c.dt_fraction) +
                         " but the scene gives " + exact_decimal(sim.dt_fraction) + fix);
  setup.dt = c.dt;
  setup.start_step = c.step;
  if (scene.neighbor.skin <= 0) setup.skin = c.skin;
  if (c.sum_force_unit > 0) setup.exact_units = exact_units_of(c.sum_force_unit, c.sum_torque_unit);
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
    checkpoint->bonds = ContactHistory{};
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
    start.checkpoint = agree_on_failure(mpi.group(), [&] {
      Checkpoint part = read_checkpoint(path, FilePart{rank, ranks});
      fit_checkpoint_to_scene(part, path, scene);
      return part;
    });
  } else {
    start.created = create_start_part(mpi.group(), scene, bed.reader(scene, FilePart{rank, ranks}));
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
    if (!c.wall_motion.empty()) engine.set_wall_motion(c.wall_motion);
    engine.restore_particles(c.particles, c.list_position_radius, c.removed, c.list_build);
    c.particles = ParticleStore{};
    c.list_position_radius = std::vector<Real4>{};
    engine.set_contact_history(std::move(c.history));
    engine.set_bonds(std::move(c.bonds), c.bonds_made);
  } catch (const std::invalid_argument& e) {
    throw InputError(path, 0, "", e.what());
  }
  share.release_rows();
}

/// Makes the bonds of a new run; a pair a [[bond]] table lists that cannot be bonded is an input
/// error.
void create_bonds(const Scene& scene, StepEngine& engine) {
  try {
    engine.create_bonds();
  } catch (const std::invalid_argument& e) {
    throw InputError(scene.file, 0, "bond", e.what());
  }
}

/// A new run's contact springs and bonds: the bed's springs, and its bonds or else those the
/// [[bond]] tables make.
void start_springs_and_bonds(const Scene& scene, const MpiContext& mpi, BedLoader& bed,
                             StepEngine& engine) {
  bed.apply_history(scene, mpi, engine);
  if (!bed.apply_bonds(mpi, engine)) create_bonds(scene, engine);
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

/// The engine's start-up notes: on the host backend the OpenMP threads per rank and a warning
/// of crowded threads, and with --verbose the memory report and the launch tuning line.
void print_engine_notes(const RunOptions& options, const MpiContext& mpi, const StepEngine& engine,
                        const ThreadPlan& threads, const std::vector<MemoryUse>& memory,
                        const std::string& tuning) {
  if (options.quiet || !mpi.is_root()) return;
  if (engine.backend_name() == "host") {
    std::printf("%s\n", threads.note.c_str());
    if (!threads.warning.empty()) std::printf("%s\n", threads.warning.c_str());
  }
  if (!options.verbose) return;
  print_memory_report(memory, engine.particle_count());
  std::printf("%s\n", tuning.c_str());
}

/// Rank 0 prints each warning to stderr.
void print_warnings(const std::vector<std::string>& warnings, const MpiContext& mpi) {
  if (mpi.is_root())
    for (const std::string& warning : warnings)
      std::fprintf(stderr, "warning: %s\n", warning.c_str());
}

/// Refuses a new run whose meshes start inside the particles and warns (rank 0) of those that
/// start touching them. Collective.
void warn_of_mesh_start_overlaps(const Scene& scene, const EngineSetup& setup,
                                 const ParticleStore& share, const MpiContext& mpi) {
  print_warnings(check_mesh_start_overlaps(scene, setup.meshes, share, mpi.group()), mpi);
}

/// --preview: the scene at t = 0 written without a step (Preview.hpp). Collective.
void preview_scene(const Scene& scene, const EngineSetup& setup, const ParticleStore& share,
                   const MpiContext& mpi) {
  write_preview(scene, setup, share, mpi);
  if (mpi.is_root())
    std::printf(
        "preview of t = 0 written to %s/preview.xmf (open it in ParaView) and %s/preview.png "
        "(from above, the front and the side)\n",
        scene.output.dir.c_str(), scene.output.dir.c_str());
}

/// What --check and --preview report of a scene set up without an engine.
struct SetUpScene {
  const ParticleStore& deciding;  ///< the particles that set the time step, from all ranks
  std::uint64_t particle_count;   ///< on all ranks
  const EngineSetup& setup;
  std::uint64_t steps;         ///< to end_time
  const MpiDomain* domain;     ///< null on one rank
  const SettleCheck* settle;   ///< null unless the scene prepares a bed
  const ParticleStore& share;  ///< this rank's particles
};

/// --check: the start-up summary and "scene is valid"; --preview: the summary and the scene at
/// t = 0 (Preview.hpp). Collective.
void check_or_preview(const Scene& scene, const RunOptions& options, const MpiContext& mpi,
                      const SetUpScene& s) {
  if (mpi.is_root()) {
    print_summary(scene, s.deciding, s.particle_count, s.setup, nullptr, -1, s.steps);
    if (s.domain) print_decomposition(*s.domain);
    if (s.settle) print_preparation(scene, *s.settle, s.setup.dt);
  }
  if (options.preview) preview_scene(scene, s.setup, s.share, mpi);
  if (options.check_only && mpi.is_root()) std::printf("scene is valid\n");
}

/// With dt = "adaptive", the substep policy: the reach displacement_fraction × r_min and the
/// fastest tool point; `substeps` those of the last base step.
std::optional<AdaptiveStep> adaptive_step(const Scene& scene, const ParticleStore& deciding,
                                          const EngineSetup& setup, std::uint32_t substeps) {
  if (!scene.simulation.dt_adaptive) return std::nullopt;
  return AdaptiveStep(setup.dt, scene.simulation.displacement_fraction * smallest_radius(deciding),
                      fastest_tool(scene, setup.meshes), substeps);
}

}  // namespace

int run_scene(const RunOptions& command_line, const MpiContext& mpi) {
  const ThreadPlan threads = share_node_cores(mpi);
  set_mpi_waiting(threads.ranks_take_turns ? MpiWaiting::nap : MpiWaiting::spin);
  Scene scene = load_scene(command_line.scene_file, command_line.overrides);
  print_warnings(scene.warnings, mpi);
  if (!command_line.output_dir.empty()) scene.output.dir = command_line.output_dir;
  RunOptions options = command_line;
  if (options.resume && !resume_from_output(scene, mpi, options)) return kExitOk;
  BedLoader bed;
  StartShare share = load_start_share(scene, options, mpi, bed);
  const Checkpoint* checkpoint = share.checkpoint ? &*share.checkpoint : nullptr;
  if (options.resume && checkpoint && reached_end(scene, mpi, *checkpoint, options.restart_file))
    return kExitOk;
  const ParticleStore deciding =
      gather_particles(mpi.group(), setup_deciding_particles(scene, share.particles()));
  const std::uint64_t particle_count = mpi.group().sum<std::uint64_t>(share.particles().size());
  EngineSetup setup = make_engine_setup(scene, deciding);
  print_warnings(time_step_warnings(scene, deciding, setup), mpi);
  if (checkpoint)
    adopt_checkpoint_step(setup, scene, *checkpoint, options.restart_file);
  else
    warn_of_mesh_start_overlaps(scene, setup, share.particles(), mpi);
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
  if (options.check_only || options.preview) {
    check_or_preview(scene, options, mpi,
                     {deciding, particle_count, setup, steps, domain.get(),
                      settle ? &*settle : nullptr, share.particles()});
    return kExitOk;
  }
  std::unique_ptr<StepEngine> engine = make_engine(options.backend, mpi, setup);
  start_engine(*engine, share, options.restart_file);
  if (!checkpoint) start_springs_and_bonds(scene, mpi, bed, *engine);
  const std::string tuning = engine->tune_launches();
  prepare_output_directory(scene.output.dir);
  const std::vector<MemoryUse> memory = memory_over_ranks(mpi, *engine);
  if (banner)
    print_summary(scene, deciding, particle_count, setup, engine.get(), total_bytes(memory), steps);
  print_engine_notes(options, mpi, *engine, threads, memory, tuning);
  if (banner) print_output_mode(scene);
  if (banner && domain) print_decomposition(*domain);
  if (banner && settle) print_preparation(scene, *settle, setup.dt);
  LoopStart start;
  if (checkpoint) start = {checkpoint->step, true, checkpoint->snapshots};
  const LoadBalance balance(scene, mpi, domain.get(), setup.dt);
  TimeLoop loop(scene, mpi, *engine, setup, balance, options.quiet, start,
                settle ? &*settle : nullptr,
                adaptive_step(scene, deciding, setup, checkpoint ? checkpoint->substeps : 1));
  const int code = loop.run();
  if (code != kExitOk || !settle) return code;
  return finish_preparation(scene, mpi, *engine, loop, setup.dt);
}

}  // namespace gpudem
