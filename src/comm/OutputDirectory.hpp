#pragma once
/// Creation of the run's output directory (the first thing a run writes).
#include <string>

namespace gpudem {

/// Creates `dir` (and parents) if needed and checks it is writable. Throws InputError with key
/// `output.dir` when it cannot be created or written.
void prepare_output_directory(const std::string& dir);

}  // namespace gpudem
