// The non-blocking exchange of contiguous buffers (DomainLink::start_exchange) and the
// collectives of MpiRankGroup: MpiDomain on however many ranks this runs (1, 2 and 4 through
// ctest), with uneven and zero byte counts and messages to a rank itself, each with MPI waits
// that spin and waits that sleep (comm/MpiWait.hpp), and OneRankDomain. Each byte a rank receives
// is compared with the byte its sender must have put there, computed here from the sender's and
// receiver's ranks.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

#include "comm/Decomposition.hpp"
#include "comm/MpiDomain.hpp"
#include "comm/MpiWait.hpp"
#include "core/RankGroup.hpp"
#include "engine/DomainLink.hpp"
#include "support/MpiRank.hpp"

namespace gpudem {
namespace {

using test::comm_rank;
using test::comm_size;

PeriodicBox unit_cube() {
  PeriodicBox box;
  box.lo = Vec3{0, 0, 0};
  box.length = Vec3{1, 1, 1};
  return box;
}

/// A domain of this communicator's ranks: 4 × 4 × 4 coarse cells dealt round robin.
MpiDomain world_domain() {
  const CoarseGrid cells = CoarseGrid::over(unit_cube(), Real(0.25));
  std::vector<int> owner(cells.count());
  for (std::size_t c = 0; c < owner.size(); ++c) owner[c] = static_cast<int>(c) % comm_size();
  return MpiDomain(MPI_COMM_WORLD, Decomposition::from_owners(cells, owner, comm_size()), Real(0.1),
                   false);
}

/// Bytes rank `from` sends rank `to` in round `round`: 0 to 12, uneven, zero for some pairs.
std::size_t message_bytes(int from, int to, int round) {
  return static_cast<std::size_t>(((from * 7 + to * 3 + round) % 5) * 3);
}

/// Byte k of the message from `from` to `to` in round `round`.
char message_byte(int from, int to, int round, std::size_t k) {
  return static_cast<char>((from * 31 + to * 17 + round * 5 + static_cast<int>(k)) & 0xff);
}

/// This rank's outgoing messages back to back in rank order, and their sizes.
std::vector<char> outgoing(int round, std::vector<std::size_t>& bytes) {
  std::vector<char> buffer;
  bytes.assign(comm_size(), 0);
  for (int q = 0; q < comm_size(); ++q) {
    bytes[q] = message_bytes(comm_rank(), q, round);
    for (std::size_t k = 0; k < bytes[q]; ++k)
      buffer.push_back(message_byte(comm_rank(), q, round, k));
  }
  return buffer;
}

/// What this rank must receive, back to back in rank order, and the sizes.
std::vector<char> expected_incoming(int round, std::vector<std::size_t>& bytes) {
  std::vector<char> buffer;
  bytes.assign(comm_size(), 0);
  for (int q = 0; q < comm_size(); ++q) {
    bytes[q] = message_bytes(q, comm_rank(), round);
    for (std::size_t k = 0; k < bytes[q]; ++k)
      buffer.push_back(message_byte(q, comm_rank(), round, k));
  }
  return buffer;
}

constexpr char kUntouched = '\x5a';
constexpr std::size_t kGuard = 16;  ///< bytes past the receive buffer that must stay untouched

/// Runs each case with the MPI waits of its parameter, and restores spinning waits after it.
class DomainExchange : public ::testing::TestWithParam<MpiWaiting> {
 protected:
  void SetUp() override { set_mpi_waiting(GetParam()); }
  void TearDown() override { set_mpi_waiting(MpiWaiting::spin); }
};

INSTANTIATE_TEST_SUITE_P(Waits, DomainExchange,
                         ::testing::Values(MpiWaiting::spin, MpiWaiting::nap),
                         [](const auto& info) {
                           return info.param == MpiWaiting::spin ? "spin" : "nap";
                         });

TEST_P(DomainExchange, UnevenAndZeroMessagesArriveInRankOrder) {
  const MpiDomain domain = world_domain();
  for (int round = 0; round < 3; ++round) {
    std::vector<std::size_t> send_bytes, receive_bytes;
    const std::vector<char> send = outgoing(round, send_bytes);
    const std::vector<char> expected = expected_incoming(round, receive_bytes);
    std::vector<char> receive(expected.size() + kGuard, kUntouched);
    std::unique_ptr<PendingExchange> pending =
        domain.start_exchange(send.data(), send_bytes, receive.data(), receive_bytes);
    domain.finish_exchange(std::move(pending));
    EXPECT_EQ(std::vector<char>(receive.begin(), receive.begin() + expected.size()), expected)
        << "rank " << comm_rank() << " round " << round;
    for (std::size_t k = expected.size(); k < receive.size(); ++k)
      EXPECT_EQ(receive[k], kUntouched) << "written past the receive buffer at " << k;
  }
}

TEST_P(DomainExchange, BuffersLongerThanTheMessageLimitArriveWhole) {
  MpiDomain domain = world_domain();
  domain.limit_message_bytes(5);  // buffers of 0 to 36 bytes: up to 8 messages each
  for (int round = 0; round < 3; ++round) {
    RankBuffers outgoing(comm_size()), incoming;
    for (int q = 0; q < comm_size(); ++q)
      for (std::size_t k = 0; k < 3 * message_bytes(comm_rank(), q, round); ++k)
        outgoing[q].push_back(message_byte(comm_rank(), q, round, k));
    domain.group().exchange(outgoing, incoming);
    ASSERT_EQ(incoming.size(), static_cast<std::size_t>(comm_size()));
    for (int q = 0; q < comm_size(); ++q) {
      std::vector<char> expected;
      for (std::size_t k = 0; k < 3 * message_bytes(q, comm_rank(), round); ++k)
        expected.push_back(message_byte(q, comm_rank(), round, k));
      EXPECT_EQ(incoming[q], expected) << "from rank " << q << " round " << round;
    }
  }
}

TEST_P(DomainExchange, TwoExchangesInFlightCompleteInOrder) {
  const MpiDomain domain = world_domain();
  std::vector<std::size_t> send_bytes[2], receive_bytes[2];
  const std::vector<char> send[2] = {outgoing(0, send_bytes[0]), outgoing(1, send_bytes[1])};
  const std::vector<char> expected[2] = {expected_incoming(0, receive_bytes[0]),
                                         expected_incoming(1, receive_bytes[1])};
  std::vector<char> receive[2] = {std::vector<char>(expected[0].size(), kUntouched),
                                  std::vector<char>(expected[1].size(), kUntouched)};
  std::unique_ptr<PendingExchange> first =
      domain.start_exchange(send[0].data(), send_bytes[0], receive[0].data(), receive_bytes[0]);
  std::unique_ptr<PendingExchange> second =
      domain.start_exchange(send[1].data(), send_bytes[1], receive[1].data(), receive_bytes[1]);
  domain.finish_exchange(std::move(second));
  domain.finish_exchange(std::move(first));
  EXPECT_EQ(receive[0], expected[0]);
  EXPECT_EQ(receive[1], expected[1]);
}

TEST_P(DomainExchange, NothingToSendCompletes) {
  const MpiDomain domain = world_domain();
  const std::vector<std::size_t> none(comm_size(), 0);
  char untouched = kUntouched;
  domain.finish_exchange(domain.start_exchange(nullptr, none, &untouched, none));
  EXPECT_EQ(untouched, kUntouched);
}

/// Reductions, broadcasts and gathers give every rank the values computed here from the ranks.
TEST_P(DomainExchange, CollectivesAgreeOnEveryRank) {
  const MpiDomain domain = world_domain();
  const RankGroup& group = domain.group();
  const int n = comm_size(), r = comm_rank();
  std::vector<double> values{double(r), 0.5 * r - 1};
  group.sum(values);
  EXPECT_EQ(values, (std::vector<double>{n * (n - 1) / 2.0, 0.25 * n * (n - 1) - n}));
  EXPECT_EQ(group.max<double>(-double(r)), 0.0);
  EXPECT_EQ(group.min<std::uint64_t>(std::uint64_t(r) + 5), 5u);
  EXPECT_EQ(group.sum<std::uint64_t>(std::uint64_t(1) << 40), std::uint64_t(n) << 40);
  const int root = n - 1;
  EXPECT_EQ(group.broadcast_value(r == root ? 77 : r, root), 77);
  std::vector<char> text(r == root ? 3 : 0, 'x');
  group.broadcast(text, root);
  EXPECT_EQ(text, std::vector<char>(3, 'x'));
  const std::vector<int> all = group.gather(std::vector<int>(static_cast<std::size_t>(r), r));
  std::vector<int> expected;
  for (int q = 0; q < n; ++q) expected.insert(expected.end(), static_cast<std::size_t>(q), q);
  EXPECT_EQ(all, expected);
}

TEST(DomainRefusal, CountsForAnotherRankCountAreRefused) {
  const MpiDomain domain = world_domain();
  const std::vector<std::size_t> counts(comm_size() + 1, 0);
  char byte = 0;
  EXPECT_THROW(domain.start_exchange(&byte, counts, &byte, counts), std::invalid_argument);
}

TEST(DomainRefusal, GhostWidthBeyondACellEdgeIsRefused) {
  const CoarseGrid cells = CoarseGrid::over(unit_cube(), Real(0.25));  // edge 0.25 m
  const auto slabs = [&] {
    std::vector<int> owner(cells.count());
    for (std::size_t c = 0; c < owner.size(); ++c)
      owner[c] = cells.coords(c)[0] * comm_size() / cells.n[0];
    return Decomposition::from_owners(cells, owner, comm_size());
  };
  EXPECT_NO_THROW(MpiDomain(MPI_COMM_WORLD, slabs(), Real(0.25), false));
  EXPECT_THROW(MpiDomain(MPI_COMM_WORLD, slabs(), Real(0.26), false), std::invalid_argument);
  MpiDomain domain(MPI_COMM_WORLD, slabs(), Real(0.25), false);
  const CoarseGrid fine = CoarseGrid::over(unit_cube(), Real(0.2));  // edge 0.2 m
  std::vector<int> owner(fine.count(), 0);
  EXPECT_THROW(domain.propose(Decomposition::from_owners(fine, owner, comm_size())),
               std::invalid_argument);
}

TEST(OneRankExchange, CopiesTheMessage) {
  const OneRankDomain domain(unit_cube());
  std::vector<char> send(11);
  std::iota(send.begin(), send.end(), char{3});
  std::vector<char> receive(send.size() + kGuard, kUntouched);
  const std::vector<std::size_t> bytes{send.size()};
  domain.finish_exchange(domain.start_exchange(send.data(), bytes, receive.data(), bytes));
  for (std::size_t k = 0; k < send.size(); ++k) EXPECT_EQ(receive[k], char(3 + k));
  for (std::size_t k = send.size(); k < receive.size(); ++k) EXPECT_EQ(receive[k], kUntouched);
  const std::vector<std::size_t> fewer{send.size() - 1};
  EXPECT_THROW(domain.start_exchange(send.data(), bytes, receive.data(), fewer),
               std::invalid_argument);
}

}  // namespace
}  // namespace gpudem
