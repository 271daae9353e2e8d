#pragma once
// Damage done to a valid checkpoint file with the HDF5 C API, for tests of the reader's
// rejections: another format version, an attribute or dataset removed, a dataset shortened or
// of another shape, values replaced; and reads of whole datasets for comparisons.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "support/H5Id.hpp"

namespace gpudem::test {

/// Sets the attribute `name` of the file's root group to `value`, of memory type `memory`.
template <class T>
void set_attribute(const std::string& path, const char* name, hid_t memory, T value) {
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  ASSERT_GE(file.id, 0) << path;
  H5Id<H5Aclose> attribute(H5Aopen(file.id, name, H5P_DEFAULT));
  ASSERT_GE(attribute.id, 0) << name;
  ASSERT_GE(H5Awrite(attribute.id, memory, &value), 0);
}

inline void set_u32_attribute(const std::string& path, const char* name, std::uint32_t value) {
  set_attribute(path, name, H5T_NATIVE_UINT32, value);
}

inline void set_f64_attribute(const std::string& path, const char* name, double value) {
  set_attribute(path, name, H5T_NATIVE_DOUBLE, value);
}

inline void remove_dataset(const std::string& path, const char* name) {
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  ASSERT_GE(file.id, 0) << path;
  ASSERT_GE(H5Ldelete(file.id, name, H5P_DEFAULT), 0) << name;
}

/// Replaces dataset `name` by a rows × columns dataset of file type `stored` holding `values`
/// (row by row, of memory type `memory`); 1-D when columns is 0.
template <class T>
void replace_dataset(const std::string& path, const char* name, hid_t stored, hid_t memory,
                     hsize_t rows, hsize_t columns, const std::vector<T>& values) {
  ASSERT_EQ(values.size(), rows * std::max<hsize_t>(columns, 1));
  remove_dataset(path, name);
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  const hsize_t dims[2] = {rows, columns};
  H5Id<H5Sclose> space(H5Screate_simple(columns == 0 ? 1 : 2, dims, nullptr));
  H5Id<H5Dclose> dataset(
      H5Dcreate2(file.id, name, stored, space.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  ASSERT_GE(dataset.id, 0) << name;
  ASSERT_GE(H5Dwrite(dataset.id, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
}

/// Replaces dataset `name` by a 1-D u32 dataset holding `values`.
inline void replace_u32_dataset(const std::string& path, const char* name,
                                const std::vector<std::uint32_t>& values) {
  replace_dataset(path, name, H5T_STD_U32LE, H5T_NATIVE_UINT32, values.size(), 0, values);
}

/// Replaces dataset `name` by a 1-D u8 dataset holding `values`.
inline void replace_u8_dataset(const std::string& path, const char* name,
                               const std::vector<std::uint8_t>& values) {
  replace_dataset(path, name, H5T_STD_U8LE, H5T_NATIVE_UINT8, values.size(), 0, values);
}

/// Replaces dataset `name` by a rows × columns f64 dataset holding `values` (row by row).
inline void replace_f64_dataset(const std::string& path, const char* name, hsize_t rows,
                                hsize_t columns, const std::vector<double>& values) {
  replace_dataset(path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rows, columns, values);
}

inline void remove_attribute(const std::string& path, const char* name) {
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  ASSERT_GE(file.id, 0) << path;
  ASSERT_GE(H5Adelete(file.id, name), 0) << name;
}

/// Whether the file's root group holds a link `name`.
inline bool has_dataset(const std::string& path, const char* name) {
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  EXPECT_GE(file.id, 0) << path;
  return H5Lexists(file.id, name, H5P_DEFAULT) > 0;
}

/// Rows of a dataset (whole file, C API), as raw values of type T.
template <class T>
std::vector<T> read_values(const std::string& path, const char* name, hid_t memory_type) {
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  EXPECT_GE(file.id, 0) << path;
  H5Id<H5Dclose> dataset(H5Dopen2(file.id, name, H5P_DEFAULT));
  EXPECT_GE(dataset.id, 0) << path << ": " << name;
  if (dataset.id < 0) return {};
  H5Id<H5Sclose> space(H5Dget_space(dataset.id));
  std::vector<T> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id)));
  if (!values.empty()) {
    EXPECT_GE(H5Dread(dataset.id, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  }
  return values;
}

/// The stored bytes of a whole dataset, in its own type (no conversion).
inline std::vector<unsigned char> raw_bytes(const std::string& path, const char* name) {
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  EXPECT_GE(file.id, 0) << path;
  H5Id<H5Dclose> dataset(H5Dopen2(file.id, name, H5P_DEFAULT));
  EXPECT_GE(dataset.id, 0) << path << ": " << name;
  if (dataset.id < 0) return {};
  H5Id<H5Tclose> type(H5Dget_type(dataset.id));
  H5Id<H5Sclose> space(H5Dget_space(dataset.id));
  std::vector<unsigned char> bytes(
      static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id)) * H5Tget_size(type.id));
  if (!bytes.empty()) {
    EXPECT_GE(H5Dread(dataset.id, type.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), 0);
  }
  return bytes;
}

}  // namespace gpudem::test
