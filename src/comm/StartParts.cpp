#include "comm/StartParts.hpp"

#include <cstdint>
#include <vector>

#include "comm/TiledParts.hpp"
#include "core/RowShare.hpp"

namespace gpudem {
namespace {

/// Box source i placed sequentially, whole on every rank, avoiding the spheres of every rank's
/// `part` that reach its region, with ids from `first_id`. Collective.
ParticleStore place_sequential_box(const MpiRankGroup& ranks, const Scene& scene, std::size_t i,
                                   const ParticleStore& part, ParticleId first_id) {
  const ParticleSource& src = scene.sources[i];
  const std::vector<Real4> avoid = ranks.gather(
      spheres_reaching(scene.domain, part.position_radius, src.region_min, src.region_max));
  return agree_on_failure(ranks, [&] {
    ParticleStore whole;
    ParticleId next_id = first_id;
    create_source(scene, i, avoid, whole, next_id);
    return whole;
  });
}

}  // namespace

ParticleStore create_start_part(const MpiRankGroup& ranks, const Scene& scene,
                                const BedReader& read_bed_part) {
  agree_on_failure(ranks, [&] {
    check_box_sources(scene);
    return 0;
  });
  const std::size_t bed_index = bed_source_index(scene);
  ParticleStore bed;
  if (bed_index < scene.sources.size())
    bed = agree_on_failure(ranks, [&] { return read_bed_source(scene, bed_index, read_bed_part); });
  ParticleId next_id = ranks.max<std::uint64_t>(id_after(bed));
  ParticleStore part;
  for (std::size_t i = 0; i < scene.sources.size(); ++i) {
    if (i == bed_index) {
      agree_on_failure(ranks, [&] {
        append_bed_particles(scene, i, bed, part);
        return 0;
      });
      bed = ParticleStore{};
    } else if (scene.sources[i].kind == SourceKind::Csv) {
      next_id += agree_on_failure(ranks, [&] {
        return import_csv_part(scene, i, FilePart{ranks.rank(), ranks.size()}, part, next_id);
      });
    } else if (is_tiled_box(scene.sources[i])) {
      next_id += ranks.sum<std::uint64_t>(append_tiled_part(ranks, scene, i, part, next_id));
    } else {
      const ParticleStore whole = place_sequential_box(ranks, scene, i, part, next_id);
      next_id += whole.size();
      part.append(share_of(whole, ranks.rank(), ranks.size()));
    }
  }
  return part;
}

}  // namespace gpudem
