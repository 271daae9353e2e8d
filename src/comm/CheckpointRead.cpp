// Checkpoint reading: the rows of a rank's part, validated.
#include "comm/Checkpoint.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "comm/Hdf5Io.hpp"
#include "core/InputError.hpp"
#include "core/contact/ParallelBond.hpp"

namespace gpudem {
namespace {

static_assert(sizeof(Real4) == 4 * sizeof(Real) && sizeof(Vec3) == 3 * sizeof(Real),
              "checkpoint rows assume Real4 and Vec3 hold their values unpadded");

/// Turns HDF5's own error printing off for its lifetime: read failures are reported as
/// InputError messages instead of library traces.
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &print_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, print_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  H5E_auto2_t print_ = nullptr;
  void* data_ = nullptr;
};

/// Datasets of one group and their row counts.
using LengthGroup = std::vector<std::pair<const char*, std::size_t>>;

/// Typed, checked reads of one checkpoint file; every problem is an InputError naming it.
class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)), file_(open()) {}

  [[noreturn]] void reject(const std::string& what) const { throw InputError(path_, 0, "", what); }

  /// A scalar attribute stored with type `file_type`.
  template <class T>
  T attribute(const char* name, hid_t file_type) const {
    if (H5Aexists(file_.id(), name) <= 0) reject(std::string("missing attribute '") + name + "'");
    H5Handle attribute(H5Aopen(file_.id(), name, H5P_DEFAULT), H5Aclose);
    H5Handle type(H5Aget_type(attribute.id()), H5Tclose);
    H5Handle space(H5Aget_space(attribute.id()), H5Sclose);
    if (H5Tequal(type.id(), file_type) <= 0 || H5Sget_simple_extent_npoints(space.id()) != 1)
      reject(std::string("attribute '") + name + "' is not a scalar of the expected type");
    T value{};
    if (H5Aread(attribute.id(), native_type<T>(), &value) < 0)
      reject(std::string("cannot read attribute '") + name + "'");
    return value;
  }

  /// Dataset `name` as rows of type Row, each sizeof(Row)/sizeof(Value) values stored with
  /// type `file_type` (1-D for one value per row, else rows × values): the rows of `part`.
  /// Adds the dataset's length (all its rows) to `lengths` when given.
  template <class Row, class Value>
  std::vector<Row> rows(const char* name, hid_t file_type, FilePart part = {},
                        LengthGroup* lengths = nullptr) const {
    static_assert(sizeof(Row) % sizeof(Value) == 0, "a row holds whole values");
    return read_part<Row>(name, file_type, native_type<Value>(), sizeof(Row) / sizeof(Value), part,
                          lengths);
  }

  /// Dataset `name` of f64 values, `width` per row (1-D for one), flattened row by row: the
  /// rows of `part`. Adds the dataset's length to `lengths`.
  std::vector<Real> columns(const char* name, hsize_t width, FilePart part,
                            LengthGroup& lengths) const {
    return read_part<Real>(name, H5T_IEEE_F64LE, native_type<Real>(), width, part, &lengths);
  }

  /// Whether the file holds a link `name`.
  bool has(const char* name) const { return H5Lexists(file_.id(), name, H5P_DEFAULT) > 0; }
  /// Whether the file's root holds an attribute `name`.
  bool has_attribute(const char* name) const { return H5Aexists(file_.id(), name) > 0; }

  /// A 1-D dataset of u8 values.
  std::vector<std::uint8_t> bytes(const char* name) const {
    const H5Handle dataset = open_typed(name, H5T_STD_U8LE);
    std::vector<std::uint8_t> out(row_count(dataset.id(), name, 1));
    read_rows(dataset.id(), name, H5T_NATIVE_UINT8, out.data(), {0, out.size()}, 1);
    return out;
  }

  /// A 1-D dataset of fixed-length strings.
  std::vector<std::string> strings(const char* name) const {
    H5Handle dataset = open_dataset(name);
    H5Handle type(H5Dget_type(dataset.id()), H5Tclose);
    if (H5Tget_class(type.id()) != H5T_STRING || H5Tis_variable_str(type.id()) != 0)
      reject(std::string("dataset '") + name + "' does not hold fixed-length strings");
    const std::size_t width = H5Tget_size(type.id());
    const hsize_t n = row_count(dataset.id(), name, 1);
    std::vector<char> text(n * width);
    if (n > 0 && H5Dread(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()) < 0)
      reject(std::string("cannot read dataset '") + name + "'");
    std::vector<std::string> out;
    for (hsize_t k = 0; k < n; ++k) {
      const char* first = text.data() + k * width;
      out.emplace_back(first, std::find(first, first + width, '\0'));
    }
    return out;
  }

 private:
  H5Handle open() const {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path_, ec)) reject("no such checkpoint file");
    H5Handle file(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (file.id() < 0) reject("not a readable HDF5 file");
    return file;
  }

  H5Handle open_dataset(const char* name) const {
    if (H5Lexists(file_.id(), name, H5P_DEFAULT) <= 0)
      reject(std::string("missing dataset '") + name + "'");
    H5Handle dataset(H5Dopen2(file_.id(), name, H5P_DEFAULT), H5Dclose);
    if (dataset.id() < 0) reject(std::string("'") + name + "' is not a dataset");
    return dataset;
  }

  /// Dataset `name`, whose values must be stored with type `file_type`.
  H5Handle open_typed(const char* name, hid_t file_type) const {
    H5Handle dataset = open_dataset(name);
    H5Handle type(H5Dget_type(dataset.id()), H5Tclose);
    if (H5Tequal(type.id(), file_type) <= 0)
      reject(std::string("dataset '") + name + "' has the wrong value type");
    return dataset;
  }

  /// The rows of `part` of dataset `name` (stored with `file_type`, `components` values per
  /// row), read as `memory_type` into values of type T, `components` per row.
  template <class T>
  std::vector<T> read_part(const char* name, hid_t file_type, hid_t memory_type, hsize_t components,
                           FilePart part, LengthGroup* lengths) const {
    const H5Handle dataset = open_typed(name, file_type);
    const hsize_t total = row_count(dataset.id(), name, components);
    if (lengths) lengths->emplace_back(name, total);
    const RowRange range = part.rows_of(total);
    std::vector<T> out(range.count * components * H5Tget_size(memory_type) / sizeof(T));
    read_rows(dataset.id(), name, memory_type, out.data(), range, components);
    return out;
  }

  /// Reads rows `range` of a dataset with `components` values per row (none when empty) as
  /// `memory_type` into `out`.
  void read_rows(hid_t dataset, const char* name, hid_t memory_type, void* out, RowRange range,
                 hsize_t components) const {
    if (range.count == 0) return;
    H5Handle file_space(H5Dget_space(dataset), H5Sclose);
    const int dims = components > 1 ? 2 : 1;
    const hsize_t start[2] = {range.first, 0}, count[2] = {range.count, components};
    H5Handle memory_space(H5Screate_simple(dims, count, nullptr), H5Sclose);
    if (H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
        H5Dread(dataset, memory_type, memory_space.id(), file_space.id(), H5P_DEFAULT, out) < 0)
      reject(std::string("cannot read dataset '") + name + "'");
  }

  /// Rows of a dataset that must be 1-D (components 1) or rows × components.
  hsize_t row_count(hid_t dataset, const char* name, hsize_t components) const {
    H5Handle space(H5Dget_space(dataset), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space.id());
    hsize_t dims[2] = {0, 0};
    if (rank != (components > 1 ? 2 : 1) ||
        H5Sget_simple_extent_dims(space.id(), dims, nullptr) < 0 ||
        (components > 1 && dims[1] != components))
      reject(
          std::string("dataset '") + name + "' must have " +
          (components > 1 ? std::to_string(components) + " columns" : std::string("one column")));
    return dims[0];
  }

  std::string path_;
  H5Handle file_;
};

