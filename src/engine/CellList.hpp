#pragma once
/// Cell list: particles binned into the cells of their radius class's grid (SizeClassGrid.hpp)
/// and sorted by (class, cell).
///
/// Use on a rebuild step:
///   1. cells.bin(position_radius, n, box, skin, region);   // keys, sort, cell ranges
///   2. permute(space, cells.order(), in, out, n);          // each particle array into cell order
///   3. neighbors.build(cells, sorted_position_radius, n, box, skin, &rows);  // NeighborList.hpp
/// Slot k of the cell order holds the particle that had index order()[k]; the particles of
/// cell c occupy slots [cell_begin()[c], cell_begin()[c + 1]).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/BinRegion.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/ParallelFor.hpp"
#include "engine/ParticleStateKernels.hpp"
#include "engine/PeriodicBox.hpp"
#include "engine/SizeClassGrid.hpp"

namespace gpudem {

namespace cell_list_kernels {

// The kernels read positions and radii held in scalar P (the engine's state) and work in Real.

template <class P>
struct NegativeRadius {
  const Vec4T<P>* position_radius;
  GPUDEM_HD Real operator()(std::size_t i) const { return -Real(position_radius[i].w); }
};

/// 1 for a particle of class `wanted`, else 0.
template <class P>
struct InClass {
  const Vec4T<P>* position_radius;
  Real radius_top;
  int class_count;
  int wanted;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return size_class(position_radius[i].w, radius_top, class_count) == wanted ? 1 : 0;
  }
};

/// Radius of a particle of class `wanted`, else 0.
template <class P>
struct RadiusInClass {
  InClass<P> member;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return member(i) > 0 ? Real(member.position_radius[i].w) : Real(0);
  }
};

/// cell[i] = the cell holding particle i; order[i] = i.
template <class P>
struct AssignCell {
  SizeClassGrids grids;
  const Vec4T<P>* position_radius;
  std::uint64_t* cell;
  std::uint32_t* order;
  GPUDEM_HD void operator()(std::size_t i) const {
    cell[i] = grids.cell_of(vec4_cast<Real>(position_radius[i]));
    order[i] = static_cast<std::uint32_t>(i);
  }
};

/// begin[c] = first slot whose cell is >= c, by binary search over the sorted cells.
struct FindCellBegin {
  const std::uint64_t* sorted_cell;
  std::uint32_t n;
  std::uint32_t* begin;
  GPUDEM_HD void operator()(std::size_t c) const {
    std::uint32_t lo = 0, hi = n;
    while (lo < hi) {
      const std::uint32_t mid = lo + (hi - lo) / 2;
      if (sorted_cell[mid] < c)
        lo = mid + 1;
      else
        hi = mid;
    }
    begin[c] = lo;
  }
};

}  // namespace cell_list_kernels

template <class Space>
class CellList {
 public:
  /// max_size_classes in [1, kMaxSizeClasses]; 1 gives a single grid sized by the largest radius.
  explicit CellList(int max_size_classes = kMaxSizeClasses) : max_size_classes_(max_size_classes) {
    if (max_size_classes < 1 || max_size_classes > kMaxSizeClasses)
      throw std::invalid_argument("CellList: max_size_classes must be in [1, " +
                                  std::to_string(kMaxSizeClasses) + "]");
  }

  /// Bins n particles (x, y, z, radius in Space memory, in scalar P, global box coordinates)
  /// into grids over
  /// `region` and sorts them by (class, cell). On a periodic axis of the box any image of a
  /// position is accepted; on the others, positions outside the region belong to its edge cells.
  /// skin [m] >= 0 is the neighbour list's skin. Throws std::invalid_argument when a radius is
  /// not finite and > 0, when the skin is negative, or when the region does not fit the box
  /// (check_region).
  template <class P>
  void bin(const Vec4T<P>* position_radius, std::size_t n, const PeriodicBox& box, Real skin,
           const BinRegion& region) {
    if (n > std::numeric_limits<std::uint32_t>::max() / (kMaxCellsPerParticle + 1))
      throw std::invalid_argument("CellList: too many particles for 32-bit cell indices");
    n_ = n;
    Real r_min = 0, r_max = 0;
    if (n > 0) {
      r_max = reduce_max(Space{}, n, Real(0), Radius<P>{position_radius});
      r_min =
          -reduce_max(Space{}, n, -r_max, cell_list_kernels::NegativeRadius<P>{position_radius});
    }
    if (n > 0) check_radii(r_min, r_max);
    check_skin(skin);
    for (int k = 0; k < 3; ++k) check_region(box, region, 2 * r_max + skin, k);
    make_grids(position_radius, box, region, skin, r_min, r_max);
    DeviceArray<std::uint64_t, Space> cell(n_);  // cell of each slot, ascending after the sort
    sort_into_cells(position_radius, cell);
    find_cell_begins(cell);
  }

  /// Bins into grids over the whole box (a run on one rank).
  template <class P>
  void bin(const Vec4T<P>* position_radius, std::size_t n, const PeriodicBox& box, Real skin) {
    bin(position_radius, n, box, skin, whole_box_region(box));
  }

  /// Number of particles binned.
  std::size_t size() const { return n_; }
  /// order()[k]: original index of the particle in slot k of the cell order.
  const std::uint32_t* order() const { return order_.data(); }
  /// total_cells + 1 entries: cell c holds slots [cell_begin()[c], cell_begin()[c + 1]).
  const std::uint32_t* cell_begin() const { return cell_begin_.data(); }
  /// The class grids of the last binning.
  const SizeClassGrids& grids() const { return grids_; }
  /// Bytes held in Space memory.
  std::size_t memory_bytes() const { return order_.bytes() + cell_begin_.bytes(); }

