#include "comm/TiledParts.hpp"

#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "comm/StartupShares.hpp"
#include "core/ParticleSources.hpp"
#include "core/RowShare.hpp"
#include "core/TiledInsertion.hpp"

namespace gpudem {
namespace {

/// `rank`, or MPI_PROC_NULL for none (-1).
int rank_or_null(int rank) { return rank < 0 ? MPI_PROC_NULL : rank; }

/// Sends `out` to rank `to` and returns what rank `from` sends (either may be MPI_PROC_NULL).
std::vector<BoundarySphere> send_receive(MPI_Comm comm, const std::vector<BoundarySphere>& out,
                                         int to, int from) {
  constexpr int kCountTag = 41, kSpheresTag = 42;
  std::uint64_t count_out = out.size(), count_in = 0;
  MPI_Sendrecv(&count_out, 1, MPI_UINT64_T, to, kCountTag, &count_in, 1, MPI_UINT64_T, from,
               kCountTag, comm, MPI_STATUS_IGNORE);
  const std::uint64_t limit = std::numeric_limits<int>::max() / sizeof(BoundarySphere);
  if (count_out > limit || count_in > limit)
    throw std::length_error("create_tiled_part: a layer of tiles too large for one message");
  std::vector<BoundarySphere> in(count_in);
  MPI_Sendrecv(out.data(), static_cast<int>(count_out * sizeof(BoundarySphere)), MPI_BYTE, to,
               kSpheresTag, in.data(), static_cast<int>(count_in * sizeof(BoundarySphere)),
               MPI_BYTE, from, kSpheresTag, comm, MPI_STATUS_IGNORE);
  return in;
}

/// After a phase: the first layer's new spheres go down and the upper neighbour's come in
/// above, then the last layer's go up and the lower neighbour's come in below.
void exchange_boundaries(MPI_Comm comm, TiledFill& fill) {
  const int below = rank_or_null(fill.neighbour(LayerSide::Below));
  const int above = rank_or_null(fill.neighbour(LayerSide::Above));
  fill.receive(LayerSide::Above, send_receive(comm, fill.boundary(LayerSide::Below), below, above));
  fill.receive(LayerSide::Below, send_receive(comm, fill.boundary(LayerSide::Above), above, below));
}

}  // namespace

ParticleStore create_tiled_part(MPI_Comm comm, const Scene& scene) {
  if (!tiled_box_is_the_only_source(scene))
    throw std::logic_error("create_tiled_part: the scene's one source must be a tiled box");
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::optional<TiledFill> fill;
  agree_on_input(comm, [&] {
    check_box_source(scene, 0);
    fill.emplace(scene, 0, FilePart{rank, ranks}, ParticleStore{});
    return 0;
  });
  for (int phase = 0; phase < kTilePhases; ++phase) {
    fill->fill_phase(phase);
    exchange_boundaries(comm, *fill);
  }
  ParticleStore part = agree_on_input(comm, [&] {
    ParticleStore placed;
    ParticleId next_id = 0;
    fill->append_to(placed, next_id);
    return placed;
  });
  const ParticleId first_id = ids_before_rank(comm, part.size());
  for (ParticleId& id : part.id) id += first_id;
  return part;
}

}  // namespace gpudem
