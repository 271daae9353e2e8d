#include "app/TimeLoop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/BedPreparation.hpp"
#include "core/ForceColumns.hpp"
#include "core/Stopwatch.hpp"
#include "engine/TimeStepLimits.hpp"

namespace gpudem {

namespace {

/// Seconds of wall time between progress lines.
constexpr double kProgressInterval = 2.0;

/// Steps between two events `every` seconds apart (at least 1).
std::uint64_t steps_between(double every, double dt) {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(every / dt)));
}

}  // namespace

std::uint64_t step_count(double end_time, double dt) {
  return static_cast<std::uint64_t>(std::ceil(end_time / dt - 1e-9));
}

namespace {

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
                                "imbalance",
                                "dt"};
  for (std::string& name : force_columns(scene)) c.push_back(std::move(name));
  if (!scene.bonds.empty()) c.insert(c.end(), {"bonds", "broken_bonds"});
  return c;
}

std::vector<double> timeseries_row(double time, std::uint64_t step, double dt, const Diagnostics& d,
                                   std::uint64_t removed, double imbalance,
                                   const ImplementLoads& loads, bool with_bonds) {
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
                             imbalance,
                             dt};
  const auto append = [&row](Vec3 v) { row.insert(row.end(), {v.x, v.y, v.z}); };
  for (const Vec3& f : d.wall_force) append(f);
  for (const WallMotion& m : d.piston_motion) row.insert(row.end(), {m.displacement, m.velocity});
  for (std::size_t m = 0; m < d.mesh_force.size(); ++m) {
    append(d.mesh_force[m]);
    append(d.mesh_torque[m]);
  }
  for (double value : loads.row(time, d.mesh_force, d.mesh_torque)) row.push_back(value);
  if (with_bonds)
    row.insert(row.end(),
               {static_cast<double>(d.bond_count), static_cast<double>(d.broken_bond_count)});
  return row;
}

/// The snapshots of the time loop: the particles' fields and precision the scene asks for,
/// with the rank field when asked, and every mesh of the scene with the counts of its setup.
SnapshotOptions snapshot_options(const Scene& scene, const EngineSetup& setup) {
  SnapshotOptions options;
  options.layout = {scene.output.rank_field, scene.output.fields, scene.output.single_precision};
  options.bonds = scene.output.bonds;
  for (std::size_t m = 0; m < setup.meshes.size(); ++m)
    options.meshes.push_back({scene.meshes[m].name, setup.meshes[m].mesh.vertices.size(),
                              setup.meshes[m].mesh.triangles.size()});
  return options;
}

/// A restarted run keeps the time-series rows up to its checkpoint's step.
std::optional<SeriesResume> series_resume(const LoopStart& start) {
  if (!start.resumed) return std::nullopt;
  return SeriesResume{"step", static_cast<double>(start.step)};
}

}  // namespace

TimeLoop::TimeLoop(const Scene& scene, const MpiContext& mpi, StepEngine& engine,
                   const EngineSetup& setup, const LoadBalance& balance, bool quiet,
                   const LoopStart& start, const SettleCheck* settle,
                   std::optional<AdaptiveStep> adaptive)
    : scene_(scene),
      mpi_(mpi),
      engine_(engine),
      balance_(balance),
      dt_(setup.dt),
      skin_(setup.skin),
      sum_units_(setup.exact_units),
      first_step_(start.step),
      first_list_builds_(engine.rebuild_count()),
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
      implement_loads_(scene),
      series_(scene.output.dir + "/timeseries.csv", timeseries_columns(scene), mpi.is_root(),
              series_resume(start)),
      progress_(!quiet && mpi.is_root(), kProgressInterval, total_steps_, start.step),
      quiet_(quiet),
      resumed_(start.resumed),
      settle_(settle),
      adaptive_(adaptive) {
  if (resumed_) snapshots_.resume(start.snapshots);
}

void TimeLoop::advance_base_step() {
  if (!adaptive_) {
    engine_.step();
    return;
  }
  const std::uint32_t substeps = adaptive_->next(engine_.fastest_speed());
  engine_.set_substeps(substeps);
  for (std::uint32_t k = 0; k < substeps; ++k) engine_.step();
  substeps_done_ += substeps;
}

