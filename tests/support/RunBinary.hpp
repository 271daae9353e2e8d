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

inline RunResult run_binary(const std::string& args) {
  const std::string command = binary_path() + " " + args + " 2>&1";
  RunResult r{-1, ""};
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace gpudem::test
