// Launch tuning across MPI ranks (run at 1, 2 and 4 ranks): each rank injects its own timings,
// with a slow first call per candidate that only the median discards; the reduction is the
// engine's, the group of an MpiDomain. Every rank must choose the same block, the one
// whose slowest rank is fastest, worked out by hand below for each rank count.
#include <gtest/gtest.h>
#include <mpi.h>

#include <array>
#include <map>
#include <vector>

#include "comm/Decomposition.hpp"
#include "comm/MpiDomain.hpp"
#include "engine/LaunchTuning.hpp"
#include "support/MpiRank.hpp"

namespace gpudem {
namespace {

/// Seconds per candidate (64 ... 1024) of ranks 0..3; each rank's own fastest differs
/// (64, 1024, 128, 512).
constexpr std::array<std::array<double, 5>, 4> kRankTimes{{{1.0, 2.0, 1.6, 3.5, 8.0},
                                                           {3.0, 2.4, 2.6, 2.0, 0.5},
                                                           {5.0, 0.2, 2.9, 4.4, 6.0},
                                                           {2.0, 3.0, 2.5, 0.3, 1.0}}};

/// The agreed block for each rank count: the slowest rank's time per candidate is
/// 1 rank:  1.0 2.0 1.6 3.5 8.0 -> 64;
/// 2 ranks: 3.0 2.4 2.6 3.5 8.0 -> 128 (the sum of the two would pick 64);
/// 4 ranks: 5.0 3.0 2.9 4.4 8.0 -> 256.
unsigned expected_block(int ranks) { return ranks == 1 ? 64 : ranks == 2 ? 128 : 256; }

/// A one-axis grid decomposition, one coarse cell per rank.
MpiDomain slab_domain() {
  const int ranks = test::comm_size();
  PeriodicBox box;
  box.length = Vec3{Real(ranks), 1, 1};
  const CoarseGrid cells = CoarseGrid::over(box, 1);
  std::array<std::vector<int>, 3> cuts{std::vector<int>{}, {0, 1}, {0, 1}};
  for (int q = 0; q <= ranks; ++q) cuts[0].push_back(q);
  return MpiDomain(MPI_COMM_WORLD, Decomposition::grid(cells, cuts), Real(0.25), false);
}

TEST(LaunchTuningAgreement, EveryRankChoosesTheBlockThatMinimisesTheSlowestRank) {
  const int rank = test::comm_rank(), ranks = test::comm_size();
  ASSERT_TRUE(ranks == 1 || ranks == 2 || ranks == 4) << "run at 1, 2 or 4 ranks";
  const MpiDomain domain = slab_domain();
  std::map<unsigned, int> calls;
  const TimeWithBlock own_times = [&](unsigned block) {
    std::size_t c = 0;
    while (kBlockSizeCandidates[c] != block) ++c;
    const double t = kRankTimes[rank][c];
    return calls[block]++ == 0 ? 100 * (10 - t) : t;  // first call: a slow outlier, reversed order
  };
  LaunchTuning table;
  const unsigned chosen = tune_block_size(table, LaunchSlot::forces, own_times, domain.group(), 3);
  EXPECT_EQ(chosen, expected_block(ranks));
  EXPECT_EQ(table.block_size(LaunchSlot::forces), chosen);

  std::vector<unsigned> everyone(ranks);
  MPI_Allgather(&chosen, 1, MPI_UNSIGNED, everyone.data(), 1, MPI_UNSIGNED, MPI_COMM_WORLD);
  EXPECT_EQ(everyone, std::vector<unsigned>(ranks, expected_block(ranks)));
}

}  // namespace
}  // namespace gpudem
