#pragma once
/// One simulation run on this rank: scene → particles → engine → time loop with output.
#include "app/RunOptions.hpp"
#include "comm/MpiContext.hpp"

namespace gpudem {

/// Exit codes of gpudem-mpi.
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,   ///< internal or system error
  kExitBadInput = 2,  ///< scene, CSV or command line rejected; nothing written
  kExitUnstable = 3,  ///< the run blew up (NaN or excessive overlap); last snapshot written
};

/// Runs (or, with --check, validates) the scene; with --resume from the output directory's
/// checkpoint when there is one, returning kExitOk at once when that checkpoint has reached
/// end_time. Throws InputError for bad input before any output is written.
int run_scene(const RunOptions& options, const MpiContext& mpi);

}  // namespace gpudem
