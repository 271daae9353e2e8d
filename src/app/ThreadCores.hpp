#pragma once
/// The OpenMP threads of the host backend's ranks and the cores they run on (README, "Running").
/// Open MPI binds each rank to one core when there are at least as many cores as ranks, and binds
/// none when it oversubscribes; OpenMP starts as many threads as the rank's affinity mask holds
/// cores. Unless OMP_NUM_THREADS says otherwise, each rank therefore takes its share of the cores
/// it may use with the node's other ranks whose masks overlap its own; a warning names the fix
/// when a rank has more threads than its cores, or a node's ranks more than the node's cores.
#include <string>

#include "comm/MpiContext.hpp"
#include "core/ThreadShare.hpp"

namespace gpudem {

/// The host backend's threads as rank 0 reports them at start-up.
struct ThreadPlan {
  /// "host backend: N OpenMP thread(s) on rank 0 (...)", saying whether OMP_NUM_THREADS set
  /// them or the cores were shared (rank 0; empty elsewhere)
  std::string note;
  std::string warning;  ///< crowded_threads_warning over all ranks (rank 0; empty elsewhere)
  /// node_has_more_ranks_than_cores for this rank (every rank)
  bool ranks_take_turns = false;
};

/// Sets this rank's OpenMP threads to shared_thread_count when OMP_NUM_THREADS is unset (and
/// OpenMP is built in) and says what every rank runs. Collective; call before any parallel work.
ThreadPlan share_node_cores(const MpiContext& mpi);

}  // namespace gpudem
