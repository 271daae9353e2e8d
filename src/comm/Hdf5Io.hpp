#pragma once
/// HDF5 pieces shared by snapshots and checkpoints: scoped identifiers, checked calls, files
/// written collectively through the MPI-IO driver, global arrays written by rank slices (each
/// rank's rows at an MPI_Exscan offset) and scalar attributes.
#include <hdf5.h>
#include <mpi.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

namespace gpudem {

/// An HDF5 identifier, closed when it goes out of scope.
class H5Handle {
 public:
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  H5Handle(H5Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  H5Handle& operator=(H5Handle&&) = delete;
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

/// Checks HDF5 calls on one file: a failure becomes std::runtime_error
/// "<kind> '<file>': HDF5 call <call> failed".
class H5Calls {
 public:
  H5Calls(std::string kind, std::string file) : kind_(std::move(kind)), file_(std::move(file)) {}

  H5Handle handle(hid_t id, herr_t (*close)(hid_t), const std::string& call) const {
    if (id < 0) fail(call);
    return H5Handle(id, close);
  }
  void check(herr_t status, const std::string& call) const {
    if (status < 0) fail(call);
  }

 private:
  [[noreturn]] void fail(const std::string& call) const;
  std::string kind_;
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
  } else if constexpr (std::is_same_v<T, std::uint8_t>) {
    return H5T_NATIVE_UINT8;
  } else {
    static_assert(std::is_same_v<T, std::uint64_t>, "no HDF5 type for this value type");
    return H5T_NATIVE_UINT64;
  }
}

/// The little-endian file type in which values of type T are stored.
template <class T>
hid_t stored_type() {
  if constexpr (std::is_same_v<T, double>) {
    return H5T_IEEE_F64LE;
  } else if constexpr (std::is_same_v<T, float>) {
    return H5T_IEEE_F32LE;
  } else if constexpr (std::is_same_v<T, std::uint32_t>) {
    return H5T_STD_U32LE;
  } else if constexpr (std::is_same_v<T, std::uint8_t>) {
    return H5T_STD_U8LE;
  } else {
    static_assert(std::is_same_v<T, std::uint64_t>, "no HDF5 type for this value type");
    return H5T_STD_U64LE;
  }
}

/// This rank's part of a global array: rows [offset, offset + count) of `total`.
struct Slice {
  hsize_t offset = 0;
  hsize_t count = 0;
  hsize_t total = 0;
};

/// Row counts of all ranks: this rank's offset (MPI_Exscan) and the total (MPI_Allreduce).
/// Collective.
Slice global_slice(MPI_Comm comm, std::uint64_t count);

/// One dataset and where its values sit in host memory: per row, `components` values
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

/// A file created by all ranks of a communicator for collective writes, with the property
/// lists its datasets use.
class ParallelFile {
 public:
  /// Creates (truncates) `path`. Collective.
  ParallelFile(MPI_Comm comm, const H5Calls& h5, const std::string& path);

  /// Creates dataset `field` (1-D for one component, else rows × components) of slice.total
  /// rows, with any groups its name passes through ("a/b/name"), and writes this rank's rows
  /// collectively.
  void write_dataset(const FieldSource& field, const Slice& slice) const;

  template <class T>
  void write_attribute(const char* name, hid_t file_type, T value) const {
    const std::string what = std::string("(") + name + ")";
    H5Handle space = h5_.handle(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate" + what);
    H5Handle attribute =
        h5_.handle(H5Acreate2(file_.id(), name, file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, "H5Acreate2" + what);
    h5_.check(H5Awrite(attribute.id(), native_type<T>(), &value), "H5Awrite" + what);
  }

  /// Flushes and closes the file; throws when that fails. Collective.
  void close();

 private:
  const H5Calls& h5_;
  H5Handle access_;
  H5Handle links_;
  H5Handle creation_;
  H5Handle transfer_;
  H5Handle file_;
};

}  // namespace gpudem
