#pragma once
/// Whether a rank's OpenMP threads have cores of their own: mpirun (Open MPI) binds each rank to
/// one core unless told otherwise, and a rank of T threads bound to C < T cores runs them in
/// turns (README, "Running").
#include <string>

#include "comm/MpiContext.hpp"

namespace gpudem {

/// The OpenMP threads a rank runs and the cores its affinity mask lets it run on.
struct ThreadCores {
  int threads = 1;
  int cores = 1;
};

/// This process's ThreadCores (threads 1 without OpenMP).
ThreadCores this_rank_thread_cores();

/// The warning for ranks with more threads than cores (`first` the lowest such rank, `rank`
/// its index, `crowded` how many of `ranks` are), or empty when `crowded` is 0.
std::string crowded_threads_warning(const ThreadCores& first, int rank, int crowded, int ranks);

/// crowded_threads_warning over all ranks, on rank 0 (empty elsewhere). Collective.
std::string crowded_threads_warning(const MpiContext& mpi);

}  // namespace gpudem
