#pragma once
/// The engines' memory over all ranks, by array: the total for the start-up summary and, with
/// --verbose, bytes per particle of each array.
#include <cstdint>
#include <vector>

#include "comm/MpiContext.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

/// Each array's bytes summed over the engines of all ranks. Collective.
std::vector<MemoryUse> memory_over_ranks(const MpiContext& mpi, const EngineDiagnostics& engine);

/// Σ bytes of `use`.
double total_bytes(const std::vector<MemoryUse>& use);

/// Prints one line per array: its bytes per particle (of `particles` on all ranks) and its
/// share of the total.
void print_memory_report(const std::vector<MemoryUse>& use, std::uint64_t particles);

}  // namespace gpudem
