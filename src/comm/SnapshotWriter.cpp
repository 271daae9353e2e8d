#include "comm/SnapshotWriter.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

#include "comm/Hdf5Io.hpp"
#include "comm/XdmfDocument.hpp"

namespace gpudem {
namespace {

static_assert(sizeof(Real4) == 4 * sizeof(Real) && sizeof(Vec3) == 3 * sizeof(Real),
              "snapshot memory selections assume Real4 and Vec3 hold their values unpadded");

/// The index of dataset `name` in kSnapshotFields; kSnapshotFields.size() for "position".
std::size_t snapshot_field_index(const char* name) {
  for (std::size_t k = 0; k < kSnapshotFields.size(); ++k)
    if (std::strcmp(kSnapshotFields[k], name) == 0) return k;
  if (std::strcmp(name, "position") == 0) return kSnapshotFields.size();
  throw std::logic_error(std::string("snapshot column '") + name + "' is not a snapshot field");
}

/// The datasets of a snapshot of `p` laid out as `layout`: "position", then the fields of
/// kSnapshotFields in its set, each taken from its field's columns in the particle field
/// table. Real values are stored as float64, or float32 in single precision (HDF5 rounds them
/// as it writes).
std::vector<FieldSource> field_sources(const ParticleStore& p, const SnapshotLayout& layout) {
  std::vector<FieldSource> by_index(kSnapshotFields.size() + 1);
  std::vector<bool> found(by_index.size(), false);
  for_each_particle_field([&](auto field) {
    using Parts = ValueComponents<FieldValue<decltype(field), Real, Real>>;
    using Scalar = typename Parts::Scalar;
    const hid_t stored = !std::is_floating_point_v<Scalar> ? stored_type<Scalar>()
                         : layout.single_precision         ? H5T_IEEE_F32LE
                                                           : H5T_IEEE_F64LE;
    for (const SnapshotColumn& c : field.snapshot) {
      const std::size_t k = snapshot_field_index(c.name);
      by_index[k] = {c.name,
                     field.of(p).data(),
                     native_type<Scalar>(),
                     stored,
                     static_cast<hsize_t>(c.count),
                     Parts::count,
                     static_cast<hsize_t>(c.first)};
      found[k] = true;
    }
  });
  if (std::find(found.begin(), found.end(), false) != found.end())
    throw std::logic_error("a snapshot field has no column in the particle field table");
  std::vector<FieldSource> sources{by_index.back()};
  for (std::size_t k = 0; k < kSnapshotFields.size(); ++k)
    if ((layout.fields >> k) & 1u) sources.push_back(by_index[k]);
  return sources;
}

void check_store_lengths(const ParticleStore& p) {
  bool long_enough = true;
  for_each_particle_field([&](auto field) {
    if (!field.snapshot.empty()) long_enough = long_enough && field.of(p).size() >= p.size();
  });
  if (!long_enough) throw std::logic_error("particle store arrays are shorter than its id array");
}

/// The Polyvertex connectivity: one vertex cell per particle, holding its global row index,
/// so every XDMF reader makes a cell per particle. 32-bit indices while they fit.
void write_connectivity(const ParallelFile& file, const Slice& slice) {
  const bool wide = slice.total > std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint64_t> wide_index(wide ? slice.count : 0);
  std::vector<std::uint32_t> narrow_index(wide ? 0 : slice.count);
  for (hsize_t k = 0; k < slice.count; ++k) {
    if (wide)
      wide_index[k] = slice.offset + k;
    else
      narrow_index[k] = static_cast<std::uint32_t>(slice.offset + k);
  }
  const FieldSource field =
      wide ? FieldSource{"connectivity",
                         wide_index.data(),
                         H5T_NATIVE_UINT64,
                         H5T_STD_U64LE,
                         1,
                         1,
                         0}
           : FieldSource{
                 "connectivity", narrow_index.data(), H5T_NATIVE_UINT32, H5T_STD_U32LE, 1, 1, 0};
  file.write_dataset(field, slice);
}

/// The owning rank of every row of this rank's slice: its rank in `comm`.
void write_rank_field(MPI_Comm comm, const ParallelFile& file, const Slice& slice) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<std::uint32_t> ranks(slice.count, static_cast<std::uint32_t>(rank));
  file.write_dataset({"rank", ranks.data(), H5T_NATIVE_UINT32, H5T_STD_U32LE, 1, 1, 0}, slice);
}

/// Throws std::invalid_argument unless every mesh name is allowed (mesh_output_name_problem)
/// and used once.
void check_mesh_names(const SnapshotOptions& options) {
  std::set<std::string> seen;
  for (const XdmfMesh& mesh : options.meshes) {
    const char* problem = mesh_output_name_problem(mesh.name, options.basename);
    if (!problem && options.bonds && mesh.name == "bonds") problem = "is the bonds' name";
    if (!problem && !seen.insert(mesh.name).second) problem = "is used twice";
    if (problem) throw std::invalid_argument("snapshot mesh name '" + mesh.name + "' " + problem);
  }
}

/// Throws std::invalid_argument unless `surfaces` are the meshes of `meshes`: as many, each
/// with the vertex and triangle counts listed and vertex ids within its vertices.
void check_mesh_surfaces(const std::vector<XdmfMesh>& meshes,
                         const std::vector<MeshSurface>& surfaces) {
  if (surfaces.size() != meshes.size())
    throw std::invalid_argument("snapshot: " + std::to_string(surfaces.size()) +
                                " mesh surfaces for " + std::to_string(meshes.size()) + " meshes");
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const MeshSurface& s = surfaces[m];
    bool fits = s.vertices.size() == meshes[m].vertex_count &&
                s.triangles.size() == meshes[m].triangle_count &&
                s.triangle_force.size() == meshes[m].triangle_count;
    for (const auto& triangle : s.triangles)
      for (const std::uint32_t v : triangle) fits = fits && v < s.vertices.size();
    if (!fits)
      throw std::invalid_argument(
          "snapshot: the surface of mesh '" + meshes[m].name +
          "' does not have the vertex and triangle counts it was listed with or has a vertex "
          "id beyond its vertices");
  }
}

