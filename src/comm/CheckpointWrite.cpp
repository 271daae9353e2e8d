// Checkpoint writing: every rank's rows in one parallel HDF5 file, published atomically.
#include "comm/Checkpoint.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include "comm/Hdf5Io.hpp"
#include "core/ContactModel.hpp"
#include "core/InputError.hpp"

namespace gpudem {
namespace {

static_assert(sizeof(Real4) == 4 * sizeof(Real) && sizeof(Vec3) == 3 * sizeof(Real),
              "checkpoint rows assume Real4 and Vec3 hold their values unpadded");

FieldSource real_rows(const char* name, const void* data, hsize_t components) {
  return {name, data, native_type<Real>(), H5T_IEEE_F64LE, components, components, 0};
}

FieldSource id_rows(const char* name, const ParticleId* data) {
  return {name, data, native_type<ParticleId>(), H5T_STD_U64LE, 1, 1, 0};
}

FieldSource index_rows(const char* name, const std::uint32_t* data) {
  return {name, data, native_type<std::uint32_t>(), H5T_STD_U32LE, 1, 1, 0};
}

void check_lengths(const Checkpoint& c) {
  const ParticleStore& p = c.particles;
  const std::size_t n = p.size();
  bool same = c.list_position_radius.size() == n;
  for_each_particle_field<field_use::checkpoint>(
      [&](auto field) { same = same && field.of(p).size() == n; });
  if (!same) throw std::logic_error("checkpoint: particle arrays differ in length");
  if (!c.history.lengths_agree())
    throw std::logic_error("checkpoint: contact history arrays differ in length");
}

/// The value datasets have `width` columns on every rank, so the ranks must agree on it.
/// Collective.
void check_same_width(MPI_Comm comm, std::uint32_t width) {
  std::uint32_t lowest = 0, highest = 0;
  MPI_Allreduce(&width, &lowest, 1, MPI_UINT32_T, MPI_MIN, comm);
  MPI_Allreduce(&width, &highest, 1, MPI_UINT32_T, MPI_MAX, comm);
  if (lowest != highest)
    throw std::logic_error("checkpoint: ranks hold contact history of " + std::to_string(lowest) +
                           " and " + std::to_string(highest) + " values per contact");
}

void write_particles(MPI_Comm comm, const ParallelFile& file, const Checkpoint& c) {
  const ParticleStore& p = c.particles;
  const Slice slice = global_slice(comm, p.size());
  for_each_particle_field<field_use::checkpoint>([&](auto field) {
    using Parts = ValueComponents<FieldValue<decltype(field), Real, Real>>;
    using Scalar = typename Parts::Scalar;
    file.write_dataset({field.name, field.of(p).data(), native_type<Scalar>(),
                        stored_type<Scalar>(), Parts::count, Parts::count, 0},
                       slice);
  });
  file.write_dataset(real_rows("list_position_radius", c.list_position_radius.data(), 4), slice);
}

/// The history records, and their values (h.width per record) when the law keeps any.
void write_history(MPI_Comm comm, const ParallelFile& file, const ContactHistory& h) {
  const Slice pairs = global_slice(comm, h.pair_owner.size());
  file.write_dataset(id_rows("pair_owner", h.pair_owner.data()), pairs);
  file.write_dataset(id_rows("pair_partner", h.pair_partner.data()), pairs);
  if (h.width > 0)
    file.write_dataset(real_rows("pair_history", h.pair_values.data(), h.width), pairs);
  const Slice walls = global_slice(comm, h.wall_owner.size());
  file.write_dataset(id_rows("wall_owner", h.wall_owner.data()), walls);
  file.write_dataset(index_rows("wall_index", h.wall_index.data()), walls);
  if (h.width > 0)
    file.write_dataset(real_rows("wall_history", h.wall_values.data(), h.width), walls);
  const Slice meshes = global_slice(comm, h.mesh_owner.size());
  file.write_dataset(id_rows("mesh_owner", h.mesh_owner.data()), meshes);
  file.write_dataset(index_rows("mesh_triangle", h.mesh_triangle.data()), meshes);
  if (h.width > 0)
    file.write_dataset(real_rows("mesh_history", h.mesh_values.data(), h.width), meshes);
}

/// Each end's record of each intact bond, with the count made at the start; nothing without
/// bonds.
void write_bonds(MPI_Comm comm, const ParallelFile& file, const Checkpoint& c) {
  const ContactHistory& b = c.bonds;
  if (b.width == 0) return;
  const Slice bonds = global_slice(comm, b.pair_owner.size());
  file.write_dataset(id_rows("bond_owner", b.pair_owner.data()), bonds);
  file.write_dataset(id_rows("bond_partner", b.pair_partner.data()), bonds);
  file.write_dataset(real_rows("bond_values", b.pair_values.data(), b.width), bonds);
  file.write_attribute("bonds_made", H5T_STD_U64LE, c.bonds_made);
}

/// Dataset `name` of rank 0's `texts` (the other ranks write no rows), as null-terminated
/// fixed-length strings. Collective.
void write_text_rows(MPI_Comm comm, const H5Calls& h5, const ParallelFile& file, const char* name,
                     const std::vector<std::string>& texts) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<std::string> rows = rank == 0 ? texts : std::vector<std::string>{};
  const Slice slice = global_slice(comm, rows.size());
  std::uint64_t local_width = 1, width = 1;
  for (const std::string& text : rows)
    local_width = std::max<std::uint64_t>(local_width, text.size() + 1);
  MPI_Allreduce(&local_width, &width, 1, MPI_UINT64_T, MPI_MAX, comm);
  std::vector<char> packed(rows.size() * width, '\0');
  for (std::size_t k = 0; k < rows.size(); ++k)
    std::memcpy(packed.data() + k * width, rows[k].data(), rows[k].size());
  const std::string what = std::string("(") + name + ")";
  H5Handle text = h5.handle(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy" + what);
  h5.check(H5Tset_size(text.id(), width), "H5Tset_size" + what);
  file.write_dataset({name, packed.data(), text.id(), text.id(), 1, 1, 0}, slice);
}

/// The snapshot table, rank 0's rows only; file names as null-terminated fixed-length strings.
void write_snapshot_table(MPI_Comm comm, const H5Calls& h5, const ParallelFile& file,
                          const std::vector<XdmfSnapshot>& table) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<XdmfSnapshot> rows = rank == 0 ? table : std::vector<XdmfSnapshot>{};
  const Slice slice = global_slice(comm, rows.size());
  std::vector<std::string> names;
  std::vector<double> times;
  std::vector<std::uint64_t> counts, bond_counts;
  std::vector<std::uint8_t> rank_fields, precisions;
  std::vector<std::uint32_t> fields;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    names.push_back(rows[k].h5_file);
    times.push_back(rows[k].time);
    counts.push_back(rows[k].count);
    bond_counts.push_back(rows[k].bond_count);
    rank_fields.push_back(rows[k].layout.rank_field ? 1 : 0);
    fields.push_back(rows[k].layout.fields);
    precisions.push_back(static_cast<std::uint8_t>(real_precision(rows[k])));
  }
  write_text_rows(comm, h5, file, "snapshot_file", names);
  file.write_dataset(real_rows("snapshot_time", times.data(), 1), slice);
  file.write_dataset(id_rows("snapshot_count", counts.data()), slice);
  file.write_dataset(id_rows("snapshot_bond_count", bond_counts.data()), slice);
  file.write_dataset(
      {"snapshot_rank_field", rank_fields.data(), H5T_NATIVE_UINT8, H5T_STD_U8LE, 1, 1, 0}, slice);
  file.write_dataset({"snapshot_fields", fields.data(), H5T_NATIVE_UINT32, H5T_STD_U32LE, 1, 1, 0},
                     slice);
  file.write_dataset(
      {"snapshot_precision", precisions.data(), H5T_NATIVE_UINT8, H5T_STD_U8LE, 1, 1, 0}, slice);
}

