#include "comm/MpiDomain.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace gpudem {

namespace {

int message_size(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX))
    throw std::overflow_error("MpiDomain: a message of more than 2^31 - 1 bytes");
  return static_cast<int>(bytes);
}

/// Requests of a start_exchange: one per message, sent or received.
struct MpiPendingExchange final : PendingExchange {
  std::vector<MPI_Request> requests;
};

constexpr int kBuffersTag = 7;     ///< exchange of RankBuffers
constexpr int kContiguousTag = 8;  ///< start_exchange

}  // namespace

MpiDomain::MpiDomain(MPI_Comm comm, Decomposition decomposition, Real ghost_width, bool gpu_aware)
    : comm_(comm),
      decomposition_(std::move(decomposition)),
      ghost_width_(ghost_width),
      gpu_aware_(gpu_aware) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  require_fits(decomposition_);
  adopt_decomposition();
}

void MpiDomain::require_fits(const Decomposition& d) const {
  if (d.ranks() != size_)
    throw std::invalid_argument("MpiDomain: the decomposition is for another rank count");
  const CoarseGrid& cells = d.cells();
  for (int k = 0; k < 3; ++k)
    if (cells.n[k] > 1 && ghost_width_ > cells.edge(k))
      throw std::invalid_argument("MpiDomain: the ghost width exceeds a coarse cell's edge");
}

void MpiDomain::adopt_decomposition() {
  region_ = decomposition_.region(rank_, ghost_width_, ghost_width_);
  ownership_ = decomposition_.ownership(rank_, ownership_.version + 1);
}

void MpiDomain::propose(Decomposition next) {
  require_fits(next);
  pending_ = std::move(next);
}

void MpiDomain::begin_rebuild() {
  if (!pending_) return;
  decomposition_ = std::move(*pending_);
  pending_.reset();
  adopt_decomposition();
}

double MpiDomain::max(double value) const {
  double result = value;
  MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return result;
}

void MpiDomain::sum(std::vector<double>& values) const {
  if (values.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM,
                comm_);
}

std::uint64_t MpiDomain::wrapping_sum(std::uint64_t value) const {
  std::uint64_t total = value;
  MPI_Allreduce(&value, &total, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return total;
}

int MpiDomain::first_rank_with(bool flag) const {
  const int mine = flag ? rank_ : size_;
  int first = mine;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm_);
  return first;
}

void MpiDomain::broadcast(std::vector<char>& bytes, int root) const {
  std::uint64_t n = bytes.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm_);
  bytes.resize(n);
  if (n > 0) MPI_Bcast(bytes.data(), message_size(n), MPI_BYTE, root, comm_);
}

void MpiDomain::exchange(const RankBuffers& outgoing, RankBuffers& incoming) const {
  std::vector<std::uint64_t> send_bytes(size_), receive_bytes(size_);
  for (int q = 0; q < size_; ++q) send_bytes[q] = outgoing[q].size();
  MPI_Alltoall(send_bytes.data(), 1, MPI_UINT64_T, receive_bytes.data(), 1, MPI_UINT64_T, comm_);
  incoming.assign(size_, {});
  for (int q = 0; q < size_; ++q) incoming[q].resize(receive_bytes[q]);
  exchange_known(outgoing, incoming);
}

void MpiDomain::exchange_known(const RankBuffers& outgoing, RankBuffers& incoming) const {
  // A buffer goes as messages of at most max_message_bytes_; both sides split it alike, and MPI
  // matches the messages of one sender and tag in the order they were posted.
  std::vector<MPI_Request> requests;
  const auto for_each_chunk = [&](std::size_t bytes, auto&& post) {
    for (std::size_t at = 0; at < bytes; at += max_message_bytes_) {
      requests.emplace_back();
      post(at, message_size(std::min(max_message_bytes_, bytes - at)), &requests.back());
    }
  };
  for (int q = 0; q < size_; ++q) {
    if (q == rank_) {
      incoming[q] = outgoing[q];
      continue;
    }
    char* data = incoming[q].data();
    for_each_chunk(incoming[q].size(), [&](std::size_t at, int count, MPI_Request* request) {
      MPI_Irecv(data + at, count, MPI_BYTE, q, kBuffersTag, comm_, request);
    });
  }
  for (int q = 0; q < size_; ++q) {
    if (q == rank_) continue;
    const char* data = outgoing[q].data();
    for_each_chunk(outgoing[q].size(), [&](std::size_t at, int count, MPI_Request* request) {
      MPI_Isend(data + at, count, MPI_BYTE, q, kBuffersTag, comm_, request);
    });
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

std::unique_ptr<PendingExchange> MpiDomain::start_exchange(
    const char* send, const std::vector<std::size_t>& send_bytes, char* receive,
    const std::vector<std::size_t>& receive_bytes) const {
  const auto ranks = static_cast<std::size_t>(size_);
  if (send_bytes.size() != ranks || receive_bytes.size() != ranks)
    throw std::invalid_argument("MpiDomain: byte counts for another rank count");
  auto pending = std::make_unique<MpiPendingExchange>();
  std::vector<MPI_Request>& requests = pending->requests;
  requests.reserve(2 * ranks);
  std::size_t offset = 0;
  for (int q = 0; q < size_; ++q) {
    if (receive_bytes[q] > 0) {
      requests.emplace_back();
      MPI_Irecv(receive + offset, message_size(receive_bytes[q]), MPI_BYTE, q, kContiguousTag,
                comm_, &requests.back());
    }
    offset += receive_bytes[q];
  }
  offset = 0;
  for (int q = 0; q < size_; ++q) {
    if (send_bytes[q] > 0) {
      requests.emplace_back();
      MPI_Isend(send + offset, message_size(send_bytes[q]), MPI_BYTE, q, kContiguousTag, comm_,
                &requests.back());
    }
    offset += send_bytes[q];
  }
  return pending;
}

void MpiDomain::finish_exchange(std::unique_ptr<PendingExchange> exchange) const {
  auto* pending = dynamic_cast<MpiPendingExchange*>(exchange.get());
  if (!pending) throw std::invalid_argument("MpiDomain: not an exchange this domain started");
  MPI_Waitall(static_cast<int>(pending->requests.size()), pending->requests.data(),
              MPI_STATUSES_IGNORE);
}

}  // namespace gpudem
