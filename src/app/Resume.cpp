#include "app/Resume.hpp"

#include <mpi.h>

#include <filesystem>

#include "core/InputError.hpp"

namespace gpudem {

std::string resume_checkpoint(const Scene& scene, const MpiContext& mpi) {
  if (scene.checkpoint.every <= 0)
    throw InputError(scene.file, 0, "checkpoint.every",
                     "--resume needs checkpoints to resume from: set checkpoint.every > 0");
  const std::filesystem::path path = std::filesystem::path(scene.output.dir) / "checkpoint.h5";
  int found = mpi.is_root() && std::filesystem::is_regular_file(path) ? 1 : 0;
  MPI_Bcast(&found, 1, MPI_INT, 0, mpi.comm());
  return found ? path.string() : std::string();
}

}  // namespace gpudem
