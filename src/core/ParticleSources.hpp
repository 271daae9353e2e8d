#pragma once
/// Particle creation from the scene's [[insert]] sources: random non-overlapping insertion in a
/// box (by count or by volume fraction) with a radius distribution, CSV import, or the
/// particles of a saved bed.
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "core/ParticleStore.hpp"
#include "core/RadiusSampling.hpp"
#include "core/RowShare.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// Reads the particles of a bed file (a checkpoint, whose format belongs to the layer that
/// reads files); throws InputError naming the file when it cannot.
using BedReader = std::function<ParticleStore(const std::string& bed_file)>;

/// Creates the particles of every source, in scene order, appending to `store`. Bed particles
/// keep their global ids; the other sources' particles get consecutive ids starting after the
/// bed's largest id, or at store.size() without a bed source.
///
/// A box source placed sequentially (the default) samples all its radii first (`count` of them, or
/// until their volume reaches volume_fraction × region volume) and places them largest first by
/// random sequential insertion: uniform random centres keeping the whole sphere inside the region,
/// rejecting any overlap with particles already in `store` (and with their periodic images in
/// the domain, of those that cross a periodic face); at most 1000 tries per particle. The
/// random stream is std::mt19937_64 seeded from scene.simulation.seed and the source index, so a
/// scene always gives the same particles. A tiled box source is placed by insert_tiled_box
/// (core/TiledInsertion.hpp): the same random sequential insertion tile by tile, the same
/// particles on any number of ranks and threads. Velocity = source velocity, angular velocity 0.
///
/// A CSV source reads columns x, y, z, r and optionally material (name or 0-based index),
/// vx, vy, vz, in any order named by the header line; missing ones take the source's
/// material and velocity. CSV particles are not checked for overlaps.
///
/// A bed source (at most one) takes the positions, radii, velocities, spins, materials and ids
/// of the file `read_bed` reads; masses follow from the scene's material densities. Bed
/// particles are not checked for overlaps either; box sources listed after a bed avoid it.
///
/// Throws InputError (file, line, key) for unreadable CSV or bed files, bad rows or values,
/// centres outside the domain on a non-periodic axis, bed materials beyond the scene's, or a
/// region that cannot hold the requested particles; std::logic_error for a bed source without
/// `read_bed`.
void create_particles(const Scene& scene, ParticleStore& store, const BedReader& read_bed = {});

/// Appends the particles of source i, a box or a CSV source, to `out` with ids from `next_id`;
/// a box source avoids the spheres `avoid` (those of earlier sources near its region; read
/// before any particle is appended, so they may be `out`'s own). Each rank that runs it on the
/// same `avoid` near the region gets the same particles.
void create_source(const Scene& scene, std::size_t i, const std::vector<Real4>& avoid,
                   ParticleStore& out, ParticleId& next_id);

/// Whether a box source is placed by tiles.
inline bool is_tiled_box(const ParticleSource& src) {
  return src.kind == SourceKind::Box && src.placement == Placement::Tiled;
}

/// Whether sphere p (centre, radius) reaches into the box [lo, hi] (overlaps its inside).
inline bool sphere_reaches_box(const Real4& p, Vec3 lo, Vec3 hi) {
  return p.x + p.w > lo.x && p.x - p.w < hi.x && p.y + p.w > lo.y && p.y - p.w < hi.y &&
         p.z + p.w > lo.z && p.z - p.w < hi.z;
}

/// The spheres of `spheres` that reach into the region [lo, hi], themselves or by a periodic
/// image in the domain (core/PeriodicImages.hpp): those a box source placed sequentially there
/// must avoid.
std::vector<Real4> spheres_reaching(const DomainSettings& domain, const std::vector<Real4>& spheres,
                                    Vec3 lo, Vec3 hi);

/// Appends part `part` of the rows of CSV source i (columns as for create_particles) to `out`:
/// row k after the header, blank lines left out, gets id first_id + k. Returns the rows of the
/// whole file. Throws InputError (file, line, column) for a bad header or a bad row of the
/// part: the parts in order report the first bad row of the file first.
std::size_t import_csv_part(const Scene& scene, std::size_t i, FilePart part, ParticleStore& out,
                            ParticleId first_id);

/// Index of the scene's bed source; scene.sources.size() when it has none.
std::size_t bed_source_index(const Scene& scene);

/// The particles `read_bed` reads for bed source i (the whole bed or a part of its rows); its
/// InputErrors are reported on the source's `bed` key.
ParticleStore read_bed_source(const Scene& scene, std::size_t i, const BedReader& read_bed);

/// Appends `bed`, read for bed source i, to `out` with its ids, velocities and spins; masses
/// from the scene's material densities. Throws InputError for a particle whose material the
/// scene lacks or whose centre lies outside the domain on a non-periodic axis.
void append_bed_particles(const Scene& scene, std::size_t i, const ParticleStore& bed,
                          ParticleStore& out);

/// The id after the largest of `particles` (0 for none).
ParticleId id_after(const ParticleStore& particles);

/// Refuses box source i when it cannot be placed: a material the scene lacks, a distribution
/// that cannot be sampled or may give radii <= 0, neither a count nor a volume fraction in
/// (0, 1), a count above what its region holds at the densest packing of its smallest radius,
/// or more particles than one source may hold. Throws InputError naming its key.
void check_box_source(const Scene& scene, std::size_t i);

/// check_box_source for every box source of the scene, in order: before any is placed, so a
/// source that cannot be placed is refused at once.
void check_box_sources(const Scene& scene);

}  // namespace gpudem