/// Rejects datasets of one group whose lengths differ from the first one's.
void check_same_length(const Reader& reader, const LengthGroup& group) {
  for (const auto& [name, length] : group)
    if (length != group.front().second)
      reader.reject(std::string("dataset '") + name + "' has " + std::to_string(length) +
                    " rows but '" + group.front().first + "' has " +
                    std::to_string(group.front().second));
}

/// The particle rows of `part`; the datasets must all have the same length.
void read_particles(const Reader& r, FilePart part, Checkpoint& c) {
  ParticleStore& p = c.particles;
  LengthGroup lengths;
  const auto read_field = [&](auto field) {
    using Value = FieldValue<decltype(field), Real, Real>;
    using Scalar = typename ValueComponents<Value>::Scalar;
    field.of(p) = r.rows<Value, Scalar>(field.name, stored_type<Scalar>(), part, &lengths);
  };
  read_field(particle_field::Id{});  // first: the other datasets' lengths are measured by it
  for_each_particle_field<field_use::checkpoint>([&](auto field) {
    if constexpr (!std::is_same_v<decltype(field), particle_field::Id>) read_field(field);
  });
  c.list_position_radius =
      r.rows<Real4, Real>("list_position_radius", H5T_IEEE_F64LE, part, &lengths);
  check_same_length(r, lengths);
  const auto positive = [](Real v) { return std::isfinite(v) && v > 0; };
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!positive(p.position_radius[i].w) || !positive(p.velocity_inv_mass[i].w))
      r.reject("particle id " + std::to_string(p.id[i]) +
               " has a radius or inverse mass that is not finite and > 0");
}

