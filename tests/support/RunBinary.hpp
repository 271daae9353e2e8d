#pragma once
// Runs the gpudem-mpi binary under test (binary_path()) with arguments and collects its exit
// code and combined stdout/stderr.
#include <sys/wait.h>

#include <cstdio>
#include <string>

#include "support/TestPaths.hpp"

namespace gpudem::test {

struct RunResult {
  int exit_code;       ///< -1 when the process did not exit normally
  std::string output;  ///< stdout and stderr together
};

/// Runs `command` through the shell, stderr into stdout.
inline RunResult run_command(const std::string& command) {
  RunResult r{-1, ""};
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline RunResult run_binary(const std::string& args) {
  return run_command(binary_path() + " " + args + " 2>&1");
}

/// The shell command that runs the binary on `ranks` MPI ranks: mpiexec_path(), allowed as root
/// and past the core count, without the variables that make this test process an MPI process
/// (under them the launcher would take itself for one of its ranks), stderr into stdout. The
/// OpenMP threads are those the environment gives; `launcher` goes before the launcher (e.g.
/// "taskset -c 0 ").
inline std::string ranks_command(int ranks, const std::string& args,
                                 const std::string& launcher = "") {
  return "for v in $(env | grep -Eo '^(OMPI|PMIX|OPAL)_[A-Za-z0-9_]*'); do unset \"$v\"; done; " +
         launcher + mpiexec_path() + " --allow-run-as-root --oversubscribe -np " +
         std::to_string(ranks) + " " + binary_path() + " " + args + " 2>&1";
}

/// The binary on `ranks` MPI ranks (ranks_command), one OpenMP thread per rank.
inline RunResult run_binary_on_ranks(int ranks, const std::string& args) {
  return run_command("OMP_NUM_THREADS=1; export OMP_NUM_THREADS; " + ranks_command(ranks, args));
}

}  // namespace gpudem::test
