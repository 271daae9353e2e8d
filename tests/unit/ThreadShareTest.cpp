// How a node's cores are shared among the OpenMP threads of its ranks: the share a rank takes
// when the user chose no thread count, and the warnings when ranks' threads exceed their cores.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/ThreadShare.hpp"

namespace {

using gpudem::RankCpus;

/// A mask holding CPUs [first, first + count).
std::vector<std::uint64_t> cpus(int first, int count) {
  std::vector<std::uint64_t> mask(4, 0);
  for (int c = first; c < first + count; ++c) mask[c / 64] |= std::uint64_t{1} << (c % 64);
  return mask;
}

/// `ranks` ranks on node `node`, each with mask `mask` and `threads` threads.
std::vector<RankCpus> ranks_on(std::uint64_t node, int ranks, std::vector<std::uint64_t> mask,
                               int threads) {
  return std::vector<RankCpus>(static_cast<std::size_t>(ranks), RankCpus{node, mask, threads});
}

TEST(ThreadShare, CountsTheCpusOfAMaskAcrossWords) {
  EXPECT_EQ(gpudem::cpu_count(cpus(0, 2)), 2);
  EXPECT_EQ(gpudem::cpu_count(cpus(60, 10)), 10);
  EXPECT_EQ(gpudem::cpu_count(cpus(0, 256)), 256);
}

TEST(ThreadShare, OneRankTakesEveryCoreOfItsMask) {
  EXPECT_EQ(gpudem::shared_thread_count(ranks_on(1, 1, cpus(0, 16), 16), 0), 16);
}

/// Unbound ranks (oversubscribed, or --bind-to none) all see the node's cores and split them.
TEST(ThreadShare, UnboundRanksSplitTheirCommonCores) {
  EXPECT_EQ(gpudem::shared_thread_count(ranks_on(1, 4, cpus(0, 64), 64), 2), 16);
  EXPECT_EQ(gpudem::shared_thread_count(ranks_on(1, 3, cpus(0, 16), 16), 0), 5);
}

TEST(ThreadShare, MoreRanksThanCoresLeaveOneThreadEach) {
  EXPECT_EQ(gpudem::shared_thread_count(ranks_on(1, 4, cpus(0, 2), 2), 3), 1);
}

/// Ranks bound to disjoint cores keep their own; ranks of other nodes do not count.
TEST(ThreadShare, DisjointMasksAndOtherNodesAreNotShared) {
  std::vector<RankCpus> all = ranks_on(1, 1, cpus(0, 8), 8);
  all.push_back(RankCpus{1, cpus(8, 8), 8});
  all.push_back(RankCpus{2, cpus(0, 8), 8});
  for (int r = 0; r < 3; ++r) EXPECT_EQ(gpudem::shared_thread_count(all, r), 8) << r;
  all.push_back(RankCpus{1, cpus(4, 8), 8});  // overlaps both masks of node 1
  EXPECT_EQ(gpudem::shared_thread_count(all, 0), 4);
  EXPECT_EQ(gpudem::shared_thread_count(all, 3), 2);  // 8 cores over 3 sharers
}

/// Ranks take turns where their node's cores (the union of its ranks' masks) are fewer than the
/// node's ranks, however many threads each runs; other nodes do not count.
TEST(ThreadShare, RanksTakeTurnsWhereANodeHasMoreRanksThanCores) {
  EXPECT_TRUE(gpudem::node_has_more_ranks_than_cores(ranks_on(1, 3, cpus(0, 2), 1), 2));
  EXPECT_FALSE(gpudem::node_has_more_ranks_than_cores(ranks_on(1, 2, cpus(0, 2), 1), 0));
  EXPECT_TRUE(gpudem::node_has_more_ranks_than_cores(ranks_on(1, 2, cpus(0, 1), 1), 1));
  std::vector<RankCpus> bound = ranks_on(1, 1, cpus(0, 1), 4);
  bound.push_back(RankCpus{1, cpus(1, 1), 4});
  EXPECT_FALSE(gpudem::node_has_more_ranks_than_cores(bound, 1));
  std::vector<RankCpus> two_nodes = ranks_on(1, 2, cpus(0, 2), 1);
  for (const RankCpus& r : ranks_on(2, 4, cpus(0, 2), 1)) two_nodes.push_back(r);
  EXPECT_FALSE(gpudem::node_has_more_ranks_than_cores(two_nodes, 1));
  EXPECT_TRUE(gpudem::node_has_more_ranks_than_cores(two_nodes, 2));
}

TEST(ThreadShare, NoWarningWhenThreadsFitTheirCores) {
  EXPECT_EQ(gpudem::crowded_threads_warning(ranks_on(1, 2, cpus(0, 4), 2)), "");
  std::vector<RankCpus> bound = ranks_on(1, 1, cpus(0, 1), 1);
  bound.push_back(RankCpus{1, cpus(1, 1), 1});
  EXPECT_EQ(gpudem::crowded_threads_warning(bound), "");
}

TEST(ThreadShare, ARankWithMoreThreadsThanItsCoresIsNamed) {
  std::vector<RankCpus> all = ranks_on(1, 1, cpus(0, 1), 1);
  all.push_back(RankCpus{1, cpus(1, 1), 4});
  const std::string w = gpudem::crowded_threads_warning(all);
  EXPECT_NE(w.find("1 of 2 rank(s) run more OpenMP threads than the cores they may use (rank 1: "
                   "4 threads on 1 core(s))"),
            std::string::npos)
      << w;
  EXPECT_NE(w.find("--bind-to none (or --map-by slot:PE=4)"), std::string::npos) << w;
}

TEST(ThreadShare, MoreRanksThanCoresOnANodeAskForFewerRanks) {
  const std::string w = gpudem::crowded_threads_warning(ranks_on(7, 4, cpus(0, 2), 1));
  EXPECT_NE(w.find("4 ranks on one node run 4 OpenMP threads in all on its 2 core(s)"),
            std::string::npos)
      << w;
  EXPECT_NE(w.find("run at most 2 rank(s) per node"), std::string::npos) << w;
}

TEST(ThreadShare, TooManyThreadsOnANodeAskForFewerThreads) {
  const std::string w = gpudem::crowded_threads_warning(ranks_on(7, 2, cpus(0, 8), 8));
  EXPECT_NE(w.find("2 ranks on one node run 16 OpenMP threads in all on its 8 core(s)"),
            std::string::npos)
      << w;
  EXPECT_NE(w.find("or set it to 4"), std::string::npos) << w;
}

TEST(ThreadShare, TheSharedCountNeverCrowdsANode) {
  for (int ranks = 1; ranks <= 6; ++ranks) {
    std::vector<RankCpus> all = ranks_on(1, ranks, cpus(0, 6), 6);
    for (int r = 0; r < ranks; ++r) all[r].threads = gpudem::shared_thread_count(all, r);
    EXPECT_EQ(gpudem::crowded_threads_warning(all), "") << ranks;
  }
}

}  // namespace
