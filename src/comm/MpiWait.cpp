#include "comm/MpiWait.hpp"

#include <atomic>
#include <thread>

namespace gpudem {

namespace {

std::atomic<MpiWaiting> waiting{MpiWaiting::spin};

}  // namespace

void set_mpi_waiting(MpiWaiting mode) { waiting.store(mode, std::memory_order_relaxed); }

MpiWaiting mpi_waiting() { return waiting.load(std::memory_order_relaxed); }

void complete_requests(int n, MPI_Request* requests) {
  if (mpi_waiting() == MpiWaiting::spin) {
    MPI_Waitall(n, requests, MPI_STATUSES_IGNORE);
    return;
  }
  int done = 0;
  for (int tests = 0;; ++tests) {
    MPI_Testall(n, requests, &done, MPI_STATUSES_IGNORE);
    if (done) return;
    if (tests >= kSpinTests) std::this_thread::sleep_for(kNap);
  }
}

}  // namespace gpudem