 private:
  static void check_radii(Real r_min, Real r_max) {
    if (!(r_min > 0) || !std::isfinite(r_max))
      throw std::invalid_argument("CellList: particle radii must be finite and > 0");
  }

  static void check_skin(Real skin) {
    if (!(skin >= 0) || !std::isfinite(skin))
      throw std::invalid_argument("CellList: skin must be finite and >= 0");
  }

  /// Axis k of the region against the box, for cutoff = 2 r_max + skin. A periodic box length L
  /// must be at least 2 cutoff, so that one image of a particle at most is within reach. A region
  /// periodic on k must span the whole periodic axis. On a box-periodic axis where the region is
  /// not periodic, its length plus the cutoff must not exceed L: the gap the region leaves is
  /// then at least one cutoff, and two images of one partner are never both in reach of it.
  static void check_region(const PeriodicBox& box, const BinRegion& region, Real cutoff, int k) {
    const Real box_length = axis(box.length, k), length = axis(region.length, k);
    const char name = "xyz"[k];
    std::ostringstream what;
    what << "CellList: ";
    if (box.periodic[k] && !(box_length >= 2 * cutoff)) {
      what << "periodic length along " << name << " (" << box_length
           << " m) must be at least 2 (2 r_max + skin) = " << 2 * cutoff << " m";
    } else if (region.periodic[k] && (!box.periodic[k] || length != box_length)) {
      what << "a region periodic along " << name << " must span the whole periodic box length ("
           << box_length << " m), not " << length << " m";
    } else if (box.periodic[k] && !region.periodic[k] && !(length + cutoff <= box_length)) {
      what << "region length along " << name << " (" << length << " m) plus 2 r_max + skin ("
           << cutoff << " m) exceeds the periodic length " << box_length
           << " m; bin the whole axis as periodic instead";
    } else {
      return;
    }
    throw std::invalid_argument(what.str());
  }

  template <class P>
  void make_grids(const Vec4T<P>* position_radius, const PeriodicBox& box, const BinRegion& region,
                  Real skin, Real r_min, Real r_max) {
    grids_ = SizeClassGrids{};
    grids_.box = box;
    grids_.region = region;
    grids_.skin = skin;
    grids_.radius_top = r_max;
    grids_.class_count = size_class_count(r_min, r_max, max_size_classes_);
    std::uint64_t total = 0;
    for (int c = 0; c < grids_.class_count; ++c) {
      CellGrid& g = grids_.grid[c];
      const cell_list_kernels::InClass<P> member{position_radius, r_max, grids_.class_count, c};
      const auto particles = static_cast<std::uint32_t>(reduce_sum(Space{}, n_, member));
      if (particles > 0) {
        const Real radius =
            reduce_max(Space{}, n_, Real(0), cell_list_kernels::RadiusInClass<P>{member});
        const std::size_t max_cells = std::min<std::size_t>(
            kMaxCellsPerParticle * particles, std::numeric_limits<int>::max());  // int per axis
        g = make_cell_grid(region, 2 * radius + skin, Real(max_cells));
        g.particles = particles;
        g.radius_max = radius;
      }
      g.first_cell = static_cast<std::uint32_t>(total);
      total += g.cell_count();
    }
    if (total >= std::numeric_limits<std::uint32_t>::max())
      throw std::invalid_argument("CellList: too many cells for 32-bit cell indices");
    grids_.total_cells = static_cast<std::uint32_t>(total);
  }

  /// Fills `cell` (n_ values) with the particles' cells and sorts it, with order_.
  template <class P>
  void sort_into_cells(const Vec4T<P>* position_radius, DeviceArray<std::uint64_t, Space>& cell) {
    order_.resize(n_);
    parallel_for(
        Space{}, n_,
        cell_list_kernels::AssignCell<P>{grids_, position_radius, cell.data(), order_.data()});
    const std::uint32_t largest_cell = std::max<std::uint32_t>(grids_.total_cells, 1) - 1;
    sort_by_key(Space{}, cell.data(), order_.data(), n_, bits_for(largest_cell));
  }

  /// cell_begin_ from the sorted cells: on a device a search per cell, on the host one pass over
  /// the sorted cells (the searches' unpredictable branches cost more there than the pass).
  void find_cell_begins(const DeviceArray<std::uint64_t, Space>& cell) {
    cell_begin_.resize(grids_.total_cells + std::size_t(1));
    if constexpr (std::is_same_v<Space, HostSpace>) {
      cell_begins_in_order(cell.data());
    } else {
      parallel_for(Space{}, cell_begin_.size(),
                   cell_list_kernels::FindCellBegin{cell.data(), static_cast<std::uint32_t>(n_),
                                                    cell_begin_.data()});
    }
  }

  /// cell_begin_[c] for every c: the first slot whose cell is c or above (n_ past the last).
  void cell_begins_in_order(const std::uint64_t* sorted_cell) {
    std::uint32_t* begin = cell_begin_.data();
    const std::uint64_t cells = cell_begin_.size();
    std::uint64_t next = 0;  // the first cell whose begin is still to be written
    for (std::uint32_t k = 0; k < n_; ++k)
      for (; next <= sorted_cell[k] && next < cells; ++next) begin[next] = k;
    for (; next < cells; ++next) begin[next] = static_cast<std::uint32_t>(n_);
  }

  int max_size_classes_;
  std::size_t n_ = 0;
  SizeClassGrids grids_;
  DeviceArray<std::uint32_t, Space> order_;
  DeviceArray<std::uint32_t, Space> cell_begin_;
};

}  // namespace gpudem
