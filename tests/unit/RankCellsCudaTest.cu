// The device side of a rebuild on several ranks on the CUDA backend against the host backend
// (skipped without a device): relocation keys and the selection of particles near another
// rank's cells at random points and at cell corners nudged by one ulp either way (where the
// cell lookup rounds), and CsrRows read-out and append, including empty cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/ParallelForCuda.cuh"
// The CUDA backend first, then the host one, as in the engine's translation units.
#include "comm/Decomposition.hpp"
#include "engine/CsrRows.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/RankCells.hpp"

namespace gpudem {
namespace {

bool have_device() { return cuda::device_count() > 0; }

template <class T>
std::vector<T> to_host(const DeviceArray<T, CudaSpace>& a) {
  std::vector<T> host;
  a.download(host);
  return host;
}

/// 3 ranks on a 2 m x 1 m x 1 m box (periodic along x and y) in 0.125 m cells, owners in
/// slabs along x with random patches; random points, and every cell's lower corner and the
/// points one ulp either side of it along each axis.
struct Scene {
  CoarseGrid grid;
  Decomposition d;
  std::vector<Real4> position;

  static PeriodicBox box() {
    PeriodicBox b;
    b.lo = {0, 0, 0};
    b.length = {2, 1, 1};
    b.periodic[0] = b.periodic[1] = true;
    return b;
  }
  static std::vector<int> owners(const CoarseGrid& g) {
    std::mt19937_64 rng(6);
    std::uniform_int_distribution<int> any(0, 2);
    std::vector<int> owner(g.count());
    for (std::size_t i = 0; i < owner.size(); ++i)
      owner[i] = g.coords(i)[0] < 10 ? g.coords(i)[0] / 5 : any(rng);
    return owner;
  }

  Scene()
      : grid(CoarseGrid::over(box(), 0.125)), d(Decomposition::from_owners(grid, owners(grid), 3)) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> x(-0.1, 2.1), yz(-0.1, 1.1);
    for (int i = 0; i < 20000; ++i) position.push_back({x(rng), yz(rng), yz(rng), 0.01});
    for (std::size_t c = 0; c < grid.count(); ++c) {
      const std::array<int, 3> at = grid.coords(c);
      Real4 corner{at[0] * grid.edge(0), at[1] * grid.edge(1), at[2] * grid.edge(2), 0.01};
      position.push_back(corner);
      for (double toward : {-1.0, 3.0}) {
        Real4 nudged = corner;
        nudged.x = std::nextafter(corner.x, toward);
        nudged.y = std::nextafter(corner.y, toward);
        nudged.z = std::nextafter(corner.z, toward);
        position.push_back(nudged);
      }
    }
  }
};

TEST(CudaRankCells, KeysAndSelectionMatchTheHost) {
  if (!have_device()) GTEST_SKIP() << "no CUDA device on this machine";
  const Scene scene;
  const std::size_t n = scene.position.size();
  for (int rank = 0; rank < 3; ++rank) {
    SCOPED_TRACE(::testing::Message() << "rank " << rank);
    const CellOwnership map = scene.d.ownership(rank, 1);
    RankCells<HostSpace> host_cells;
    RankCells<CudaSpace> device_cells;
    host_cells.update(map, rank);
    device_cells.update(map, rank);
    DeviceArray<Real4, HostSpace> host_position;
    DeviceArray<Real4, CudaSpace> device_position;
    host_position.upload(scene.position);
    device_position.upload(scene.position);

    DeviceArray<std::uint64_t, HostSpace> host_key(n);
    DeviceArray<std::uint32_t, HostSpace> host_index(n);
    const std::uint64_t removed = 3 + 1;
    parallel_for(HostSpace{}, n,
                 rank_cell_kernels::RelocationKey<Real>{host_cells.view(), Scene::box(), removed,
                                                        host_position.data(), host_key.data(),
                                                        host_index.data()});
    DeviceArray<std::uint64_t, CudaSpace> key(n);
    DeviceArray<std::uint32_t, CudaSpace> index(n);
    parallel_for(
        CudaSpace{}, n,
        rank_cell_kernels::RelocationKey<Real>{device_cells.view(), Scene::box(), removed,
                                               device_position.data(), key.data(), index.data()});
    std::vector<std::uint64_t> host_keys(host_key.data(), host_key.data() + n);
    EXPECT_EQ(to_host(key), host_keys);
    EXPECT_NE(std::count(host_keys.begin(), host_keys.end(), removed), 0);

    std::vector<std::uint32_t> host_selected, selected;
    std::vector<Real4> host_near, near;
    host_cells.near_other_rank(host_position.data(), n, host_selected, host_near);
    device_cells.near_other_rank(device_position.data(), n, selected, near);
    EXPECT_EQ(selected, host_selected);
    ASSERT_EQ(near.size(), host_near.size());
    for (std::size_t k = 0; k < near.size(); ++k)
      EXPECT_TRUE(near[k].x == host_near[k].x && near[k].w == host_near[k].w) << k;
    EXPECT_GT(host_selected.size(), 0u);
    EXPECT_LT(host_selected.size(), n);

    device_cells.near_other_rank(device_position.data(), 0, selected, near);
    EXPECT_TRUE(selected.empty());
  }
}

TEST(CudaCsrRows, DownloadAndAppendMatchTheHost) {
  if (!have_device()) GTEST_SKIP() << "no CUDA device on this machine";
  std::mt19937_64 rng(8);
  std::uniform_int_distribution<int> length(0, 5);
  std::vector<std::uint32_t> offsets{0}, keys;
  std::vector<double> values;
  for (int r = 0; r < 300; ++r) {
    for (int e = length(rng); e > 0; --e) {
      keys.push_back(static_cast<std::uint32_t>(rng() % 1000));
      values.push_back(static_cast<double>(rng() % 1000) / 7);
    }
    offsets.push_back(static_cast<std::uint32_t>(keys.size()));
  }
  CsrRows<HostSpace, std::uint32_t, double> host;
  CsrRows<CudaSpace, std::uint32_t, double> device;
  EXPECT_EQ(device.rows(), 0u);
  host.append(offsets, keys, values);  // both start empty
  device.append(offsets, keys, values);
  host.append(offsets, keys, values);  // and grow
  device.append(offsets, keys, values);
  ASSERT_EQ(device.rows(), 600u);
  const std::vector<std::uint32_t> which = {599, 0, 17, 17, 300, 42};
  DeviceArray<std::uint32_t, HostSpace> host_which;
  DeviceArray<std::uint32_t, CudaSpace> device_which;
  host_which.upload(which);
  device_which.upload(which);
  for (const std::size_t count : {which.size(), std::size_t(0)}) {
    std::vector<std::uint32_t> ho, hk, o, k;
    std::vector<double> hv, v;
    host.download(host_which.data(), count, ho, hk, hv);
    device.download(device_which.data(), count, o, k, v);
    EXPECT_EQ(o, ho);
    EXPECT_EQ(k, hk);
    EXPECT_EQ(v, hv);
    EXPECT_EQ(o.size(), count + 1);
  }
}

}  // namespace
}  // namespace gpudem
