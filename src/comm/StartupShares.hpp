#pragma once
/// Start-up on several ranks from shares (DESIGN §4): each rank holds a share of the particles
/// (rows of a file it read by parts, or of particles it created), and the ranks agree through
/// these collectives on what the whole run needs: input errors, the particles that set the
/// time step, the particle count.
#include <mpi.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "core/InputError.hpp"
#include "core/ParticleStore.hpp"

namespace gpudem {

/// Throws InputError(message) of the lowest rank whose `message` is not empty on every rank;
/// returns when none has one. Collective.
void throw_first_input_error(MPI_Comm comm, const std::string& message);

/// What `attempt()` returns, when it throws an InputError on no rank; else every rank throws
/// the lowest failing rank's error, so that rank 0 reports it and no rank is left waiting in
/// a collective. Collective.
template <class Attempt>
auto agree_on_input(MPI_Comm comm, Attempt&& attempt) -> decltype(attempt()) {
  std::optional<decltype(attempt())> result;
  std::string message;
  try {
    result.emplace(attempt());
  } catch (const InputError& e) {
    message = e.what();
  }
  throw_first_input_error(comm, message);
  return std::move(*result);
}

/// Every rank's `share` (all its arrays the same length, or force and torque empty on every
/// rank), concatenated in rank order, on every rank. For small selections. Collective.
ParticleStore gather_particles(MPI_Comm comm, const ParticleStore& share);

/// Σ over ranks of `value`. Collective.
std::uint64_t sum_over_ranks(MPI_Comm comm, std::uint64_t value);

}  // namespace gpudem
