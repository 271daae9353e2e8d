#include "comm/StartupShares.hpp"

#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace gpudem {
namespace {

/// Every rank's `part` concatenated in rank order, on every rank (T holds plain values).
template <class T>
std::vector<T> gather_rows(MPI_Comm comm, const std::vector<T>& part) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const std::uint64_t part_bytes = part.size() * sizeof(T);
  if (sum_over_ranks(comm, part_bytes) > kMaxMessageBytes)
    throw std::length_error("gathering rows on every rank: more than 2^31 - 1 bytes in all");
  const int bytes = static_cast<int>(part_bytes);
  std::vector<int> counts(ranks), offsets(ranks, 0);
  MPI_Allgather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
  std::vector<T> all((offsets.back() + counts.back()) / sizeof(T));
  MPI_Allgatherv(part.data(), bytes, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE,
                 comm);
  return all;
}

}  // namespace

void throw_first_failure(MPI_Comm comm, const RankFailure& failure) {
  int ranks = 1, rank = 0;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm_rank(comm, &rank);
  const int mine = failure.message.empty() ? ranks : rank;
  int first = ranks;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == ranks) return;
  int header[2] = {static_cast<int>(failure.message.size()), failure.input ? 1 : 0};
  MPI_Bcast(header, 2, MPI_INT, first, comm);
  std::string text =
      rank == first ? failure.message : std::string(static_cast<std::size_t>(header[0]), ' ');
  MPI_Bcast(text.data(), header[0], MPI_CHAR, first, comm);
  if (header[1]) throw InputError("", 0, "", text);
  throw std::runtime_error(text);
}

ParticleStore gather_particles(MPI_Comm comm, const ParticleStore& share) {
  ParticleStore all;
  all.position_radius = gather_rows(comm, share.position_radius);
  all.velocity_inv_mass = gather_rows(comm, share.velocity_inv_mass);
  all.angular_velocity = gather_rows(comm, share.angular_velocity);
  all.force = gather_rows(comm, share.force);
  all.torque = gather_rows(comm, share.torque);
  all.id = gather_rows(comm, share.id);
  all.material = gather_rows(comm, share.material);
  return all;
}

std::vector<Real4> gather_spheres(MPI_Comm comm, const std::vector<Real4>& spheres) {
  return gather_rows(comm, spheres);
}

std::uint64_t max_over_ranks(MPI_Comm comm, std::uint64_t value) {
  std::uint64_t max = 0;
  MPI_Allreduce(&value, &max, 1, MPI_UINT64_T, MPI_MAX, comm);
  return max;
}

std::uint64_t sum_over_ranks(MPI_Comm comm, std::uint64_t value) {
  std::uint64_t sum = 0;
  MPI_Allreduce(&value, &sum, 1, MPI_UINT64_T, MPI_SUM, comm);
  return sum;
}

std::uint64_t ids_before_rank(MPI_Comm comm, std::uint64_t count) {
  std::uint64_t before = 0;
  MPI_Exscan(&count, &before, 1, MPI_UINT64_T, MPI_SUM, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank == 0 ? 0 : before;  // MPI_Exscan leaves rank 0's result undefined
}

}  // namespace gpudem
