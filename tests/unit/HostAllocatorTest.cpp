// The host buffers' allocator (engine/HostAllocator.hpp): a buffer of a huge page or more
// starts on a huge-page boundary and, where the kernel gives transparent huge pages on advice,
// its mapping is eligible for them; a smaller one keeps its type's alignment; the values survive
// growth and the copies in and out of a host DeviceArray.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "engine/DeviceArray.hpp"
#include "engine/HostAllocator.hpp"

namespace gpudem::test {
namespace {

bool aligned_to(const void* p, std::size_t alignment) {
  return reinterpret_cast<std::uintptr_t>(p) % alignment == 0;
}

/// The kernel's transparent-huge-page mode: "always", "madvise" or "never" ("" unknown).
std::string huge_page_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  const auto open = line.find('['), close = line.find(']');
  if (open == std::string::npos || close == std::string::npos) return "";
  return line.substr(open + 1, close - open - 1);
}

/// The THPeligible field of the mapping of this process that holds `p`: 1 or 0, −1 where
/// /proc/self/smaps does not say.
int huge_page_eligible(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto address = reinterpret_cast<std::uintptr_t>(p);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    std::uintptr_t from = 0, to = 0;
    char dash = 0;
    std::istringstream head(line);
    if (line.find(':') > line.find(' ') && (head >> std::hex >> from >> dash >> to) &&
        dash == '-') {
      inside = from <= address && address < to;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

TEST(HostAllocator, ABufferOfAHugePageOrMoreStartsOnAHugePageBoundary) {
  HostVector<double> buffer(kHugePageBytes / sizeof(double) + 3, 1.5);
  EXPECT_TRUE(aligned_to(buffer.data(), kHugePageBytes));
  for (std::size_t k = 0; k < buffer.size(); ++k) buffer[k] = double(k);
  EXPECT_EQ(buffer.back(), double(buffer.size() - 1));
}

TEST(HostAllocator, ASmallBufferKeepsItsTypesAlignment) {
  struct alignas(64) Wide {
    double value[8];
  };
  HostVector<Wide> buffer(3);
  EXPECT_TRUE(aligned_to(buffer.data(), 64));
}

TEST(HostAllocator, ABufferOfAHugePageOrMoreIsEligibleForHugePages) {
  const std::string mode = huge_page_mode();
  if (mode != "always" && mode != "madvise")
    GTEST_SKIP() << "transparent huge pages are '" << mode << "' on this kernel";
  HostVector<double> buffer(2 * kHugePageBytes / sizeof(double));
  const int eligible = huge_page_eligible(buffer.data());
  if (eligible < 0) GTEST_SKIP() << "/proc/self/smaps has no THPeligible field";
  EXPECT_EQ(eligible, 1);
}

TEST(HostAllocator, ValuesSurviveGrowthAndTheCopiesOfAHostArray) {
  std::vector<std::uint32_t> values(kHugePageBytes / sizeof(std::uint32_t) + 5);
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = std::uint32_t(3 * k + 1);
  DeviceArray<std::uint32_t, HostSpace> array(10);
  array.upload(values);
  ASSERT_EQ(array.size(), values.size());
  array.resize(values.size() * 2);  // grows past the first huge-page buffer
  std::vector<std::uint32_t> back;
  array.download(back, values.size());
  EXPECT_EQ(back, values);
}

}  // namespace
}  // namespace gpudem::test
