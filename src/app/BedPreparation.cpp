#include "app/BedPreparation.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/ContactModel.hpp"
#include "core/InputError.hpp"
#include "core/RowShare.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;

/// Unit vector opposite to gravity, along which heights are measured (gravity is non-zero in a
/// preparation; the scene loader refuses it otherwise).
Vec3 up_direction(Vec3 gravity) { return (-1 / norm(gravity)) * gravity; }

/// Time for a particle at rest to fall the domain's extent along gravity, √(2H/|g|) with
/// H = Σ_k |L_k ĝ_k|; 0 without gravity.
double domain_fall_time(const Scene& scene) {
  const Vec3 g = scene.simulation.gravity;
  const double g_norm = norm(g);
  if (!(g_norm > 0)) return 0;
  const Vec3 size = scene.domain.max - scene.domain.min;
  double height = 0;
  for (int k = 0; k < 3; ++k) height += std::abs(axis(size, k) * axis(g, k) / g_norm);
  return std::sqrt(2 * height / g_norm);
}

/// Keeps the records k of `rows` (`width` values each) whose keep[k] is set.
template <class T>
void keep_rows(std::vector<T>& rows, const std::vector<char>& keep, std::size_t width = 1) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < keep.size(); ++k) {
    if (!keep[k]) continue;
    std::copy_n(rows.begin() + k * width, width, rows.begin() + kept * width);
    ++kept;
  }
  rows.resize(kept * width);
}

void keep_particles(Checkpoint& c, const std::vector<char>& keep) {
  ParticleStore& p = c.particles;
  for_each_particle_field([&](auto field) { keep_rows(field.of(p), keep); });
  keep_rows(c.list_position_radius, keep);
}

/// Keeps the pair records of a kept owner whose partner (on any rank) was not removed.
void keep_pairs(ContactHistory& h, const std::unordered_set<ParticleId>& kept,
                const std::unordered_set<ParticleId>& removed) {
  std::vector<char> pairs(h.pair_owner.size());
  for (std::size_t k = 0; k < pairs.size(); ++k)
    pairs[k] = kept.count(h.pair_owner[k]) && !removed.count(h.pair_partner[k]);
  keep_rows(h.pair_owner, pairs);
  keep_rows(h.pair_partner, pairs);
  keep_rows(h.pair_values, pairs, h.width);
}

/// Keeps the pair records of the kept pairs (keep_pairs) and the wall records of kept
/// particles; drops every mesh record (a bed starts other scenes, with tools of their own).
void keep_history(ContactHistory& h, const std::unordered_set<ParticleId>& kept,
                  const std::unordered_set<ParticleId>& removed) {
  keep_pairs(h, kept, removed);
  std::vector<char> walls(h.wall_owner.size());
  for (std::size_t k = 0; k < walls.size(); ++k) walls[k] = kept.count(h.wall_owner[k]);
  keep_rows(h.wall_owner, walls);
  keep_rows(h.wall_index, walls);
  keep_rows(h.wall_values, walls, h.width);
  h.mesh_owner.clear();
  h.mesh_triangle.clear();
  h.mesh_values.clear();
}

/// What trimming did: particles kept and removed, and the highest top of a kept particle [m].
struct TrimResult {
  std::size_t kept = 0;
  std::size_t removed = 0;
  double bed_height = -std::numeric_limits<double>::infinity();
};

/// The trim results of all ranks together (each trims the particles it owns). Collective.
TrimResult over_ranks(const MpiContext& mpi, const TrimResult& mine) {
  std::vector<std::uint64_t> counts = {mine.kept, mine.removed};
  mpi.group().sum(counts);
  return TrimResult{counts[0], counts[1], mpi.group().max<double>(mine.bed_height)};
}

/// The ids of `mine` of every rank. Collective.
std::unordered_set<ParticleId> ids_of_all_ranks(const MpiContext& mpi,
                                                const std::vector<ParticleId>& mine) {
  const std::vector<ParticleId> all = mpi.group().gather(mine);
  return std::unordered_set<ParticleId>(all.begin(), all.end());
}

