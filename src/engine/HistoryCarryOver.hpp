#pragma once
/// The contact history a neighbour rebuild carries from the old lists to the new ones
/// (docs/architecture.md, "Contact history": history is keyed, never lost by a rebuild). Before the
/// particles are re-sorted, each owned particle's old row keeps the records that differ from a
/// fresh one, each with its key (the partner's global id for a particle contact); after the new
/// list is built, each new entry takes the kept record of its particle's old row with the same key,
/// or a fresh one. A record equal bit for bit to a fresh one is not kept, since the remap
/// re-creates it unchanged, so the kept rows hold about one record per touching contact rather than
/// one per list entry. They exist only during a rebuild.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "core/Config.hpp"
#include "engine/ArrayKernels.hpp"
#include "engine/CsrRows.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/ParallelFor.hpp"

namespace gpudem {

/// True when the `width` values at `record` are bit for bit a fresh record (every value +0):
/// each value's bits read as one unsigned word of its size, all words or'ed.
template <class S>
GPUDEM_HD bool is_fresh(const S* record, std::uint32_t width) {
  static_assert(sizeof(S) == sizeof(std::uint64_t) || sizeof(S) == sizeof(std::uint32_t),
                "history values are doubles or floats");
  using Bits = std::conditional_t<sizeof(S) == sizeof(std::uint64_t), std::uint64_t, std::uint32_t>;
  Bits any = 0;
  for (std::uint32_t v = 0; v < width; ++v) {
    Bits bits;
    std::memcpy(&bits, record + v, sizeof(Bits));
    any |= bits;
  }
  return any == 0;
}

/// Copies the `width` values of one record.
template <class S>
GPUDEM_HD void copy_record(const S* from, S* to, std::uint32_t width) {
  for (std::uint32_t v = 0; v < width; ++v) to[v] = from[v];
}

/// Key of neighbour-list entry e: its partner's global id.
struct PartnerIdKey {
  const std::uint32_t* neighbors;
  const ParticleId* id;
  GPUDEM_HD ParticleId operator()(std::uint32_t e) const { return id[neighbors[e]]; }
};

namespace carry_over_kernels {

/// Records of row r of a CSR history (offsets; history: `width` values per entry) that are not
/// fresh; as a Real, for reduce_sum.
template <class S>
struct KeptInRow {
  const std::uint32_t* offsets;
  const S* history;
  std::uint32_t width;
  GPUDEM_HD std::uint32_t count(std::size_t r) const {
    std::uint32_t kept = 0;
    for (std::uint32_t e = offsets[r]; e < offsets[r + 1]; ++e)
      kept += is_fresh(history + std::size_t(e) * width, width) ? 0 : 1;
    return kept;
  }
  GPUDEM_HD Real operator()(std::size_t r) const { return count(r); }
};

/// kept[r] = the records row r keeps.
template <class S>
struct CountKept {
  KeptInRow<S> row;
  std::uint32_t* kept;
  GPUDEM_HD void operator()(std::size_t r) const { kept[r] = row.count(r); }
};

/// Writes the records row r keeps, with their keys, from kept_offsets[r] on, in row order.
template <class Key, class S, class KeyOf>
struct Keep {
  KeptInRow<S> row;
  KeyOf key_of;
  const std::uint32_t* kept_offsets;
  Key* keys;
  S* records;
  GPUDEM_HD void operator()(std::size_t r) const {
    const std::uint32_t width = row.width;
    std::uint32_t k = kept_offsets[r];
    for (std::uint32_t e = row.offsets[r]; e < row.offsets[r + 1]; ++e) {
      const S* record = row.history + std::size_t(e) * width;
      if (is_fresh(record, width)) continue;
      keys[k] = key_of(e);
      copy_record(record, records + std::size_t(k) * width, width);
      ++k;
    }
  }
};

/// For each entry e of new row r: the record kept by old row previous_row[r] with key key_of(e),
/// or a fresh one.
template <class Key, class S, class KeyOf>
struct Remap {
  const std::uint32_t* offsets;
  KeyOf key_of;
  const std::uint32_t* previous_row;
  const std::uint32_t* kept_offsets;
  const Key* keys;
  const S* records;
  S* history;
  std::uint32_t width;
  GPUDEM_HD void operator()(std::size_t r) const {
    const std::uint32_t old = previous_row[r];
    for (std::uint32_t e = offsets[r]; e < offsets[r + 1]; ++e) {
      const Key key = key_of(e);
      S* record = history + std::size_t(e) * width;
      for (std::uint32_t v = 0; v < width; ++v) record[v] = S{};
      for (std::uint32_t f = kept_offsets[old]; f < kept_offsets[old + 1]; ++f)
        if (keys[f] == key) {
          copy_record(records + std::size_t(f) * width, record, width);
          break;
        }
    }
  }
};

}  // namespace carry_over_kernels

/// Kept history rows: row r's records are keys / records [offsets[r], offsets[r + 1]), each
/// record `width` values of scalar S, in Space memory.
template <class Space, class Key, class S>
class HistoryCarryOver {
 public:
  explicit HistoryCarryOver(std::uint32_t width = 0) : width_(width) { kept_.value_width = width; }

