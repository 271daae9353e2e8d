#pragma once
/// Full Verlet neighbour list in CSR form, built from a CellList.
///
/// Particles i != j are neighbours when |d_ij| < r_i + r_j + skin, with d_ij = x_j − x_i reduced
/// to its minimum image on periodic axes. The list is full: each pair is in both particles'
/// lists, so forces can be summed one thread per particle without atomics. The caller rebuilds the
/// list (bin, permute, build) once any particle has moved more than skin / 2 since the last build.
///
/// Two layouts. Built for every binned particle, row k holds the neighbours of slot k of the cell
/// order (CellList.hpp) as ascending slots. Built for given rows (NeighborRows: a rank's owned
/// particles, among owned + ghosts), row r holds the neighbours of the particle in slot
/// rows.slot[r] as storage indices, ascending in the partners' keys (global ids), so that each
/// force sum visits its partners in an order set by the ids alone, whatever the storage order or
/// rank count.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "core/Config.hpp"
#include "core/Lanes.hpp"
#include "core/Vec3.hpp"
#include "engine/ArrayKernels.hpp"
#include "engine/CellList.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/HostRanges.hpp"
#include "engine/NeighborSlots.hpp"
#include "engine/ParallelFor.hpp"
#include "engine/PeriodicBox.hpp"
#include "engine/SizeClassGrid.hpp"

namespace gpudem {

/// What a search thread reads: the class grids, the cell ranges and the sorted particles.
struct NeighborSearch {
  SizeClassGrids grids;
  const std::uint32_t* cell_begin;
  const Real4* position_radius;  ///< in cell order

  /// Calls visit(j, within) for every candidate j != i in the cells within reach of particle
  /// i, in ascending j; `within` tells whether the pair meets the neighbour criterion.
  template <class Visitor>
  GPUDEM_HD void for_each_candidate(std::uint32_t i, Visitor& visit) const {
    SlotsOfRuns<Visitor> slots{this, &visit};
    for_each_run(i, slots);
  }

  /// Calls visit(i, p, begin, end) for every run of slots [begin, end) in the cells within reach
  /// of particle i (p: its centre and radius), in ascending slots; a run may hold slot i.
  template <class RunVisitor>
  GPUDEM_HD void for_each_run(std::uint32_t i, RunVisitor& visit) const {
    const Real4 p = position_radius[i];
    const Vec3 binned = make_vec3(grids.binned(0, p.x), grids.binned(1, p.y), grids.binned(2, p.z));
    for (int c = 0; c < grids.class_count; ++c)
      if (grids.grid[c].particles > 0) visit_class(i, p, binned, grids.grid[c], visit);
  }

  /// Whether the particle in slot j meets the neighbour criterion with p (centre and radius).
  GPUDEM_HD bool within(const Real4& p, std::uint32_t j) const {
    const Real4 q = position_radius[j];
    const Real cutoff = p.w + q.w + grids.skin;
    return norm2(grids.box.minimum_image(xyz(q) - xyz(p))) < cutoff * cutoff;
  }

 private:
  /// Runs of slots as single candidates.
  template <class Visitor>
  struct SlotsOfRuns {
    const NeighborSearch* search;
    Visitor* visit;
    GPUDEM_HD void operator()(std::uint32_t i, const Real4& p, std::uint32_t begin,
                              std::uint32_t end) const {
      for (std::uint32_t j = begin; j < end; ++j)
        if (j != i) (*visit)(j, search->within(p, j));
    }
  };

