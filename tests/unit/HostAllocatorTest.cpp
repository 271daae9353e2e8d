// The host buffers' allocator (engine/HostAllocator.hpp): a buffer of a huge page or more
// starts on a huge-page boundary and, where the kernel gives transparent huge pages on advice,
// its mapping is eligible for them (in `madvise` mode only the advice makes it so); a smaller one
// keeps its type's alignment; the values survive growth and the copies in and out of a host
// DeviceArray.
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

/// Whether this process may have transparent huge pages at all: false where
/// prctl(PR_SET_THP_DISABLE) or the container turned them off (THP_enabled: 0 in
/// /proc/self/status).
bool process_may_have_huge_pages() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("THP_enabled:", 0) == 0) return std::stoi(line.substr(12)) != 0;
  return true;
}

/// Whether a line of /proc/self/smaps starts a mapping ("from-to perms offset dev inode path"):
/// its first colon is in the device field, after a space, where a field line ("Name: value")
/// has its colon before any space.
bool is_mapping_header(const std::string& line) { return line.find(':') > line.find(' '); }

/// The THPeligible field of the mapping of this process that holds `p`: 1 or 0, −1 where
/// /proc/self/smaps does not say.
int huge_page_eligible(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto address = reinterpret_cast<std::uintptr_t>(p);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    if (is_mapping_header(line)) {
      std::uintptr_t from = 0, to = 0;
      char dash = 0;
      std::istringstream head(line);
      head >> std::hex >> from >> dash >> to;
      inside = dash == '-' && from <= address && address < to;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

TEST(HostAllocator, ABufferOfAHugePageOrMoreStartsOnAHugePageBoundary) {
  for (const std::size_t extra : {0, 3, 1000}) {  // exactly a huge page, and more
    const HostVector<double> buffer(kHugePageBytes / sizeof(double) + extra);
    EXPECT_TRUE(aligned_to(buffer.data(), kHugePageBytes)) << extra << " doubles over";
  }
}

TEST(HostAllocator, ASmallBufferKeepsItsTypesAlignment) {
  struct alignas(4096) Page {
    double value[512];
  };
  std::vector<HostVector<Page>> buffers;
  for (int k = 0; k < 8; ++k) {  // ordinary allocations are 16-aligned: one in 256 is by chance
    buffers.emplace_back(3);
    EXPECT_TRUE(aligned_to(buffers.back().data(), alignof(Page))) << "buffer " << k;
  }
}

TEST(HostAllocator, ABufferOfAHugePageOrMoreIsEligibleForHugePages) {
  const std::string mode = huge_page_mode();
  if (mode != "always" && mode != "madvise")
    GTEST_SKIP() << "transparent huge pages are '" << mode << "' on this kernel";
  if (!process_may_have_huge_pages())
    GTEST_SKIP() << "transparent huge pages are off for this process";
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
  array.resize(values.size());
  array.download(back);
  EXPECT_EQ(back, values);
}

}  // namespace
}  // namespace gpudem::test
