// The collectives every layer shares (core/RankGroup.hpp) on four fake ranks in one process:
// reductions, gather in rank order, the prefix sum of counts, broadcast, and the agreement on
// the lowest failing rank's error (its kind and message thrown on every rank). The same through
// MPI is in tests/mpi/ShareRoutingTest.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/RankGroup.hpp"
#include "support/FakeRanks.hpp"

namespace gpudem {
namespace {

constexpr int kRanks = 4;

/// body(group) on kRanks fake ranks.
template <class Body>
void on_fake_ranks(Body&& body) {
  test::run_on_fake_ranks(kRanks, [&](test::FakeRankLink& link) { body(link.group()); });
}

TEST(RankGroup, ReductionsAndFirstRankAgreeOnEveryRank) {
  std::vector<double> max(kRanks), sum(kRanks), min(kRanks);
  std::vector<std::uint64_t> wrapped(kRanks);
  std::vector<int> first(kRanks), none(kRanks);
  std::vector<std::vector<char>> broadcast(kRanks);
  on_fake_ranks([&](const RankGroup& ranks) {
    const int r = ranks.rank();
    max[r] = ranks.max(r == 2 ? 5.5 : -1.0 * r);
    sum[r] = ranks.sum(1.0 + r);
    min[r] = ranks.min(r == 1 ? -7.0 : 1.0 * r);
    wrapped[r] = ranks.sum(~std::uint64_t{0});  // -1 four times, modulo 2^64
    first[r] = ranks.first_rank_with(r >= 1);
    none[r] = ranks.first_rank_with(false);
    std::vector<char> bytes(r == 3 ? 3 : 1, static_cast<char>('a' + r));
    ranks.broadcast(bytes, 3);
    broadcast[r] = bytes;
  });
  for (int r = 0; r < kRanks; ++r) {
    EXPECT_EQ(max[r], 5.5);
    EXPECT_EQ(sum[r], 10.0);
    EXPECT_EQ(min[r], -7.0);
    EXPECT_EQ(wrapped[r], ~std::uint64_t{0} - 3);
    EXPECT_EQ(first[r], 1);
    EXPECT_EQ(none[r], kRanks);
    EXPECT_EQ(broadcast[r], (std::vector<char>{'d', 'd', 'd'}));
  }
}

TEST(RankGroup, GatherConcatenatesInRankOrderAndSumBeforeCountsTheEarlierRanks) {
  std::vector<std::vector<int>> gathered(kRanks);
  std::vector<std::uint64_t> before(kRanks);
  on_fake_ranks([&](const RankGroup& ranks) {
    const int r = ranks.rank();
    gathered[r] = ranks.gather(std::vector<int>(r, 10 * r));  // rank r holds r values
    before[r] = ranks.sum_before(static_cast<std::uint64_t>(r + 1));
  });
  const std::vector<int> expected = {10, 20, 20, 30, 30, 30};
  for (int r = 0; r < kRanks; ++r) EXPECT_EQ(gathered[r], expected) << "rank " << r;
  EXPECT_EQ(before, (std::vector<std::uint64_t>{0, 1, 3, 6}));
}

TEST(RankGroup, TheLowestFailingRanksErrorIsThrownOnEveryRank) {
  std::vector<std::string> thrown(kRanks);
  std::vector<bool> input(kRanks);
  on_fake_ranks([&](const RankGroup& ranks) {
    const int r = ranks.rank();
    try {
      agree_on_failure(ranks, [&] {
        if (r == 2) throw std::runtime_error("rank 2 broke");
        if (r == 3) throw InputError("scene.toml", 4, "domain.max", "too small");
        return r;
      });
    } catch (const InputError& e) {
      thrown[r] = e.what();
      input[r] = true;
    } catch (const std::runtime_error& e) {
      thrown[r] = e.what();
    }
  });
  for (int r = 0; r < kRanks; ++r) {
    EXPECT_EQ(thrown[r], "rank 2 broke") << "rank " << r;
    EXPECT_FALSE(input[r]) << "rank " << r;
  }
}

TEST(RankGroup, AnInputErrorStaysOneAndNoFailureReturnsEachRanksResult) {
  std::vector<bool> input(kRanks);
  std::vector<int> result(kRanks);
  on_fake_ranks([&](const RankGroup& ranks) {
    const int r = ranks.rank();
    try {
      agree_on_failure(ranks, [&] {
        if (r == 3) throw InputError("scene.toml", 4, "domain.max", "too small");
        return r;
      });
    } catch (const InputError& e) {
      input[r] = std::string(e.what()).find("too small") != std::string::npos;
    }
    result[r] = agree_on_failure(ranks, [&] { return 10 + r; });
  });
  EXPECT_EQ(input, std::vector<bool>(kRanks, true));
  EXPECT_EQ(result, (std::vector<int>{10, 11, 12, 13}));
}

}  // namespace
}  // namespace gpudem