  /// Runs of one class: the cells of its grid within r_i + r_c + skin of particle i, whose
  /// position as the grids see it is `binned`.
  template <class RunVisitor>
  GPUDEM_HD void visit_class(std::uint32_t i, const Real4& p, const Vec3& binned, const CellGrid& g,
                             RunVisitor& visit) const {
    const Real reach = p.w + g.radius_max + grids.skin;
    const AxisSpan sx = axis_span(g, grids.region, 0, binned.x, reach);
    const AxisSpan sy = axis_span(g, grids.region, 1, binned.y, reach);
    const AxisSpan sz = axis_span(g, grids.region, 2, binned.z, reach);
    for (int rz = 0; rz < sz.runs; ++rz)
      for (int z = sz.first[rz]; z <= sz.last[rz]; ++z)
        for (int ry = 0; ry < sy.runs; ++ry)
          for (int y = sy.first[ry]; y <= sy.last[ry]; ++y)
            for (int rx = 0; rx < sx.runs; ++rx)  // a run of cells is a run of slots
              visit(i, p, cell_begin[cell_index(g, sx.first[rx], y, z)],
                    cell_begin[cell_index(g, sx.last[rx], y, z) + 1]);
  }
};

/// Rows of a list built for some of the binned particles only (a rank's owned particles), in the
/// caller's storage order, holding storage indices ordered by partner key (global id). Null slots
/// and storage indices mean the storage order is the cell order (row r is slot r).
struct NeighborRows {
  const std::uint32_t* slot;           ///< cell-order slot of row r's particle, `count` entries
  std::size_t count;                   ///< number of rows
  const std::uint32_t* index_of_slot;  ///< storage index of each slot's particle (cells.order())
  const ParticleId* key;  ///< by storage index; each row ascending in key (ties: index)
};

namespace neighbor_list_kernels {

/// What a row kernel needs of the rows: the slot of each row and the names of its entries. Null
/// pointers give today's full layout: row k is slot k, entries are slots, ascending.
struct RowLayout {
  const std::uint32_t* slot = nullptr;
  const std::uint32_t* index_of_slot = nullptr;
  const ParticleId* key = nullptr;

  GPUDEM_HD std::uint32_t slot_of_row(std::size_t r) const {
    return slot ? slot[r] : static_cast<std::uint32_t>(r);
  }
  GPUDEM_HD std::uint32_t entry_of_slot(std::uint32_t j) const {
    return index_of_slot ? index_of_slot[j] : j;
  }
  /// Entry a goes before entry b: ascending (key, index).
  GPUDEM_HD bool before(std::uint32_t a, std::uint32_t b) const {
    return key[a] < key[b] || (key[a] == key[b] && a < b);
  }
  /// Insertion sort of one row by (key, index); rows are short (tens of entries).
  GPUDEM_HD void sort_row(std::uint32_t* row, std::uint32_t length) const {
    for (std::uint32_t m = 1; m < length; ++m) {
      const std::uint32_t entry = row[m];
      std::uint32_t k = m;
      for (; k > 0 && before(entry, row[k - 1]); --k) row[k] = row[k - 1];
      row[k] = entry;
    }
  }
};

struct PairCounter {
  std::uint32_t examined = 0;
  std::uint32_t kept = 0;
  GPUDEM_HD void operator()(std::uint32_t, bool within) {
    ++examined;
    kept += within ? 1 : 0;
  }
};

struct PairWriter {
  RowLayout layout;
  std::uint32_t* next;
  GPUDEM_HD void operator()(std::uint32_t j, bool within) {
    if (within) *next++ = layout.entry_of_slot(j);
  }
};

/// The host's one-pass search: appends each run's neighbours to a thread's buffer,
/// entries[0, used), and counts the candidates. A run is tested `vector_doubles` slots at once:
/// eight where the CPU runs AVX-512 (slots_within_avx512), four where it runs AVX2
/// (slots_within_avx2), else slot by slot, each slot written at `used`, which only a neighbour
/// advances: about one candidate in seven is a neighbour, and a branch on it would go either
/// way.
struct RunAppender {
  const NeighborSearch* search;
  RowLayout layout;
  std::vector<std::uint32_t>* entries;
  int vector_doubles = 1;  ///< 8, 4 or 1: at most host_vector_doubles()
  std::size_t used = 0;
  std::uint64_t examined = 0;

  void operator()(std::uint32_t i, const Real4& p, std::uint32_t begin, std::uint32_t end) {
    const std::size_t room = used + (end - begin) + kSlotsWithinSlack;
    if (room > entries->size()) entries->resize(2 * room + 256);
    std::uint32_t* out = entries->data() + used;
    const std::uint32_t kept = vector_doubles > 1 ? vector_within(i, p, begin, end, out)
                                                  : scalar_within(i, p, begin, end, out);
    examined += end - begin - (i >= begin && i < end ? 1 : 0);
    if (layout.index_of_slot)
      for (std::uint32_t k = 0; k < kept; ++k) out[k] = layout.index_of_slot[out[k]];
    used += kept;
  }

