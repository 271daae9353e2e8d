// GhostRowSplit on the host backend: the owned particles split into those whose neighbour-list
// row reads only owned particles (interior) and those whose row reads a ghost (boundary), for
// lists written by hand and random lists over owned particles and fake ghosts, each checked
// against the rows themselves.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "engine/GhostExchange.hpp"

namespace gpudem {
namespace {

using Rows = std::vector<std::vector<std::uint32_t>>;

/// The split of `rows` (one per owned particle; entries >= owned are ghosts) as host vectors.
struct HostSplit {
  std::vector<std::uint32_t> interior;
  std::vector<std::uint32_t> boundary;
};

HostSplit split(const Rows& rows) {
  std::vector<std::uint32_t> offsets{0}, neighbors;
  for (const std::vector<std::uint32_t>& row : rows) {
    neighbors.insert(neighbors.end(), row.begin(), row.end());
    offsets.push_back(static_cast<std::uint32_t>(neighbors.size()));
  }
  DeviceArray<std::uint32_t, HostSpace> device_offsets, device_neighbors;
  device_offsets.upload(offsets);
  device_neighbors.upload(neighbors);
  GhostRowSplit<HostSpace> rows_split;
  rows_split.build(device_offsets.data(), device_neighbors.data(), rows.size());
  HostSplit result;
  result.interior.assign(rows_split.interior(),
                         rows_split.interior() + rows_split.interior_count());
  result.boundary.assign(rows_split.boundary(),
                         rows_split.boundary() + rows_split.boundary_count());
  return result;
}

TEST(GhostRowSplit, HandWrittenRows) {
  // Six owned particles (0..5), ghosts 6..8.
  const Rows rows = {{1, 2}, {0, 7}, {}, {6}, {3, 5, 8}, {4}};
  const HostSplit s = split(rows);
  EXPECT_EQ(s.interior, (std::vector<std::uint32_t>{0, 2, 5}));
  EXPECT_EQ(s.boundary, (std::vector<std::uint32_t>{1, 3, 4}));
}

TEST(GhostRowSplit, NoGhostsMakesEveryRowInterior) {
  const Rows rows = {{1}, {0, 2}, {1}};
  const HostSplit s = split(rows);
  EXPECT_EQ(s.interior, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_TRUE(s.boundary.empty());
}

TEST(GhostRowSplit, NoOwnedParticles) {
  const HostSplit s = split(Rows{});
  EXPECT_TRUE(s.interior.empty());
  EXPECT_TRUE(s.boundary.empty());
}

TEST(GhostRowSplit, RandomRowsArePartitionedByWhetherTheyReadAGhost) {
  std::mt19937 random(12345);
  for (int trial = 0; trial < 40; ++trial) {
    const std::uint32_t owned = std::uniform_int_distribution<std::uint32_t>(1, 300)(random);
    const std::uint32_t ghosts = std::uniform_int_distribution<std::uint32_t>(0, 60)(random);
    const std::uint32_t row_length = std::uniform_int_distribution<std::uint32_t>(0, 8)(random);
    std::uniform_int_distribution<std::uint32_t> partner(0, owned + ghosts - 1);
    Rows rows(owned);
    for (std::vector<std::uint32_t>& row : rows) {
      const std::uint32_t length =
          std::uniform_int_distribution<std::uint32_t>(0, row_length)(random);
      for (std::uint32_t e = 0; e < length; ++e) row.push_back(partner(random));
    }
    const HostSplit s = split(rows);
    std::vector<int> seen(owned, 0);
    for (const std::uint32_t i : s.interior) {
      ASSERT_LT(i, owned);
      ++seen[i];
      for (const std::uint32_t j : rows[i]) EXPECT_LT(j, owned) << "interior row " << i;
    }
    for (const std::uint32_t i : s.boundary) {
      ASSERT_LT(i, owned);
      ++seen[i];
      bool reads_ghost = false;
      for (const std::uint32_t j : rows[i]) reads_ghost = reads_ghost || j >= owned;
      EXPECT_TRUE(reads_ghost) << "boundary row " << i;
    }
    for (std::uint32_t i = 0; i < owned; ++i)
      EXPECT_EQ(seen[i], 1) << "particle " << i << " in " << seen[i] << " lists";
    for (std::size_t k = 1; k < s.interior.size(); ++k) EXPECT_LT(s.interior[k - 1], s.interior[k]);
    for (std::size_t k = 1; k < s.boundary.size(); ++k) EXPECT_LT(s.boundary[k - 1], s.boundary[k]);
  }
}

}  // namespace
}  // namespace gpudem
