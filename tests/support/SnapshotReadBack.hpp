#pragma once
// Particle snapshots read back with the HDF5 C API: each rank checks its own rows of a
// snapshot file against a particle store, bit for bit (after rounding to float for a snapshot
// in single precision).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "core/ParticleStore.hpp"
#include "support/H5Id.hpp"
#include "support/MpiRank.hpp"

namespace gpudem::test {

/// `count` particles with random values in every field; ids are unique over ranks (the seed
/// differs per rank), not contiguous, and above 2^40.
inline ParticleStore random_store(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> value(-1e3, 1e3);
  std::uniform_int_distribution<std::uint32_t> material;
  ParticleStore p;
  std::uint64_t id = (std::uint64_t(1) << 40) + seed * (std::uint64_t(1) << 32);
  for (std::size_t i = 0; i < count; ++i) {
    id += 1 + rng() % 1000;
    p.position_radius.push_back({value(rng), value(rng), value(rng), value(rng)});
    p.velocity_inv_mass.push_back({value(rng), value(rng), value(rng), value(rng)});
    p.angular_velocity.push_back({value(rng), value(rng), value(rng)});
    p.force.push_back({value(rng), value(rng), value(rng)});
    p.torque.push_back({value(rng), value(rng), value(rng)});
    p.id.push_back(id);
    p.material.push_back(material(rng));
  }
  return p;
}

/// This rank's first row in the file: the counts of lower ranks added up.
inline std::uint64_t expected_offset(std::uint64_t count) {
  std::vector<std::uint64_t> counts(comm_size());
  MPI_Allgather(&count, 1, MPI_UINT64_T, counts.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  std::uint64_t offset = 0;
  for (int r = 0; r < comm_rank(); ++r) offset += counts[r];
  return offset;
}

inline std::uint64_t global_count(std::uint64_t count) {
  std::uint64_t total = 0;
  MPI_Allreduce(&count, &total, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return total;
}

inline std::vector<double> xyz_of(const std::vector<Real4>& values) {
  std::vector<double> out;
  for (const Real4& v : values) out.insert(out.end(), {v.x, v.y, v.z});
  return out;
}

inline std::vector<double> xyz_of(const std::vector<Vec3>& values) {
  std::vector<double> out;
  for (const Vec3& v : values) out.insert(out.end(), {v.x, v.y, v.z});
  return out;
}

inline std::vector<double> radii_of(const ParticleStore& p) {
  std::vector<double> out;
  for (const Real4& v : p.position_radius) out.push_back(v.w);
  return out;
}

/// Checks a dataset's stored type and global shape, then reads rows [offset, offset + rows).
template <class T>
std::vector<T> read_rows(hid_t file, const char* name, hid_t stored_type, hid_t memory_type,
                         std::vector<hsize_t> global_dims, hsize_t offset, hsize_t rows) {
  H5Id<H5Dclose> dataset(H5Dopen2(file, name, H5P_DEFAULT));
  EXPECT_GE(dataset.id, 0) << "no dataset " << name;
  if (dataset.id < 0) return {};
  H5Id<H5Tclose> type(H5Dget_type(dataset.id));
  EXPECT_GT(H5Tequal(type.id, stored_type), 0) << name << " has the wrong stored type";
  H5Id<H5Sclose> file_space(H5Dget_space(dataset.id));
  std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(file_space.id));
  H5Sget_simple_extent_dims(file_space.id, dims.data(), nullptr);
  EXPECT_EQ(dims, global_dims) << name << " has the wrong shape";
  const hsize_t columns = global_dims.size() > 1 ? global_dims[1] : 1;
  std::vector<T> values(rows * columns);
  if (rows == 0 || dims != global_dims) return values;
  const hsize_t start[2] = {offset, 0}, count[2] = {rows, columns};
  H5Sselect_hyperslab(file_space.id, H5S_SELECT_SET, start, nullptr, count, nullptr);
  const hsize_t memory_dims[1] = {rows * columns};
  H5Id<H5Sclose> memory_space(H5Screate_simple(1, memory_dims, nullptr));
  EXPECT_GE(
      H5Dread(dataset.id, memory_type, memory_space.id, file_space.id, H5P_DEFAULT, values.data()),
      0)
      << "cannot read " << name;
  return values;
}

template <class T>
void expect_bit_identical(const std::vector<T>& expected, const std::vector<T>& actual,
                          const char* name) {
  ASSERT_EQ(expected.size(), actual.size()) << name;
  for (std::size_t i = 0; i < expected.size(); ++i)
    ASSERT_EQ(0, std::memcmp(&expected[i], &actual[i], sizeof(T)))
        << name << " differs at value " << i << " on rank " << comm_rank();
}

template <class T>
T read_attribute(hid_t file, const char* name, hid_t stored_type, hid_t memory_type) {
  T value{};
  H5Id<H5Aclose> attribute(H5Aopen(file, name, H5P_DEFAULT));
  EXPECT_GE(attribute.id, 0) << "no attribute " << name;
  if (attribute.id < 0) return value;
  H5Id<H5Tclose> type(H5Aget_type(attribute.id));
  EXPECT_GT(H5Tequal(type.id, stored_type), 0) << name << " has the wrong stored type";
  EXPECT_GE(H5Aread(attribute.id, memory_type, &value), 0);
  return value;
}

/// `values` as T: rounded to the nearest float when T is float, as a float32 dataset holds them.
template <class T>
std::vector<T> as(const std::vector<double>& values) {
  return std::vector<T>(values.begin(), values.end());
}

/// Reads back one snapshot file holding every field and compares this rank's rows with `p`,
/// its real values stored as T (double, or float in single precision).
template <class T = double>
void expect_snapshot_holds(const std::string& path, const ParticleStore& p, double time,
                           std::uint64_t step) {
  MPI_Barrier(MPI_COMM_WORLD);
  const hsize_t n = global_count(p.size()), offset = expected_offset(p.size()), rows = p.size();
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  ASSERT_GE(file.id, 0) << "cannot open " << path;
  const hid_t f64 = H5T_IEEE_F64LE, f64_mem = H5T_NATIVE_DOUBLE;
  constexpr bool single = std::is_same_v<T, float>;
  const hid_t real = single ? H5T_IEEE_F32LE : f64, real_mem = single ? H5T_NATIVE_FLOAT : f64_mem;
  expect_bit_identical(as<T>(xyz_of(p.position_radius)),
                       read_rows<T>(file.id, "position", real, real_mem, {n, 3}, offset, rows),
                       "position");
  expect_bit_identical(as<T>(radii_of(p)),
                       read_rows<T>(file.id, "radius", real, real_mem, {n}, offset, rows),
                       "radius");
  expect_bit_identical(as<T>(xyz_of(p.velocity_inv_mass)),
                       read_rows<T>(file.id, "velocity", real, real_mem, {n, 3}, offset, rows),
                       "velocity");
  expect_bit_identical(
      as<T>(xyz_of(p.angular_velocity)),
      read_rows<T>(file.id, "angular_velocity", real, real_mem, {n, 3}, offset, rows),
      "angular_velocity");
  expect_bit_identical(as<T>(xyz_of(p.force)),
                       read_rows<T>(file.id, "force", real, real_mem, {n, 3}, offset, rows),
                       "force");
  expect_bit_identical(p.material,
                       read_rows<std::uint32_t>(file.id, "material", H5T_STD_U32LE,
                                                H5T_NATIVE_UINT32, {n}, offset, rows),
                       "material");
  expect_bit_identical(
      p.id,
      read_rows<std::uint64_t>(file.id, "id", H5T_STD_U64LE, H5T_NATIVE_UINT64, {n}, offset, rows),
      "id");
  std::vector<std::uint32_t> rows_in_file(rows);
  for (hsize_t k = 0; k < rows; ++k) rows_in_file[k] = static_cast<std::uint32_t>(offset + k);
  expect_bit_identical(rows_in_file,
                       read_rows<std::uint32_t>(file.id, "connectivity", H5T_STD_U32LE,
                                                H5T_NATIVE_UINT32, {n}, offset, rows),
                       "connectivity");
  const double stored_time = read_attribute<double>(file.id, "time", f64, f64_mem);
  EXPECT_EQ(0, std::memcmp(&stored_time, &time, sizeof(double))) << "time " << stored_time;
  EXPECT_EQ(step,
            (read_attribute<std::uint64_t>(file.id, "step", H5T_STD_U64LE, H5T_NATIVE_UINT64)));
}

}  // namespace gpudem::test