/// Group `/mesh/<name>/` of a snapshot: rank 0 writes every row of `mesh`, the other ranks
/// take part with none.
void write_mesh(MPI_Comm comm, const ParallelFile& file, const std::string& name,
                const MeshSurface& mesh) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const auto rows = [rank](std::size_t n) { return Slice{0, rank == 0 ? n : 0, n}; };
  const std::string group = "mesh/" + name + "/";
  const std::string vertices = group + "vertices", triangles = group + "triangles",
                    force = group + "force", pressure = group + "pressure";
  const hid_t real = native_type<Real>();
  const hid_t f64 = H5T_IEEE_F64LE;
  const std::size_t v = mesh.vertices.size(), t = mesh.triangles.size();
  file.write_dataset({vertices.c_str(), mesh.vertices.data(), real, f64, 3, 3, 0}, rows(v));
  file.write_dataset(
      {triangles.c_str(), mesh.triangles.data(), H5T_NATIVE_UINT32, H5T_STD_U32LE, 3, 3, 0},
      rows(t));
  file.write_dataset({force.c_str(), mesh.triangle_force.data(), real, f64, 3, 3, 0}, rows(t));
  const std::vector<double> values = triangle_pressures(mesh);
  file.write_dataset({pressure.c_str(), values.data(), H5T_NATIVE_DOUBLE, f64, 1, 1, 0}, rows(t));
}

/// Group `/bonds/` of a snapshot: each rank's bonds at its offset among all ranks' (the two
/// points of bond k at rows 2k and 2k + 1). Returns the bonds of all ranks.
std::uint64_t write_bonds(MPI_Comm comm, const ParallelFile& file, const BondLines& bonds) {
  const Slice slice = global_slice(comm, bonds.size());
  const Slice ends{2 * slice.offset, 2 * slice.count, 2 * slice.total};
  std::vector<std::uint64_t> connectivity(2 * bonds.size());
  for (std::size_t k = 0; k < connectivity.size(); ++k) connectivity[k] = 2 * slice.offset + k;
  const hid_t real = native_type<Real>(), f64 = H5T_IEEE_F64LE;
  file.write_dataset({"bonds/ids", bonds.ids.data(), H5T_NATIVE_UINT64, H5T_STD_U64LE, 2, 2, 0},
                     slice);
  file.write_dataset(
      {"bonds/connectivity", connectivity.data(), H5T_NATIVE_UINT64, H5T_STD_U64LE, 2, 2, 0},
      slice);
  file.write_dataset({"bonds/points", bonds.points.data(), real, f64, 3, 3, 0}, ends);
  file.write_dataset(
      {"bonds/normal_force", bonds.normal_force.data(), H5T_NATIVE_DOUBLE, f64, 1, 1, 0}, slice);
  file.write_dataset(
      {"bonds/strength_used", bonds.strength_used.data(), H5T_NATIVE_DOUBLE, f64, 1, 1, 0}, slice);
  return slice.total;
}

