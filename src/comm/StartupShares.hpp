#pragma once
/// Start-up on several ranks from shares (docs/architecture.md, "One time step"): each rank holds a
/// share of the particles (rows of a file it read by parts, or of particles it created), and the
/// ranks agree through these collectives on what the whole run needs: input errors, the particles
/// that set the time step, the particle count.
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/InputError.hpp"
#include "core/ParticleStore.hpp"

namespace gpudem {

/// The most bytes one MPI call with int counts moves.
inline constexpr std::size_t kMaxMessageBytes = std::numeric_limits<int>::max();

/// A failure of one rank, to be thrown on every rank.
struct RankFailure {
  std::string message;  ///< empty: no failure
  bool input = false;   ///< an InputError (exit 2), else a std::runtime_error (exit 1)
};

/// Throws the failure of the lowest rank that has one on every rank: InputError(message) or
/// std::runtime_error(message); returns when no rank has one. Collective.
void throw_first_failure(MPI_Comm comm, const RankFailure& failure);

/// What `attempt()` returns, when it throws on no rank; else every rank throws the lowest
/// failing rank's error (an InputError as such, any other std::exception as a
/// std::runtime_error with its message), so that rank 0 reports it and no rank is left waiting
/// in a collective. Collective.
template <class Attempt>
auto agree_on_input(MPI_Comm comm, Attempt&& attempt) -> decltype(attempt()) {
  std::optional<decltype(attempt())> result;
  RankFailure failure;
  try {
    result.emplace(attempt());
  } catch (const InputError& e) {
    failure = {e.what(), true};
  } catch (const std::exception& e) {
    failure = {e.what(), false};
  }
  throw_first_failure(comm, failure);
  return std::move(*result);
}

/// Every rank's `share` (all its arrays the same length, or force and torque empty on every
/// rank), concatenated in rank order, on every rank. For small selections. Collective.
ParticleStore gather_particles(MPI_Comm comm, const ParticleStore& share);

/// Every rank's `spheres` concatenated in rank order, on every rank. For small selections
/// (below 2^31 bytes). Collective.
std::vector<Real4> gather_spheres(MPI_Comm comm, const std::vector<Real4>& spheres);

/// The largest `value` over ranks. Collective.
std::uint64_t max_over_ranks(MPI_Comm comm, std::uint64_t value);

/// Σ over ranks of `value`. Collective.
std::uint64_t sum_over_ranks(MPI_Comm comm, std::uint64_t value);

/// The sum of `count` over the ranks before this one (0 on rank 0): the first global id of
/// this rank's part when the parts hold consecutive ids in rank order. Collective.
std::uint64_t ids_before_rank(MPI_Comm comm, std::uint64_t count);

}  // namespace gpudem