/// The history values of one kind of record, `width` per record, flat, for the rows of
/// `part`; none (and no dataset) at width 0. Adds the dataset's length to `group`.
std::vector<Real> read_history_values(const Reader& r, const char* name, std::uint32_t width,
                                      FilePart part, LengthGroup& group) {
  if (width == 0) return {};
  return r.columns(name, width, part, group);
}

/// The records of `part` of each kind; the datasets of one kind must have the same length.
void read_history(const Reader& r, FilePart part, ContactHistory& h) {
  h.width = r.attribute<std::uint32_t>("history_width", H5T_STD_U32LE);
  LengthGroup pairs;
  h.pair_owner = r.rows<ParticleId, ParticleId>("pair_owner", H5T_STD_U64LE, part, &pairs);
  h.pair_partner = r.rows<ParticleId, ParticleId>("pair_partner", H5T_STD_U64LE, part, &pairs);
  h.pair_values = read_history_values(r, "pair_history", h.width, part, pairs);
  check_same_length(r, pairs);
  LengthGroup walls;
  h.wall_owner = r.rows<ParticleId, ParticleId>("wall_owner", H5T_STD_U64LE, part, &walls);
  h.wall_index = r.rows<std::uint32_t, std::uint32_t>("wall_index", H5T_STD_U32LE, part, &walls);
  h.wall_values = read_history_values(r, "wall_history", h.width, part, walls);
  check_same_length(r, walls);
  if (!r.has("mesh_owner")) return;  // written before mesh records existed: none
  LengthGroup meshes;
  h.mesh_owner = r.rows<ParticleId, ParticleId>("mesh_owner", H5T_STD_U64LE, part, &meshes);
  h.mesh_triangle =
      r.rows<std::uint32_t, std::uint32_t>("mesh_triangle", H5T_STD_U32LE, part, &meshes);
  h.mesh_values = read_history_values(r, "mesh_history", h.width, part, meshes);
  check_same_length(r, meshes);
}

/// The bond records of `part` (bond_values of 9 columns) and the count made; none in a file
/// without bonds.
void read_bonds(const Reader& r, FilePart part, Checkpoint& c) {
  if (!r.has("bond_owner")) return;
  ContactHistory& b = c.bonds;
  b.width = bond_value::width;
  LengthGroup bonds;
  b.pair_owner = r.rows<ParticleId, ParticleId>("bond_owner", H5T_STD_U64LE, part, &bonds);
  b.pair_partner = r.rows<ParticleId, ParticleId>("bond_partner", H5T_STD_U64LE, part, &bonds);
  b.pair_values = r.columns("bond_values", b.width, part, bonds);
  check_same_length(r, bonds);
  c.bonds_made = r.attribute<std::uint64_t>("bonds_made", H5T_STD_U64LE);
}

