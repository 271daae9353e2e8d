#pragma once
/// Cell grids for the neighbour search of polydisperse particles: one grid per radius class.
///
/// Particles are split into geometric radius classes of ratio 2: class c holds radii in
/// (r_top / 2^(c+1), r_top / 2^c], the last class also every smaller radius. Each class has its
/// own grid with cell edges of at least 2 r_c + skin (r_c the largest radius in the class), and a
/// particle i looks for partners of class c only in the cells of grid c within
/// r_i + r_c + skin. A single grid sized for the largest radius would make every small particle
/// scan cells sized for the largest pair; with a 10:1 radius ratio that is ~1000 times the volume
/// and the candidate count. This is the multi-cutoff binning of in 't Veld, Plimpton and Grest,
/// Comput. Phys. Commun. 179 (2008) 320 (LAMMPS "neighbor multi").
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/BinRegion.hpp"
#include "engine/PeriodicBox.hpp"

namespace gpudem {

/// Most radius classes; radii below r_top / 2^(kMaxSizeClasses - 1) share the last class.
constexpr int kMaxSizeClasses = 8;

/// Memory bound: a class grid has at most this many cells per particle of the class. A sparse
/// class (few particles in a large box) gets coarser cells instead of mostly empty ones.
constexpr std::size_t kMaxCellsPerParticle = 8;

/// Widening, in cells, of a search span, so that rounding in (x ± reach − lo) / side never drops
/// the cell on the edge of the span (rounding stays far below 1e-9 cells for < 1e6 cells/axis).
constexpr Real kSpanMarginCells = 1e-9;

/// Number of classes of ratio 2 that span [r_min, r_max]: at least 1, at most max_classes.
inline int size_class_count(Real r_min, Real r_max, int max_classes) {
  int count = 1;
  for (Real lower = r_max / 2; count < max_classes && lower > r_min; lower /= 2) ++count;
  return count;
}

/// Class of radius r: the c with r_top / 2^(c+1) < r <= r_top / 2^c, or the last class.
GPUDEM_HD inline int size_class(Real r, Real r_top, int class_count) {
  int c = 0;
  for (Real lower = r_top / 2; c + 1 < class_count && r <= lower; lower /= 2) ++c;
  return c;
}

/// A regular grid of cells over a rank's region (BinRegion.hpp). On an axis where the region is
/// periodic the cells tile its length exactly, so a periodic image of a point lies a whole number
/// of grid lengths away from the point's cell; on the other axes, points outside the region belong
/// to the edge cells.
struct CellGrid {
  int cells[3] = {1, 1, 1};      ///< cells along x, y, z
  Real side[3] = {1, 1, 1};      ///< [m] cell edge along x, y, z
  std::uint32_t first_cell = 0;  ///< index of this grid's cell (0,0,0) among all grids' cells
  std::uint32_t particles = 0;   ///< particles binned in this grid
  Real radius_max = 0;           ///< [m] largest radius binned in this grid

