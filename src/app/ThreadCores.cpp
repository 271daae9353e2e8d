#include "app/ThreadCores.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#if defined(GPUDEM_HAVE_OPENMP)
#include <omp.h>
#endif

namespace gpudem {

namespace {

constexpr std::size_t kMaskWords = CPU_SETSIZE / 64;

/// FNV-1a of this machine's host name: the same on every rank of a node.
std::uint64_t node_id() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  std::uint64_t h = 1469598103934665603ull;
  for (const char* c = name; *c; ++c) h = (h ^ static_cast<unsigned char>(*c)) * 1099511628211ull;
  return h;
}

/// This process's affinity mask as words of 64 CPUs (all CPUs online when it cannot be read).
std::vector<std::uint64_t> affinity_mask() {
  std::vector<std::uint64_t> mask(kMaskWords, 0);
  cpu_set_t set;
  CPU_ZERO(&set);
  const bool read = sched_getaffinity(0, sizeof set, &set) == 0;
  const long online = sysconf(_SC_NPROCESSORS_ONLN);
  for (std::size_t c = 0; c < CPU_SETSIZE; ++c)
    if (read ? CPU_ISSET(c, &set) : static_cast<long>(c) < online)
      mask[c / 64] |= std::uint64_t{1} << (c % 64);
  return mask;
}

/// Every rank's RankCpus, this rank's with `threads`. Collective.
std::vector<RankCpus> gather_rank_cpus(const MpiContext& mpi, int threads) {
  std::vector<std::uint64_t> mine{node_id(), static_cast<std::uint64_t>(threads)};
  const std::vector<std::uint64_t> mask = affinity_mask();
  mine.insert(mine.end(), mask.begin(), mask.end());
  const std::vector<std::uint64_t> flat = mpi.group().gather(mine);
  std::vector<RankCpus> all(static_cast<std::size_t>(mpi.size()));
  const std::size_t stride = mine.size();
  for (std::size_t r = 0; r < all.size(); ++r) {
    const std::uint64_t* row = flat.data() + r * stride;
    all[r].node = row[0];
    all[r].threads = static_cast<int>(row[1]);
    all[r].mask.assign(row + 2, row + stride);
  }
  return all;
}

int openmp_threads() {
#if defined(GPUDEM_HAVE_OPENMP)
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// Why rank 0 runs the threads it does.
std::string thread_source(bool chosen, int cores) {
#if defined(GPUDEM_HAVE_OPENMP)
  if (chosen) return "OMP_NUM_THREADS";
  return "OMP_NUM_THREADS unset: its " + std::to_string(cores) +
         " core(s) shared with the node's ranks whose cores overlap them";
#else
  (void)chosen;
  (void)cores;
  return "built without OpenMP";
#endif
}

}  // namespace

ThreadPlan share_node_cores(const MpiContext& mpi) {
  const bool chosen = std::getenv("OMP_NUM_THREADS") != nullptr;
  std::vector<RankCpus> all = gather_rank_cpus(mpi, openmp_threads());
  int threads = openmp_threads();
#if defined(GPUDEM_HAVE_OPENMP)
  if (!chosen) {
    threads = shared_thread_count(all, mpi.rank());
    omp_set_num_threads(threads);
    for (std::size_t r = 0; r < all.size(); ++r)
      all[r].threads = shared_thread_count(all, static_cast<int>(r));
  }
#endif
  ThreadPlan plan;
  plan.ranks_take_turns = node_has_more_ranks_than_cores(all, mpi.rank());
  if (!mpi.is_root()) return plan;
  plan.note = "host backend: " + std::to_string(threads) + " OpenMP thread(s) on rank 0 (" +
              thread_source(chosen, cpu_count(all[0].mask)) + ")";
  plan.warning = crowded_threads_warning(all);
  if (plan.ranks_take_turns)
    plan.warning += "; meanwhile a rank that waits for another's messages sleeps between its tests";
  return plan;
}

}  // namespace gpudem