/// Whether each of the table's `snapshots` holds the rank field (0 or 1); none does when the
/// table has no snapshot_rank_field (written before it existed).
std::vector<std::uint8_t> read_rank_field_flags(const Reader& r, std::size_t snapshots) {
  if (!r.has("snapshot_rank_field")) return std::vector<std::uint8_t>(snapshots, 0);
  std::vector<std::uint8_t> flags = r.bytes("snapshot_rank_field");
  for (const std::uint8_t flag : flags)
    if (flag > 1)
      r.reject("dataset 'snapshot_rank_field' holds " + std::to_string(flag) + "; expected 0 or 1");
  return flags;
}

/// The field set of each of the table's `snapshots` (a subset of kAllSnapshotFields); every
/// field when the table has no snapshot_fields (written before it existed).
std::vector<std::uint32_t> read_field_sets(const Reader& r, std::size_t snapshots) {
  if (!r.has("snapshot_fields")) return std::vector<std::uint32_t>(snapshots, kAllSnapshotFields);
  std::vector<std::uint32_t> sets =
      r.rows<std::uint32_t, std::uint32_t>("snapshot_fields", H5T_STD_U32LE);
  for (const std::uint32_t set : sets)
    if ((set & ~kAllSnapshotFields) != 0)
      r.reject("dataset 'snapshot_fields' holds " + std::to_string(set) + "; expected a set of " +
               std::to_string(kSnapshotFields.size()) + " fields, below " +
               std::to_string(kAllSnapshotFields + 1));
  return sets;
}

/// The bytes per real value of each of the table's `snapshots` (8 or 4); 8 when the table has
/// no snapshot_precision (written before it existed).
std::vector<std::uint8_t> read_precisions(const Reader& r, std::size_t snapshots) {
  if (!r.has("snapshot_precision")) return std::vector<std::uint8_t>(snapshots, 8);
  std::vector<std::uint8_t> bytes = r.bytes("snapshot_precision");
  for (const std::uint8_t b : bytes)
    if (b != 4 && b != 8)
      r.reject("dataset 'snapshot_precision' holds " + std::to_string(b) + "; expected 4 or 8");
  return bytes;
}

void read_snapshot_table(const Reader& r, std::vector<XdmfSnapshot>& table) {
  const std::vector<std::string> files = r.strings("snapshot_file");
  const std::vector<double> times = r.rows<double, double>("snapshot_time", H5T_IEEE_F64LE);
  const std::vector<std::uint64_t> counts =
      r.rows<std::uint64_t, std::uint64_t>("snapshot_count", H5T_STD_U64LE);
  const std::vector<std::uint8_t> rank_fields = read_rank_field_flags(r, files.size());
  const std::vector<std::uint32_t> fields = read_field_sets(r, files.size());
  const std::vector<std::uint8_t> precisions = read_precisions(r, files.size());
  const std::vector<std::uint64_t> bond_counts =  // none before bonds were written
      r.has("snapshot_bond_count")
          ? r.rows<std::uint64_t, std::uint64_t>("snapshot_bond_count", H5T_STD_U64LE)
          : std::vector<std::uint64_t>(files.size(), 0);
  check_same_length(r, {{"snapshot_file", files.size()},
                        {"snapshot_time", times.size()},
                        {"snapshot_count", counts.size()},
                        {"snapshot_rank_field", rank_fields.size()},
                        {"snapshot_fields", fields.size()},
                        {"snapshot_precision", precisions.size()},
                        {"snapshot_bond_count", bond_counts.size()}});
  for (std::size_t k = 0; k < files.size(); ++k)
    table.push_back({files[k],
                     times[k],
                     counts[k],
                     {rank_fields[k] == 1, fields[k], precisions[k] == 4},
                     bond_counts[k]});
}

void read_wall_motion(const Reader& r, std::vector<WallMotion>& motion) {
  motion = r.rows<WallMotion, double>("wall_motion", H5T_IEEE_F64LE);
  for (const WallMotion& m : motion)
    if (!(std::isfinite(m.displacement) && std::isfinite(m.velocity) && std::isfinite(m.push)))
      r.reject("dataset 'wall_motion' holds a value that is not finite");
}

/// An optional u32 attribute, `fallback` when missing.
std::uint32_t optional_u32(const Reader& r, const char* name, std::uint32_t fallback) {
  return r.has_attribute(name) ? r.attribute<std::uint32_t>(name, H5T_STD_U32LE) : fallback;
}

