// The device side of a rebuild on several ranks, on the host backend: CsrRows reads out chosen
// rows of a CSR table and appends rows after the last one (the history rows of migrating
// particles), RankCells selects the particles in cells near another rank's, and
// RelocationKey sorts the leaving particles to the end by destination and the particles that
// left the box after them; each checked against a plain host computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "comm/Decomposition.hpp"
#include "engine/CsrRows.hpp"
#include "engine/RankCells.hpp"

namespace gpudem {
namespace {

using Table = std::vector<std::vector<std::pair<std::uint32_t, double>>>;

/// A table as host CSR arrays.
struct HostRows {
  std::vector<std::uint32_t> offsets{0};
  std::vector<std::uint32_t> keys;
  std::vector<double> values;
};

HostRows flatten(const Table& table) {
  HostRows h;
  for (const auto& row : table) {
    for (const auto& [key, value] : row) {
      h.keys.push_back(key);
      h.values.push_back(value);
    }
    h.offsets.push_back(static_cast<std::uint32_t>(h.keys.size()));
  }
  return h;
}

CsrRows<HostSpace, std::uint32_t, double> upload(const Table& table) {
  const HostRows h = flatten(table);
  CsrRows<HostSpace, std::uint32_t, double> rows;
  rows.offsets.upload(h.offsets);
  rows.keys.upload(h.keys);
  rows.values.upload(h.values);
  return rows;
}

Table download(const CsrRows<HostSpace, std::uint32_t, double>& rows,
               const std::vector<std::uint32_t>& which) {
  DeviceArray<std::uint32_t, HostSpace> device_which;
  device_which.upload(which);
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> keys;
  std::vector<double> values;
  rows.download(device_which.data(), which.size(), offsets, keys, values);
  EXPECT_EQ(offsets.size(), which.size() + 1);
  Table out(which.size());
  for (std::size_t r = 0; r < which.size(); ++r)
    for (std::uint32_t e = offsets[r]; e < offsets[r + 1]; ++e)
      out[r].emplace_back(keys[e], values[e]);
  return out;
}

Table random_table(std::mt19937_64& rng, std::size_t rows) {
  std::uniform_int_distribution<int> length(0, 4);
  std::uniform_int_distribution<std::uint32_t> key(0, 1000);
  std::uniform_real_distribution<double> value(-1, 1);
  Table t(rows);
  for (auto& row : t)
    for (int e = length(rng); e > 0; --e) row.emplace_back(key(rng), value(rng));
  return t;
}

TEST(CsrRows, DownloadsChosenRowsInTheGivenOrder) {
  std::mt19937_64 rng(1);
  const Table table = random_table(rng, 50);
  const auto rows = upload(table);
  const std::vector<std::uint32_t> which = {7, 0, 49, 7, 13, 2};
  const Table got = download(rows, which);
  for (std::size_t r = 0; r < which.size(); ++r) EXPECT_EQ(got[r], table[which[r]]) << r;
  EXPECT_TRUE(download(rows, {}).empty());
}

TEST(CsrRows, AppendKeepsTheRowsAndAddsNewOnesAfterThem) {
  std::mt19937_64 rng(2);
  const Table first = random_table(rng, 20), more = random_table(rng, 9);
  auto rows = upload(first);
  const HostRows extra = flatten(more);
  rows.append(extra.offsets, extra.keys, extra.values);
  ASSERT_EQ(rows.rows(), first.size() + more.size());
  std::vector<std::uint32_t> all(rows.rows());
  for (std::size_t r = 0; r < all.size(); ++r) all[r] = static_cast<std::uint32_t>(r);
  Table expected = first;
  expected.insert(expected.end(), more.begin(), more.end());
  EXPECT_EQ(download(rows, all), expected);
}

TEST(CsrRows, AppendToAnEmptyTable) {
  std::mt19937_64 rng(3);
  const Table more = random_table(rng, 5);
  const HostRows extra = flatten(more);
  CsrRows<HostSpace, std::uint32_t, double> rows;
  EXPECT_EQ(rows.rows(), 0u);
  rows.append(extra.offsets, extra.keys, extra.values);
  EXPECT_EQ(download(rows, {0, 1, 2, 3, 4}), more);
}

/// A 2 m x 1 m x 1 m box in 0.125 m cells, periodic along x, cut into slabs at x = 0.5 and
/// x = 1.25 m (ranks 0, 1, 2), with random positions inside it and slightly beyond its faces.
struct SlabScene {
  Decomposition d =
      Decomposition::grid(CoarseGrid::over(make_box(), 0.125), {{{0, 4, 10, 16}, {0, 8}, {0, 8}}});
  std::vector<Real4> position;

  static PeriodicBox make_box() {
    PeriodicBox box;
    box.lo = {0, 0, 0};
    box.length = {2, 1, 1};
    box.periodic[0] = true;
    return box;
  }

