// The pieces the host's sweep in lanes (engine/PairLanesForces.hpp) moves its entries with, in
// the build's own instructions (the lanes units use AVX-512 or AVX2 for the same operations):
// a mask's bits, gathers by index, stores of the chosen lanes packed to the front, and the
// queue of touching entries, whose waiting entries survive evaluations and moves to the front in
// order, also when every entry has been evaluated and the columns are full.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/LaneMemory.hpp"
#include "engine/PairLanesForces.hpp"

namespace gpudem::test {
namespace {

template <int W>
void expect_packed_in_order() {
  Lanes<double, W> v;
  Lanes<std::uint32_t, W> u;
  for (int l = 0; l < W; ++l) v.v[l] = 10.0 + l, u.v[l] = 100u + static_cast<unsigned>(l);
  for (LaneBits take = 0; take < (1u << W); ++take) {
    double packed[W];
    std::uint32_t packed_u[W];
    store_packed(packed, v, take);
    store_packed(packed_u, u, take);
    int n = 0;
    for (int l = 0; l < W; ++l)
      if (take >> l & 1u) {
        EXPECT_EQ(packed[n], 10.0 + l) << "mask " << take << ", lane " << l;
        EXPECT_EQ(packed_u[n], 100u + static_cast<unsigned>(l)) << "mask " << take;
        ++n;
      }
  }
}

TEST(LaneMemory, PackedStoresKeepTheChosenLanesInOrder) {
  expect_packed_in_order<4>();
  expect_packed_in_order<8>();
}

TEST(LaneMemory, MaskBitsAndFirstLanes) {
  Lanes<double, 8> x;
  for (int l = 0; l < 8; ++l) x.v[l] = l % 3 == 0 ? 1.0 : -1.0;
  EXPECT_EQ(bits_of(x > 0.0), 0b01001001u);
  EXPECT_EQ(first_lanes<8>(0), 0u);
  EXPECT_EQ(first_lanes<8>(3), 0b111u);
  EXPECT_EQ(first_lanes<8>(8), 0xffu);
  EXPECT_EQ(first_lanes<8>(20), 0xffu);
  EXPECT_EQ(first_lanes<4>(9), 0xfu);
}

TEST(LaneMemory, GatherReadsEachLanesOffset) {
  std::vector<double> base(64);
  for (std::size_t k = 0; k < base.size(); ++k) base[k] = 0.5 * static_cast<double>(k);
  Lanes<std::int64_t, 8> at;
  for (int l = 0; l < 8; ++l) at.v[l] = (l * 7 + 3) % 64;
  const Lanes<double, 8> g = gather(base.data(), at);
  for (int l = 0; l < 8; ++l) EXPECT_EQ(g[l], 0.5 * static_cast<double>((l * 7 + 3) % 64));
}

/// Appends `n` entries numbered from `next` to the queue as a test of W lanes does.
template <int W>
void append(TouchingEntries<W>& q, int n, std::uint32_t& next) {
  Lanes<std::uint32_t, W> ids;
  Lanes<double, W> xs;
  for (int l = 0; l < W; ++l) ids.v[l] = next + static_cast<std::uint32_t>(l), xs.v[l] = ids.v[l];
  const LaneBits take = first_lanes<W>(static_cast<unsigned>(n));
  using Q = TouchingEntries<W>;
  for (int c = 0; c < Q::indices; ++c) store_packed(q.index[c] + q.count, ids, take);
  for (auto& column : q.xj) store_packed(column + q.count, xs, take);
  q.count += n;
  next += static_cast<std::uint32_t>(n);
}

TEST(TouchingEntries, WaitingEntriesSurviveEvaluationsAndMoves) {
  constexpr int W = 8;
  using Q = TouchingEntries<W>;
  Q q;
  std::uint32_t next = 0, evaluated = 0;
  for (int round = 0; round < 200; ++round) {
    append(q, (round * 5 + 3) % (W + 1), next);  // 0 to W entries, as a test of W lanes finds
    if (q.waiting() >= W) {
      for (int l = 0; l < W; ++l) {  // the first W wait in order, in every column
        EXPECT_EQ(q.at(Q::entry)[l], evaluated + static_cast<std::uint32_t>(l));
        EXPECT_EQ(q.partner_positions().w[l], static_cast<double>(evaluated + l));
      }
      evaluated += W;
      q.drop_first();
    }
    q.make_room();
    ASSERT_LE(q.count + W, Q::capacity);
    ASSERT_LT(q.waiting(), W);
    for (int l = 0; l < q.waiting(); ++l)
      EXPECT_EQ(q.at(Q::j)[l], evaluated + static_cast<std::uint32_t>(l));
  }
  EXPECT_GT(evaluated, 4u * Q::capacity);  // the columns filled and moved several times
}

TEST(TouchingEntries, FullColumnsAllEvaluatedMoveNothing) {
  constexpr int W = 8;
  using Q = TouchingEntries<W>;
  Q q;
  std::uint32_t next = 0;
  for (int b = 0; b < Q::capacity / W; ++b) {
    append(q, W, next);
    q.drop_first();
  }
  ASSERT_EQ(q.count, Q::capacity);
  ASSERT_EQ(q.waiting(), 0);
  q.make_room();  // reads nothing past the columns (the sanitized build checks)
  EXPECT_EQ(q.count, 0);
  EXPECT_EQ(q.waiting(), 0);
}

}  // namespace
}  // namespace gpudem::test
