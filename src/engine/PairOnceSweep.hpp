#pragma once
/// The state of the host's pair-once force sweeps between steps (PairOnceSweep): each particle's
/// group, the partners' integer sums, and the history that the last sweeps advanced at one end
/// of a pair only, mirrored to the other end before anything reads it. Host code only.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/Lanes.hpp"
#include "engine/HostAllocator.hpp"
#include "engine/PairOnceForces.hpp"
#if GPUDEM_HOST_LANES
#include "engine/PairLanesForces.hpp"
#endif

namespace gpudem {

/// Copies, for each pair the last sweeps evaluated once, the evaluating end's history (the
/// lower index) to the other end, mirrored (Law::mirrored).
template <class Law>
struct MirrorPairHistory {
  ListRows list;
  const std::uint64_t* group;
  typename Law::State* history;

  void operator()(std::uint32_t begin, std::uint32_t end) const {
    const std::uint32_t* offsets = list.offsets;
    const std::uint32_t* index = list.index;
    for (std::uint32_t i = begin; i < end; ++i)
      for (std::uint32_t k = offsets[i]; k < offsets[i + 1]; ++k) {
        const std::uint32_t j = index[k];
        if (j >= i || !in_one_group(i, j, list.owned, group)) continue;  // i evaluated it
        // j's entry for i, which a symmetric list always has
        std::uint32_t m = offsets[j];
        while (m < offsets[j + 1] && index[m] != i) ++m;
        if (m < offsets[j + 1]) history[k] = Law::mirrored(history[m]);
      }
  }
};

/// The state of the host's pair-once sweeps: the particles' groups, the partners' integer sums,
/// and the history the last sweeps left with only one end of some pairs advanced.
template <class Law, class P>
class PairOnceSweep {
 public:
  using S = typename Law::Scalar;
  using State = typename Law::State;

  /// `units`: of the integer sums; `most_lanes`: evaluate up to that many contacts at once, as
  /// many as this build and CPU can (8, 4 or 1; the same bits).
  PairOnceSweep(const ExactUnits& units, int most_lanes)
      : units_(units), lanes_(lanes_for(most_lanes)) {}

  /// Runs `kernel` (its subset, rows and sums filled in here) over positions [0, count) of
  /// its subset, on the owned particles' rows `list`.
  void run(PairOnceForces<Law, P> kernel, std::size_t count, const ListRows& list) {
    const Grouping grouping{host_thread_count(), kernel.sweep.subset != nullptr};
    if (grouping.ranges != grouping_.ranges || grouping.split != grouping_.split) {
      // A regrouping: no end of a regrouped pair may start from a record left behind.
      mirror(list);
      grouping_ = grouping;
    }
    if (group_.size() < list.owned) {
      group_.resize(list.owned);
      pair_force_.resize(list.owned);
      if constexpr (Law::needs_spin) pair_torque_.resize(list.owned);
      pair_ratio_.resize(list.owned);
    }
    kernel.units = units_;
    kernel.pair_force = pair_force_.arrays();
    if constexpr (Law::needs_spin) kernel.pair_torque = pair_torque_.arrays();
    kernel.pair_ratio = pair_ratio_.data();
    kernel.evaluated = evaluated_rows(kernel.sweep.subset, count, list);
    if (!sweep_in_lanes(kernel, count)) host_ranges(count, grouping_.ranges, kernel);
    if constexpr (Law::history_size > 0) pending_ = kernel.sweep.history.pair;
  }

  /// Contacts a thread evaluates at once.
  int contact_lanes() const { return lanes_; }

  std::size_t bytes() const {
    return group_.capacity() * sizeof(std::uint64_t) + pair_force_.bytes() + pair_torque_.bytes() +
           pair_ratio_.capacity() * sizeof(Real) + rows_bytes();
  }

  /// Fills in the other ends of the pairs the sweeps since the last call evaluated once, in the
  /// history they wrote; the list must be the one they swept. Nothing when none is pending.
  void mirror(const ListRows& list) {
    if constexpr (Law::history_size > 0) {
      if (!pending_) return;
      host_ranges(list.owned, host_thread_count(),
                  MirrorPairHistory<Law>{list, group_.data(), pending_});
      pending_ = nullptr;
    }
  }

 private:
  /// The widest lanes of at most `most_lanes` this build and CPU run the law's sweep in.
  static int lanes_for(int most_lanes) {
    if (!GPUDEM_HOST_LANES || !Law::evaluates_in_lanes) return 1;
    const int widest = host_vector_doubles();
    for (const int lanes : {8, 4})
      if (lanes <= most_lanes && lanes <= widest) return lanes;
    return 1;
  }

