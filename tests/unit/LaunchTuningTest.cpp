// Launch tuning on one process: the block-size table, medians of repeated timings, and the choice
// that every rank agrees on, with injected timings and a stand-in for the max-over-ranks
// reduction that folds in the other ranks' rows of a table. Expected choices are worked out by
// hand in the comments. The same choice through MPI at 1, 2 and 4 ranks is in
// tests/mpi/LaunchTuningAgreementTest.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "engine/LaunchTuning.hpp"
#include "engine/ParallelFor.hpp"

namespace gpudem {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using Rows = std::vector<std::vector<double>>;  // rows[rank][candidate]

/// The ranks of `rows` as one of them sees them: a max folds its own values with every row
/// (nothing else is asked of it).
class FoldRows final : public RankGroup {
 public:
  explicit FoldRows(Rows rows) : rows_(std::move(rows)) {}
  int rank() const override { return 0; }
  int size() const override { return static_cast<int>(rows_.size()); }
  void reduce(Reduction op, double* values, std::size_t n) const override {
    if (op != Reduction::Max) throw std::logic_error("FoldRows: only max");
    for (const auto& row : rows_)
      for (std::size_t i = 0; i < n; ++i) values[i] = std::max(values[i], row[i]);
  }
  void reduce(Reduction, std::uint64_t*, std::size_t) const override { unused(); }
  void broadcast(std::vector<char>&, int) const override { unused(); }
  void all_gather(const std::vector<char>&, RankBuffers&) const override { unused(); }
  void exchange(const RankBuffers&, RankBuffers&) const override { unused(); }

