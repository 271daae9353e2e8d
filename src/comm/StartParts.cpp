#include "comm/StartParts.hpp"

#include <cstdint>
#include <vector>

#include "comm/StartupShares.hpp"
#include "comm/TiledParts.hpp"
#include "core/RowShare.hpp"

namespace gpudem {
namespace {

/// Box source i placed sequentially, whole on every rank, avoiding the spheres of every rank's
/// `part` that reach its region, with ids from `first_id`. Collective.
ParticleStore place_sequential_box(MPI_Comm comm, const Scene& scene, std::size_t i,
                                   const ParticleStore& part, ParticleId first_id) {
  const ParticleSource& src = scene.sources[i];
  const std::vector<Real4> avoid = gather_spheres(
      comm, spheres_reaching(scene.domain, part.position_radius, src.region_min, src.region_max));
  return agree_on_input(comm, [&] {
    ParticleStore whole;
    ParticleId next_id = first_id;
    create_source(scene, i, avoid, whole, next_id);
    return whole;
  });
}

}  // namespace

ParticleStore create_start_part(MPI_Comm comm, const Scene& scene, const BedReader& read_bed_part) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const std::size_t bed_index = bed_source_index(scene);
  ParticleStore bed;
  if (bed_index < scene.sources.size())
    bed = agree_on_input(comm, [&] { return read_bed_source(scene, bed_index, read_bed_part); });
  ParticleId next_id = max_over_ranks(comm, id_after(bed));
  ParticleStore part;
  for (std::size_t i = 0; i < scene.sources.size(); ++i) {
    if (i == bed_index) {
      agree_on_input(comm, [&] {
        append_bed_particles(scene, i, bed, part);
        return 0;
      });
      bed = ParticleStore{};
    } else if (scene.sources[i].kind == SourceKind::Csv) {
      next_id += agree_on_input(comm, [&] {
        return import_csv_part(scene, i, FilePart{rank, ranks}, part, next_id);
      });
    } else if (is_tiled_box(scene.sources[i])) {
      next_id += sum_over_ranks(comm, append_tiled_part(comm, scene, i, part, next_id));
    } else {
      const ParticleStore whole = place_sequential_box(comm, scene, i, part, next_id);
      next_id += whole.size();
      part.append(share_of(whole, rank, ranks));
    }
  }
  return part;
}

}  // namespace gpudem
