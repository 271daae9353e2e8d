#include "core/ParticleSources.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/CsvReader.hpp"
#include "core/FreeCentre.hpp"
#include "core/InputError.hpp"
#include "core/PeriodicImages.hpp"
#include "core/RowShare.hpp"
#include "core/SphereHash.hpp"
#include "core/TiledInsertion.hpp"

namespace gpudem {
namespace {

/// π/√18: the solid fraction of the densest packing of equal spheres (Hales 2005).
constexpr double densest_packing = 0.74048048969306104;
/// Radii drawn at a time while filling a volume fraction (the unused rest is dropped).
constexpr std::size_t radius_batch = 4096;

std::mt19937_64 source_rng(std::uint64_t seed, std::size_t source_index) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(source_index)};
  return std::mt19937_64(seq);
}

std::string source_key(std::size_t i) { return "insert[" + std::to_string(i) + "]"; }

double box_volume(Vec3 lo, Vec3 hi) { return (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z); }

/// Refuses distributions that cannot be sampled or could produce radii <= 0.
void check_distribution(const Scene& scene, std::size_t i) {
  const RadiusDistribution& d = scene.sources[i].radius;
  const std::string key = source_key(i) + ".radius";
  const std::string problem = sampling_problem(d);
  if (!problem.empty()) throw InputError(scene.file, 0, key, problem);
  if (!(min_radius(d) > 0))
    throw InputError(scene.file, 0, key, "the distribution can produce radii <= 0");
}

void check_material(const Scene& scene, std::size_t i) {
  if (scene.sources[i].material >= scene.materials.size())
    throw InputError(scene.file, 0, source_key(i) + ".material", "no such material");
}

/// The most spheres of radius >= r that fit in the box [lo, hi] (without overlap, inside it):
/// those of radius r at the densest packing of equal spheres.
/// Shrinking each sphere to radius r about its centre keeps them apart, so no mix of larger
/// spheres holds more.
double densest_sphere_count(Vec3 lo, Vec3 hi, double r) {
  return std::floor(densest_packing * box_volume(lo, hi) / sphere_volume(r));
}

/// Refuses a box source without a count or a volume fraction in (0, 1), with more particles
/// than its region can hold (densest_sphere_count of its smallest radius) or (at least) than
/// one source may hold.
void check_source_size(const Scene& scene, std::size_t i) {
  const ParticleSource& src = scene.sources[i];
  const std::string key = source_key(i);
  if (src.count > 0) {
    const double r_min = min_radius(src.radius);
    const double capacity = densest_sphere_count(src.region_min, src.region_max, r_min);
    if (static_cast<double>(src.count) > capacity)
      throw InputError(
          scene.file, 0, key + ".count",
          "count = " + std::to_string(src.count) + " is more than the region can hold: at most " +
              std::to_string(static_cast<std::uint64_t>(capacity)) +
              " spheres of the smallest radius " + four_digits(r_min) + " m fit in its " +
              four_digits(box_volume(src.region_min, src.region_max)) +
              " m^3 even at the densest packing (solid fraction 0.7405; random "
              "insertion jams near 0.38); enlarge the region or lower count");
    if (src.count > SphereHash::max_size)
      throw InputError(scene.file, 0, key + ".count", "too many particles for one source");
    return;
  }
  if (!(src.volume_fraction > 0 && src.volume_fraction < 1))
    throw InputError(scene.file, 0, key, "needs count > 0 or volume_fraction in (0, 1)");
  const double target = src.volume_fraction * box_volume(src.region_min, src.region_max);
  if (target / sphere_volume(max_radius(src.radius)) > static_cast<double>(SphereHash::max_size))
    throw InputError(scene.file, 0, key + ".volume_fraction", "too many particles for one source");
}

/// Radii of a box source (checked by check_source_size), largest first: `count` of them, or
/// enough that their volume reaches volume_fraction × region volume.
std::vector<double> box_radii(const Scene& scene, std::size_t i, std::mt19937_64& rng) {
  const ParticleSource& src = scene.sources[i];
  std::vector<double> radii;
  if (src.count > 0) {
    radii = sample_radii(src.radius, src.count, rng);
  } else {
    const double target = src.volume_fraction * box_volume(src.region_min, src.region_max);
    double volume = 0;
    while (volume < target) {
      if (radii.size() >= SphereHash::max_size)
        throw InputError(scene.file, 0, source_key(i) + ".volume_fraction",
                         "too many particles for one source");
      for (double r : sample_radii(src.radius, radius_batch, rng)) {
        if (volume >= target) break;
        radii.push_back(r);
        volume += sphere_volume(r);
      }
    }
  }
  std::sort(radii.begin(), radii.end(), std::greater<double>());
  return radii;
}

