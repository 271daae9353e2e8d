#pragma once
/// Soil beds: a [preparation] run settles the particles, trims them at a height and saves the
/// bed as a checkpoint file; a later scene starts from it with `[[insert]] bed = "file"`.
#include <cstdint>
#include <optional>
#include <string>

#include "comm/Checkpoint.hpp"
#include "comm/MpiContext.hpp"
#include "core/ContactHistory.hpp"
#include "core/ParticleSources.hpp"
#include "core/RowShare.hpp"
#include "core/Scene.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

/// Mean kinetic energy per particle, (Σ ½ m v² + Σ ½ I ω²) / N [J]; 0 without particles.
double mean_kinetic_energy(const Diagnostics& d);

/// The settle criterion of [preparation]: from step first_step() on, a time-series row whose
/// mean kinetic energy per particle is below preparation.kinetic_energy. Checks start once a
/// particle at rest could have fallen the height of the domain, t = √(2H/|g|) with
/// H = Σ_k |L_k ĝ_k| (the domain's extent along gravity), unless check_after gives the time:
/// particles inserted at rest have almost no kinetic energy at first.
class SettleCheck {
 public:
  SettleCheck(const Scene& scene, double dt);
  std::uint64_t first_step() const { return first_step_; }
  bool settled(std::uint64_t step, const Diagnostics& d) const {
    return step >= first_step_ && mean_kinetic_energy(d) < threshold_;
  }

 private:
  double threshold_;
  std::uint64_t first_step_;
};

/// Prints, on the calling rank, one line saying how the preparation settles, trims and saves.
void print_preparation(const Scene& scene, const SettleCheck& settle, double dt);

/// Where the bed of a preparation goes: preparation.bed_file, or `<output.dir>/bed.h5`.
std::string bed_file_path(const Scene& scene);

/// Prints, on rank 0, why a preparation failed: the mean kinetic energy per particle `d`
/// gives at `time` and the threshold.
void report_unsettled(const Scene& scene, const MpiContext& mpi, double time, const Diagnostics& d);

/// Removes from `state` (the settled run's checkpoint) every particle whose centre lies above
/// preparation.remove_above along −gravity, with the contact history of its contacts, writes
/// the rest atomically to bed_file_path(scene) and prints one summary line on rank 0.
/// Collective.
void save_bed(const Scene& scene, const MpiContext& mpi, Checkpoint state);

/// Reads this rank's part of the bed file of a scene's bed source (for create_start_part) and
/// keeps the contact history and bonds it read to give to the engine.
class BedLoader {
 public:
  /// Reads the rows of `part` of a bed file (of the particles and of each kind of history
  /// record, as read_checkpoint), its particles' materials renumbered to those of the same
  /// names in `scene` (map_materials_by_name), its bonds checked against the scene's [[bond]]
  /// tables (require_bond_tables); its errors are InputErrors naming the file.
  BedReader reader(const Scene& scene, FilePart part);
  /// Gives `engine` this rank's part of the bed's contact history when the scene's contact law
  /// keeps as many values per contact (otherwise says on rank 0 that the bed starts without
  /// history) and re-evaluates the forces with it, then frees it. Wall records are kept by wall
  /// index, for the walls the scene has. Nothing happens when no bed was read. Collective.
  void apply_history(const Scene& scene, const MpiContext& mpi, StepEngine& engine);
  /// Gives `engine` this rank's part of the bed's bonds (StepEngine::continue_bonds) when the
  /// bed holds bonds (bonds_made > 0), says so on rank 0 and returns true; returns false (the
  /// scene's [[bond]] tables make the run's bonds) when it holds none or no bed was read.
  /// Collective.
  bool apply_bonds(const MpiContext& mpi, StepEngine& engine);

 private:
  std::string path_;
  std::optional<ContactHistory> history_;
  std::optional<ContactHistory> bonds_;  ///< this rank's part; none when the bed holds none
  std::uint64_t bonds_made_ = 0;         ///< the bed's intact bonds
};

}  // namespace gpudem