int TimeLoop::run() {
  if (!resumed_) record(first_step_, true);
  for (std::uint64_t step = first_step_ + 1; step <= total_steps_; ++step) {
    advance_base_step();
    HealthFailure failure;
    if (engine_.find_unhealthy(kUnstableOverlapRatio, failure)) return stop_unstable(step, failure);
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

Checkpoint TimeLoop::capture(std::uint64_t step) const {
  Checkpoint c;
  engine_.get_particles(c.particles);
  engine_.get_list_positions(c.list_position_radius);
  c.list_build = engine_.list_build_clock();
  c.substeps = adaptive_ ? adaptive_->substeps() : 1;
  c.wall_motion = engine_.wall_motion();
  engine_.get_contact_history(c.history);
  engine_.get_bonds(c.bonds, c.bonds_made);
  c.snapshots = snapshots_.writer().table();
  c.time = step * dt_;
  c.step = step;
  c.removed = engine_.removed_count();
  c.dt = dt_;
  c.dt_fraction = scene_.simulation.dt_auto ? scene_.simulation.dt_fraction : 0.0;
  c.dt_adaptive = scene_.simulation.dt_adaptive;
  c.skin = skin_;
  c.sum_force_unit = sum_units_.force;
  c.sum_torque_unit = sum_units_.torque;
  for (const Material& m : scene_.materials) c.material_names.push_back(m.name);
  return c;
}

int TimeLoop::finish(std::uint64_t step) {
  wait_for_snapshots();
  report_times();
  const std::string split =
      adaptive_ ? " (base steps, split into " + std::to_string(substeps_done_) + ")" : "";
  if (mpi_.is_root())
    std::printf(
        "done: %llu steps%s in %.2f s; %llu particles removed (left the domain); output "
        "in %s (open %s in ParaView)\n",
        static_cast<unsigned long long>(step - first_step_), split.c_str(), progress_.elapsed(),
        static_cast<unsigned long long>(engine_.removed_count()), scene_.output.dir.c_str(),
        snapshots_.writer().xmf_path().c_str());
  return kExitOk;
}

void TimeLoop::report_times() const {
  const StepTimes t = engine_.step_times();
  std::vector<double> slowest = {t.integrate,
                                 t.forces,
                                 t.neighbors,
                                 t.ghosts,
                                 t.migration,
                                 output_seconds_,
                                 snapshots_.write_seconds()};
  mpi_.group().max(slowest);
  std::vector<double> halo = {static_cast<double>(t.halo_bytes), static_cast<double>(t.refreshes)};
  mpi_.group().sum(halo);
  if (quiet_ || !mpi_.is_root()) return;
  std::printf(
      "time split (slowest rank): integration %.3g s, forces %.3g s, neighbour lists %.3g s "
      "(%llu builds), ghost exchange %.3g s, migration %.3g s, output %.3g s%s; halo %.4g bytes "
      "per rank per step\n",
      slowest[0], slowest[1], slowest[2],
      static_cast<unsigned long long>(engine_.rebuild_count() - first_list_builds_), slowest[3],
      slowest[4], slowest[5], writer_thread_note(slowest[6]).c_str(),
      halo[1] > 0 ? halo[0] / halo[1] : 0.0);
}

std::string TimeLoop::writer_thread_note(double seconds) const {
  if (!snapshots_.asynchronous()) return {};
  char note[64];
  std::snprintf(note, sizeof(note), " (snapshots %.3g s on the writer thread)", seconds);
  return note;
}

std::optional<Diagnostics> TimeLoop::record(std::uint64_t step, bool snapshot) {
  Stopwatch watch;
  const std::optional<Diagnostics> row = record_row(step, snapshot);
  output_seconds_ += watch.lap();
  return row;
}

std::optional<Diagnostics> TimeLoop::record_row(std::uint64_t step, bool snapshot) {
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
    series_.append(timeseries_row(time, step, step_dt(), *row, removed, imbalance_,
                                  implement_loads_, !scene_.bonds.empty()));
  }
  if (snapshot) write_snapshot(time, step);
  return row;
}

void TimeLoop::wait_for_snapshots() {
  Stopwatch watch;
  snapshots_.wait();
  output_seconds_ += watch.lap();
}

void TimeLoop::checkpoint(std::uint64_t step) {
  wait_for_snapshots();
  Stopwatch watch;
  write_checkpoint(mpi_.comm(), scene_.output.dir, capture(step));
  output_seconds_ += watch.lap();
}

int TimeLoop::stop_unstable(std::uint64_t step, const HealthFailure& f) {
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

std::string TimeLoop::describe(const HealthFailure& f) {
  if (f.non_finite) return "has a non-finite position or velocity";
  return "overlaps by " + std::to_string(f.overlap_ratio * 100) + " % of its radius";
}
}  // namespace gpudem