/// The images of `spheres` in the domain (for_each_image_in_domain) that reach into [lo, hi].
std::vector<Real4> images_reaching(const DomainSettings& domain, const std::vector<Real4>& spheres,
                                   Vec3 lo, Vec3 hi) {
  std::vector<Real4> images;
  for (const Real4& p : spheres)
    for_each_image_in_domain(domain, p, [&](const Real4& q) {
      if (sphere_reaches_box(q, lo, hi)) images.push_back(q);
    });
  return images;
}

/// A random centre keeping the sphere inside [lo, hi] and off every stored sphere.
std::optional<Vec3> free_spot(Vec3 lo, Vec3 hi, double r, const SphereHash& hash,
                              std::mt19937_64& rng) {
  Vec3 first, width;
  for (int k = 0; k < 3; ++k) {
    axis(first, k) = axis(lo, k) + r;
    axis(width, k) = axis(hi, k) - axis(lo, k) - 2 * r;
  }
  return free_centre(first, width, r, hash, rng);
}

/// Box source i, placed by one random sequence over its whole region avoiding `avoid`.
void insert_box_sequential(const Scene& scene, std::size_t i, const std::vector<Real4>& avoid,
                           ParticleStore& out, ParticleId& next_id) {
  const ParticleSource& src = scene.sources[i];
  std::mt19937_64 rng = source_rng(scene.simulation.seed, i);
  const std::vector<double> radii = box_radii(scene, i, rng);
  if (radii.empty()) return;
  const std::vector<Real4> near =
      images_reaching(scene.domain, avoid, src.region_min, src.region_max);
  if (near.size() + radii.size() > SphereHash::max_size)
    throw InputError(scene.file, 0, source_key(i), "too many particles in and near the region");
  SphereHash hash(radii.back(), near.size() + radii.size());
  for (const Real4& p : near) hash.insert(xyz(p), p.w);
  const double density = scene.materials[src.material].density;
  const double region_volume = box_volume(src.region_min, src.region_max);
  double placed_volume = 0;
  for (std::size_t n = 0; n < radii.size(); ++n) {
    const double r = radii[n];
    const std::optional<Vec3> c = free_spot(src.region_min, src.region_max, r, hash, rng);
    if (!c)
      throw InputError(scene.file, 0, source_key(i),
                       "could only place " + std::to_string(n) + " of " +
                           std::to_string(radii.size()) + " particles (solid fraction " +
                           four_digits(placed_volume / region_volume) +
                           ") in the region; enlarge the region or lower count/volume_fraction");
    hash.insert(*c, r);
    placed_volume += sphere_volume(r);
    out.add(next_id++, *c, r, src.material, src.velocity, 1.0 / sphere_mass(density, r));
  }
}

/// Box source i, checked, then placed sequentially or by tiles.
void insert_box(const Scene& scene, std::size_t i, const std::vector<Real4>& avoid,
                ParticleStore& out, ParticleId& next_id) {
  check_box_source(scene, i);
  if (scene.sources[i].placement == Placement::Tiled)
    insert_tiled_box(scene, i, avoid, out, next_id);
  else
    insert_box_sequential(scene, i, avoid, out, next_id);
}

/// Positions in the header of the columns a particle CSV file may have.
struct CsvColumns {
  int x = -1, y = -1, z = -1, r = -1, material = -1, vx = -1, vy = -1, vz = -1, wx = -1, wy = -1,
      wz = -1;
};

CsvColumns csv_columns(const CsvReader& csv) {
  CsvColumns c;
  const std::pair<const char*, int*> known[] = {
      {"x", &c.x},   {"y", &c.y},   {"z", &c.z},   {"r", &c.r},   {"material", &c.material},
      {"vx", &c.vx}, {"vy", &c.vy}, {"vz", &c.vz}, {"wx", &c.wx}, {"wy", &c.wy},
      {"wz", &c.wz}};
  const std::vector<std::string>& header = csv.header();
  for (std::size_t k = 0; k < header.size(); ++k) {
    const auto match = std::find_if(std::begin(known), std::end(known),
                                    [&](const auto& kc) { return header[k] == kc.first; });
    if (match == std::end(known))
      throw InputError(
          csv.path(), 1, header[k],
          "unknown column '" + header[k] +
              "'; expected x, y, z, r and optionally material, vx, vy, vz, wx, wy, wz");
    if (*match->second >= 0)
      throw InputError(csv.path(), 1, header[k], "column '" + header[k] + "' appears twice");
    *match->second = static_cast<int>(k);
  }
  const std::pair<const char*, int> required[] = {{"x", c.x}, {"y", c.y}, {"z", c.z}, {"r", c.r}};
  for (const auto& [name, position] : required)
    if (position < 0)
      throw InputError(csv.path(), 1, name, std::string("missing required column '") + name + "'");
  return c;
}

