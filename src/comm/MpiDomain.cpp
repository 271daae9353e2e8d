#include "comm/MpiDomain.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "comm/MpiWait.hpp"

namespace gpudem {

namespace {

/// Requests of a start_exchange: one per message, sent or received.
struct MpiPendingExchange final : PendingExchange {
  std::vector<MPI_Request> requests;
};

constexpr int kContiguousTag = 8;  ///< start_exchange (MpiRankGroup::exchange uses 7)

}  // namespace

MpiDomain::MpiDomain(MPI_Comm comm, Decomposition decomposition, Real ghost_width, bool gpu_aware)
    : group_(comm),
      decomposition_(std::move(decomposition)),
      ghost_width_(ghost_width),
      gpu_aware_(gpu_aware) {
  require_fits(decomposition_);
  adopt_decomposition();
}

void MpiDomain::require_fits(const Decomposition& d) const {
  if (d.ranks() != group_.size())
    throw std::invalid_argument("MpiDomain: the decomposition is for another rank count");
  const CoarseGrid& cells = d.cells();
  for (int k = 0; k < 3; ++k)
    if (cells.n[k] > 1 && ghost_width_ > cells.edge(k))
      throw std::invalid_argument("MpiDomain: the ghost width exceeds a coarse cell's edge");
}

void MpiDomain::adopt_decomposition() {
  region_ = decomposition_.region(group_.rank(), ghost_width_, ghost_width_);
  ownership_ = decomposition_.ownership(group_.rank(), ownership_.version + 1);
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

std::unique_ptr<PendingExchange> MpiDomain::start_exchange(
    const char* send, const std::vector<std::size_t>& send_bytes, char* receive,
    const std::vector<std::size_t>& receive_bytes) const {
  const auto ranks = static_cast<std::size_t>(group_.size());
  if (send_bytes.size() != ranks || receive_bytes.size() != ranks)
    throw std::invalid_argument("MpiDomain: byte counts for another rank count");
  auto pending = std::make_unique<MpiPendingExchange>();
  std::vector<MPI_Request>& requests = pending->requests;
  requests.reserve(2 * ranks);
  std::size_t offset = 0;
  for (int q = 0; q < group_.size(); ++q) {
    if (receive_bytes[q] > 0) {
      requests.emplace_back();
      MPI_Irecv(receive + offset, mpi_message_size(receive_bytes[q]), MPI_BYTE, q, kContiguousTag,
                group_.comm(), &requests.back());
    }
    offset += receive_bytes[q];
  }
  offset = 0;
  for (int q = 0; q < group_.size(); ++q) {
    if (send_bytes[q] > 0) {
      requests.emplace_back();
      MPI_Isend(send + offset, mpi_message_size(send_bytes[q]), MPI_BYTE, q, kContiguousTag,
                group_.comm(), &requests.back());
    }
    offset += send_bytes[q];
  }
  return pending;
}

void MpiDomain::finish_exchange(std::unique_ptr<PendingExchange> exchange) const {
  auto* pending = dynamic_cast<MpiPendingExchange*>(exchange.get());
  if (!pending) throw std::invalid_argument("MpiDomain: not an exchange this domain started");
  complete_requests(static_cast<int>(pending->requests.size()), pending->requests.data());
}

}  // namespace gpudem
