#include "app/Runner.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "app/Progress.hpp"
#include "comm/OutputDirectory.hpp"
#include "comm/SnapshotWriter.hpp"
#include "comm/TimeSeriesWriter.hpp"
#include "core/InputError.hpp"
#include "core/ParticleSources.hpp"
#include "core/SceneLoader.hpp"
#include "core/SceneSetup.hpp"
#include "kernels/CudaMemory.hpp"

namespace gpudem {

namespace {

/// Overlap beyond this fraction of the smaller radius stops the run.
constexpr double kOverlapLimit = 0.5;
/// Seconds of wall time between progress lines.
constexpr double kProgressInterval = 2.0;

std::unique_ptr<StepEngine> make_engine(BackendChoice choice, const EngineSetup& setup) {
  switch (choice) {
    case BackendChoice::Host:
      return make_host_engine(setup);
    case BackendChoice::Cuda:
      if (!cuda::compiled_in() || cuda::device_count() == 0)
        throw InputError("", 0, "--backend",
                         cuda::compiled_in() ? "cuda requested but no CUDA device is visible"
                                             : "cuda requested but this build has no CUDA backend");
      return make_cuda_engine(setup);
    case BackendChoice::Auto:
      break;
  }
  return cuda::device_count() > 0 ? make_cuda_engine(setup) : make_host_engine(setup);
}

/// Steps between two events `every` seconds apart (at least 1).
std::uint64_t steps_between(double every, double dt) {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(every / dt)));
}

std::vector<std::string> timeseries_columns(const Scene& scene) {
  std::vector<std::string> c = {"time",          "step",          "particles",
                                "contacts",      "kinetic_translational",
                                "kinetic_rotational", "potential_gravity",
                                "potential_elastic",  "max_overlap_ratio", "removed"};
  for (const WallSettings& w : scene.walls)
    for (const char* axis_name : {"fx", "fy", "fz"}) c.push_back(w.name + "_" + axis_name);
  return c;
}

std::vector<double> timeseries_row(double time, std::uint64_t step, const Diagnostics& d,
                                   std::uint64_t removed) {
  std::vector<double> row = {time,
                             static_cast<double>(step),
                             static_cast<double>(d.particle_count),
                             static_cast<double>(d.contact_count),
                             d.kinetic_translational,
                             d.kinetic_rotational,
                             d.potential_gravity,
                             d.potential_elastic,
                             d.max_overlap_ratio,
                             static_cast<double>(removed)};
  for (const Vec3& f : d.wall_force) {
    row.push_back(f.x);
    row.push_back(f.y);
    row.push_back(f.z);
  }
  return row;
}

void print_summary(const Scene& scene, const ParticleStore& particles, const EngineSetup& setup,
                   const StepEngine* engine, std::uint64_t steps) {
  const TimeStepLimits limits = time_step_limits(scene, particles);
  std::printf("scene %s: %zu particles, %zu materials, %zu walls\n", scene.file.c_str(),
              particles.size(), scene.materials.size(), scene.walls.size());
  std::printf("dt = %.4g s (%s; contact duration %.4g s, Rayleigh time %.4g s), %llu steps to "
              "t = %.4g s, skin %.4g m\n",
              setup.dt, scene.simulation.dt_auto ? "auto" : "explicit", limits.contact_duration,
              limits.rayleigh, static_cast<unsigned long long>(steps), scene.simulation.end_time,
              setup.skin);
  if (engine)
    std::printf("backend %s, %.1f bytes per particle\n", engine->backend_name().c_str(),
                particles.size() ? double(engine->memory_bytes()) / particles.size() : 0.0);
  std::fflush(stdout);
}

/// The time loop with its output schedule.
class TimeLoop {
 public:
  TimeLoop(const Scene& scene, const MpiContext& mpi, StepEngine& engine, double dt, bool quiet)
      : scene_(scene), mpi_(mpi), engine_(engine), dt_(dt),
        total_steps_(static_cast<std::uint64_t>(std::ceil(scene.simulation.end_time / dt - 1e-9))),
        snapshot_every_(scene.output.every > 0 ? steps_between(scene.output.every, dt)
                                               : total_steps_),
        series_every_(scene.output.timeseries_every > 0
                          ? steps_between(scene.output.timeseries_every, dt)
                          : std::max<std::uint64_t>(1, total_steps_ / 200)),
        snapshots_(mpi.comm(), scene.output.dir),
        series_(scene.output.dir + "/timeseries.csv", timeseries_columns(scene), mpi.is_root()),
        progress_(!quiet && mpi.is_root(), kProgressInterval, total_steps_) {}