/// A material given by name, or else by 0-based index.
MaterialId csv_material(const Scene& scene, const CsvReader& csv, const std::string& field) {
  for (std::size_t m = 0; m < scene.materials.size(); ++m)
    if (scene.materials[m].name == field) return static_cast<MaterialId>(m);
  const bool digits = !field.empty() && field.find_first_not_of("0123456789") == std::string::npos;
  if (digits && field.size() < 10 && std::stoul(field) < scene.materials.size())
    return static_cast<MaterialId>(std::stoul(field));
  throw InputError(csv.path(), csv.line(), "material",
                   "unknown material '" + field + "' (neither a material name nor an index)");
}

/// The first non-periodic axis (0, 1, 2) along which `centre` lies outside the domain, or -1.
int axis_outside_domain(const Scene& scene, Vec3 centre) {
  for (int k = 0; k < 3; ++k) {
    const double c = axis(centre, k);
    if (!scene.domain.periodic[k] &&
        (c < axis(scene.domain.min, k) || c > axis(scene.domain.max, k)))
      return k;
  }
  return -1;
}

/// "centre x = 1.2 lies outside the domain [0, 1]" for axis k.
std::string outside_domain_text(const Scene& scene, Vec3 centre, int k) {
  return "centre " + std::string(1, "xyz"[k]) + " = " + four_digits(axis(centre, k)) +
         " lies outside the domain [" + four_digits(axis(scene.domain.min, k)) + ", " +
         four_digits(axis(scene.domain.max, k)) + "]";
}

/// Rejects a centre outside the domain along a non-periodic axis.
void check_in_domain(const Scene& scene, const CsvReader& csv, Vec3 centre) {
  const int k = axis_outside_domain(scene, centre);
  if (k >= 0)
    throw InputError(csv.path(), csv.line(), std::string(1, "xyz"[k]),
                     outside_domain_text(scene, centre, k));
}

/// The rows of a CSV file after its header, blank lines left out.
std::size_t csv_row_count(const std::string& path) {
  CsvReader csv(path);
  std::size_t rows = 0;
  while (csv.skip()) ++rows;
  return rows;
}

/// Appends particle `id` of CSV row `f` of source i.
void add_csv_particle(const Scene& scene, std::size_t i, const CsvReader& csv,
                      const CsvColumns& col, const std::vector<std::string>& f, ParticleId id,
                      ParticleStore& out) {
  const ParticleSource& src = scene.sources[i];
  const auto optional = [&](int k, const char* name, double fallback) {
    return k < 0 ? fallback : csv.number(f[k], name);
  };
  const Vec3 centre{csv.number(f[col.x], "x"), csv.number(f[col.y], "y"),
                    csv.number(f[col.z], "z")};
  const double r = csv.number(f[col.r], "r");
  if (!(r > 0))
    throw InputError(csv.path(), csv.line(), "r", "radius must be > 0, got " + f[col.r]);
  const MaterialId mat =
      col.material < 0 ? src.material : csv_material(scene, csv, f[col.material]);
  check_in_domain(scene, csv, centre);
  const Vec3 v{optional(col.vx, "vx", src.velocity.x), optional(col.vy, "vy", src.velocity.y),
               optional(col.vz, "vz", src.velocity.z)};
  out.add(id, centre, r, mat, v, 1.0 / sphere_mass(scene.materials[mat].density, r));
  out.angular_velocity.back() = {optional(col.wx, "wx", 0.0), optional(col.wy, "wy", 0.0),
                                 optional(col.wz, "wz", 0.0)};
}

/// Fails on the `bed` key of source i with `what`.
[[noreturn]] void reject_bed(const Scene& scene, std::size_t i, const std::string& what) {
  const ParticleSource& src = scene.sources[i];
  throw InputError(scene.file, src.bed_line, source_key(i) + ".bed",
                   "bed file '" + src.bed_file + "': " + what);
}

/// Rejects bed particle n when its material or its centre does not fit the scene.
void check_bed_particle(const Scene& scene, std::size_t i, const ParticleStore& bed,
                        std::size_t n) {
  const std::string particle = "particle id " + std::to_string(bed.id[n]);
  if (bed.material[n] >= scene.materials.size())
    reject_bed(scene, i,
               particle + " has material index " + std::to_string(bed.material[n]) +
                   " but the scene defines " + std::to_string(scene.materials.size()) +
                   " material(s)");
  const Vec3 centre = xyz(bed.position_radius[n]);
  const int k = axis_outside_domain(scene, centre);
  if (k >= 0) reject_bed(scene, i, particle + ": " + outside_domain_text(scene, centre, k));
}

}  // namespace

