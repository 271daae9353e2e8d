#pragma once
/// Names that become output file names: the particle snapshots' basename and each mesh's name
/// (group /mesh/<name>/ of every snapshot and file <name>.xmf beside the particles' .xmf).
#include <string>

namespace gpudem {

/// Basename of the particle snapshots: `particles_<index>.h5` and `particles.xmf`.
inline const std::string kParticlesBasename = "particles";

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
