#pragma once
/// Names that become output file and dataset names: the particle snapshots' basename, the
/// particle datasets a snapshot may hold, and each mesh's name (group /mesh/<name>/ of every
/// snapshot and file <name>.xmf beside the particles' .xmf).
#include <array>
#include <cstdint>
#include <string>

namespace gpudem {

/// Basename of the particle snapshots: `particles_<index>.h5` and `particles.xmf`.
inline const std::string kParticlesBasename = "particles";

/// The particle datasets a snapshot may hold beside "position" (which every snapshot holds),
/// in the order the .xmf lists them; bit k of a field set stands for kSnapshotFields[k].
inline constexpr std::array<const char*, 6> kSnapshotFields = {
    "radius", "velocity", "angular_velocity", "force", "material", "id"};

/// The field set of every dataset of kSnapshotFields.
inline constexpr std::uint32_t kAllSnapshotFields = (1u << kSnapshotFields.size()) - 1;

/// Why `name` cannot name a mesh's output beside snapshots of basename `particles_basename`,
/// or null.
inline const char* mesh_output_name_problem(const std::string& name,
                                            const std::string& particles_basename) {
  if (name.empty()) return "is empty";
  if (name.find('/') != std::string::npos) return "contains '/'";
  if (name == "." || name == "..") return "is not a file name";
  if (name == particles_basename) return "is the particles' basename";
  return nullptr;
}

}  // namespace gpudem
