#include "app/Resume.hpp"

#include <filesystem>

#include "app/BedPreparation.hpp"
#include "core/InputError.hpp"

namespace gpudem {
namespace {

/// `path` when rank 0 finds a file there, else "". Collective.
std::string existing_on_root(const std::filesystem::path& path, const MpiContext& mpi) {
  const bool here = mpi.is_root() && std::filesystem::is_regular_file(path);
  return mpi.group().broadcast_value(here, 0) ? path.string() : std::string();
}

}  // namespace

ResumePoint find_resume_point(const Scene& scene, const MpiContext& mpi) {
  if (scene.checkpoint.every <= 0)
    throw InputError(scene.file, 0, "checkpoint.every",
                     "--resume needs checkpoints to resume from: set checkpoint.every > 0");
  ResumePoint point;
  point.checkpoint =
      existing_on_root(std::filesystem::path(scene.output.dir) / "checkpoint.h5", mpi);
  if (scene.preparation.enabled) point.bed = existing_on_root(bed_file_path(scene), mpi);
  return point;
}

}  // namespace gpudem