/// Removes this rank's particles whose centre lies above `remove_above` along `up`, and their
/// contacts, also those with particles another rank removed. Collective.
TrimResult trim(const MpiContext& mpi, Checkpoint& c, Vec3 up, double remove_above) {
  const ParticleStore& p = c.particles;
  std::vector<char> keep(p.size());
  std::unordered_set<ParticleId> kept;
  std::vector<ParticleId> removed;
  TrimResult result;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double height = dot(xyz(p.position_radius[i]), up);
    keep[i] = height <= remove_above;
    if (!keep[i]) {
      removed.push_back(p.id[i]);
      continue;
    }
    kept.insert(p.id[i]);
    result.bed_height = std::max(result.bed_height, height + p.position_radius[i].w);
  }
  result.kept = kept.size();
  result.removed = removed.size();
  keep_particles(c, keep);
  const std::unordered_set<ParticleId> removed_anywhere = ids_of_all_ranks(mpi, removed);
  keep_history(c.history, kept, removed_anywhere);
  keep_pairs(c.bonds, kept, removed_anywhere);  // each end's record: two per bond
  c.bonds_made = mpi.group().sum<std::uint64_t>(c.bonds.pair_owner.size()) / 2;
  return result;
}

/// fsync of a directory, so that a rename in it is on disk; false when it cannot be done.
bool sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return false;
  const bool synced = ::fsync(fd) == 0;
  return ::close(fd) == 0 && synced;
}

/// Moves the complete checkpoint in `staging` to `path` and removes `staging`. Returns what went
/// wrong, or "".
std::string publish_bed(const fs::path& staging, const fs::path& path) {
  std::error_code ec;
  fs::rename(checkpoint_path(staging.string()), path, ec);
  if (ec) return "cannot rename the bed to '" + path.string() + "': " + ec.message();
  if (!sync_directory(path.parent_path()))
    return "cannot sync the folder of '" + path.string() + "'";
  fs::remove_all(staging, ec);
  return {};
}

/// Writes `bed` to `path` with the checkpoint writer: into a staging folder next to it (the
/// writer's own temporary name, sync and rename), then renamed into place, so `path` is either
/// the previous file or the complete bed. Collective.
void write_bed_file(const MpiContext& mpi, const fs::path& path, const Checkpoint& bed) {
  const fs::path staging = path.string() + ".staging";
  std::error_code ec;
  if (mpi.is_root()) fs::create_directories(staging, ec);
  throw_first_failure(mpi.group(),
                      {ec ? "cannot create folder '" + staging.string() + "'" : std::string()});
  write_checkpoint(mpi.comm(), staging.string(), bed);
  throw_first_failure(mpi.group(), {mpi.is_root() ? publish_bed(staging, path) : std::string()});
}

void print_bed_summary(const Scene& scene, const TrimResult& r, double time,
                       const std::string& path) {
  const std::string height =
      r.kept > 0 ? std::to_string(r.bed_height) + " m" : std::string("none (no particle kept)");
  std::printf(
      "bed: %zu particles kept, %zu removed above %.6g m; bed height %s (highest top of a kept "
      "particle); settled at t = %.6g s; written to %s\n",
      r.kept, r.removed, scene.preparation.remove_above, height.c_str(), time, path.c_str());
  std::fflush(stdout);
}

/// The bed's wall records for the walls `wall_count` of the scene; returns how many it drops.
std::size_t keep_known_walls(ContactHistory& h, std::size_t wall_count) {
  std::vector<char> keep(h.wall_owner.size());
  for (std::size_t k = 0; k < keep.size(); ++k) keep[k] = h.wall_index[k] < wall_count;
  const std::size_t dropped = std::count(keep.begin(), keep.end(), 0);
  keep_rows(h.wall_owner, keep);
  keep_rows(h.wall_index, keep);
  keep_rows(h.wall_values, keep, h.width);
  return dropped;
}

}  // namespace

double mean_kinetic_energy(const Diagnostics& d) {
  if (d.particle_count == 0) return 0;
  return (d.kinetic_translational + d.kinetic_rotational) / static_cast<double>(d.particle_count);
}

SettleCheck::SettleCheck(const Scene& scene, double dt)
    : threshold_(scene.preparation.kinetic_energy) {
  const double after =
      scene.preparation.check_after >= 0 ? scene.preparation.check_after : domain_fall_time(scene);
  first_step_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(after / dt)));
}

