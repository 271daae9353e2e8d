#pragma once
/// Block sizes of the tunable CUDA launches, chosen once per run by timing and identical on every
/// rank (after HOOMD-blue's Autotuner). Host code: no CUDA header.
///
/// How a backend is meant to use it (collective: every rank calls it, for the same slots in the
/// same order, whether or not it holds particles):
///
///     if (!has_block_sizes(Space{})) { report launch_tuning_report(..., false); return; }
///     tune_block_size(launch_tuning(), LaunchSlot::forces,
///                     [&](unsigned) { return seconds_to_run(Space{}, [&] { forces(); }); },
///                     domain.group());
///     ... the same for LaunchSlot::neighbor_list and LaunchSlot::integrate ...
///
/// and its kernels launch with `parallel_for(space, n, functor, LaunchSlot::forces)`. While a
/// candidate is timed the table already holds it for that slot, so the timed work only has to
/// launch as it always does. The timed work runs several times per candidate: it must leave the
/// state as a real step would (forces recomputed, a list rebuilt), never advance it twice, and it
/// must not communicate (a rank whose launch fails skips the rest of that run).
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/RankGroup.hpp"
#include "engine/ExecutionSpace.hpp"

namespace gpudem {

/// The launches whose block size is tuned.
enum class LaunchSlot { forces, neighbor_list, integrate };
constexpr std::size_t kLaunchSlotCount = 3;

/// "forces", "neighbor_list", "integrate".
const char* slot_name(LaunchSlot slot);

/// Threads per block of a slot that was never tuned, and of the plain parallel_for.
constexpr unsigned kDefaultBlockSize = 256;
/// Threads per block tried for each slot, ascending.
constexpr std::array<unsigned, 5> kBlockSizeCandidates{64, 128, 256, 512, 1024};

/// Threads per block for each slot; every slot starts at kDefaultBlockSize.
class LaunchTuning {
 public:
  LaunchTuning() { reset(); }
  unsigned block_size(LaunchSlot slot) const { return block_[static_cast<std::size_t>(slot)]; }
  /// Throws std::invalid_argument unless `block` is one of kBlockSizeCandidates.
  void set_block_size(LaunchSlot slot, unsigned block);
  /// Every slot back to kDefaultBlockSize.
  void reset() { block_.fill(kDefaultBlockSize); }

 private:
  std::array<unsigned, kLaunchSlotCount> block_{};
};

/// The process-wide table that parallel_for(CudaSpace, n, f, slot) reads.
LaunchTuning& launch_tuning();

/// Whether a backend's launches have a block size to tune: CUDA kernels do, host loops do not.
constexpr bool has_block_sizes(HostSpace) { return false; }
constexpr bool has_block_sizes(CudaSpace) { return true; }

/// Seconds that one run of the tuned work takes on this rank with `block` threads per block.
using TimeWithBlock = std::function<double(unsigned block)>;

/// The median of `samples` (the mean of the two middle ones for an even count); throws
/// std::invalid_argument when empty.
double median(std::vector<double> samples);

/// For each of kBlockSizeCandidates, the median of `repetitions` calls of time_with(block) on
/// this rank, with `table` holding that block for `slot` during the calls. A candidate whose
/// call throws std::exception (a block the kernel cannot launch) or returns a negative or
/// non-finite time gets +infinity. Leaves the slot at its former block size.
std::vector<double> time_candidates(LaunchTuning& table, LaunchSlot slot,
                                    const TimeWithBlock& time_with, int repetitions);

/// Index of the smallest time; the first (smaller block) on ties.
std::size_t fastest_candidate(const std::vector<double>& times);

/// The block size all ranks agree on: each candidate's time becomes its slowest rank's time
/// (max over ranks), and the candidate with the smallest is chosen, the smaller block on ties.
/// Every rank gets the same answer whatever its own times. Collective; throws
/// std::runtime_error on every rank when no candidate ran on all ranks.
unsigned agree_on_block_size(std::vector<double> local_times, const RankGroup& ranks);

/// Times every candidate for `slot` (time_candidates), agrees across ranks
/// (agree_on_block_size) and stores the choice in `table`; returns it. Collective.
unsigned tune_block_size(LaunchTuning& table, LaunchSlot slot, const TimeWithBlock& time_with,
                         const RankGroup& ranks, int repetitions = 5);

/// The --verbose line: each slot's block size, or, for a backend without block sizes, that
/// launch tuning does not apply.
std::string launch_tuning_report(const LaunchTuning& table, bool backend_has_block_sizes);

}  // namespace gpudem
