// Coarse cells, the cell -> rank map and its queries, grid dims and cuts, and METIS parts.
#include "comm/Decomposition.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "comm/CoarseCells.hpp"
#include "core/InputError.hpp"

namespace gpudem {

using coarse_cells::adjacent_cells;
using coarse_cells::require_cell_work;
using coarse_cells::require_valid_cuts;

namespace {

/// c reduced to [0, n).
int wrap_index(int c, int n) {
  c %= n;
  return c < 0 ? c + n : c;
}

/// Cell coordinate of neighbour offset `step` from c along axis k, or -1 beyond a non-periodic
/// face.
int neighbour_coordinate(const CoarseGrid& cells, int k, int c, int step) {
  const int m = c + step;
  if (cells.periodic[k]) return wrap_index(m, cells.n[k]);
  return m >= 0 && m < cells.n[k] ? m : -1;
}

/// Block index along axis k of coarse coordinate c: the i with cuts[i] <= c < cuts[i + 1].
int block_of(const std::vector<int>& cuts, int c) {
  return static_cast<int>(std::upper_bound(cuts.begin(), cuts.end(), c) - cuts.begin()) - 1;
}

/// Per-axis candidate cells within `reach` of x along axis k, each with its squared distance
/// along k to the nearest of its images: the unwrapped cells j whose interval [j, j + 1) lies
/// within reach/edge of x's coordinate t, wrapped on a periodic axis, dropped beyond a
/// non-periodic face. At most 4 distinct cells when reach <= edge (the j span 2 reach/edge + 2
/// integers at most) or when the axis has one cell.
struct AxisCandidates {
  int cell[4];
  Real distance2[4];
  int size = 0;

