#pragma once
/// --resume: continue a run from its own latest checkpoint when there is one, so that a chain
/// of batch jobs (each cut short by its time limit) can run the same command line until the
/// run is complete.
#include <string>

#include "comm/MpiContext.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// The checkpoint a resumed run continues from: <output.dir>/checkpoint.h5 when rank 0 finds
/// that file, else "" (the run starts from the scene's sources). Throws InputError naming
/// checkpoint.every when the scene writes no checkpoints (a resumed chain would restart from
/// the beginning every time). Collective.
std::string resume_checkpoint(const Scene& scene, const MpiContext& mpi);

}  // namespace gpudem