/// The walls' motion, rank 0's rows only.
void write_wall_motion(MPI_Comm comm, const ParallelFile& file,
                       const std::vector<WallMotion>& motion) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<WallMotion> rows = rank == 0 ? motion : std::vector<WallMotion>{};
  static_assert(sizeof(WallMotion) == 3 * sizeof(double), "a row is three f64 values");
  file.write_dataset(real_rows("wall_motion", rows.data(), 3), global_slice(comm, rows.size()));
}

void write_attributes(const ParallelFile& file, const Checkpoint& c) {
  file.write_attribute("format_version", H5T_STD_U32LE, kCheckpointFormatVersion);
  file.write_attribute("history_width", H5T_STD_U32LE, c.history.width);
  file.write_attribute("time", H5T_IEEE_F64LE, c.time);
  file.write_attribute("step", H5T_STD_U64LE, c.step);
  file.write_attribute("list_build_step", H5T_STD_U64LE, c.list_build.step);
  file.write_attribute("list_build_substep", H5T_STD_U32LE, c.list_build.substep);
  file.write_attribute("list_build_substeps", H5T_STD_U32LE, c.list_build.substeps);
  file.write_attribute("substeps", H5T_STD_U32LE, c.substeps);
  file.write_attribute("removed", H5T_STD_U64LE, c.removed);
  file.write_attribute("dt", H5T_IEEE_F64LE, c.dt);
  file.write_attribute("dt_fraction", H5T_IEEE_F64LE, c.dt_fraction);
  file.write_attribute("dt_adaptive", H5T_STD_U8LE, std::uint8_t(c.dt_adaptive ? 1 : 0));
  file.write_attribute("skin", H5T_IEEE_F64LE, c.skin);
  file.write_attribute("sum_force_unit", H5T_IEEE_F64LE, c.sum_force_unit);
  file.write_attribute("sum_torque_unit", H5T_IEEE_F64LE, c.sum_torque_unit);
}