  /// Adds `c` at squared distance d2, or lowers the distance of `c` when already listed.
  void add(int c, Real d2) {
    for (int i = 0; i < size; ++i)
      if (cell[i] == c) {
        distance2[i] = std::min(distance2[i], d2);
        return;
      }
    cell[size] = c;
    distance2[size++] = d2;
  }
};

AxisCandidates axis_candidates(const CoarseGrid& cells, int k, Real x, Real reach) {
  const Real e = cells.edge(k);
  const Real t = (x - axis(cells.lo, k)) / e;
  const Real r = reach / e;
  AxisCandidates out;
  for (int j = static_cast<int>(std::ceil(t - r)) - 1; j <= static_cast<int>(std::floor(t + r));
       ++j) {
    const Real d = std::max({Real(0), j - t, t - (j + 1)}) * e;
    if (d > reach) continue;
    const int cell = cells.periodic[k] ? wrap_index(j, cells.n[k]) : j;
    if (cell >= 0 && cell < cells.n[k]) out.add(cell, d * d);
  }
  return out;
}

/// Coarse coordinates along axis k of the cells `rank` owns, as a flag per coordinate.
std::array<std::vector<char>, 3> occupied_coordinates(const CoarseGrid& cells,
                                                      const std::vector<int>& owner, int rank) {
  std::array<std::vector<char>, 3> used;
  for (int k = 0; k < 3; ++k) used[k].assign(static_cast<std::size_t>(cells.n[k]), 0);
  for (std::size_t i = 0; i < owner.size(); ++i) {
    if (owner[i] != rank) continue;
    const std::array<int, 3> c = cells.coords(i);
    for (int k = 0; k < 3; ++k) used[k][static_cast<std::size_t>(c[k])] = 1;
  }
  return used;
}

/// The shortest interval [first, first + count) of coordinates holding every flagged one:
/// circular (first + count may pass n) on a periodic axis, where it is the complement of the
/// longest circular run of unflagged coordinates (of those equally long, the one whose interval
/// starts at the lowest coordinate).
std::pair<int, int> covering_interval(const std::vector<char>& used, bool periodic) {
  const int n = static_cast<int>(used.size());
  if (!periodic) {
    const int first = static_cast<int>(std::find(used.begin(), used.end(), 1) - used.begin());
    const int last =
        n - 1 - static_cast<int>(std::find(used.rbegin(), used.rend(), 1) - used.rbegin());
    return {first, last - first + 1};
  }
  int best_gap = 0, best_end = 0;  // longest run of empty coordinates, ending before best_end
  for (int start = 0; start < n; ++start) {
    if (used[start] || used[wrap_index(start - 1, n)] == 0) continue;  // runs start after a used
    int length = 0;
    while (length < n && !used[wrap_index(start + length, n)]) ++length;
    const int end = wrap_index(start + length, n);
    if (length > best_gap || (length == best_gap && end < best_end)) {
      best_gap = length;
      best_end = end;
    }
  }
  return {best_end, n - best_gap};
}

/// Sorted `values` without repeats.
void sort_unique(std::vector<int>& values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
}

}  // namespace

namespace coarse_cells {

/// Distinct cells adjacent to `cell` (26 neighbours, periodic wrap), without `cell` itself.
std::vector<std::size_t> adjacent_cells(const CoarseGrid& cells, std::size_t cell) {
  const std::array<int, 3> c = cells.coords(cell);
  std::vector<std::size_t> result;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = neighbour_coordinate(cells, 0, c[0], dx);
        const int y = neighbour_coordinate(cells, 1, c[1], dy);
        const int z = neighbour_coordinate(cells, 2, c[2], dz);
        if (x < 0 || y < 0 || z < 0) continue;
        const std::size_t other = cells.index(x, y, z);
        if (other != cell) result.push_back(other);
      }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

/// Fails unless cuts[k] are dims[k] + 1 strictly ascending boundaries from 0 to n[k].
void require_valid_cuts(const CoarseGrid& cells, const std::array<std::vector<int>, 3>& cuts) {
  for (int k = 0; k < 3; ++k) {
    const std::vector<int>& c = cuts[k];
    const bool ascending =
        std::adjacent_find(c.begin(), c.end(), std::greater_equal<int>()) == c.end();
    if (c.size() < 2 || c.front() != 0 || c.back() != cells.n[k] || !ascending)
      throw std::invalid_argument(std::string("grid cuts along ") + "xyz"[k] +
                                  " must rise strictly from 0 to " + std::to_string(cells.n[k]));
  }
}

/// Fails unless `cell_work` has one entry per coarse cell.
void require_cell_work(const CoarseGrid& cells, const std::vector<double>& cell_work) {
  if (cell_work.size() != cells.count())
    throw std::invalid_argument("cell work has " + std::to_string(cell_work.size()) +
                                " entries for " + std::to_string(cells.count()) + " coarse cells");
}

}  // namespace coarse_cells

Decomposition::Decomposition(const CoarseGrid& cells, std::vector<int> owner, int ranks)
    : cells_(cells), owner_(std::move(owner)), ranks_(ranks) {}

Decomposition Decomposition::grid(const CoarseGrid& cells,
                                  const std::array<std::vector<int>, 3>& cuts) {
  require_valid_cuts(cells, cuts);
  const int dims0 = static_cast<int>(cuts[0].size()) - 1;
  const int dims1 = static_cast<int>(cuts[1].size()) - 1;
  const int dims2 = static_cast<int>(cuts[2].size()) - 1;
  std::vector<int> owner(cells.count());
  for (std::size_t i = 0; i < owner.size(); ++i) {
    const std::array<int, 3> c = cells.coords(i);
    owner[i] = block_of(cuts[0], c[0]) +
               dims0 * (block_of(cuts[1], c[1]) + dims1 * block_of(cuts[2], c[2]));
  }
  Decomposition d(cells, std::move(owner), dims0 * dims1 * dims2);
  d.is_grid_ = true;
  d.cuts_ = cuts;
  return d;
}

Decomposition Decomposition::from_owners(const CoarseGrid& cells, std::vector<int> owner,
                                         int ranks) {
  if (ranks < 1) throw std::invalid_argument("a decomposition needs at least one rank");
  if (owner.size() != cells.count())
    throw std::invalid_argument("owner map has " + std::to_string(owner.size()) + " entries for " +
                                std::to_string(cells.count()) + " coarse cells");
  for (int r : owner)
    if (r < 0 || r >= ranks)
      throw std::invalid_argument("owner " + std::to_string(r) + " is not a rank in [0, " +
                                  std::to_string(ranks) + ")");
  return Decomposition(cells, std::move(owner), ranks);
}

const std::array<std::vector<int>, 3>& Decomposition::cuts() const {
  if (!is_grid_) throw std::logic_error("cuts() of a decomposition that is not a grid");
  return cuts_;
}

void Decomposition::ghost_ranks(Vec3 p, int rank, Real reach, std::vector<int>& out) const {
  out.clear();
  for (int k = 0; k < 3; ++k)
    if (reach > cells_.edge(k) && cells_.n[k] > 1)
      throw std::invalid_argument("ghost reach exceeds the coarse cell edge");
  const AxisCandidates x = axis_candidates(cells_, 0, p.x, reach);
  const AxisCandidates y = axis_candidates(cells_, 1, p.y, reach);
  const AxisCandidates z = axis_candidates(cells_, 2, p.z, reach);
  const Real reach2 = reach * reach;
  for (int c = 0; c < z.size; ++c)
    for (int b = 0; b < y.size; ++b)
      for (int a = 0; a < x.size; ++a) {
        if (x.distance2[a] + y.distance2[b] + z.distance2[c] > reach2) continue;
        const int owner = owner_[cells_.index(x.cell[a], y.cell[b], z.cell[c])];
        if (owner != rank) out.push_back(owner);
      }
  sort_unique(out);
}

std::vector<int> Decomposition::neighbor_ranks(int rank) const {
  std::vector<int> result;
  for (std::size_t i = 0; i < owner_.size(); ++i) {
    if (owner_[i] != rank) continue;
    for (std::size_t j : adjacent_cells(cells_, i))
      if (owner_[j] != rank) result.push_back(owner_[j]);
  }
  sort_unique(result);
  return result;
}

namespace {

/// flag dilated along axis k by kGhostReachCells cells: out[c] = 1 where a cell of `flag` no
/// further than that along k (periodic wrap) is 1.
std::vector<std::uint8_t> dilated_along(const CoarseGrid& cells,
                                        const std::vector<std::uint8_t>& flag, int k) {
  std::vector<std::uint8_t> out(flag.size(), 0);
  for (std::size_t i = 0; i < flag.size(); ++i) {
    std::array<int, 3> c = cells.coords(i);
    const int centre = c[k];
    for (int step = -kGhostReachCells; step <= kGhostReachCells && out[i] == 0; ++step) {
      c[k] = neighbour_coordinate(cells, k, centre, step);
      if (c[k] >= 0 && flag[cells.index(c[0], c[1], c[2])] != 0) out[i] = 1;
    }
  }
  return out;
}

}  // namespace

CellOwnership Decomposition::ownership(int rank, std::uint64_t version) const {
  CellOwnership map;
  map.grid = cells_;
  map.owner = owner_;
  map.version = version;
  std::vector<std::uint8_t> other(owner_.size());
  for (std::size_t i = 0; i < owner_.size(); ++i) other[i] = owner_[i] != rank ? 1 : 0;
  for (int k = 0; k < 3; ++k) other = dilated_along(cells_, other, k);
  map.near_other = std::move(other);
  return map;
}

BinRegion Decomposition::region(int rank, Real ghost_width, Real cutoff) const {
  BinRegion r;
  r.lo = cells_.lo;
  if (std::find(owner_.begin(), owner_.end(), rank) == owner_.end()) return r;
  const std::array<std::vector<char>, 3> used = occupied_coordinates(cells_, owner_, rank);
  for (int k = 0; k < 3; ++k) {
    const std::pair<int, int> span = covering_interval(used[k], cells_.periodic[k]);
    const Real e = cells_.edge(k), L = axis(cells_.length, k);
    const Real grown = span.second * e + 2 * ghost_width;
    if (cells_.periodic[k] && grown + cutoff >= L) {
      axis(r.lo, k) = axis(cells_.lo, k);
      axis(r.length, k) = L;
      r.periodic[k] = true;
    } else {
      axis(r.lo, k) = axis(cells_.lo, k) + span.first * e - ghost_width;
      axis(r.length, k) = grown;
    }
  }
  return r;
}

std::vector<double> Decomposition::rank_work(const std::vector<double>& cell_work) const {
  require_cell_work(cells_, cell_work);
  std::vector<double> work(static_cast<std::size_t>(ranks_), 0.0);
  for (std::size_t i = 0; i < cell_work.size(); ++i)
    work[static_cast<std::size_t>(owner_[i])] += cell_work[i];
  return work;
}

}  // namespace gpudem