 private:
  std::uint32_t scalar_within(std::uint32_t i, const Real4& p, std::uint32_t begin,
                              std::uint32_t end, std::uint32_t* out) const {
    std::uint32_t kept = 0;
    for (std::uint32_t j = begin; j < end; ++j) {
      out[kept] = j;
      kept += j != i && search->within(p, j) ? 1 : 0;
    }
    return kept;
  }
  std::uint32_t vector_within(std::uint32_t i, const Real4& p, std::uint32_t begin,
                              std::uint32_t end, std::uint32_t* out) const {
#if GPUDEM_HOST_LANES
    const PeriodicBox& box = search->grids.box;
    const SlotTest test{&search->position_radius[0].x,
                        {p.x, p.y, p.z, p.w},
                        i,
                        search->grids.skin,
                        {box.length.x, box.length.y, box.length.z},
                        {box.periodic[0], box.periodic[1], box.periodic[2]}};
    return vector_doubles == 8 ? slots_within_avx512(test, begin, end, out)
                               : slots_within_avx2(test, begin, end, out);
#else
    return scalar_within(i, p, begin, end, out);
#endif
  }
};

/// kept[r], examined[r]: neighbours and candidates of row r's particle.
struct CountNeighbors {
  NeighborSearch search;
  RowLayout layout;
  std::uint32_t* kept;
  std::uint32_t* examined;
  GPUDEM_HD void operator()(std::size_t r) const {
    PairCounter counter;
    search.for_each_candidate(layout.slot_of_row(r), counter);
    kept[r] = counter.kept;
    examined[r] = counter.examined;
  }
};

/// Writes the neighbours of row r's particle from neighbors[offsets[r]] on, sorted by key when
/// the layout has keys.
struct WriteNeighbors {
  NeighborSearch search;
  RowLayout layout;
  const std::uint32_t* offsets;
  std::uint32_t* neighbors;
  GPUDEM_HD void operator()(std::size_t r) const {
    std::uint32_t* row = neighbors + offsets[r];
    PairWriter writer{layout, row};
    search.for_each_candidate(layout.slot_of_row(r), writer);
    if (layout.key) layout.sort_row(row, offsets[r + 1] - offsets[r]);
  }
};

struct ValueOf {
  const std::uint32_t* values;
  GPUDEM_HD Real operator()(std::size_t i) const { return values[i]; }
};

}  // namespace neighbor_list_kernels

template <class Space>
class NeighborList {
 public:
  /// Builds the list of the n particles binned in `cells`, whose positions and radii
  /// (x, y, z, radius) are given in cell order (cells.order()); box and skin [m] must be those of
  /// the binning. Without `rows`, one row per slot; with them, the given rows only (their
  /// pointers in Space memory, slots < n). Frees the previous list first; the list holds exactly
  /// its entries. A device counts the neighbours, scans the counts into offsets, then writes
  /// them, so that a rebuild never holds two lists; the host searches once (search_once).
  void build(const CellList<Space>& cells, const Real4* sorted_position_radius, std::size_t n,
             const PeriodicBox& box, Real skin, const NeighborRows* rows = nullptr) {
    check_matches(cells, n, box, skin);
    ++builds_;
    const NeighborSearch search{cells.grids(), cells.cell_begin(), sorted_position_radius};
    const neighbor_list_kernels::RowLayout layout = layout_of(rows);
    n_ = rows ? rows->count : n;
    release(offsets_);
    release(neighbors_);
    offsets_.resize(n_ + 1);
    if constexpr (std::is_same_v<Space, HostSpace>) {
      search_once(search, layout);
    } else {
      candidates_examined_ = count_neighbors(search, layout);
      pairs_kept_ = counts_to_offsets<Space>(offsets_.data(), n_, kTooManyEntries);
      neighbors_.resize(pairs_kept_);
      parallel_for(
          Space{}, n_,
          neighbor_list_kernels::WriteNeighbors{search, layout, offsets_.data(), neighbors_.data()},
          LaunchSlot::neighbor_list);
    }
  }

  /// Number of rows in the list: n, or rows.count when built for given rows.
  std::size_t size() const { return n_; }
  /// size() + 1 entries; row r is neighbors()[offsets()[r] .. offsets()[r + 1]).
  const std::uint32_t* offsets() const { return offsets_.data(); }
  const std::uint32_t* neighbors() const { return neighbors_.data(); }
  /// Ordered pairs (i, j) tested against the criterion in the last build.
  std::uint64_t candidates_examined() const { return candidates_examined_; }
  /// Ordered pairs kept in the last build: the list's length (without rows, twice the number of
  /// pairs).
  std::uint64_t pairs_kept() const { return pairs_kept_; }
  /// Bytes held in Space memory.
  std::size_t memory_bytes() const { return offsets_.bytes() + neighbors_.bytes(); }
  /// How many times the list was built: a new count, a new list.
  std::uint64_t builds() const { return builds_; }

