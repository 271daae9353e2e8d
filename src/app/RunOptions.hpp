#pragma once
/// What the command line asks of a run.
#include <string>
#include <vector>

#include "comm/GpuAwareMpi.hpp"

namespace gpudem {

enum class BackendChoice { Auto, Host, Cuda };

struct RunOptions {
  std::string scene_file;
  std::vector<std::string> overrides;  ///< --set key=value, in order
  std::string output_dir;              ///< --output-dir (empty: the scene's output.dir)
  std::string restart_file;            ///< --restart: checkpoint to continue from (empty: none)
  bool resume = false;  ///< --resume: continue from <output dir>/checkpoint.h5 if it exists
  BackendChoice backend = BackendChoice::Auto;
  GpuAwareChoice gpu_aware_mpi = GpuAwareChoice::Auto;  ///< --gpu-aware-mpi
  bool check_only = false;                              ///< --check
  bool preview = false;                                 ///< --preview
  bool quiet = false;                                   ///< --quiet
  bool verbose = false;           ///< --verbose: the memory report at start-up
  bool exact_time_split = false;  ///< --exact-time-split: EngineSetup::exact_phase_times
};

}  // namespace gpudem
