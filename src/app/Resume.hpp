#pragma once
/// --resume: continue a run from its own latest checkpoint when there is one, so that a chain
/// of batch jobs (each cut short by its time limit) can run the same command line until the
/// run is complete.
#include <string>

#include "comm/MpiContext.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// What a resumed run finds in its output folder, as rank 0 sees it.
struct ResumePoint {
  std::string checkpoint;  ///< <output.dir>/checkpoint.h5 when that file exists, else ""
  /// A bed preparation's bed file when it exists (the preparation is complete), else ""
  std::string bed;
};

/// Looks for the files a resumed run continues from or is complete with. Throws InputError
/// naming checkpoint.every when the scene writes no checkpoints (a resumed chain would restart
/// from the beginning every time). Collective.
ResumePoint find_resume_point(const Scene& scene, const MpiContext& mpi);

}  // namespace gpudem