  /// Keeps, for rows [0, rows) of a CSR list (offsets: rows + 1 of them; history: one record per
  /// entry), the records that are not fresh, each keyed by key_of(entry).
  template <class KeyOf>
  void keep(std::size_t rows, const std::uint32_t* offsets, const S* history, KeyOf key_of) {
    release();
    kept_.offsets.resize(rows + 1);
    const carry_over_kernels::KeptInRow<S> row{offsets, history, width_};
    parallel_for(Space{}, rows, carry_over_kernels::CountKept<S>{row, kept_.offsets.data()});
    const std::uint64_t total = counts_to_offsets<Space>(
        kept_.offsets.data(), rows, "HistoryCarryOver: more than 2^32 - 1 kept records");
    kept_.keys.resize(total);
    kept_.values.resize(total * width_);
    parallel_for(Space{}, rows,
                 carry_over_kernels::Keep<Key, S, KeyOf>{row, key_of, kept_.offsets.data(),
                                                         kept_.keys.data(), kept_.values.data()});
  }

  /// The kept rows: those of the owned particles at keep time (each read through its
  /// previous_index), then those of particles that arrived from other ranks, appended.
  CsrRows<Space, Key, S>& rows() { return kept_; }
  const CsrRows<Space, Key, S>& rows() const { return kept_; }

  /// history[e] for every entry e of new rows [0, rows) (offsets: rows + 1 of them): the record
  /// kept by old row previous_row[r] under key_of(e), or a fresh one.
  template <class KeyOf>
  void remap(std::size_t rows, const std::uint32_t* offsets, KeyOf key_of,
             const std::uint32_t* previous_row, S* history) const {
    parallel_for(Space{}, rows,
                 carry_over_kernels::Remap<Key, S, KeyOf>{offsets, key_of, previous_row,
                                                          kept_.offsets.data(), kept_.keys.data(),
                                                          kept_.values.data(), history, width_});
  }

  /// Frees the kept rows.
  void release() { kept_.release(); }

  /// Bytes held in Space memory.
  std::size_t bytes() const { return kept_.bytes(); }

  /// Bytes keep() allocates for `rows` rows of a CSR history (offsets, history): their offsets
  /// and the records that are not fresh with their keys. A reduction over the rows.
  std::size_t bytes_to_keep(std::size_t rows, const std::uint32_t* offsets,
                            const S* history) const {
    const auto kept = static_cast<std::size_t>(
        reduce_sum(Space{}, rows, carry_over_kernels::KeptInRow<S>{offsets, history, width_}));
    return (rows + 1) * sizeof(std::uint32_t) + kept * (sizeof(Key) + width_ * sizeof(S));
  }

 private:
  std::uint32_t width_;  ///< values per record
  CsrRows<Space, Key, S> kept_;
};

}  // namespace gpudem
