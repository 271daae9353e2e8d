#pragma once
// RAII for HDF5 identifiers in tests.
#include <hdf5.h>

namespace gpudem::test {

/// An HDF5 identifier closed at scope exit.
template <herr_t (*Close)(hid_t)>
struct H5Id {
  explicit H5Id(hid_t value) : id(value) {}
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  ~H5Id() {
    if (id >= 0) Close(id);
  }
  hid_t id;
};

}  // namespace gpudem::test
