#pragma once
// A decomposed domain on fake ranks in one process (support/FakeRanks.hpp): each rank's
// DomainLink answers the geometric queries (region, owner, ghost ranks, cell map) from a real
// Decomposition, as MpiDomain does, and its contiguous exchange (the ghost refresh) meets the
// other ranks' through the hub. Host memory only.
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "comm/Decomposition.hpp"
#include "support/FakeRanks.hpp"

namespace gpudem::test {

class FakeDomain final : public DomainLink {
 public:
  FakeDomain(FakeRankHub& hub, int rank, const Decomposition& decomposition, Real ghost_width)
      : hub_(hub),
        group_(hub, rank),
        decomposition_(decomposition),
        ghost_width_(ghost_width),
        region_(decomposition.region(rank, ghost_width, ghost_width)),
        ownership_(decomposition.ownership(rank, 1)) {}

  const RankGroup& group() const override { return group_; }
  BinRegion region() const override { return region_; }
  int owner_of(Vec3 p) const override { return decomposition_.owner_of(p); }
  void ghost_ranks(Vec3 p, std::vector<int>& out) const override {
    decomposition_.ghost_ranks(p, rank(), ghost_width_, out);
  }
  const CellOwnership& cell_ownership() const override { return ownership_; }

  /// The messages go through the hub at once (a collective), so nothing stays pending.
  std::unique_ptr<PendingExchange> start_exchange(
      const char* send, const std::vector<std::size_t>& send_bytes, char* receive,
      const std::vector<std::size_t>& receive_bytes) const override {
    RankBuffers outgoing(ranks()), incoming;
    std::size_t at = 0;
    for (int q = 0; q < ranks(); ++q) {
      outgoing[q].assign(send + at, send + at + send_bytes[q]);
      at += send_bytes[q];
    }
    hub_.exchange(rank(), outgoing, incoming);
    at = 0;
    for (int q = 0; q < ranks(); ++q) {
      if (incoming[q].size() != receive_bytes[q])
        throw std::logic_error("FakeDomain: rank " + std::to_string(q) + " sent " +
                               std::to_string(incoming[q].size()) + " bytes, " +
                               std::to_string(receive_bytes[q]) + " expected");
      if (!incoming[q].empty()) std::memcpy(receive + at, incoming[q].data(), incoming[q].size());
      at += receive_bytes[q];
    }
    return nullptr;
  }
  void finish_exchange(std::unique_ptr<PendingExchange>) const override {}

 private:
  FakeRankHub& hub_;
  FakeRankGroup group_;
  const Decomposition& decomposition_;
  Real ghost_width_;
  BinRegion region_;
  CellOwnership ownership_;
};

/// Runs body(domain) for the ranks of `decomposition`, each on its own thread; rethrows the
/// first failure.
inline void run_on_fake_domain(const Decomposition& decomposition, Real ghost_width,
                               const std::function<void(FakeDomain&)>& body) {
  const int ranks = decomposition.ranks();
  FakeRankHub hub(ranks);
  std::vector<std::exception_ptr> failure(ranks);
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      FakeDomain domain(hub, r, decomposition, ghost_width);
      try {
        body(domain);
      } catch (...) {
        failure[r] = std::current_exception();
      }
    });
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& f : failure)
    if (f) std::rethrow_exception(f);
}

}  // namespace gpudem::test
