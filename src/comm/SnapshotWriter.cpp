#include "comm/SnapshotWriter.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

#include "comm/XdmfDocument.hpp"

namespace gpudem {
namespace {

static_assert(sizeof(Real4) == 4 * sizeof(Real) && sizeof(Vec3) == 3 * sizeof(Real),
              "snapshot memory selections assume Real4 and Vec3 hold their values unpadded");

/// An HDF5 identifier, closed when it goes out of scope.
class H5Handle {
 public:
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  ~H5Handle() { close(); }

  hid_t id() const { return id_; }
  /// Closes now (for calls whose failure matters, such as the final flush of a file).
  herr_t close() {
    const herr_t status = id_ >= 0 ? close_(id_) : 0;
    id_ = -1;
    return status;
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// Checks HDF5 calls on one file: a failure becomes std::runtime_error naming file and call.
class H5Calls {
 public:
  explicit H5Calls(std::string file) : file_(std::move(file)) {}

  H5Handle handle(hid_t id, herr_t (*close)(hid_t), const std::string& call) const {
    if (id < 0) fail(call);
    return H5Handle(id, close);
  }
  void check(herr_t status, const std::string& call) const {
    if (status < 0) fail(call);
  }

 private:
  [[noreturn]] void fail(const std::string& call) const {
    throw std::runtime_error("snapshot '" + file_ + "': HDF5 call " + call + " failed");
  }
  std::string file_;
};

template <class T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, double>) {
    return H5T_NATIVE_DOUBLE;
  } else if constexpr (std::is_same_v<T, float>) {
    return H5T_NATIVE_FLOAT;
  } else if constexpr (std::is_same_v<T, std::uint32_t>) {
    return H5T_NATIVE_UINT32;
  } else {
    static_assert(std::is_same_v<T, std::uint64_t>, "no HDF5 type for this value type");
    return H5T_NATIVE_UINT64;
  }
}

/// This rank's part of a snapshot: particles [offset, offset + count) of `total`.
struct Slice {
  hsize_t offset = 0;
  hsize_t count = 0;
  hsize_t total = 0;
};

/// One dataset and where its values sit in host memory: per particle, `components` values
/// starting at value `first` of a record `stride` values long.
struct FieldSource {
  const char* name;
  const void* data;
  hid_t memory_type;
  hid_t file_type;
  hsize_t components;
  hsize_t stride;
  hsize_t first;
};

std::vector<FieldSource> field_sources(const ParticleStore& p) {
  const hid_t real = native_type<Real>();
  const hid_t f64 = H5T_IEEE_F64LE;
  return {{"position", p.position_radius.data(), real, f64, 3, 4, 0},
          {"radius", p.position_radius.data(), real, f64, 1, 4, 3},
          {"velocity", p.velocity_inv_mass.data(), real, f64, 3, 4, 0},
          {"angular_velocity", p.angular_velocity.data(), real, f64, 3, 3, 0},
          {"force", p.force.data(), real, f64, 3, 3, 0},
          {"material", p.material.data(), native_type<MaterialId>(), H5T_STD_U32LE, 1, 1, 0},
          {"id", p.id.data(), native_type<ParticleId>(), H5T_STD_U64LE, 1, 1, 0}};
}

void check_store_lengths(const ParticleStore& p) {
  const std::size_t n = p.size();
  if (p.position_radius.size() < n || p.velocity_inv_mass.size() < n ||
      p.angular_velocity.size() < n || p.force.size() < n || p.material.size() < n)
    throw std::logic_error("particle store arrays are shorter than its id array");
}

/// Particle counts of all ranks: this rank's offset (MPI_Exscan) and the total (MPI_Allreduce).
Slice global_slice(MPI_Comm comm, std::uint64_t count) {
  std::uint64_t offset = 0, total = 0;
  MPI_Exscan(&count, &offset, 1, MPI_UINT64_T, MPI_SUM, comm);
  MPI_Allreduce(&count, &total, 1, MPI_UINT64_T, MPI_SUM, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) offset = 0;  // MPI_Exscan leaves rank 0's result undefined
  return {offset, count, total};
}

/// Selects this rank's rows in the file and the matching values in memory; nothing at all on
/// a rank without particles, which still takes part in the collective write.
void select_slice(const H5Calls& h5, hid_t file_space, hid_t memory_space, const FieldSource& field,
                  const Slice& slice, const std::string& what) {
  if (slice.count == 0) {
    h5.check(H5Sselect_none(file_space), "H5Sselect_none" + what);
    h5.check(H5Sselect_none(memory_space), "H5Sselect_none" + what);
    return;
  }
  const hsize_t count[2] = {slice.count, field.components};
  const hsize_t file_start[2] = {slice.offset, 0};
  const hsize_t memory_start[2] = {0, field.first};
  h5.check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, file_start, nullptr, count, nullptr),
           "H5Sselect_hyperslab" + what);
  h5.check(H5Sselect_hyperslab(memory_space, H5S_SELECT_SET, memory_start, nullptr, count, nullptr),
           "H5Sselect_hyperslab" + what);
}

