// The CUDA backend's sort and slot launches against the host backend (skipped without a device):
// sort_by_key on random keys with duplicates gives the host sort's order for several bit counts,
// twice in a row (the kept scratch), and parallel_for with a slot visits every index exactly once
// at each candidate block size, exclusive_scan's total does not wrap at 32 bits, and reduce_sum
// and reduce_max give the host's results from one block to a grid whose threads stride.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "engine/ParallelForCuda.cuh"
// The CUDA backend first, then the host one, as in the engine's translation units.
#include "engine/DeviceArray.hpp"
#include "engine/ParallelFor.hpp"

namespace gpudem {
namespace {

bool have_device() { return cuda::device_count() > 0; }

/// Adds one to hits[i].
struct CountVisit {
  std::uint32_t* hits;
  __host__ __device__ void operator()(std::size_t i) const { ++hits[i]; }
};

/// n random keys below 2^key_bits drawn from 300 values (many duplicates).
std::vector<std::uint64_t> random_keys(std::size_t n, int key_bits, std::uint32_t seed) {
  std::mt19937_64 random(seed);
  const std::uint64_t top = key_bits == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << key_bits) - 1;
  std::uniform_int_distribution<std::uint64_t> any_key(0, top);
  std::vector<std::uint64_t> pool{top};
  while (pool.size() < 300) pool.push_back(any_key(random));
  std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
  std::vector<std::uint64_t> keys(n);
  for (auto& k : keys) k = pool[pick(random)];
  return keys;
}

TEST(CudaSortByKey, GivesTheHostOrder) {
  if (!have_device()) GTEST_SKIP() << "no CUDA device on this machine";
  for (int key_bits : {1, 9, 22, 33, 64}) {
    for (int round = 0; round < 2; ++round) {
      SCOPED_TRACE(::testing::Message() << key_bits << " bits, round " << round);
      std::vector<std::uint64_t> host_keys = random_keys(100000, key_bits, key_bits + round);
      std::vector<std::uint32_t> host_values(host_keys.size());
      for (std::size_t i = 0; i < host_values.size(); ++i) host_values[i] = std::uint32_t(i);
      DeviceArray<std::uint64_t, CudaSpace> keys;
      DeviceArray<std::uint32_t, CudaSpace> values;
      keys.upload(host_keys);
      values.upload(host_values);
      sort_by_key(CudaSpace{}, keys.data(), values.data(), keys.size(), key_bits);
      sort_by_key(HostSpace{}, host_keys.data(), host_values.data(), host_keys.size(), key_bits);
      std::vector<std::uint64_t> device_keys;
      std::vector<std::uint32_t> device_values;
      keys.download(device_keys);
      values.download(device_values);
      EXPECT_EQ(device_keys, host_keys);
      EXPECT_EQ(device_values, host_values);
    }
  }
}

TEST(CudaParallelFor, SlotLaunchVisitsEveryIndexOnceAtEachBlockSize) {
  if (!have_device()) GTEST_SKIP() << "no CUDA device on this machine";
  const std::size_t n = 100003;  // not a multiple of any block size
  for (const unsigned block : kBlockSizeCandidates) {
    SCOPED_TRACE(::testing::Message() << block << " threads per block");
    launch_tuning().set_block_size(LaunchSlot::integrate, block);
    DeviceArray<std::uint32_t, CudaSpace> hits;
    hits.upload(std::vector<std::uint32_t>(n, 0));
    parallel_for(CudaSpace{}, n, CountVisit{hits.data()}, LaunchSlot::integrate);
    std::vector<std::uint32_t> seen;
    hits.download(seen);
    EXPECT_EQ(seen, std::vector<std::uint32_t>(n, 1));
  }
  launch_tuning().reset();
}

/// The scan's total is a 64-bit sum: counts past 2^32 - 1 (a neighbour list too long for
/// 32-bit offsets) are seen as such, as on the host, and the prefixes agree with the host's.
TEST(CudaExclusiveScan, TotalDoesNotWrapAt32Bits) {
  if (!have_device()) GTEST_SKIP() << "no CUDA device on this machine";
  const std::vector<std::uint32_t> counts{0x80000000u, 0x80000000u, 5u, 7u};
  std::vector<std::uint32_t> host_out(counts.size());
  const std::uint64_t host_total =
      exclusive_scan(HostSpace{}, counts.data(), host_out.data(), counts.size());
  DeviceArray<std::uint32_t, CudaSpace> values;
  values.upload(counts);
  const std::uint64_t total =
      exclusive_scan(CudaSpace{}, values.data(), values.data(), counts.size());  // in place
  std::vector<std::uint32_t> out;
  values.download(out);
  EXPECT_EQ(total, (std::uint64_t(1) << 32) + 12);
  EXPECT_EQ(total, host_total);
  EXPECT_EQ(out, host_out);
}

/// Multiples of ½ from a device array, so that every partial sum is exact in double and the sum
/// does not depend on the order of the additions.
struct HalfSteps {
  const double* values;
  __host__ __device__ Real operator()(std::size_t i) const { return values[i]; }
};

TEST(CudaReduce, SumAndMaxEqualTheHostOnesFromOneBlockToAStridingGrid) {
  if (!have_device()) GTEST_SKIP() << "no CUDA device on this machine";
  // 1 block, a partly filled block, several blocks, and more indices than the 1,024 blocks of
  // 256 threads hold, so that threads stride.
  for (const std::size_t n : {std::size_t(1), std::size_t(255), std::size_t(257),
                              std::size_t(100000), std::size_t(1000003)}) {
    std::mt19937_64 random(n);
    std::uniform_int_distribution<int> half_steps(-2000, 2000);
    std::vector<double> values(n);
    for (double& v : values) v = 0.5 * half_steps(random);
    values[n / 3] = 1500.5;  // the largest, somewhere inside
    DeviceArray<double, CudaSpace> device_values;
    device_values.upload(values);
    const Real host_sum = reduce_sum(HostSpace{}, n, HalfSteps{values.data()});
    const Real host_max = reduce_max(HostSpace{}, n, Real(-1e9), HalfSteps{values.data()});
    EXPECT_EQ(reduce_sum(CudaSpace{}, n, HalfSteps{device_values.data()}), host_sum) << n;
    EXPECT_EQ(reduce_max(CudaSpace{}, n, Real(-1e9), HalfSteps{device_values.data()}), host_max)
        << n;
    EXPECT_EQ(host_max, 1500.5);
  }
  EXPECT_EQ(reduce_sum(CudaSpace{}, 0, HalfSteps{nullptr}), 0.0);
  EXPECT_EQ(reduce_max(CudaSpace{}, 0, Real(-7), HalfSteps{nullptr}), -7.0);
}

}  // namespace
}  // namespace gpudem
