#pragma once
/// How this process waits for its MPI operations (docs/architecture.md, "Ranks that take turns
/// on a core"). By default MPI's own wait, which spins: the shortest wait where each rank has a
/// core. Where a node runs more ranks than it has cores, a spinning rank holds a core that the
/// rank it waits for needs, for a whole scheduler slice at every wait; there each wait instead
/// tests its requests kSpinTests times and then sleeps kNap between tests, so that the waiting
/// rank gives its core away.
#include <mpi.h>

#include <chrono>

namespace gpudem {

enum class MpiWaiting {
  spin,  ///< MPI_Waitall
  nap    ///< MPI_Testall, then short sleeps between tests
};

/// Tests before a napping wait first sleeps, and each sleep.
inline constexpr int kSpinTests = 1000;
inline constexpr std::chrono::microseconds kNap{50};

/// Sets how complete_requests waits, for the whole process. Call it before any thread other
/// than the main one makes MPI calls.
void set_mpi_waiting(MpiWaiting mode);
MpiWaiting mpi_waiting();

/// Completes requests[0, n) (their statuses ignored) as set_mpi_waiting says.
void complete_requests(int n, MPI_Request* requests);

}  // namespace gpudem