  std::uint64_t total_steps() const { return total_steps_; }

  int run() {
    record(0, true);
    for (std::uint64_t step = 1; step <= total_steps_; ++step) {
      engine_.step();
      HealthFailure failure;
      if (engine_.find_unhealthy(kOverlapLimit, failure)) return stop_unstable(step, failure);
      const bool last = step == total_steps_;
      record(step, last || step % snapshot_every_ == 0);
      progress_.update(step * dt_, step, engine_.particle_count(), last);
    }
    if (mpi_.is_root())
      std::printf("done: %llu steps in %.2f s; %llu particles removed (left the domain); output "
                  "in %s (open %s in ParaView)\n",
                  static_cast<unsigned long long>(total_steps_), progress_.elapsed(),
                  static_cast<unsigned long long>(engine_.removed_count()),
                  scene_.output.dir.c_str(), snapshots_.xmf_path().c_str());
    return kExitOk;
  }

 private:
  void record(std::uint64_t step, bool snapshot) {
    const double time = step * dt_;
    if (step % series_every_ == 0 || snapshot) {
      const std::uint64_t removed = engine_.removed_count();
      if (removed > reported_removed_ && mpi_.is_root())
        std::printf("warning: %llu particle(s) left the domain and were removed (total %llu)\n",
                    static_cast<unsigned long long>(removed - reported_removed_),
                    static_cast<unsigned long long>(removed));
      reported_removed_ = removed;
      series_.append(timeseries_row(time, step, engine_.diagnostics(), removed));
    }
    if (snapshot) write_snapshot(time, step);
  }

  void write_snapshot(double time, std::uint64_t step) {
    engine_.get_particles(host_);
    snapshots_.write(host_, time, step);
  }

  int stop_unstable(std::uint64_t step, const HealthFailure& f) {
    write_snapshot(step * dt_, step);
    if (mpi_.is_root())
      std::fprintf(stderr,
                   "gpudem-mpi: error: unstable at step %llu (t = %.6g s): particle id %llu at "
                   "(%.6g, %.6g, %.6g) %s; last state written to %s. Reduce dt or check "
                   "stiffness and initial overlaps.\n",
                   static_cast<unsigned long long>(step), step * dt_,
                   static_cast<unsigned long long>(f.id), f.position.x, f.position.y, f.position.z,
                   f.non_finite ? "has a non-finite position or velocity"
                                : ("overlaps by " + std::to_string(f.overlap_ratio * 100) +
                                   " % of its radius")
                                      .c_str(),
                   snapshots_.files().back().c_str());
    return kExitUnstable;
  }

  const Scene& scene_;
  const MpiContext& mpi_;
  StepEngine& engine_;
  double dt_;
  std::uint64_t total_steps_;
  std::uint64_t snapshot_every_;
  std::uint64_t series_every_;
  SnapshotWriter snapshots_;
  TimeSeriesWriter series_;
  Progress progress_;
  ParticleStore host_;
  std::uint64_t reported_removed_ = 0;
};

}  // namespace

int run_scene(const RunOptions& options, const MpiContext& mpi) {
  Scene scene = load_scene(options.scene_file, options.overrides);
  if (!options.output_dir.empty()) scene.output.dir = options.output_dir;
  ParticleStore particles;
  create_particles(scene, particles);
  const EngineSetup setup = make_engine_setup(scene, particles);
  const auto steps = static_cast<std::uint64_t>(std::ceil(scene.simulation.end_time / setup.dt - 1e-9));
  if (options.check_only) {
    if (mpi.is_root()) {
      print_summary(scene, particles, setup, nullptr, steps);
      std::printf("scene is valid\n");
    }
    return kExitOk;
  }
  std::unique_ptr<StepEngine> engine = make_engine(options.backend, setup);
  prepare_output_directory(scene.output.dir);
  engine->set_particles(particles);
  if (!options.quiet && mpi.is_root()) print_summary(scene, particles, setup, engine.get(), steps);
  TimeLoop loop(scene, mpi, *engine, setup.dt, options.quiet);
  return loop.run();
}

}  // namespace gpudem