 private:
  /// Writes each row's neighbour count to offsets_ and returns the candidates examined (counted
  /// per row in scratch that is freed before the entries are allocated).
  std::uint64_t count_neighbors(const NeighborSearch& search,
                                const neighbor_list_kernels::RowLayout& layout) {
    DeviceArray<std::uint32_t, Space> examined(n_);
    parallel_for(
        Space{}, n_,
        neighbor_list_kernels::CountNeighbors{search, layout, offsets_.data(), examined.data()},
        LaunchSlot::neighbor_list);
    return static_cast<std::uint64_t>(
        reduce_sum(Space{}, n_, neighbor_list_kernels::ValueOf{examined.data()}));
  }

  /// The host's build, one search per row instead of a count and a write: each thread searches a
  /// contiguous range of rows, appending their entries (each row sorted by key) to a buffer of
  /// its own and writing each row's length to offsets_; the buffers are then copied in row order
  /// into the list. The entries are held twice for that moment.
  void search_once(const NeighborSearch& search, const neighbor_list_kernels::RowLayout& layout) {
    const std::size_t parts = host_thread_count();
    std::vector<std::vector<std::uint32_t>> entries(parts);
    std::vector<std::uint64_t> examined(parts, 0);
    std::uint32_t* length = offsets_.data();
    const int vector_doubles = GPUDEM_HOST_LANES ? host_vector_doubles() : 1;
    host_numbered_ranges(n_, parts, [&](std::size_t part, std::uint32_t begin, std::uint32_t end) {
      neighbor_list_kernels::RunAppender append{&search, layout, &entries[part], vector_doubles};
      for (std::uint32_t r = begin; r < end; ++r) {
        const std::size_t first = append.used;
        search.for_each_run(layout.slot_of_row(r), append);
        length[r] = static_cast<std::uint32_t>(append.used - first);
        if (layout.key) layout.sort_row(entries[part].data() + first, length[r]);
      }
      entries[part].resize(append.used);
      examined[part] = append.examined;
    });
    candidates_examined_ = 0;
    for (const std::uint64_t e : examined) candidates_examined_ += e;
    pairs_kept_ = counts_to_offsets<Space>(offsets_.data(), n_, kTooManyEntries);
    neighbors_.resize(pairs_kept_);
    std::uint32_t* list = neighbors_.data();
    const std::uint32_t* offsets = offsets_.data();
    host_numbered_ranges(n_, parts, [&](std::size_t part, std::uint32_t begin, std::uint32_t) {
      std::copy(entries[part].begin(), entries[part].end(), list + offsets[begin]);
    });
  }

  static constexpr const char* kTooManyEntries =
      "NeighborList: more than 2^32 - 1 neighbour entries";

  static void check_matches(const CellList<Space>& cells, std::size_t n, const PeriodicBox& box,
                            Real skin) {
    if (n != cells.size())
      throw std::invalid_argument("NeighborList: particle count differs from the cell list's");
    if (!same_box(box, cells.grids().box) || skin != cells.grids().skin)
      throw std::invalid_argument("NeighborList: box or skin differs from the cell list's");
  }

  static neighbor_list_kernels::RowLayout layout_of(const NeighborRows* rows) {
    if (!rows) return {};
    if (rows->count > 0 && (!rows->key || !rows->slot != !rows->index_of_slot))
      throw std::invalid_argument(
          "NeighborList: rows need keys, and slots and storage indices both or neither");
    return {rows->slot, rows->index_of_slot, rows->key};
  }

  static bool same_box(const PeriodicBox& a, const PeriodicBox& b) {
    for (int k = 0; k < 3; ++k)
      if (axis(a.lo, k) != axis(b.lo, k) || axis(a.length, k) != axis(b.length, k) ||
          a.periodic[k] != b.periodic[k])
        return false;
    return true;
  }

  std::size_t n_ = 0;
  std::uint64_t candidates_examined_ = 0;
  std::uint64_t pairs_kept_ = 0;
  std::uint64_t builds_ = 0;
  DeviceArray<std::uint32_t, Space> offsets_;
  DeviceArray<std::uint32_t, Space> neighbors_;
};

}  // namespace gpudem
