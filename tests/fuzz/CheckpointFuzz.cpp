/// Fuzz target: the checkpoint and bed reader (read_checkpoint, whole and a rank's part, then
/// fit_checkpoint_to_scene, and a bed source through read_bed_source and append_bed_particles).
///
/// The input does not go to HDF5's own parser (whose robustness is HDF5's concern) but
/// describes a file of the checkpoint layout (comm/Checkpoint.hpp) that this target writes
/// with the HDF5 library: for each dataset and attribute whether it is there, its type, its
/// rows and columns, and its values (small numbers, negatives, NaN, infinities, raw bits).
/// The reader's own checks are what this explores.
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "FuzzSupport.hpp"
#include "comm/Checkpoint.hpp"
#include "core/ParticleSources.hpp"
#include "core/SceneLoader.hpp"

namespace {

using namespace gpudem;

/// The input, consumed a byte or a value at a time; zeros once it is used up.
class ByteSource {
 public:
  ByteSource(const std::uint8_t* data, std::size_t size) : data_(data), left_(size) {}

  std::uint8_t byte() { return left_ ? (--left_, *data_++) : 0; }

  template <class T>
  T raw() {
    T value{};
    const std::size_t n = std::min(sizeof(T), left_);
    std::memcpy(&value, data_, n);
    data_ += n;
    left_ -= n;
    return value;
  }

 private:
  const std::uint8_t* data_;
  std::size_t left_;
};

enum class Kind { F64, U64, U32, U8, Text };

/// A real: mostly small multiples of 0.01 of either sign, sometimes NaN, ±inf or raw bits.
double real_value(ByteSource& in) {
  const std::uint8_t b = in.byte();
  switch (b % 8) {
    case 5:
      return std::numeric_limits<double>::quiet_NaN();
    case 6:
      return (b & 8 ? -1 : 1) * std::numeric_limits<double>::infinity();
    case 7:
      return in.raw<double>();
    case 4:
      return -0.01 * (b / 8);
    default:
      return 0.01 * (b / 8);
  }
}

/// An unsigned integer: mostly small, sometimes raw bits.
template <class T>
T integer_value(ByteSource& in) {
  const std::uint8_t b = in.byte();
  return b == 255 ? in.raw<T>() : static_cast<T>(b % 16);
}

constexpr std::size_t kTextWidth = 12;

/// A fixed-length name: a material of the scene, a snapshot file, empty, or raw characters.
std::string text_value(ByteSource& in) {
  static const char* const kNames[] = {"soil", "steel", "snap_0000.h5", "", "clay"};
  const std::uint8_t b = in.byte();
  if (b % 8 < 5) return kNames[b % 8];
  std::string text(kTextWidth, '\0');
  for (char& c : text) c = static_cast<char>(in.byte());
  return text;
}

hid_t file_type(Kind kind) {
  switch (kind) {
    case Kind::F64:
      return H5T_IEEE_F64LE;
    case Kind::U64:
      return H5T_STD_U64LE;
    case Kind::U32:
      return H5T_STD_U32LE;
    case Kind::U8:
      return H5T_STD_U8LE;
    case Kind::Text:
      break;
  }
  const hid_t text = H5Tcopy(H5T_C_S1);
  H5Tset_size(text, kTextWidth);
  return text;
}

/// `count` values of `kind` as bytes in the file type's layout (native = little-endian here).
std::vector<char> values(ByteSource& in, Kind kind, std::size_t count) {
  std::vector<char> bytes;
  const auto append = [&bytes](const void* p, std::size_t n) {
    bytes.insert(bytes.end(), static_cast<const char*>(p), static_cast<const char*>(p) + n);
  };
  for (std::size_t k = 0; k < count; ++k) {
    if (kind == Kind::F64) {
      const double v = real_value(in);
      append(&v, 8);
    } else if (kind == Kind::U64) {
      const auto v = integer_value<std::uint64_t>(in);
      append(&v, 8);
    } else if (kind == Kind::U32) {
      const auto v = integer_value<std::uint32_t>(in);
      append(&v, 4);
    } else if (kind == Kind::U8) {
      const std::uint8_t v = in.byte();
      append(&v, 1);
    } else {
      std::string v = text_value(in);
      v.resize(kTextWidth, '\0');
      append(v.data(), kTextWidth);
    }
  }
  return bytes;
}

/// Another kind than `kind`: a mistyped dataset or attribute.
Kind other_kind(Kind kind) { return kind == Kind::F64 ? Kind::U64 : Kind::F64; }

/// Writes dataset or attribute values of `kind`, `rows` × `columns` (1-D when columns is 1).
void write_values(hid_t file, const char* name, bool attribute, Kind kind, hsize_t rows,
                  hsize_t columns, ByteSource& in) {
  const hsize_t dims[2] = {rows, columns};
  const hid_t space =
      attribute ? H5Screate(H5S_SCALAR) : H5Screate_simple(columns == 1 ? 1 : 2, dims, nullptr);
  const hid_t type = file_type(kind);
  const std::vector<char> bytes = values(in, kind, attribute ? 1 : rows * columns);
  if (attribute) {
    const hid_t a = H5Acreate2(file, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, type, bytes.data());
    H5Aclose(a);
  } else {
    const hid_t d = H5Dcreate2(file, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (!bytes.empty()) H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data());
    H5Dclose(d);
  }
  if (kind == Kind::Text) H5Tclose(type);
  H5Sclose(space);
}

struct DatasetSpec {
  const char* name;
  Kind kind;
  int columns;  ///< 0: the history width
  int group;    ///< datasets of one group share their row count
};

constexpr DatasetSpec kDatasets[] = {
    {"position_radius", Kind::F64, 4, 0},
    {"velocity_inv_mass", Kind::F64, 4, 0},
    {"angular_velocity", Kind::F64, 3, 0},
    {"force", Kind::F64, 3, 0},
    {"torque", Kind::F64, 3, 0},
    {"id", Kind::U64, 1, 0},
    {"material", Kind::U32, 1, 0},
    {"list_position_radius", Kind::F64, 4, 0},
    {"pair_owner", Kind::U64, 1, 1},
    {"pair_partner", Kind::U64, 1, 1},
    {"pair_history", Kind::F64, 0, 1},
    {"wall_owner", Kind::U64, 1, 2},
    {"wall_index", Kind::U32, 1, 2},
    {"wall_history", Kind::F64, 0, 2},
    {"mesh_owner", Kind::U64, 1, 3},
    {"mesh_triangle", Kind::U32, 1, 3},
    {"mesh_history", Kind::F64, 0, 3},
    {"snapshot_file", Kind::Text, 1, 4},
    {"snapshot_time", Kind::F64, 1, 4},
    {"snapshot_count", Kind::U64, 1, 4},
    {"snapshot_rank_field", Kind::U8, 1, 4},
    {"snapshot_fields", Kind::U32, 1, 4},
    {"snapshot_precision", Kind::U8, 1, 4},
    {"material_names", Kind::Text, 1, 5},
    {"wall_motion", Kind::F64, 3, 6},
};
constexpr int kGroups = 7;

struct AttributeSpec {
  const char* name;
  Kind kind;
};

constexpr AttributeSpec kAttributes[] = {
    {"time", Kind::F64},
    {"dt", Kind::F64},
    {"dt_fraction", Kind::F64},
    {"skin", Kind::F64},
    {"step", Kind::U64},
    {"removed", Kind::U64},
    {"list_build_step", Kind::U64},
    {"list_build_substep", Kind::U32},
    {"list_build_substeps", Kind::U32},
    {"substeps", Kind::U32},
    {"dt_adaptive", Kind::U8},
};

void write_u32_attribute(hid_t file, const char* name, std::uint32_t value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(file, name, H5T_STD_U32LE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_UINT32, &value);
  H5Aclose(a);
  H5Sclose(space);
}

/// Writes the checkpoint the input describes to `path`.
void write_described_file(const std::string& path, ByteSource& in) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const std::uint8_t version = in.byte();
  const std::uint32_t format = version % 16 == 15 ? version : kCheckpointFormatVersion;
  const std::uint32_t width = in.byte() % 4;
  write_u32_attribute(file, "format_version", format);
  write_u32_attribute(file, "history_width", width);
  for (const AttributeSpec& a : kAttributes) {
    const std::uint8_t shape = in.byte();
    if (shape % 16 == 15) continue;
    write_values(file, a.name, true, shape % 16 == 14 ? other_kind(a.kind) : a.kind, 1, 1, in);
  }
  hsize_t rows[kGroups];
  for (hsize_t& r : rows) r = in.byte() % 4;
  for (const DatasetSpec& d : kDatasets) {
    const std::uint8_t shape = in.byte();
    if (shape % 16 == 15 || (d.columns == 0 && width == 0 && shape % 16 != 11)) continue;
    const Kind kind = shape % 16 == 14 ? other_kind(d.kind) : d.kind;
    const hsize_t columns =
        (d.columns == 0 ? std::max<hsize_t>(width, 1) : d.columns) + (shape % 16 == 13 ? 1 : 0);
    write_values(file, d.name, false, kind, rows[d.group] + (shape % 16 == 12 ? 1 : 0), columns,
                 in);
  }
  H5Fclose(file);
}