void create_source(const Scene& scene, std::size_t i, const std::vector<Real4>& avoid,
                   ParticleStore& out, ParticleId& next_id) {
  switch (scene.sources[i].kind) {
    case SourceKind::Box:
      insert_box(scene, i, avoid, out, next_id);
      return;
    case SourceKind::Csv:
      next_id += import_csv_part(scene, i, FilePart{}, out, next_id);
      return;
    case SourceKind::Bed:
      throw std::logic_error("create_source: a bed source is read with read_bed_source");
  }
}

std::vector<Real4> spheres_reaching(const DomainSettings& domain, const std::vector<Real4>& spheres,
                                    Vec3 lo, Vec3 hi) {
  std::vector<Real4> reaching;
  for (const Real4& p : spheres) {
    bool reaches = false;
    for_each_image_in_domain(domain, p,
                             [&](const Real4& q) { reaches |= sphere_reaches_box(q, lo, hi); });
    if (reaches) reaching.push_back(p);
  }
  return reaching;
}

std::size_t import_csv_part(const Scene& scene, std::size_t i, FilePart part, ParticleStore& out,
                            ParticleId first_id) {
  const std::string& path = scene.sources[i].csv_file;
  const RowRange rows =
      part.count == 1 ? RowRange{0, ~std::size_t{0}} : part.rows_of(csv_row_count(path));
  CsvReader csv(path);
  const CsvColumns col = csv_columns(csv);
  if (col.material < 0) check_material(scene, i);
  std::size_t row = 0;
  for (; row < rows.first && csv.skip(); ++row) {
  }
  std::vector<std::string> f;
  for (; row - rows.first < rows.count && csv.next(f); ++row)
    add_csv_particle(scene, i, csv, col, f, first_id + row, out);
  while (csv.skip()) ++row;
  return row;
}

std::size_t bed_source_index(const Scene& scene) {
  const auto is_bed = [](const ParticleSource& s) { return s.kind == SourceKind::Bed; };
  return std::find_if(scene.sources.begin(), scene.sources.end(), is_bed) - scene.sources.begin();
}

ParticleStore read_bed_source(const Scene& scene, std::size_t i, const BedReader& read_bed) {
  if (!read_bed) throw std::logic_error("read_bed_source: a bed source needs a bed reader");
  try {
    return read_bed(scene.sources[i].bed_file);
  } catch (const InputError& e) {
    throw InputError(scene.file, scene.sources[i].bed_line, source_key(i) + ".bed",
                     std::string("cannot read the bed: ") + e.what());
  }
}

void append_bed_particles(const Scene& scene, std::size_t i, const ParticleStore& bed,
                          ParticleStore& out) {
  for (std::size_t n = 0; n < bed.size(); ++n) {
    check_bed_particle(scene, i, bed, n);
    const Real4 p = bed.position_radius[n];
    const double density = scene.materials[bed.material[n]].density;
    out.add(bed.id[n], xyz(p), p.w, bed.material[n], xyz(bed.velocity_inv_mass[n]),
            1.0 / sphere_mass(density, p.w));
    out.angular_velocity.back() = bed.angular_velocity[n];
  }
}

ParticleId id_after(const ParticleStore& particles) {
  ParticleId next = 0;
  for (const ParticleId id : particles.id) next = std::max(next, id + 1);
  return next;
}

void create_particles(const Scene& scene, ParticleStore& store, const BedReader& read_bed) {
  check_box_sources(scene);
  const std::size_t bed_index = bed_source_index(scene);
  ParticleStore bed;
  if (bed_index < scene.sources.size()) bed = read_bed_source(scene, bed_index, read_bed);
  ParticleId next_id = std::max<ParticleId>(store.size(), id_after(bed));
  for (std::size_t i = 0; i < scene.sources.size(); ++i) {
    if (i == bed_index)
      append_bed_particles(scene, i, bed, store);
    else
      create_source(scene, i, store.position_radius, store, next_id);
  }
}

void check_box_source(const Scene& scene, std::size_t i) {
  check_material(scene, i);
  check_distribution(scene, i);
  check_source_size(scene, i);
}

void check_box_sources(const Scene& scene) {
  for (std::size_t i = 0; i < scene.sources.size(); ++i)
    if (scene.sources[i].kind == SourceKind::Box) check_box_source(scene, i);
}

}  // namespace gpudem