/// fsync on a file or directory; returns false when it cannot be done.
bool sync_path(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) return false;
  const bool synced = ::fsync(fd) == 0;
  return ::close(fd) == 0 && synced;
}

/// Puts the complete temporary file in place of the checkpoint: its data reach the disk
/// before the rename, and the rename before this returns. Returns what went wrong, or "".
std::string publish(const std::string& temporary, const std::string& path) {
  if (!sync_path(temporary, O_RDONLY)) return "cannot sync '" + temporary + "'";
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) return "cannot rename '" + temporary + "' to '" + path + "': " + ec.message();
  const std::string dir = std::filesystem::path(path).parent_path().string();
  if (!sync_path(dir.empty() ? "." : dir, O_RDONLY | O_DIRECTORY))
    return "cannot sync directory of '" + path + "'";
  return {};
}

}  // namespace

std::string checkpoint_path(const std::string& dir) {
  return (std::filesystem::path(dir) / "checkpoint.h5").string();
}

void write_checkpoint(MPI_Comm comm, const std::string& dir, const Checkpoint& checkpoint) {
  check_lengths(checkpoint);
  check_same_width(comm, checkpoint.history.width);
  const std::string path = checkpoint_path(dir);
  const std::string temporary = path + ".tmp";
  {
    const H5Calls h5("checkpoint", temporary);
    ParallelFile file(comm, h5, temporary);
    write_particles(comm, file, checkpoint);
    write_history(comm, file, checkpoint.history);
    write_bonds(comm, file, checkpoint);
    write_snapshot_table(comm, h5, file, checkpoint.snapshots);
    write_text_rows(comm, h5, file, "material_names", checkpoint.material_names);
    write_wall_motion(comm, file, checkpoint.wall_motion);
    write_attributes(file, checkpoint);
    file.close();
  }
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string error = rank == 0 ? publish(temporary, path) : std::string();
  int failed = error.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  if (failed)
    throw std::runtime_error("checkpoint: " +
                             (rank == 0 ? error : "rank 0 could not publish '" + path + "'"));
}

}  // namespace gpudem