/// The contact law and the source, after two_material_scene().
const char* const kBedSceneTail = R"([contact]
normal = "hertz"
tangential = "mindlin"
[[wall]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "steel"
[[insert]]
bed = "checkpoint.h5"
)";

/// The scene whose bed source reads the scratch file checkpoint.h5.
const Scene& bed_scene() {
  static const Scene scene = load_scene(
      fuzz::write_scratch_file("bed_scene.toml", fuzz::two_material_scene() + kBedSceneTail));
  return scene;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Scene& scene = bed_scene();
  const std::string path = fuzz::write_scratch_file("checkpoint.h5", "");
  ByteSource in(data, size);
  write_described_file(path, in);
  for (const FilePart part : {FilePart{}, FilePart{1, 2}}) {
    fuzz::reject_only_with_input_error([&] {
      Checkpoint checkpoint = read_checkpoint(path, part);
      fit_checkpoint_to_scene(checkpoint, path, scene);
    });
    fuzz::reject_only_with_input_error([&] {
      const BedReader read_bed = [&](const std::string& bed_file) {
        Checkpoint bed = read_checkpoint(bed_file, part);
        map_materials_by_name(bed, bed_file, scene);
        return std::move(bed.particles);
      };
      ParticleStore particles;
      append_bed_particles(scene, 0, read_bed_source(scene, 0, read_bed), particles);
    });
  }
  return 0;
}
