#pragma once
/// Full Verlet neighbour list in CSR form, built from a CellList.
///
/// Particles i != j are neighbours when |d_ij| < r_i + r_j + skin, with d_ij = x_j − x_i reduced
/// to its minimum image on periodic axes. The list is full: each pair is in both particles'
/// lists, so forces can be summed one thread per particle without atomics. The neighbours of
/// particle i are neighbors()[offsets()[i] .. offsets()[i + 1]), ascending. All indices are
/// slots of the cell order (CellList.hpp). The caller rebuilds the list (bin, permute, build)
/// once any particle has moved more than skin / 2 since the last build.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "kernels/CellList.hpp"
#include "kernels/DeviceArray.hpp"
#include "kernels/ParallelFor.hpp"
#include "kernels/PeriodicBox.hpp"
#include "kernels/SizeClassGrid.hpp"

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
    const Real4 p = position_radius[i];
    for (int c = 0; c < grids.class_count; ++c)
      if (grids.grid[c].particles > 0) visit_class(i, p, grids.grid[c], visit);
  }

 private:
  /// Candidates of one class: the cells of its grid within r_i + r_c + skin of particle i.
  template <class Visitor>
  GPUDEM_HD void visit_class(std::uint32_t i, const Real4& p, const CellGrid& g,
                             Visitor& visit) const {
    const Real reach = p.w + g.radius_max + grids.skin;
    const AxisSpan sx = axis_span(g, grids.box, 0, p.x, reach);
    const AxisSpan sy = axis_span(g, grids.box, 1, p.y, reach);
    const AxisSpan sz = axis_span(g, grids.box, 2, p.z, reach);
    for (int rz = 0; rz < sz.runs; ++rz)
      for (int z = sz.first[rz]; z <= sz.last[rz]; ++z)
        for (int ry = 0; ry < sy.runs; ++ry)
          for (int y = sy.first[ry]; y <= sy.last[ry]; ++y)
            for (int rx = 0; rx < sx.runs; ++rx)  // a run of cells is a run of slots
              visit_slots(i, p, cell_begin[cell_index(g, sx.first[rx], y, z)],
                          cell_begin[cell_index(g, sx.last[rx], y, z) + 1], visit);
  }

  template <class Visitor>
  GPUDEM_HD void visit_slots(std::uint32_t i, const Real4& p, std::uint32_t begin,
                             std::uint32_t end, Visitor& visit) const {
    for (std::uint32_t j = begin; j < end; ++j) {
      if (j == i) continue;
      const Real4 q = position_radius[j];
      const Real cutoff = p.w + q.w + grids.skin;
      visit(j, norm2(grids.box.minimum_image(xyz(q) - xyz(p))) < cutoff * cutoff);
    }
  }
};

namespace neighbor_list_kernels {

struct PairCounter {
  std::uint32_t examined = 0;
  std::uint32_t kept = 0;
  GPUDEM_HD void operator()(std::uint32_t, bool within) {
    ++examined;
    kept += within ? 1 : 0;
  }
};

struct PairWriter {
  std::uint32_t* next;
  GPUDEM_HD void operator()(std::uint32_t j, bool within) {
    if (within) *next++ = j;
  }
};

/// kept[i], examined[i]: neighbours and candidates of particle i.
struct CountNeighbors {
  NeighborSearch search;
  std::uint32_t* kept;
  std::uint32_t* examined;
  GPUDEM_HD void operator()(std::size_t i) const {
    PairCounter counter;
    search.for_each_candidate(static_cast<std::uint32_t>(i), counter);
    kept[i] = counter.kept;
    examined[i] = counter.examined;
  }
};

/// Writes the neighbours of particle i from neighbors[offsets[i]] on.
struct WriteNeighbors {
  NeighborSearch search;
  const std::uint32_t* offsets;
  std::uint32_t* neighbors;
  GPUDEM_HD void operator()(std::size_t i) const {
    PairWriter writer{neighbors + offsets[i]};
    search.for_each_candidate(static_cast<std::uint32_t>(i), writer);
  }
};

struct StoreValue {
  std::uint32_t* target;
  std::uint32_t value;
  GPUDEM_HD void operator()(std::size_t) const { *target = value; }
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
  /// the binning. Counts the neighbours, scans the counts into offsets, then writes them.
  void build(const CellList<Space>& cells, const Real4* sorted_position_radius, std::size_t n,
             const PeriodicBox& box, Real skin) {
    if (n != cells.size())
      throw std::invalid_argument("NeighborList: particle count differs from the cell list's");
    if (!same_box(box, cells.grids().box) || skin != cells.grids().skin)
      throw std::invalid_argument("NeighborList: box or skin differs from the cell list's");
    const NeighborSearch search{cells.grids(), cells.cell_begin(), sorted_position_radius};
    n_ = n;
    offsets_.resize(n + 1);
    candidates_per_particle_.resize(n);
    parallel_for(Space{}, n,
                 neighbor_list_kernels::CountNeighbors{search, offsets_.data(),
                                                       candidates_per_particle_.data()});
    pairs_kept_ = exclusive_scan(Space{}, offsets_.data(), offsets_.data(), n);
    if (pairs_kept_ > std::numeric_limits<std::uint32_t>::max())
      throw std::overflow_error("NeighborList: more than 2^32 - 1 neighbour entries");
    parallel_for(Space{}, 1,
                 neighbor_list_kernels::StoreValue{offsets_.data() + n,
                                                   static_cast<std::uint32_t>(pairs_kept_)});
    neighbors_.resize(pairs_kept_);
    parallel_for(Space{}, n,
                 neighbor_list_kernels::WriteNeighbors{search, offsets_.data(), neighbors_.data()});
    candidates_examined_ = static_cast<std::uint64_t>(
        reduce_sum(Space{}, n, neighbor_list_kernels::ValueOf{candidates_per_particle_.data()}));
  }

  /// Number of particles in the list.
  std::size_t size() const { return n_; }
  /// n + 1 entries; the neighbours of i are neighbors()[offsets()[i] .. offsets()[i + 1]).
  const std::uint32_t* offsets() const { return offsets_.data(); }
  const std::uint32_t* neighbors() const { return neighbors_.data(); }
  /// Ordered pairs (i, j) tested against the criterion in the last build.
  std::uint64_t candidates_examined() const { return candidates_examined_; }
  /// Ordered pairs kept in the last build: the list's length, twice the number of pairs.
  std::uint64_t pairs_kept() const { return pairs_kept_; }
  /// Bytes held in Space memory.
  std::size_t memory_bytes() const {
    return offsets_.bytes() + neighbors_.bytes() + candidates_per_particle_.bytes();
  }

 private:
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
  DeviceArray<std::uint32_t, Space> offsets_;
  DeviceArray<std::uint32_t, Space> neighbors_;
  DeviceArray<std::uint32_t, Space> candidates_per_particle_;
};

}  // namespace gpudem
