#pragma once
/// The coarse cells of the global box that the domain decomposition hands to ranks
/// (docs/architecture.md, "Ranks"), and the cell -> rank map as the engine reads it. The cell
/// lookup is a host and device function, so that the host's decomposition and the engine's kernels
/// place a point in the same cell.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/PeriodicBox.hpp"

namespace gpudem {

/// The most coarse cells a box is cut into: every rank holds the cell -> rank map (5 bytes a
/// cell in its engine's memory, 9 on the host), so its size must not grow with the bed. 2^22
/// cells are 20 MiB in the engine; cells of the ghost width (12.5 mm) would number about
/// 4.5 × 10^8 in a bed of 10^9 spheres of 5 mm radius packed to 60 %.
constexpr std::size_t kMaxCoarseCells = std::size_t(1) << 22;

/// The coarse cells of the global box: n[k] = max(1, floor(L_k / s)) per axis, edge L_k / n[k]
/// (so the edge is >= s whenever L_k >= s; where L_k / s rounds across an integer, n[k] is the
/// one for which the edge, as computed, is). The side s is min_side, or where that gives more
/// than max_cells cells (Π max(1, L_k / min_side) > max_cells), the least of
/// max(min_side, (Π L_k / max_cells)^(1/3)) × 1.0625^j, j = 0, 1, ..., that gives at most
/// max_cells. Cells numbered x fastest.
struct CoarseGrid {
  Vec3 lo;      ///< [m] lower corner of the box
  Vec3 length;  ///< [m] edge lengths of the box
  int n[3] = {1, 1, 1};
  bool periodic[3] = {false, false, false};

  /// A grid over `box` of cells at least `min_side` long along every axis (CoarseGrid.cpp).
  static CoarseGrid over(const PeriodicBox& box, Real min_side,
                         std::size_t max_cells = kMaxCoarseCells);

  std::size_t count() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) *
           static_cast<std::size_t>(n[2]);
  }
  GPUDEM_HD std::size_t index(int x, int y, int z) const {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(n[0]) *
               (static_cast<std::size_t>(y) + static_cast<std::size_t>(n[1]) * z);
  }
  std::array<int, 3> coords(std::size_t i) const {
    const std::size_t nx = static_cast<std::size_t>(n[0]), ny = static_cast<std::size_t>(n[1]);
    return {static_cast<int>(i % nx), static_cast<int>((i / nx) % ny),
            static_cast<int>(i / (nx * ny))};
  }
  /// [m] edge of a cell along axis k.
  GPUDEM_HD Real edge(int k) const { return axis(length, k) / n[k]; }
  /// Cell coordinate of x along k: wrapped on a periodic axis, clamped otherwise (so points
  /// slightly outside the box belong to the edge cells).
  GPUDEM_HD int coordinate(int k, Real x) const {
    Real t = (x - axis(lo, k)) / axis(length, k) * n[k];
    if (periodic[k]) t -= n[k] * floor(t / n[k]);
    t = t < Real(-1) ? Real(-1) : (t > Real(n[k]) ? Real(n[k]) : t);
    const int c = static_cast<int>(floor(t));
    return c < 0 ? 0 : (c > n[k] - 1 ? n[k] - 1 : c);
  }
  GPUDEM_HD std::size_t cell_of(Vec3 p) const {
    return index(coordinate(0, p.x), coordinate(1, p.y), coordinate(2, p.z));
  }
};

/// How far, in coarse cells along each axis, a point can lie from a cell within the ghost
/// width of it: the ghost width is at most one cell edge, and a point on a cell's lower face is
/// one edge from the cell two below.
constexpr int kGhostReachCells = 2;

/// The decomposition as one rank's engine reads it: the owner of each coarse cell, and which
/// cells lie within kGhostReachCells (periodic wrap) of a cell another rank owns, i.e. where
/// this rank's particles may be another rank's ghosts.
struct CellOwnership {
  CoarseGrid grid;
  std::vector<int> owner;                ///< owning rank of each coarse cell
  std::vector<std::uint8_t> near_other;  ///< 1 where another rank's cell is within reach
  std::uint64_t version = 0;             ///< changes whenever the map does
};

}  // namespace gpudem
