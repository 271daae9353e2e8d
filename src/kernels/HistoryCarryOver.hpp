#pragma once
/// The contact history a neighbour rebuild carries from the old lists to the new ones (DESIGN §3:
/// history is keyed, never lost by a rebuild). Before the particles are re-sorted, each owned
/// particle's old row keeps the records that differ from a fresh one, each with its key (the
/// partner's global id for a particle contact); after the new list is built, each new entry takes
/// the kept record of its particle's old row with the same key, or a fresh one. A record equal
/// bit for bit to a fresh one is not kept, since the remap re-creates it unchanged, so the kept
/// rows hold about one record per touching contact rather than one per list entry. They exist
/// only during a rebuild.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Config.hpp"
#include "kernels/ArrayKernels.hpp"
#include "kernels/CsrRows.hpp"
#include "kernels/DeviceArray.hpp"
#include "kernels/ParallelFor.hpp"

namespace gpudem {

/// True when `record` is bit for bit a fresh record (State{}: every value +0).
template <class State>
GPUDEM_HD bool is_fresh(const State& record) {
  const unsigned char* byte = reinterpret_cast<const unsigned char*>(&record);
  for (std::size_t k = 0; k < sizeof(State); ++k)
    if (byte[k] != 0) return false;
  return true;
}

/// Key of neighbour-list entry e: its partner's global id.
struct PartnerIdKey {
  const std::uint32_t* neighbors;
  const ParticleId* id;
  GPUDEM_HD ParticleId operator()(std::uint32_t e) const { return id[neighbors[e]]; }
};

namespace carry_over_kernels {

/// Records of row r of a CSR history (offsets, history) that are not fresh; as a Real, for
/// reduce_sum.
template <class State>
struct KeptInRow {
  const std::uint32_t* offsets;
  const State* history;
  GPUDEM_HD std::uint32_t count(std::size_t r) const {
    std::uint32_t kept = 0;
    for (std::uint32_t e = offsets[r]; e < offsets[r + 1]; ++e)
      kept += is_fresh(history[e]) ? 0 : 1;
    return kept;
  }
  GPUDEM_HD Real operator()(std::size_t r) const { return count(r); }
};

/// kept[r] = the records row r keeps.
template <class State>
struct CountKept {
  KeptInRow<State> row;
  std::uint32_t* kept;
  GPUDEM_HD void operator()(std::size_t r) const { kept[r] = row.count(r); }
};

/// Writes the records row r keeps, with their keys, from kept_offsets[r] on, in row order.
template <class Key, class State, class KeyOf>
struct Keep {
  const std::uint32_t* offsets;
  const State* history;
  KeyOf key_of;
  const std::uint32_t* kept_offsets;
  Key* keys;
  State* records;
  GPUDEM_HD void operator()(std::size_t r) const {
    std::uint32_t k = kept_offsets[r];
    for (std::uint32_t e = offsets[r]; e < offsets[r + 1]; ++e) {
      if (is_fresh(history[e])) continue;
      keys[k] = key_of(e);
      records[k] = history[e];
      ++k;
    }
  }
};

/// For each entry e of new row r: the record kept by old row previous_row[r] with key key_of(e),
/// or a fresh one.
template <class Key, class State, class KeyOf>
struct Remap {
  const std::uint32_t* offsets;
  KeyOf key_of;
  const std::uint32_t* previous_row;
  const std::uint32_t* kept_offsets;
  const Key* keys;
  const State* records;
  State* history;
  GPUDEM_HD void operator()(std::size_t r) const {
    const std::uint32_t old = previous_row[r];
    for (std::uint32_t e = offsets[r]; e < offsets[r + 1]; ++e) {
      const Key key = key_of(e);
      State carried{};
      for (std::uint32_t f = kept_offsets[old]; f < kept_offsets[old + 1]; ++f)
        if (keys[f] == key) {
          carried = records[f];
          break;
        }
      history[e] = carried;
    }
  }
};

}  // namespace carry_over_kernels

/// Kept history rows: row r's records are keys / records [offsets[r], offsets[r + 1]), in Space
/// memory.
template <class Space, class Key, class State>
class HistoryCarryOver {
 public:
  /// Keeps, for rows [0, rows) of a CSR list (offsets: rows + 1 of them; history: one record per
  /// entry), the records that are not fresh, each keyed by key_of(entry).
  template <class KeyOf>
  void keep(std::size_t rows, const std::uint32_t* offsets, const State* history, KeyOf key_of) {
    release();
    kept_.offsets.resize(rows + 1);
    const carry_over_kernels::KeptInRow<State> row{offsets, history};
    parallel_for(Space{}, rows, carry_over_kernels::CountKept<State>{row, kept_.offsets.data()});
    const std::uint64_t total = counts_to_offsets<Space>(
        kept_.offsets.data(), rows, "HistoryCarryOver: more than 2^32 - 1 kept records");
    kept_.keys.resize(total);
    kept_.values.resize(total);
    parallel_for(
        Space{}, rows,
        carry_over_kernels::Keep<Key, State, KeyOf>{offsets, history, key_of, kept_.offsets.data(),
                                                    kept_.keys.data(), kept_.values.data()});
  }

  /// The kept rows: those of the owned particles at keep time (each read through its
  /// previous_index), then those of particles that arrived from other ranks, appended.
  CsrRows<Space, Key, State>& rows() { return kept_; }
  const CsrRows<Space, Key, State>& rows() const { return kept_; }

  /// history[e] for every entry e of new rows [0, rows) (offsets: rows + 1 of them): the record
  /// kept by old row previous_row[r] under key_of(e), or a fresh one.
  template <class KeyOf>
  void remap(std::size_t rows, const std::uint32_t* offsets, KeyOf key_of,
             const std::uint32_t* previous_row, State* history) const {
    parallel_for(Space{}, rows,
                 carry_over_kernels::Remap<Key, State, KeyOf>{
                     offsets, key_of, previous_row, kept_.offsets.data(), kept_.keys.data(),
                     kept_.values.data(), history});
  }

  /// Frees the kept rows.
  void release() { kept_.release(); }

  /// Bytes held in Space memory.
  std::size_t bytes() const { return kept_.bytes(); }

  /// Bytes keep() allocates for `rows` rows of a CSR history (offsets, history): their offsets
  /// and the records that are not fresh with their keys. A reduction over the rows.
  static std::size_t bytes_to_keep(std::size_t rows, const std::uint32_t* offsets,
                                   const State* history) {
    const auto kept = static_cast<std::size_t>(
        reduce_sum(Space{}, rows, carry_over_kernels::KeptInRow<State>{offsets, history}));
    return (rows + 1) * sizeof(std::uint32_t) + kept * (sizeof(Key) + sizeof(State));
  }

 private:
  CsrRows<Space, Key, State> kept_;
};

}  // namespace gpudem
