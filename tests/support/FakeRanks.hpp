#pragma once
// Several ranks of a decomposed run in one process, for unit tests of the engine's exchanges
// without MPI: FakeRanks::run(n, body) calls body(link) on n threads, each with a DomainLink of
// its own rank; the links' collectives (exchange, reductions, broadcast) meet in shared memory.
// The geometric queries (region, owner, ghost ranks, cell map) are not faked and throw.
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "engine/DomainLink.hpp"

namespace gpudem::test {

/// The shared state of n fake ranks: a mailbox per (sender, receiver) and a reusable barrier.
class FakeRankHub {
 public:
  explicit FakeRankHub(int ranks) : ranks_(ranks), mail_(ranks, RankBuffers(ranks)) {}

  int ranks() const { return ranks_; }

  /// Every rank's outgoing[q] delivered as incoming[sender] of rank q. Collective.
  void exchange(int rank, const RankBuffers& outgoing, RankBuffers& incoming) {
    if (static_cast<int>(outgoing.size()) != ranks_)
      throw std::invalid_argument("fake exchange: outgoing has a buffer per rank");
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (int q = 0; q < ranks_; ++q) mail_[rank][q] = outgoing[q];
    }
    barrier();
    incoming.assign(ranks_, {});
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (int q = 0; q < ranks_; ++q) incoming[q] = mail_[q][rank];
    }
    barrier();  // no rank writes its next messages before every rank has read these
  }

  /// Every rank's `bytes` on every rank, in rank order. Collective.
  RankBuffers all_gather(int rank, const std::vector<char>& bytes) {
    RankBuffers outgoing(ranks_, bytes);
    RankBuffers incoming;
    exchange(rank, outgoing, incoming);
    return incoming;
  }

 private:
  void barrier() {
    std::unique_lock<std::mutex> lock(mutex_);
    const std::uint64_t generation = generation_;
    if (++waiting_ == ranks_) {
      waiting_ = 0;
      ++generation_;
      arrived_.notify_all();
      return;
    }
    arrived_.wait(lock, [&] { return generation_ != generation; });
  }

  int ranks_;
  std::vector<RankBuffers> mail_;  ///< mail_[sender][receiver]
  std::mutex mutex_;
  std::condition_variable arrived_;
  int waiting_ = 0;
  std::uint64_t generation_ = 0;
};

/// The RankGroup of one fake rank: every collective meets the other ranks' in the hub.
class FakeRankGroup final : public RankGroup {
 public:
  FakeRankGroup(FakeRankHub& hub, int rank) : hub_(hub), rank_(rank) {}

  int rank() const override { return rank_; }
  int size() const override { return hub_.ranks(); }
  void reduce(Reduction op, double* values, std::size_t n) const override {
    reduce_values(op, values, n);
  }
  void reduce(Reduction op, std::uint64_t* values, std::size_t n) const override {
    reduce_values(op, values, n);
  }
  void broadcast(std::vector<char>& bytes, int root) const override {
    bytes = hub_.all_gather(rank_, bytes)[root];
  }
  void all_gather(const std::vector<char>& mine, RankBuffers& all) const override {
    all = hub_.all_gather(rank_, mine);
  }
  void exchange(const RankBuffers& outgoing, RankBuffers& incoming) const override {
    hub_.exchange(rank_, outgoing, incoming);
  }

 private:
  /// Each rank's values folded in rank order (an unsigned sum wraps).
  template <class T>
  void reduce_values(Reduction op, T* values, std::size_t n) const {
    std::vector<char> mine(n * sizeof(T));
    if (n > 0) std::memcpy(mine.data(), values, mine.size());
    const RankBuffers all = hub_.all_gather(rank_, mine);
    for (std::size_t k = 0; k < n; ++k) {
      T folded{};
      for (std::size_t q = 0; q < all.size(); ++q) {
        T v;
        std::memcpy(&v, all[q].data() + k * sizeof(T), sizeof(T));
        if (q == 0)
          folded = v;
        else if (op == Reduction::Sum)
          folded += v;
        else if (op == Reduction::Max)
          folded = v > folded ? v : folded;
        else
          folded = v < folded ? v : folded;
      }
      values[k] = folded;
    }
  }

  FakeRankHub& hub_;
  int rank_;
};

/// The DomainLink of one fake rank: its collectives are a FakeRankGroup's.
class FakeRankLink final : public DomainLink {
 public:
  FakeRankLink(FakeRankHub& hub, int rank) : group_(hub, rank) {}

  const RankGroup& group() const override { return group_; }
  BinRegion region() const override { throw unfaked("region"); }
  int owner_of(Vec3) const override { throw unfaked("owner_of"); }
  void ghost_ranks(Vec3, std::vector<int>&) const override { throw unfaked("ghost_ranks"); }
  const CellOwnership& cell_ownership() const override { throw unfaked("cell_ownership"); }
  std::unique_ptr<PendingExchange> start_exchange(const char*, const std::vector<std::size_t>&,
                                                  char*,
                                                  const std::vector<std::size_t>&) const override {
    throw unfaked("start_exchange");
  }
  void finish_exchange(std::unique_ptr<PendingExchange>) const override {
    throw unfaked("finish_exchange");
  }

 private:
  static std::logic_error unfaked(const char* what) {
    return std::logic_error(std::string("FakeRankLink::") + what + " is not faked");
  }

  FakeRankGroup group_;
};

/// Runs body(link) for ranks 0..ranks-1, each on its own thread; rethrows the first failure.
inline void run_on_fake_ranks(int ranks, const std::function<void(FakeRankLink&)>& body) {
  FakeRankHub hub(ranks);
  std::vector<std::exception_ptr> failure(ranks);
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      FakeRankLink link(hub, r);
      try {
        body(link);
      } catch (...) {
        failure[r] = std::current_exception();
      }
    });
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& f : failure)
    if (f) std::rethrow_exception(f);
}

}  // namespace gpudem::test