/// One snapshot file written by all ranks of `comm` through the MPI-IO driver.
struct SnapshotFile {
  MPI_Comm comm;
  std::string path;
  double time;
  std::uint64_t step;
  const SnapshotOptions& options;
};

std::uint64_t write_snapshot_file(const SnapshotFile& target, const ParticleStore& particles,
                                  const Slice& slice, const std::vector<MeshSurface>& surfaces,
                                  const BondLines& bonds) {
  const H5Calls h5("snapshot", target.path);
  ParallelFile file(target.comm, h5, target.path);
  const SnapshotOptions& options = target.options;
  for (const FieldSource& field : field_sources(particles, options.layout))
    file.write_dataset(field, slice);
  if (options.layout.rank_field) write_rank_field(target.comm, file, slice);
  write_connectivity(file, slice);
  for (std::size_t m = 0; m < options.meshes.size(); ++m)
    write_mesh(target.comm, file, options.meshes[m].name, surfaces[m]);
  const std::uint64_t bond_count = options.bonds ? write_bonds(target.comm, file, bonds) : 0;
  file.write_attribute("time", H5T_IEEE_F64LE, target.time);
  file.write_attribute("step", H5T_STD_U64LE, target.step);
  file.close();
  return bond_count;
}

/// Replaces `path` by `text` through a temporary file and a rename, so a reader never sees a
/// partial document. Returns what went wrong, or an empty string.
std::string replace_file(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) return "cannot write '" + temporary + "'";
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) return "cannot rename '" + temporary + "' to '" + path + "': " + ec.message();
  return {};
}

std::string snapshot_file_name(const std::string& basename, std::size_t index) {
  char digits[24];
  std::snprintf(digits, sizeof(digits), "_%06zu.h5", index);
  return basename + digits;
}

}  // namespace

SnapshotWriter::SnapshotWriter(MPI_Comm comm, std::string dir, SnapshotOptions options)
    : comm_(comm),
      dir_(std::move(dir)),
      options_(std::move(options)),
      xmf_path_((std::filesystem::path(dir_) / (options_.basename + ".xmf")).string()) {
  check_mesh_names(options_);
}

void SnapshotWriter::write(const ParticleStore& particles, double time, std::uint64_t step) {
  write(particles, {}, time, step);
}

void SnapshotWriter::write(const ParticleStore& particles, const std::vector<MeshSurface>& meshes,
                           double time, std::uint64_t step) {
  write(particles, meshes, BondLines{}, time, step);
}

void SnapshotWriter::write(const ParticleStore& particles, const std::vector<MeshSurface>& meshes,
                           const BondLines& bonds, double time, std::uint64_t step) {
  check_store_lengths(particles);
  check_mesh_surfaces(options_.meshes, meshes);
  const Slice slice = global_slice(comm_, particles.size());
  const std::string name = snapshot_file_name(options_.basename, files_.size());
  const std::string path = (std::filesystem::path(dir_) / name).string();
  const std::uint64_t bond_count =
      write_snapshot_file({comm_, path, time, step, options_}, particles, slice, meshes, bonds);
  files_.push_back(path);
  written_.push_back({name, time, slice.total, options_.layout, bond_count});
  publish_xmf();
}

std::vector<XdmfSnapshot> SnapshotWriter::table() const { return written_; }

void SnapshotWriter::resume(const std::vector<XdmfSnapshot>& table) {
  files_.clear();
  for (const XdmfSnapshot& snapshot : table)
    files_.push_back((std::filesystem::path(dir_) / snapshot.h5_file).string());
  written_ = table;
  publish_xmf();
}

void SnapshotWriter::publish_xmf() const {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  std::string error;
  if (rank == 0) {
    const std::vector<XdmfSnapshot> snapshots = table();
    error = replace_file(xmf_path_, particle_xdmf(options_.basename, snapshots));
    for (const XdmfMesh& mesh : options_.meshes)
      if (error.empty()) error = replace_file(mesh_xmf_path(mesh), mesh_xdmf(mesh, snapshots));
    if (error.empty() && options_.bonds)
      error =
          replace_file((std::filesystem::path(dir_) / "bonds.xmf").string(), bond_xdmf(snapshots));
  }
  int failed = error.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm_);
  if (failed)
    throw std::runtime_error(
        rank == 0 ? error : "rank 0 could not write the .xmf documents in '" + dir_ + "'");
}

std::string SnapshotWriter::mesh_xmf_path(const XdmfMesh& mesh) const {
  return (std::filesystem::path(dir_) / (mesh.name + ".xmf")).string();
}

}  // namespace gpudem
