// The host backend's sort_by_key against std::stable_sort of (key, value) pairs by key, on random
// keys with many duplicates, for bit counts from 1 to 64; and bits_for against hand-counted
// values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "engine/ParallelFor.hpp"

namespace gpudem {
namespace {

using Pairs = std::vector<std::pair<std::uint64_t, std::uint32_t>>;

/// n pairs (key, position) with keys drawn from `distinct` random values below 2^key_bits, the
/// largest of which is 2^key_bits - 1, so that the sort needs all key_bits bits.
Pairs random_pairs(std::size_t n, int key_bits, std::size_t distinct, std::uint32_t seed) {
  std::mt19937_64 random(seed);
  const std::uint64_t top = key_bits == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << key_bits) - 1;
  std::uniform_int_distribution<std::uint64_t> any_key(0, top);
  std::vector<std::uint64_t> pool{top};
  while (pool.size() < distinct) pool.push_back(any_key(random));
  std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
  Pairs pairs(n);
  for (std::size_t i = 0; i < n; ++i)
    pairs[i] = {pool[pick(random)], static_cast<std::uint32_t>(i)};
  return pairs;
}

/// The expected order: std::stable_sort by key only.
Pairs stably_sorted(Pairs pairs) {
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  return pairs;
}

/// The pairs after sort_by_key(HostSpace) on separate key and value arrays.
Pairs sorted_by_portable_layer(const Pairs& pairs, int key_bits) {
  std::vector<std::uint64_t> keys;
  std::vector<std::uint32_t> values;
  for (const auto& [k, v] : pairs) {
    keys.push_back(k);
    values.push_back(v);
  }
  sort_by_key(HostSpace{}, keys.data(), values.data(), keys.size(), key_bits);
  Pairs out;
  for (std::size_t i = 0; i < keys.size(); ++i) out.emplace_back(keys[i], values[i]);
  return out;
}

TEST(BitsFor, CountsTheBitsOfTheLargestKey) {
  EXPECT_EQ(bits_for(0), 0);
  EXPECT_EQ(bits_for(1), 1);
  EXPECT_EQ(bits_for(2), 2);
  EXPECT_EQ(bits_for(3), 2);
  EXPECT_EQ(bits_for(4), 3);
  EXPECT_EQ(bits_for(255), 8);
  EXPECT_EQ(bits_for(256), 9);
  EXPECT_EQ(bits_for(0xFFFFFFFFull), 32);
  EXPECT_EQ(bits_for(0x100000000ull), 33);
  EXPECT_EQ(bits_for(0x8000000000000000ull), 64);
  EXPECT_EQ(bits_for(~0ull), 64);
}

TEST(HostSortByKey, MatchesStableSortForEveryBitCount) {
  for (int key_bits : {1, 2, 7, 8, 9, 16, 17, 24, 31, 32, 33, 40, 48, 63, 64}) {
    for (std::size_t distinct : {std::size_t(2), std::size_t(50), std::size_t(5000)}) {
      SCOPED_TRACE(::testing::Message() << key_bits << " bits, " << distinct << " keys");
      const Pairs pairs = random_pairs(20000, key_bits, distinct, 17u * key_bits + distinct);
      EXPECT_EQ(sorted_by_portable_layer(pairs, key_bits), stably_sorted(pairs));
    }
  }
}

TEST(HostSortByKey, KeysWithEqualHighDigitsSortOnTheirLowBits) {
  // Every key shares bits 8..39: only the lowest digit decides, and the skipped digits must not
  // lose it.
  Pairs pairs;
  std::mt19937 random(3);
  for (std::uint32_t i = 0; i < 3000; ++i)
    pairs.emplace_back((std::uint64_t(0xABCDEF12) << 8) | (random() % 7), i);
  EXPECT_EQ(sorted_by_portable_layer(pairs, 40), stably_sorted(pairs));
}

TEST(HostSortByKey, EmptyOneAndZeroBitSortsLeaveTheInputAsItIs) {
  EXPECT_TRUE(sorted_by_portable_layer({}, 12).empty());
  const Pairs one{{5, 9}};
  EXPECT_EQ(sorted_by_portable_layer(one, 3), one);
  const Pairs zeros{{0, 4}, {0, 1}, {0, 3}};
  EXPECT_EQ(sorted_by_portable_layer(zeros, 0), zeros);
}

TEST(HostSortByKey, RefusesKeysWiderThanTheBitCountAndBadBitCounts) {
  std::vector<std::uint64_t> keys{1, 8, 2};
  std::vector<std::uint32_t> values{0, 1, 2};
  EXPECT_THROW(sort_by_key(HostSpace{}, keys.data(), values.data(), 3, 3), std::invalid_argument);
  EXPECT_THROW(sort_by_key(HostSpace{}, keys.data(), values.data(), 3, -1), std::invalid_argument);
  EXPECT_THROW(sort_by_key(HostSpace{}, keys.data(), values.data(), 3, 65), std::invalid_argument);
}

}  // namespace
}  // namespace gpudem
