#include "engine/LaunchTuning.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gpudem {

namespace {

constexpr double kUnusable = std::numeric_limits<double>::infinity();

/// One timed run, +infinity when it failed or gave no usable time.
double usable_time(const TimeWithBlock& time_with, unsigned block) {
  try {
    const double seconds = time_with(block);
    return std::isfinite(seconds) && seconds >= 0 ? seconds : kUnusable;
  } catch (const std::exception&) {
    return kUnusable;
  }
}

}  // namespace

const char* slot_name(LaunchSlot slot) {
  switch (slot) {
    case LaunchSlot::forces:
      return "forces";
    case LaunchSlot::neighbor_list:
      return "neighbor_list";
    case LaunchSlot::integrate:
      return "integrate";
  }
  return "unknown";
}

void LaunchTuning::set_block_size(LaunchSlot slot, unsigned block) {
  if (std::find(kBlockSizeCandidates.begin(), kBlockSizeCandidates.end(), block) ==
      kBlockSizeCandidates.end())
    throw std::invalid_argument("LaunchTuning: " + std::to_string(block) +
                                " threads per block is not a candidate block size");
  block_[static_cast<std::size_t>(slot)] = block;
}

LaunchTuning& launch_tuning() {
  static LaunchTuning table;
  return table;
}

double median(std::vector<double> samples) {
  if (samples.empty()) throw std::invalid_argument("median: no samples");
  const std::size_t mid = samples.size() / 2;
  std::nth_element(samples.begin(), samples.begin() + mid, samples.end());
  const double upper = samples[mid];
  if (samples.size() % 2 == 1) return upper;
  const double lower = *std::max_element(samples.begin(), samples.begin() + mid);
  return lower + (upper - lower) / 2;
}

std::vector<double> time_candidates(LaunchTuning& table, LaunchSlot slot,
                                    const TimeWithBlock& time_with, int repetitions) {
  if (repetitions < 1) throw std::invalid_argument("time_candidates: repetitions must be >= 1");
  const unsigned former = table.block_size(slot);
  std::vector<double> times;
  for (const unsigned block : kBlockSizeCandidates) {
    table.set_block_size(slot, block);
    std::vector<double> samples;
    for (int r = 0; r < repetitions; ++r) samples.push_back(usable_time(time_with, block));
    times.push_back(median(samples));
  }
  table.set_block_size(slot, former);
  return times;
}

std::size_t fastest_candidate(const std::vector<double>& times) {
  if (times.empty()) throw std::invalid_argument("fastest_candidate: no times");
  return static_cast<std::size_t>(std::min_element(times.begin(), times.end()) - times.begin());
}

unsigned agree_on_block_size(std::vector<double> local_times, const RankGroup& ranks) {
  if (local_times.size() != kBlockSizeCandidates.size())
    throw std::invalid_argument("agree_on_block_size: one time per candidate block size");
  ranks.max(local_times);
  const std::size_t best = fastest_candidate(local_times);
  if (local_times[best] == kUnusable)
    throw std::runtime_error("launch tuning: no candidate block size ran on every rank");
  return kBlockSizeCandidates[best];
}

unsigned tune_block_size(LaunchTuning& table, LaunchSlot slot, const TimeWithBlock& time_with,
                         const RankGroup& ranks, int repetitions) {
  const unsigned block =
      agree_on_block_size(time_candidates(table, slot, time_with, repetitions), ranks);
  table.set_block_size(slot, block);
  return block;
}

std::string launch_tuning_report(const LaunchTuning& table, bool backend_has_block_sizes) {
  if (!backend_has_block_sizes)
    return "launch tuning: host backend, no block sizes to tune (nothing timed)";
  std::ostringstream line;
  line << "launch tuning (threads per block):";
  for (std::size_t s = 0; s < kLaunchSlotCount; ++s) {
    const auto slot = static_cast<LaunchSlot>(s);
    line << ' ' << slot_name(slot) << ' ' << table.block_size(slot);
  }
  return line.str();
}

}  // namespace gpudem