/// Where the last list build was (the step when missing) and the last base step's substeps.
void read_list_build(const Reader& r, Checkpoint& c) {
  StepClock& b = c.list_build;
  b.step = r.has_attribute("list_build_step")
               ? r.attribute<std::uint64_t>("list_build_step", H5T_STD_U64LE)
               : c.step;
  b.substep = optional_u32(r, "list_build_substep", 0);
  b.substeps = optional_u32(r, "list_build_substeps", 1);
  c.substeps = optional_u32(r, "substeps", 1);
  if (b.step > c.step || (b.step == c.step && b.substep > 0))
    r.reject("attribute 'list_build_step' (" + std::to_string(b.step) + ", substep " +
             std::to_string(b.substep) + ") is after attribute 'step' (" + std::to_string(c.step) +
             ")");
  if (b.substeps == 0 || b.substep >= b.substeps)
    r.reject("attribute 'list_build_substep' (" + std::to_string(b.substep) +
             ") is not below attribute 'list_build_substeps' (" + std::to_string(b.substeps) + ")");
  if (c.substeps == 0 || c.substeps > kMaxSubsteps)
    r.reject("attribute 'substeps' (" + std::to_string(c.substeps) + ") is not in 1.." +
             std::to_string(kMaxSubsteps));
}

/// An integer sum's unit: a positive power of two; 0 when the file has none.
void read_sum_unit(const Reader& r, const char* name, double& unit) {
  unit = r.has_attribute(name) ? r.attribute<double>(name, H5T_IEEE_F64LE) : 0.0;
  int exponent = 0;
  if (unit != 0 && !(std::isfinite(unit) && unit > 0 && std::frexp(unit, &exponent) == 0.5))
    r.reject("attribute '" + std::string(name) + "' is not a positive power of two");
}

void read_attributes(const Reader& r, Checkpoint& c) {
  const auto version = r.attribute<std::uint32_t>("format_version", H5T_STD_U32LE);
  if (version != kCheckpointFormatVersion)
    r.reject("checkpoint format version " + std::to_string(version) +
             "; this program reads version " + std::to_string(kCheckpointFormatVersion));
  c.time = r.attribute<double>("time", H5T_IEEE_F64LE);
  c.step = r.attribute<std::uint64_t>("step", H5T_STD_U64LE);
  read_list_build(r, c);
  c.removed = r.attribute<std::uint64_t>("removed", H5T_STD_U64LE);
  c.dt = r.attribute<double>("dt", H5T_IEEE_F64LE);
  c.dt_fraction = r.attribute<double>("dt_fraction", H5T_IEEE_F64LE);
  c.dt_adaptive =
      r.has_attribute("dt_adaptive") && r.attribute<std::uint8_t>("dt_adaptive", H5T_STD_U8LE) != 0;
  c.skin = r.attribute<double>("skin", H5T_IEEE_F64LE);
  if (!(std::isfinite(c.dt) && c.dt > 0)) r.reject("attribute 'dt' is not finite and > 0");
  if (!(std::isfinite(c.skin) && c.skin >= 0)) r.reject("attribute 'skin' is not finite and >= 0");
  read_sum_unit(r, "sum_force_unit", c.sum_force_unit);
  read_sum_unit(r, "sum_torque_unit", c.sum_torque_unit);
  if ((c.sum_force_unit == 0) != (c.sum_torque_unit == 0))
    r.reject("attributes 'sum_force_unit' and 'sum_torque_unit' are not both there");
}

}  // namespace

Checkpoint read_checkpoint(const std::string& path, FilePart part) {
  const QuietHdf5 quiet;
  const Reader reader(path);
  Checkpoint c;
  read_attributes(reader, c);  // the version first: other versions may lay datasets out otherwise
  read_particles(reader, part, c);
  read_history(reader, part, c.history);
  read_bonds(reader, part, c);
  read_snapshot_table(reader, c.snapshots);
  if (reader.has("material_names")) c.material_names = reader.strings("material_names");
  if (reader.has("wall_motion")) read_wall_motion(reader, c.wall_motion);
  return c;
}

}  // namespace gpudem