  /// The sweep in lanes, where chosen; false where it did not run.
  bool sweep_in_lanes(const PairOnceForces<Law, P>& kernel, std::size_t count) const {
#if GPUDEM_HOST_LANES
    if constexpr (Law::evaluates_in_lanes) {
      if (lanes_ == 8)
        host_ranges(count, grouping_.ranges, PairLanesInVectors<Law, P, 8>{{kernel}});
      if (lanes_ == 4)
        host_ranges(count, grouping_.ranges, PairLanesInVectors<Law, P, 4>{{kernel}});
      return lanes_ > 1;
    }
#endif
    (void)kernel, (void)count;
    return false;
  }

  /// The entries each particle of this sweep evaluates (EvaluatedRows), kept per sweep and
  /// selected again after a new list or a regrouping, when the sweep's particles are tagged
  /// with their groups (GroupRange). Between list builds the grouping and the tags stay. The
  /// subsets of the sweeps kept are disjoint: a sweep over all particles and one over a subset
  /// are not kept together, since each would retag the other's particles.
  EvaluatedRows evaluated_rows(const std::uint32_t* subset, std::size_t count,
                               const ListRows& list) {
    const SweepKey key{list.builds, subset, count, grouping_.ranges};
    const auto overlaps = [subset](const SweepRows& r) {
      return (r.key.subset == nullptr) != (subset == nullptr);
    };
    if (!sweeps_.empty() && sweeps_.front().key.list_builds != list.builds) sweeps_.clear();
    if (std::any_of(sweeps_.begin(), sweeps_.end(), overlaps)) sweeps_.clear();
    SweepRows* rows = nullptr;
    for (SweepRows& r : sweeps_)
      if (r.key.subset == subset) rows = &r;
    if (rows && rows->key == key) return rows->view();
    if (!rows) rows = &sweeps_.emplace_back();
    rows->key = key;
    host_ranges(count, grouping_.ranges, GroupRange{subset, ++selections_, group_.data()});
    rows->begin.resize(count);
    rows->group_end.resize(count);
    rows->end.resize(count);
    std::uint32_t total = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t i = swept_index(subset, k);
      rows->begin[k] = total;
      total += list.offsets[i + 1] - list.offsets[i];
    }
    // past the last row, what a sweep that reads in blocks or ahead reads and does not use
    rows->entry.resize(total + kRowsPadding);
    rows->partner.resize(total + kRowsPadding);
    host_ranges(count, grouping_.ranges,
                SelectEvaluated{subset, list, group_.data(), rows->view()});
    return rows->view();
  }

  std::size_t rows_bytes() const {
    std::size_t words = 0;
    for (const SweepRows& r : sweeps_)
      words += r.begin.capacity() + r.group_end.capacity() + r.end.capacity() + r.entry.capacity() +
               r.partner.capacity();
    return words * sizeof(std::uint32_t);
  }

  struct Grouping {
    std::size_t ranges = 0;
    bool split = false;  ///< sweeps over subsets
  };
  /// What a sweep's evaluated rows depend on: the list, the particles swept and their ranges.
  struct SweepKey {
    std::uint64_t list_builds;
    const std::uint32_t* subset;
    std::size_t count;
    std::size_t ranges;
    bool operator==(const SweepKey& o) const {
      return list_builds == o.list_builds && subset == o.subset && count == o.count &&
             ranges == o.ranges;
    }
  };
  struct SweepRows {
    SweepKey key;
    HostVector<std::uint32_t> begin, group_end, end, entry, partner;
    EvaluatedRows view() {
      return {begin.data(), group_end.data(), end.data(), entry.data(), partner.data()};
    }
  };
  Grouping grouping_;
  /// Selections of evaluated rows so far. A tag of an older selection does not match: every
  /// owned particle is tagged anew after each list build (the count wraps after 2^32).
  std::uint32_t selections_ = 0;
  HostVector<std::uint64_t> group_;
  ExactUnits units_;
  /// What each particle's lower partners in its group leave for its turn; zero between sweeps
  /// (each particle clears its own when it takes them).
  ExactSumStore pair_force_;
  ExactSumStore pair_torque_;
  HostVector<Real> pair_ratio_;
  std::vector<SweepRows> sweeps_;  ///< per subset swept since the last list build
  State* pending_ = nullptr;       ///< the history the last sweeps wrote, other ends not filled in
  int lanes_;                      ///< contacts PairLanesInVectors evaluates at once; 1: none
};

}  // namespace gpudem
