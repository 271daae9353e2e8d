#pragma once
// A fresh temporary directory that every rank of MPI_COMM_WORLD shares: rank 0 makes it and
// broadcasts its path; named after the running test so parallel test processes never collide.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "support/MpiRank.hpp"

namespace gpudem::test {

inline std::string make_shared_temp_dir(const std::string& prefix) {
  namespace fs = std::filesystem;
  std::string path;
  if (comm_rank() == 0) {
    path = (fs::temp_directory_path() /
            (prefix + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name()))
               .string();
    fs::remove_all(path);
    fs::create_directories(path);
  }
  int length = static_cast<int>(path.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  path.resize(length);
  MPI_Bcast(path.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  return path;
}

/// Removes the directory once every rank is done with it.
inline void remove_shared_temp_dir(const std::string& path) {
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm_rank() == 0) std::filesystem::remove_all(path);
}

}  // namespace gpudem::test
