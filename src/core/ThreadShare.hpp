#pragma once
/// How a node's cores are shared among the OpenMP threads of its ranks (README, "Running"): the
/// threads a rank takes when the user chose none, and the warning when the ranks' threads exceed
/// the cores they may use. Plain values, so the rules are tested without MPI or a machine of
/// a given shape; app/ThreadCores gathers the values over the ranks.
#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace gpudem {

/// Where a rank runs: its node (a hash of the host name), the CPUs its affinity mask holds (bit
/// c of word c / 64 for CPU c) and the OpenMP threads it runs.
struct RankCpus {
  std::uint64_t node = 0;
  std::vector<std::uint64_t> mask;
  int threads = 1;
};

/// CPUs in the mask.
inline int cpu_count(const std::vector<std::uint64_t>& mask) {
  int n = 0;
  for (const std::uint64_t w : mask) n += __builtin_popcountll(w);
  return n;
}

namespace detail {

/// A node's ranks, their threads in all and the CPUs of their masks together.
struct NodeShare {
  int ranks = 0, threads = 0;
  std::vector<std::uint64_t> cpus;
};

/// Each node's NodeShare, by node.
inline std::map<std::uint64_t, NodeShare> node_shares(const std::vector<RankCpus>& all) {
  std::map<std::uint64_t, NodeShare> nodes;
  for (const RankCpus& r : all) {
    NodeShare& n = nodes[r.node];
    ++n.ranks;
    n.threads += r.threads;
    n.cpus.resize(std::max(n.cpus.size(), r.mask.size()), 0);
    for (std::size_t w = 0; w < r.mask.size(); ++w) n.cpus[w] |= r.mask[w];
  }
  return nodes;
}

inline bool overlap(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
  for (std::size_t w = 0; w < std::min(a.size(), b.size()); ++w)
    if (a[w] & b[w]) return true;
  return false;
}

/// The first node whose ranks run more threads in all than the cores of their masks together.
inline std::string node_crowding_warning(const std::vector<RankCpus>& all) {
  for (const auto& [id, n] : node_shares(all)) {
    const int cores = cpu_count(n.cpus);
    if (n.threads <= cores) continue;
    const std::string fix =
        n.ranks > cores
            ? "run at most " + std::to_string(cores) + " rank(s) per node (mpirun -np " +
                  std::to_string(cores) + " on one node)"
            : "unset OMP_NUM_THREADS (each rank then takes its share of the cores) "
              "or set it to " +
                  std::to_string(cores / n.ranks);
    return "warning: " + std::to_string(n.ranks) + " ranks on one node run " +
           std::to_string(n.threads) + " OpenMP threads in all on its " + std::to_string(cores) +
           " core(s), so they take turns; " + fix;
  }
  return {};
}

/// The ranks with more threads than the cores of their own mask, the lowest named.
inline std::string rank_crowding_warning(const std::vector<RankCpus>& all) {
  int crowded = 0, first = -1;
  for (std::size_t r = 0; r < all.size(); ++r)
    if (all[r].threads > cpu_count(all[r].mask)) {
      ++crowded;
      if (first < 0) first = static_cast<int>(r);
    }
  if (crowded == 0) return {};
  const std::string threads = std::to_string(all[first].threads);
  return "warning: " + std::to_string(crowded) + " of " + std::to_string(all.size()) +
         " rank(s) run more OpenMP threads than the cores they may use (rank " +
         std::to_string(first) + ": " + threads + " threads on " +
         std::to_string(cpu_count(all[first].mask)) +
         " core(s)), so the threads take turns; mpirun binds each rank to one core unless told "
         "otherwise: run it with --bind-to none (or --map-by slot:PE=" +
         threads + "), or set OMP_NUM_THREADS=" + std::to_string(cpu_count(all[first].mask));
}

}  // namespace detail

/// Threads for rank `rank` of `all` when the user chose none: the cores of its mask divided by
/// the ranks of its node whose masks overlap its own (itself included), at least 1.
inline int shared_thread_count(const std::vector<RankCpus>& all, int rank) {
  const RankCpus& me = all[static_cast<std::size_t>(rank)];
  int sharers = 0;
  for (const RankCpus& other : all)
    if (other.node == me.node && detail::overlap(other.mask, me.mask)) ++sharers;
  return std::max(1, cpu_count(me.mask) / std::max(1, sharers));
}

/// Whether the node of rank `rank` of `all` runs more ranks than the cores of their masks
/// together: then they take turns on the cores, whatever their threads.
inline bool node_has_more_ranks_than_cores(const std::vector<RankCpus>& all, int rank) {
  const detail::NodeShare n = detail::node_shares(all).at(all[static_cast<std::size_t>(rank)].node);
  return n.ranks > cpu_count(n.cpus);
}

/// The warning for ranks with more threads than cores, or empty: either a rank with more
/// threads than its mask's cores (the lowest such rank named, with the mpirun options that give
/// it more), or a node whose ranks' threads exceed the cores of their masks together (fewer
/// ranks or threads per node).
inline std::string crowded_threads_warning(const std::vector<RankCpus>& all) {
  const std::string rank = detail::rank_crowding_warning(all);
  return rank.empty() ? detail::node_crowding_warning(all) : rank;
}

}  // namespace gpudem
