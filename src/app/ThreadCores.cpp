#include "app/ThreadCores.hpp"

#include <sched.h>

#include <vector>

#if defined(GPUDEM_HAVE_OPENMP)
#include <omp.h>
#endif

namespace gpudem {

ThreadCores this_rank_thread_cores() {
  ThreadCores tc;
#if defined(GPUDEM_HAVE_OPENMP)
  tc.threads = omp_get_max_threads();
#endif
  cpu_set_t mask;
  CPU_ZERO(&mask);
  if (sched_getaffinity(0, sizeof mask, &mask) == 0) tc.cores = CPU_COUNT(&mask);
  return tc;
}

std::string crowded_threads_warning(const ThreadCores& first, int rank, int crowded, int ranks) {
  if (crowded == 0) return {};
  const std::string threads = std::to_string(first.threads);
  return "warning: " + std::to_string(crowded) + " of " + std::to_string(ranks) +
         " rank(s) run more OpenMP threads than the cores they may use (rank " +
         std::to_string(rank) + ": " + threads + " threads on " + std::to_string(first.cores) +
         " core(s)), so the threads take turns; mpirun binds each rank to one core unless told "
         "otherwise: run it with --bind-to none (or --map-by slot:PE=" +
         threads + "), or set OMP_NUM_THREADS=" + std::to_string(first.cores);
}

std::string crowded_threads_warning(const MpiContext& mpi) {
  const ThreadCores mine = this_rank_thread_cores();
  const std::vector<int> all = mpi.group().gather(std::vector<int>{mine.threads, mine.cores});
  if (!mpi.is_root()) return {};
  int crowded = 0, first = -1;
  for (int r = 0; r < mpi.size(); ++r)
    if (all[2 * r] > all[2 * r + 1]) {
      ++crowded;
      if (first < 0) first = r;
    }
  const ThreadCores worst =
      first < 0 ? ThreadCores{} : ThreadCores{all[2 * first], all[2 * first + 1]};
  return crowded_threads_warning(worst, first, crowded, mpi.size());
}

}  // namespace gpudem