  GPUDEM_HD std::uint32_t cell_count() const {
    return static_cast<std::uint32_t>(cells[0]) * cells[1] * cells[2];
  }
};

/// Index, among all grids' cells, of cell (x, y, z) of grid g: x fastest.
GPUDEM_HD inline std::uint32_t cell_index(const CellGrid& g, int x, int y, int z) {
  return g.first_cell + (static_cast<std::uint32_t>(z) * g.cells[1] + y) * g.cells[0] + x;
}

/// Cell coordinate c clamped to [0, n); NaN goes to 0.
GPUDEM_HD inline int clamp_cell(Real c, int n) {
  return static_cast<int>(fmin(fmax(c, Real(0)), Real(n - 1)));
}

/// Cell coordinate c wrapped into [0, n).
GPUDEM_HD inline int wrap_cell(Real c, int n) { return clamp_cell(c - n * floor(c / n), n); }

/// Cell coordinate of x (a region image, region_image) along axis k: wrapped where the region is
/// periodic, clamped otherwise.
GPUDEM_HD inline int cell_coordinate(const CellGrid& g, const BinRegion& region, int k, Real x) {
  const Real c = floor((x - axis(region.lo, k)) / g.side[k]);
  return region.periodic[k] ? wrap_cell(c, g.cells[k]) : clamp_cell(c, g.cells[k]);
}

/// The cells along one axis within reach of a point, as at most two ascending runs of cell
/// coordinates (two when the reach wraps around a periodic axis). No cell appears twice, even
/// when the reach is wider than the grid.
struct AxisSpan {
  int first[2] = {0, 0};
  int last[2] = {0, 0};
  int runs = 1;
};

/// Cells of grid g along axis k that overlap [x − reach, x + reach], x a region image.
GPUDEM_HD inline AxisSpan axis_span(const CellGrid& g, const BinRegion& region, int k, Real x,
                                    Real reach) {
  const int n = g.cells[k];
  const Real offset = x - axis(region.lo, k);
  const Real from = floor((offset - reach) / g.side[k] - kSpanMarginCells);
  const Real to = floor((offset + reach) / g.side[k] + kSpanMarginCells);
  AxisSpan span;
  if (!region.periodic[k]) {
    span.first[0] = clamp_cell(from, n);
    span.last[0] = clamp_cell(to, n);
    return span;
  }
  const Real width = to - from + 1;
  if (!(width < n)) {  // the whole axis (also when x is NaN)
    span.last[0] = n - 1;
    return span;
  }
  const int first = wrap_cell(from, n);
  const int last = first + static_cast<int>(width) - 1;
  if (last < n) {
    span.first[0] = first;
    span.last[0] = last;
  } else {
    span.runs = 2;
    span.last[0] = last - n;
    span.first[1] = first;
    span.last[1] = n - 1;
  }
  return span;
}

/// Cells along an axis of the given length for cell edges of at least `side`.
inline Real cells_along(Real length, Real side) {
  return std::max(Real(1), std::floor(length / side));
}

/// Grid over the region with cell edges of at least min_side (> 0) and at most max_cells (>= 1)
/// cells; the edges grow beyond min_side only as far as max_cells requires.
inline CellGrid make_cell_grid(const BinRegion& region, Real min_side, Real max_cells) {
  Real side = min_side;
  const auto total = [&region](Real s) {
    return cells_along(region.length.x, s) * cells_along(region.length.y, s) *
           cells_along(region.length.z, s);
  };
  while (total(side) > max_cells) side *= Real(1.25);
  CellGrid g;
  for (int k = 0; k < 3; ++k) {
    const Real length = axis(region.length, k);
    const Real n = cells_along(length, side);
    g.cells[k] = static_cast<int>(n);
    g.side[k] = region.periodic[k] ? length / n : std::max(length / n, side);
  }
  return g;
}

/// The class grids of one binning, with everything a search thread needs to use them.
struct SizeClassGrids {
  PeriodicBox box;      ///< the global box, for minimum-image distances only
  BinRegion region;     ///< the part of the box the grids cover
  Real skin = 0;        ///< [m] added to every pair's contact distance
  Real radius_top = 0;  ///< [m] largest radius, upper bound of class 0
  int class_count = 1;
  CellGrid grid[kMaxSizeClasses];  ///< grid of each class, cells numbered class after class
  std::uint32_t total_cells = 1;   ///< cells of all grids

  GPUDEM_HD int class_of(Real radius) const { return size_class(radius, radius_top, class_count); }

  /// Coordinate x along axis k as the grids see it: its image nearest the region.
  GPUDEM_HD Real binned(int k, Real x) const { return region_image(box, region, k, x); }

  /// Index, among all grids' cells, of the cell that holds particle p (x, y, z, radius).
  GPUDEM_HD std::uint32_t cell_of(const Real4& p) const {
    const CellGrid& g = grid[class_of(p.w)];
    return cell_index(g, cell_coordinate(g, region, 0, binned(0, p.x)),
                      cell_coordinate(g, region, 1, binned(1, p.y)),
                      cell_coordinate(g, region, 2, binned(2, p.z)));
  }
};

}  // namespace gpudem