  explicit SlabScene(std::size_t n) {
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> x(0, 2), yz(-0.05, 1.05);
    for (std::size_t i = 0; i < n; ++i) position.push_back({x(rng), yz(rng), yz(rng), 0.01});
    position.push_back({0.5, 0.5, 0.5, 0.01});   // on the cut between ranks 0 and 1
    position.push_back({0.25, 0.5, 0.5, 0.01});  // two cells from the cut
  }
};

TEST(RankCells, SelectsExactlyTheParticlesInCellsNearAnotherRank) {
  const SlabScene scene(4000);
  const Real reach = 0.125;
  for (int rank = 0; rank < 3; ++rank) {
    const CellOwnership map = scene.d.ownership(rank, 1);
    RankCells<HostSpace> cells;
    cells.update(map, rank);
    DeviceArray<Real4, HostSpace> device_position;
    device_position.upload(scene.position);
    std::vector<std::uint32_t> index;
    std::vector<Real4> position;
    cells.near_other_rank(device_position.data(), scene.position.size(), index, position);
    std::vector<std::uint32_t> expected;
    std::vector<int> ghost_ranks;
    std::size_t with_ghost_ranks = 0;
    for (std::size_t i = 0; i < scene.position.size(); ++i) {
      const Vec3 p = xyz(scene.position[i]);
      if (map.near_other[scene.d.cells().cell_of(p)] != 0)
        expected.push_back(static_cast<std::uint32_t>(i));
      scene.d.ghost_ranks(p, rank, reach, ghost_ranks);
      if (ghost_ranks.empty()) continue;
      ++with_ghost_ranks;
      EXPECT_TRUE(std::binary_search(expected.begin(), expected.end(), i))
          << "particle " << i << " has ghost ranks but was not selected, rank " << rank;
    }
    EXPECT_EQ(index, expected) << "rank " << rank;
    ASSERT_EQ(position.size(), index.size());
    for (std::size_t k = 0; k < index.size(); ++k) {
      const Real4 a = position[k], b = scene.position[index[k]];
      EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w) << k;
    }
    EXPECT_GT(with_ghost_ranks, 100u);
    // Ranks 1 and 2 have two of the 16 columns of cells more than two cells from the others'
    // (rank 0, four cells wide, has none): the selection spares the ~500 particles there.
    if (rank > 0) {
      EXPECT_LT(index.size(), scene.position.size() - 300);
    }
  }
}

/// Whether p lies outside the slab scene's box along y or z (x is periodic), by hand.
bool outside_slab_box(const Real4& p) { return p.y < 0 || p.y > 1 || p.z < 0 || p.z > 1; }

/// The relocation keys of a scene's particles and their indices.
struct Keyed {
  DeviceArray<std::uint64_t, HostSpace> key;
  DeviceArray<std::uint32_t, HostSpace> index;
};

/// RelocationKey over the slab scene's particles for `view`, `removed` the removed key.
Keyed relocation_keys(const SlabScene& scene, const RankCellsView& view, std::uint64_t removed) {
  DeviceArray<Real4, HostSpace> position;
  position.upload(scene.position);
  const std::size_t n = scene.position.size();
  Keyed k{DeviceArray<std::uint64_t, HostSpace>(n), DeviceArray<std::uint32_t, HostSpace>(n)};
  parallel_for(
      HostSpace{}, n,
      rank_cell_kernels::RelocationKey<Real>{view, SlabScene::make_box(), removed, position.data(),
                                             k.key.data(), k.index.data()});
  return k;
}

/// Sorts the keys stably and checks the order and that each group is in index order.
void sort_and_check(Keyed& k, std::uint64_t removed) {
  const std::size_t n = k.key.size();
  sort_by_key(HostSpace{}, k.key.data(), k.index.data(), n, bits_for(removed));
  for (std::size_t i = 1; i < n; ++i) {
    ASSERT_LE(k.key.data()[i - 1], k.key.data()[i]);
    if (k.key.data()[i - 1] == k.key.data()[i]) {
      EXPECT_LT(k.index.data()[i - 1], k.index.data()[i]);  // stable: each group in index order
    }
  }
}

TEST(RankCells, RelocationKeysRemoveWhatLeftTheBoxAndSortLeaversByDestination) {
  const SlabScene scene(3000);
  const int rank = 1;
  const std::uint64_t removed = 3 + 1;  // three ranks
  RankCells<HostSpace> cells;
  cells.update(scene.d.ownership(rank, 1), rank);
  Keyed k = relocation_keys(scene, cells.view(), removed);
  const std::size_t n = scene.position.size();
  const std::uint64_t* key = k.key.data();
  std::size_t leaving = 0, outside = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int owner = scene.d.owner_of(xyz(scene.position[i]));
    const bool out = outside_slab_box(scene.position[i]);
    const std::uint64_t expected = out             ? removed
                                   : owner == rank ? 0u
                                                   : 1u + static_cast<std::uint64_t>(owner);
    EXPECT_EQ(key[i], expected) << i;
    leaving += !out && owner != rank;
    outside += out;
  }
  const auto count_from = [&](std::uint64_t least) {
    return reduce_sum(HostSpace{}, n, rank_cell_kernels::KeyAtLeast{key, least});
  };
  EXPECT_EQ(count_from(1), Real(leaving + outside));
  EXPECT_EQ(count_from(removed), Real(outside));
  sort_and_check(k, removed);
  for (std::size_t i = n - outside; i < n; ++i)
    EXPECT_TRUE(outside_slab_box(scene.position[k.index.data()[i]])) << i;
  EXPECT_GT(leaving, 1000u);
  EXPECT_GT(outside, 100u);
  EXPECT_LT(leaving + outside, n);
}

TEST(RankCells, OnOneRankOnlyWhatLeftTheBoxIsKeyed) {
  const SlabScene scene(2000);
  const std::uint64_t removed = 1 + 1;
  Keyed k = relocation_keys(scene, RankCellsView{}, removed);
  const std::size_t n = scene.position.size();
  std::size_t outside = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool out = outside_slab_box(scene.position[i]);
    EXPECT_EQ(k.key.data()[i], out ? removed : 0u) << i;
    outside += out;
  }
  sort_and_check(k, removed);
  EXPECT_GT(outside, 100u);
}

}  // namespace
}  // namespace gpudem
