#include "app/MemoryReport.hpp"

#include <cstdio>

namespace gpudem {

std::vector<MemoryUse> memory_over_ranks(const MpiContext& mpi, const EngineDiagnostics& engine) {
  std::vector<MemoryUse> use = engine.memory_use();
  std::vector<std::uint64_t> bytes;
  for (const MemoryUse& array : use) bytes.push_back(array.bytes);
  mpi.group().sum(bytes);
  for (std::size_t k = 0; k < use.size(); ++k) use[k].bytes = bytes[k];
  return use;
}

double total_bytes(const std::vector<MemoryUse>& use) {
  double total = 0;
  for (const MemoryUse& array : use) total += static_cast<double>(array.bytes);
  return total;
}

void print_memory_report(const std::vector<MemoryUse>& use, std::uint64_t particles) {
  const double total = total_bytes(use);
  const double n = particles > 0 ? static_cast<double>(particles) : 1.0;
  std::printf("memory by array, all ranks (bytes per particle, share):\n");
  for (const MemoryUse& array : use)
    std::printf("  %-24s %9.1f  %5.1f %%\n", array.name, static_cast<double>(array.bytes) / n,
                total > 0 ? 100.0 * static_cast<double>(array.bytes) / total : 0.0);
  std::printf("  %-24s %9.1f  (%.4g MB)\n", "total", total / n, total / 1e6);
}

}  // namespace gpudem
