#pragma once
// Where the tests find the source tree's data and the gpudem-mpi binary under test, and where
// they leave fixtures: the paths of the build, unless the environment names others
// (GPUDEM_SOURCE_DIR, GPUDEM_BINARY, GPUDEM_MPIEXEC, GPUDEM_SNAPSHOT_FIXTURE_DIR), as it does
// when the tests
// run from a bundle copied to another machine (scripts/gpu_check.sh).
#include <cstdlib>
#include <string>

namespace gpudem::test {

/// The value of the environment variable, or `built_in` when it is unset or empty.
inline std::string path_from_environment(const char* variable, const char* built_in) {
  const char* value = std::getenv(variable);
  return value && *value ? value : built_in;
}

/// The source tree (test data, inputs).
inline std::string source_dir() {
  return path_from_environment("GPUDEM_SOURCE_DIR", GPUDEM_SOURCE_DIR);
}

/// The gpudem-mpi binary under test.
inline std::string binary_path() { return path_from_environment("GPUDEM_BINARY", GPUDEM_BINARY); }

/// The MPI launcher the build found, which starts the binary on several ranks.
inline std::string mpiexec_path() {
  return path_from_environment("GPUDEM_MPIEXEC", GPUDEM_MPIEXEC);
}

}  // namespace gpudem::test