void print_preparation(const Scene& scene, const SettleCheck& settle, double dt) {
  std::printf(
      "preparation: settled once the mean kinetic energy per particle is below %.6g J (checked "
      "at every time-series row from t = %.6g s); then particles above %.6g m are removed and "
      "the bed is written to %s\n",
      scene.preparation.kinetic_energy, settle.first_step() * dt, scene.preparation.remove_above,
      bed_file_path(scene).c_str());
  std::fflush(stdout);
}

std::string bed_file_path(const Scene& scene) {
  if (!scene.preparation.bed_file.empty()) return scene.preparation.bed_file;
  return (fs::path(scene.output.dir) / "bed.h5").string();
}

void report_unsettled(const Scene& scene, const MpiContext& mpi, double time,
                      const Diagnostics& d) {
  if (!mpi.is_root()) return;
  std::fprintf(stderr,
               "gpudem-mpi: error: did not settle: mean kinetic energy %.6g J per particle at "
               "t = %.6g s, threshold %.6g J; no bed written. Raise simulation.end_time or "
               "preparation.kinetic_energy.\n",
               mean_kinetic_energy(d), time, scene.preparation.kinetic_energy);
}

void save_bed(const Scene& scene, const MpiContext& mpi, Checkpoint state) {
  const TrimResult result = over_ranks(mpi, trim(mpi, state, up_direction(scene.simulation.gravity),
                                                 scene.preparation.remove_above));
  const std::string path = bed_file_path(scene);
  write_bed_file(mpi, path, state);
  if (mpi.is_root()) print_bed_summary(scene, result, state.time, path);
}

BedReader BedLoader::reader(const Scene& scene, FilePart part) {
  return [this, &scene, part](const std::string& path) {
    Checkpoint bed = read_checkpoint(path, part);
    map_materials_by_name(bed, path, scene);
    require_bond_tables(bed, path, scene);
    path_ = path;
    history_ = std::move(bed.history);
    if (bed.bonds_made > 0) bonds_ = std::move(bed.bonds);  // a bed with no bond left has none
    bonds_made_ = bed.bonds_made;
    return std::move(bed.particles);
  };
}

void BedLoader::apply_history(const Scene& scene, const MpiContext& mpi, StepEngine& engine) {
  if (!history_) return;
  ContactHistory history = std::move(*history_);
  history_.reset();
  const std::uint32_t width = contact_history_width(scene.contact.model);
  if (scene.contact.model.cohesion == CohesionLaw::Jkr && history.width + 1 == width) {
    // A bed of the same law without JKR: every record was a touching contact when written.
    history = with_value_appended(history, 1);
    if (mpi.is_root())
      std::printf(
          "bed %s: its contact history keeps %u values per contact, this law's without JKR's "
          "formed flag; its contacts keep their springs and start formed\n",
          path_.c_str(), width - 1);
  }
  if (history.width != width) {
    if (mpi.is_root())
      std::printf(
          "bed %s: its contact history keeps %u values per contact but this contact law keeps "
          "%u; the bed starts with zero contact history\n",
          path_.c_str(), history.width, width);
    return;
  }
  const std::uint64_t dropped =
      mpi.group().sum<std::uint64_t>(keep_known_walls(history, scene.walls.size()));
  if (dropped > 0 && mpi.is_root())
    std::printf(
        "bed %s: %llu wall contact record(s) name walls this scene does not have; dropped\n",
        path_.c_str(), static_cast<unsigned long long>(dropped));
  try {
    engine.set_contact_history(std::move(history));
  } catch (const std::invalid_argument& e) {
    throw InputError(path_, 0, "", e.what());
  }
  engine.rebuild_neighbors();
}

bool BedLoader::apply_bonds(const MpiContext& mpi, StepEngine& engine) {
  if (!bonds_) return false;
  ContactHistory bonds = std::move(*bonds_);
  bonds_.reset();
  try {
    engine.continue_bonds(std::move(bonds), bonds_made_);
  } catch (const std::invalid_argument& e) {
    throw InputError(path_, 0, "", e.what());
  }
  if (mpi.is_root())
    std::printf("bed %s: its %llu bonds hold; the [[bond]] tables make no others\n", path_.c_str(),
                static_cast<unsigned long long>(bonds_made_));
  return true;
}

}  // namespace gpudem
