#include "comm/MpiRankGroup.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include "comm/MpiWait.hpp"

namespace gpudem {

namespace {

constexpr int kBuffersTag = 7;  ///< exchange of RankBuffers

/// Waits for the one request of a non-blocking collective (complete_requests).
void complete(MPI_Request request) { complete_requests(1, &request); }

MPI_Op mpi_op(Reduction op) {
  switch (op) {
    case Reduction::Max:
      return MPI_MAX;
    case Reduction::Min:
      return MPI_MIN;
    case Reduction::Sum:
      break;
  }
  return MPI_SUM;
}

}  // namespace

int mpi_message_size(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX))
    throw std::overflow_error("MPI: a message of more than 2^31 - 1 bytes");
  return static_cast<int>(bytes);
}

MpiRankGroup::MpiRankGroup(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

void MpiRankGroup::reduce(Reduction op, double* values, std::size_t n) const {
  MPI_Request request;
  MPI_Iallreduce(MPI_IN_PLACE, values, mpi_message_size(n), MPI_DOUBLE, mpi_op(op), comm_,
                 &request);
  complete(request);
}

void MpiRankGroup::reduce(Reduction op, std::uint64_t* values, std::size_t n) const {
  MPI_Request request;
  MPI_Iallreduce(MPI_IN_PLACE, values, mpi_message_size(n), MPI_UINT64_T, mpi_op(op), comm_,
                 &request);
  complete(request);
}

void MpiRankGroup::broadcast(std::vector<char>& bytes, int root) const {
  std::uint64_t n = bytes.size();
  MPI_Request request;
  MPI_Ibcast(&n, 1, MPI_UINT64_T, root, comm_, &request);
  complete(request);
  bytes.resize(n);
  if (n == 0) return;
  MPI_Ibcast(bytes.data(), mpi_message_size(n), MPI_BYTE, root, comm_, &request);
  complete(request);
}

void MpiRankGroup::all_gather(const std::vector<char>& mine, RankBuffers& all) const {
  const int bytes = mpi_message_size(mine.size());
  std::vector<int> counts(size_), offsets(size_, 0);
  MPI_Request request;
  MPI_Iallgather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_, &request);
  complete(request);
  std::uint64_t total = 0;
  for (int c : counts) total += static_cast<std::uint64_t>(c);
  mpi_message_size(total);
  std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
  std::vector<char> joined(total);
  MPI_Iallgatherv(mine.data(), bytes, MPI_BYTE, joined.data(), counts.data(), offsets.data(),
                  MPI_BYTE, comm_, &request);
  complete(request);
  all.assign(size_, {});
  for (int q = 0; q < size_; ++q)
    all[q].assign(joined.begin() + offsets[q], joined.begin() + offsets[q] + counts[q]);
}

void MpiRankGroup::exchange(const RankBuffers& outgoing, RankBuffers& incoming) const {
  if (outgoing.size() != static_cast<std::size_t>(size_))
    throw std::invalid_argument("MpiRankGroup::exchange: outgoing has a buffer per rank");
  std::vector<std::uint64_t> send_bytes(size_), receive_bytes(size_);
  for (int q = 0; q < size_; ++q) send_bytes[q] = outgoing[q].size();
  MPI_Request request;
  MPI_Ialltoall(send_bytes.data(), 1, MPI_UINT64_T, receive_bytes.data(), 1, MPI_UINT64_T, comm_,
                &request);
  complete(request);
  incoming.assign(size_, {});
  for (int q = 0; q < size_; ++q) incoming[q].resize(receive_bytes[q]);
  exchange_known(outgoing, incoming);
}

void MpiRankGroup::exchange_known(const RankBuffers& outgoing, RankBuffers& incoming) const {
  // A buffer goes as messages of at most max_message_bytes_; both sides split it alike, and MPI
  // matches the messages of one sender and tag in the order they were posted.
  std::vector<MPI_Request> requests;
  const auto for_each_chunk = [&](std::size_t bytes, auto&& post) {
    for (std::size_t at = 0; at < bytes; at += max_message_bytes_) {
      requests.emplace_back();
      post(at, mpi_message_size(std::min(max_message_bytes_, bytes - at)), &requests.back());
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
  complete_requests(static_cast<int>(requests.size()), requests.data());
}

}  // namespace gpudem