 private:
  [[noreturn]] static void unused() { throw std::logic_error("FoldRows: not a reduction"); }
  Rows rows_;
};

FoldRows fold_rows(const Rows& rows) { return FoldRows(rows); }

/// The block each simulated rank of `rows` chooses.
std::vector<unsigned> choices(const Rows& rows) {
  std::vector<unsigned> chosen;
  for (const auto& row : rows) chosen.push_back(agree_on_block_size(row, fold_rows(rows)));
  return chosen;
}

TEST(LaunchTuning, StartsAtTheDefaultAndTakesOnlyCandidates) {
  LaunchTuning table;
  EXPECT_EQ(table.block_size(LaunchSlot::forces), 256u);
  EXPECT_EQ(table.block_size(LaunchSlot::neighbor_list), 256u);
  EXPECT_EQ(table.block_size(LaunchSlot::integrate), 256u);
  table.set_block_size(LaunchSlot::integrate, 1024);
  EXPECT_EQ(table.block_size(LaunchSlot::integrate), 1024u);
  EXPECT_EQ(table.block_size(LaunchSlot::forces), 256u);
  EXPECT_THROW(table.set_block_size(LaunchSlot::forces, 96), std::invalid_argument);
  EXPECT_THROW(table.set_block_size(LaunchSlot::forces, 2048), std::invalid_argument);
  table.reset();
  EXPECT_EQ(table.block_size(LaunchSlot::integrate), 256u);
}

TEST(LaunchTuning, MedianOfOddAndEvenCounts) {
  EXPECT_EQ(median({7.0}), 7.0);
  EXPECT_EQ(median({3.0, 100.0, 1.0}), 3.0);
  EXPECT_EQ(median({4.0, 1.0, 1e9, 2.0}), 3.0);  // (2 + 4) / 2
  EXPECT_EQ(median({5.0, 5.0, 0.5, 5.0, 90.0}), 5.0);
  EXPECT_THROW(median({}), std::invalid_argument);
}

TEST(LaunchTuning, TimesEachCandidateByItsMedianWithTheTableHoldingIt) {
  LaunchTuning table;
  table.set_block_size(LaunchSlot::forces, 512);
  // Per block: the first call is a slow outlier (10 s), the next ones alternate t, 2t, t, so the
  // median of the 4 calls {10, t, 2t, t} is (t + 2t) / 2 = 1.5 t, with t = block / 1024 s.
  std::map<unsigned, int> calls;
  std::vector<unsigned> seen_in_table;
  const TimeWithBlock fake = [&](unsigned block) {
    seen_in_table.push_back(table.block_size(LaunchSlot::forces));
    const int call = calls[block]++;
    const double t = block / 1024.0;
    return call == 0 ? 10.0 : (call % 2 == 1 ? t : 2 * t);
  };
  const std::vector<double> times = time_candidates(table, LaunchSlot::forces, fake, 4);
  EXPECT_EQ(times, (std::vector<double>{0.09375, 0.1875, 0.375, 0.75, 1.5}));
  EXPECT_EQ(seen_in_table,
            (std::vector<unsigned>{64,  64,  64,  64,  128, 128, 128,  128,  256,  256,
                                   256, 256, 512, 512, 512, 512, 1024, 1024, 1024, 1024}));
  EXPECT_EQ(table.block_size(LaunchSlot::forces), 512u);  // restored
  EXPECT_EQ(table.block_size(LaunchSlot::integrate), 256u);
}

TEST(LaunchTuning, FailedOrMeaninglessTimingsMakeACandidateUnusable) {
  LaunchTuning table;
  const TimeWithBlock fake = [](unsigned block) -> double {
    if (block == 1024) throw std::runtime_error("too many resources requested for launch");
    if (block == 64) return std::nan("");
    if (block == 128) return -1.0;
    if (block == 512) return kInf;
    return 0.25;
  };
  EXPECT_EQ(time_candidates(table, LaunchSlot::neighbor_list, fake, 3),
            (std::vector<double>{kInf, kInf, 0.25, kInf, kInf}));
}

TEST(LaunchTuning, FastestCandidateTakesTheSmallerBlockOnTies) {
  EXPECT_EQ(fastest_candidate({3, 2, 1, 1, 4}), 2u);
  EXPECT_EQ(fastest_candidate({1, 1, 1, 1, 1}), 0u);
  EXPECT_EQ(fastest_candidate({5, 4, 3, 2, 2}), 3u);
}

TEST(LaunchTuning, OneRankTakesItsOwnFastest) {
  EXPECT_EQ(choices({{2.0, 1.5, 1.0, 1.2, 3.0}}), (std::vector<unsigned>{256}));
}

TEST(LaunchTuning, TwoRanksAgreeOnTheBlockThatMinimisesTheSlowerRank) {
  // Own fastest: rank 0 64, rank 1 1024. Slower rank per block: 3.0 2.4 2.6 3.5 8.0 -> 128.
  // (The sum, 4.0 4.4 4.2 5.5 8.5, would pick 64: the slowest rank decides, not the average.)
  const Rows rows{{1.0, 2.0, 1.6, 3.5, 8.0}, {3.0, 2.4, 2.6, 2.0, 0.5}};
  EXPECT_EQ(choices(rows), (std::vector<unsigned>{128, 128}));
}

TEST(LaunchTuning, FourRanksAgreeOnTheBlockThatMinimisesTheSlowestRank) {
  // Own fastest: 64, 1024, 128, 512. Slowest rank per block: 9.0 4.0 3.9 4.5 9.5 -> 256.
  const Rows rows{{1.0, 2.0, 3.0, 4.0, 9.5},
                  {9.0, 4.0, 3.9, 4.5, 0.1},
                  {5.0, 0.2, 3.8, 4.4, 6.0},
                  {2.0, 3.0, 2.5, 0.3, 1.0}};
  EXPECT_EQ(choices(rows), (std::vector<unsigned>(4, 256)));
}

TEST(LaunchTuning, TiesAcrossRanksGoToTheSmallerBlock) {
  // Slowest rank per block: 4 3 3 3 5 -> a three-way tie, won by 128.
  const Rows rows{{4.0, 3.0, 1.0, 3.0, 5.0}, {1.0, 2.0, 3.0, 1.0, 1.0}};
  EXPECT_EQ(choices(rows), (std::vector<unsigned>{128, 128}));
}

TEST(LaunchTuning, ABlockThatFailedOnOneRankIsNotChosen) {
  // 64 is the fastest on rank 0 and failed on rank 1; next best slowest-rank time is 256's 2.0.
  const Rows rows{{0.1, 3.0, 2.0, 2.5, 4.0}, {kInf, 1.0, 1.0, 1.0, 1.0}};
  EXPECT_EQ(choices(rows), (std::vector<unsigned>{256, 256}));
}

TEST(LaunchTuning, NoUsableCandidateOnEveryRankThrowsEverywhere) {
  const Rows rows{{kInf, 1.0, kInf, 1.0, kInf}, {1.0, kInf, 1.0, kInf, 1.0}};
  for (const auto& row : rows)
    EXPECT_THROW(agree_on_block_size(row, fold_rows(rows)), std::runtime_error);
  EXPECT_THROW(agree_on_block_size({1.0, 2.0}, fold_rows({})), std::invalid_argument);
}

TEST(LaunchTuning, TuneStoresTheAgreedBlockForItsSlotOnly) {
  LaunchTuning table;
  // This rank is fastest at 1024; another rank (folded in) is slow there: 512 wins.
  const TimeWithBlock fake = [](unsigned block) { return 1.0 / block; };
  const Rows other{{0.0, 0.0, 0.0, 0.0, 0.5}};
  EXPECT_EQ(tune_block_size(table, LaunchSlot::integrate, fake, fold_rows(other), 3), 512u);
  EXPECT_EQ(table.block_size(LaunchSlot::integrate), 512u);
  EXPECT_EQ(table.block_size(LaunchSlot::forces), 256u);
}

TEST(LaunchTuning, VerboseReportNamesEachSlotOrSaysTheHostHasNothingToTune) {
  EXPECT_FALSE(has_block_sizes(HostSpace{}));
  EXPECT_TRUE(has_block_sizes(CudaSpace{}));
  LaunchTuning table;
  table.set_block_size(LaunchSlot::neighbor_list, 64);
  EXPECT_EQ(launch_tuning_report(table, true),
            "launch tuning (threads per block): forces 256 neighbor_list 64 integrate 256");
  EXPECT_NE(launch_tuning_report(table, false).find("host backend"), std::string::npos);
}

TEST(LaunchTuning, HostSlotLaunchIsThePlainLoopAndHostTimingMeasuresTheWork) {
  std::vector<int> hits(1000, 0);
  launch_tuning().set_block_size(LaunchSlot::forces, 64);
  parallel_for(
      HostSpace{}, hits.size(), [&](std::size_t i) { ++hits[i]; }, LaunchSlot::forces);
  launch_tuning().reset();
  EXPECT_EQ(hits, std::vector<int>(1000, 1));
  const double seconds = seconds_to_run(
      HostSpace{}, [] { std::this_thread::sleep_for(std::chrono::milliseconds(20)); });
  EXPECT_GE(seconds, 0.02);
  EXPECT_LT(seconds, 10.0);
}

}  // namespace
}  // namespace gpudem