/// Creates one dataset and writes this rank's slice of it collectively.
void write_dataset(const H5Calls& h5, hid_t file, hid_t creation, hid_t transfer,
                   const FieldSource& field, const Slice& slice) {
  const std::string what = std::string("(") + field.name + ")";
  const hsize_t file_dims[2] = {slice.total, field.components};
  H5Handle file_space =
      h5.handle(H5Screate_simple(field.components > 1 ? 2 : 1, file_dims, nullptr), H5Sclose,
                "H5Screate_simple" + what);
  H5Handle dataset = h5.handle(H5Dcreate2(file, field.name, field.file_type, file_space.id(),
                                          H5P_DEFAULT, creation, H5P_DEFAULT),
                               H5Dclose, "H5Dcreate2" + what);
  // An empty dataset has no storage address, and HDF5 1.10 fails a collective write to it
  // even with nothing selected; every rank knows the total, so all skip together.
  if (slice.total == 0) return;
  const hsize_t memory_dims[2] = {std::max<hsize_t>(slice.count, 1), field.stride};
  H5Handle memory_space =
      h5.handle(H5Screate_simple(2, memory_dims, nullptr), H5Sclose, "H5Screate_simple" + what);
  select_slice(h5, file_space.id(), memory_space.id(), field, slice, what);
  static const std::uint64_t no_values = 0;
  const void* data = slice.count > 0 ? field.data : &no_values;
  h5.check(
      H5Dwrite(dataset.id(), field.memory_type, memory_space.id(), file_space.id(), transfer, data),
      "H5Dwrite" + what);
}

/// The Polyvertex connectivity: one vertex cell per particle, holding its global row index,
/// so every XDMF reader makes a cell per particle. 32-bit indices while they fit.
void write_connectivity(const H5Calls& h5, hid_t file, hid_t creation, hid_t transfer,
                        const Slice& slice) {
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
      wide ? FieldSource{"connectivity", wide_index.data(), H5T_NATIVE_UINT64, H5T_STD_U64LE, 1, 1, 0}
           : FieldSource{"connectivity", narrow_index.data(), H5T_NATIVE_UINT32, H5T_STD_U32LE, 1,
                         1, 0};
  write_dataset(h5, file, creation, transfer, field, slice);
}

template <class T>
void write_attribute(const H5Calls& h5, hid_t file, const char* name, hid_t file_type, T value) {
  const std::string what = std::string("(") + name + ")";
  H5Handle space = h5.handle(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate" + what);
  H5Handle attribute =
      h5.handle(H5Acreate2(file, name, file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                "H5Acreate2" + what);
  h5.check(H5Awrite(attribute.id(), native_type<T>(), &value), "H5Awrite" + what);
}

/// One snapshot file written by all ranks of `comm` through the MPI-IO driver.
struct SnapshotFile {
  MPI_Comm comm;
  std::string path;
  double time;
  std::uint64_t step;
};

void write_snapshot_file(const SnapshotFile& target, const ParticleStore& particles,
                         const Slice& slice) {
  const H5Calls h5(target.path);
  H5Handle access = h5.handle(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate(access)");
  h5.check(H5Pset_fapl_mpio(access.id(), target.comm, MPI_INFO_NULL), "H5Pset_fapl_mpio");
  h5.check(H5Pset_all_coll_metadata_ops(access.id(), true), "H5Pset_all_coll_metadata_ops");
  h5.check(H5Pset_coll_metadata_write(access.id(), true), "H5Pset_coll_metadata_write");
  H5Handle creation = h5.handle(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate(create)");
  h5.check(H5Pset_fill_time(creation.id(), H5D_FILL_TIME_NEVER), "H5Pset_fill_time");
  H5Handle transfer = h5.handle(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate(transfer)");
  h5.check(H5Pset_dxpl_mpio(transfer.id(), H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio");

  H5Handle file = h5.handle(H5Fcreate(target.path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.id()),
                            H5Fclose, "H5Fcreate");
  for (const FieldSource& field : field_sources(particles))
    write_dataset(h5, file.id(), creation.id(), transfer.id(), field, slice);
  write_connectivity(h5, file.id(), creation.id(), transfer.id(), slice);
  write_attribute(h5, file.id(), "time", H5T_IEEE_F64LE, target.time);
  write_attribute(h5, file.id(), "step", H5T_STD_U64LE, target.step);
  h5.check(file.close(), "H5Fclose");
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

SnapshotWriter::SnapshotWriter(MPI_Comm comm, std::string dir, std::string basename)
    : comm_(comm),
      dir_(std::move(dir)),
      basename_(std::move(basename)),
      xmf_path_((std::filesystem::path(dir_) / (basename_ + ".xmf")).string()) {}

void SnapshotWriter::write(const ParticleStore& particles, double time, std::uint64_t step) {
  check_store_lengths(particles);
  const Slice slice = global_slice(comm_, particles.size());
  const std::string name = snapshot_file_name(basename_, files_.size());
  const std::string path = (std::filesystem::path(dir_) / name).string();
  write_snapshot_file({comm_, path, time, step}, particles, slice);
  files_.push_back(path);
  times_.push_back(time);
  counts_.push_back(slice.total);
  publish_xmf();
}

void SnapshotWriter::publish_xmf() const {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  std::string error;
  if (rank == 0) {
    std::vector<XdmfSnapshot> snapshots;
    for (std::size_t k = 0; k < files_.size(); ++k)
      snapshots.push_back(
          {std::filesystem::path(files_[k]).filename().string(), times_[k], counts_[k]});
    error = replace_file(xmf_path_, particle_xdmf(basename_, snapshots));
  }
  int failed = error.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm_);
  if (failed)
    throw std::runtime_error(rank == 0 ? error : "rank 0 could not write '" + xmf_path_ + "'");
}

}  // namespace gpudem
