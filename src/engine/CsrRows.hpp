#pragma once
/// Rows of a CSR table in Space memory (row r: keys and values [offsets[r], offsets[r + 1])),
/// read out or appended a few rows at a time: the history rows of the particles that migrate.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "engine/ArrayKernels.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/ParallelFor.hpp"

namespace gpudem {

namespace csr_row_kernels {

/// count[k] = the length of row rows[k].
struct RowLength {
  const std::uint32_t* rows;
  const std::uint32_t* offsets;
  std::uint32_t* count;
  GPUDEM_HD void operator()(std::size_t k) const {
    count[k] = offsets[rows[k] + 1] - offsets[rows[k]];
  }
};

/// Row rows[k]'s entries (`width` values each) to [out_offsets[k], out_offsets[k + 1]).
template <class Key, class Value>
struct GatherRow {
  const std::uint32_t* rows;
  const std::uint32_t* offsets;
  const Key* keys;
  const Value* values;
  std::uint32_t width;
  const std::uint32_t* out_offsets;
  Key* out_keys;
  Value* out_values;
  GPUDEM_HD void operator()(std::size_t k) const {
    std::uint32_t to = out_offsets[k];
    for (std::uint32_t e = offsets[rows[k]]; e < offsets[rows[k] + 1]; ++e, ++to) {
      out_keys[to] = keys[e];
      for (std::uint32_t v = 0; v < width; ++v)
        out_values[std::size_t(to) * width + v] = values[std::size_t(e) * width + v];
    }
  }
};

/// out[k] = in[k] + shift.
struct Shifted {
  const std::uint32_t* in;
  std::uint32_t shift;
  std::uint32_t* out;
  GPUDEM_HD void operator()(std::size_t k) const { out[k] = in[k] + shift; }
};

}  // namespace csr_row_kernels

/// A CSR table in Space memory, each entry a key and `value_width` values; empty offsets mean
/// no rows.
template <class Space, class Key, class Value>
struct CsrRows {
  DeviceArray<std::uint32_t, Space> offsets;
  DeviceArray<Key, Space> keys;
  DeviceArray<Value, Space> values;  ///< value_width per entry
  std::uint32_t value_width = 1;

  std::size_t rows() const { return offsets.size() == 0 ? 0 : offsets.size() - 1; }
  std::size_t bytes() const { return offsets.bytes() + keys.bytes() + values.bytes(); }
  void release() {
    gpudem::release(offsets);
    gpudem::release(keys);
    gpudem::release(values);
  }

  /// Host copies of rows `rows`[0, n) (row numbers in Space memory), in that order, with their
  /// offsets from 0 (n + 1 of them).
  void download(const std::uint32_t* rows, std::size_t n, std::vector<std::uint32_t>& out_offsets,
                std::vector<Key>& out_keys, std::vector<Value>& out_values) const {
    DeviceArray<std::uint32_t, Space> picked_offsets(n + 1);
    parallel_for(Space{}, n,
                 csr_row_kernels::RowLength{rows, offsets.data(), picked_offsets.data()});
    const std::uint64_t total = counts_to_offsets<Space>(
        picked_offsets.data(), n, "CsrRows: more than 2^32 - 1 entries in the rows read out");
    DeviceArray<Key, Space> picked_keys(total);
    DeviceArray<Value, Space> picked_values(total * value_width);
    parallel_for(Space{}, n,
                 csr_row_kernels::GatherRow<Key, Value>{
                     rows, offsets.data(), keys.data(), values.data(), value_width,
                     picked_offsets.data(), picked_keys.data(), picked_values.data()});
    picked_offsets.download(out_offsets);
    picked_keys.download(out_keys);
    picked_values.download(out_values);
  }

  /// Appends host rows (`more_offsets` from 0, one more than their rows) after the last row.
  void append(const std::vector<std::uint32_t>& more_offsets, const std::vector<Key>& more_keys,
              const std::vector<Value>& more_values) {
    if (more_offsets.size() < 2) return;
    if (offsets.size() == 0) {
      offsets.resize(1);
      parallel_for(Space{}, 1, Fill<std::uint32_t>{offsets.data(), 0});
    }
    const std::size_t first_row = rows();
    const std::size_t first_entry = keys.size();
    if (first_entry + more_keys.size() > std::uint64_t(std::numeric_limits<std::uint32_t>::max()))
      throw std::overflow_error("CsrRows: more than 2^32 - 1 entries");
    const std::size_t more_rows = more_offsets.size() - 1;
    DeviceArray<std::uint32_t, Space> ends;
    ends.upload(std::vector<std::uint32_t>(more_offsets.begin() + 1, more_offsets.end()));
    offsets.resize(first_row + 1 + more_rows);
    parallel_for(Space{}, more_rows,
                 csr_row_kernels::Shifted{ends.data(), static_cast<std::uint32_t>(first_entry),
                                          offsets.data() + first_row + 1});
    keys.resize(first_entry + more_keys.size());
    values.resize(first_entry * value_width + more_values.size());
    upload_values<Space>(more_keys, keys.data() + first_entry);
    upload_values<Space>(more_values, values.data() + first_entry * value_width);
  }
};

}  // namespace gpudem
