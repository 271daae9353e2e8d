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

#include "core/InputError.hpp"

namespace gpudem {
namespace {

/// c reduced to [0, n).
int wrap_index(int c, int n) {
  c %= n;
  return c < 0 ? c + n : c;
}

/// max(1, floor(L / s)), corrected where the quotient rounds across an integer so that the
/// cell edge L / n, as computed, is >= s and L / (n + 1) is not.
int most_cells(Real L, Real s) {
  int n = std::max(1, static_cast<int>(std::floor(L / s)));
  if (n > 1 && L / n < s) --n;
  if (L / (n + 1) >= s) ++n;
  return n;
}

/// Cell coordinate of neighbour offset `step` from c along axis k, or -1 beyond a non-periodic
/// face.
int neighbour_coordinate(const CoarseGrid& cells, int k, int c, int step) {
  const int m = c + step;
  if (cells.periodic[k]) return wrap_index(m, cells.n[k]);
  return m >= 0 && m < cells.n[k] ? m : -1;
}

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

/// Sorted `values` without repeats.
void sort_unique(std::vector<int>& values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
}

void require_cell_work(const CoarseGrid& cells, const std::vector<double>& cell_work) {
  if (cell_work.size() != cells.count())
    throw std::invalid_argument("cell work has " + std::to_string(cell_work.size()) +
                                " entries for " + std::to_string(cells.count()) + " coarse cells");
}

/// Per-axis marginal sums of cell_work: m[k][c] = work of all cells with coordinate c along k.
std::array<std::vector<double>, 3> marginal_work(const CoarseGrid& cells,
                                                 const std::vector<double>& cell_work) {
  require_cell_work(cells, cell_work);
  std::array<std::vector<double>, 3> m;
  for (int k = 0; k < 3; ++k) m[k].assign(static_cast<std::size_t>(cells.n[k]), 0.0);
  for (std::size_t i = 0; i < cell_work.size(); ++i) {
    const std::array<int, 3> c = cells.coords(i);
    for (int k = 0; k < 3; ++k) m[k][static_cast<std::size_t>(c[k])] += cell_work[i];
  }
  return m;
}

/// Prefix sums P[b] = work of cells [0, b), b = 0..n.
std::vector<double> prefix_sums(const std::vector<double>& work) {
  std::vector<double> prefix(work.size() + 1, 0.0);
  std::partial_sum(work.begin(), work.end(), prefix.begin() + 1);
  return prefix;
}

/// Boundaries 0 = b_0 < ... < b_parts = n splitting `work` into contiguous parts, the largest
/// part as small as possible: best[i][j] = min over p of max(best[i-1][p], P[j] - P[p]) (the
/// linear partition problem; Skiena, The Algorithm Design Manual, §8.5). Needs parts <= n.
std::vector<int> min_max_partition(const std::vector<double>& work, int parts) {
  const int n = static_cast<int>(work.size());
  const std::vector<double> prefix = prefix_sums(work);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> best(parts + 1, std::vector<double>(n + 1, inf));
  std::vector<std::vector<int>> split(parts + 1, std::vector<int>(n + 1, 0));
  best[0][0] = 0;
  for (int i = 1; i <= parts; ++i)
    for (int j = i; j <= n - (parts - i); ++j)
      for (int p = i - 1; p < j; ++p) {
        const double largest = std::max(best[i - 1][p], prefix[j] - prefix[p]);
        if (largest < best[i][j]) {
          best[i][j] = largest;
          split[i][j] = p;
        }
      }
  std::vector<int> cuts(parts + 1, n);
  for (int i = parts; i > 0; --i) cuts[i - 1] = split[i][cuts[i]];
  return cuts;
}

/// The boundary b in [lo, hi] whose prefix work is nearest `target`, ties going to the one
/// nearest `current`.
int nearest_boundary(const std::vector<double>& prefix, double target, int lo, int hi,
                     int current) {
  int chosen = lo;
  for (int b = lo + 1; b <= hi; ++b) {
    const double d = std::abs(prefix[b] - target), d_chosen = std::abs(prefix[chosen] - target);
    if (d < d_chosen || (d == d_chosen && std::abs(b - current) < std::abs(chosen - current)))
      chosen = b;
  }
  return chosen;
}

/// `cuts` made strictly increasing with 0 and n kept at the ends: each internal cut at least
/// one above the one before it and one below the one after it. Needs cuts.size() - 1 <= n.
void enforce_min_width(std::vector<int>& cuts) {
  const std::size_t last = cuts.size() - 1;
  for (std::size_t i = 1; i < last; ++i) cuts[i] = std::max(cuts[i], cuts[i - 1] + 1);
  for (std::size_t i = last - 1; i >= 1; --i) cuts[i] = std::min(cuts[i], cuts[i + 1] - 1);
}

/// One axis of rebalance_cuts.
std::vector<int> rebalance_axis(const std::vector<double>& work, const std::vector<int>& cuts,
                                int max_shift) {
  const std::vector<double> prefix = prefix_sums(work);
  const double total = prefix.back();
  if (!(total > 0)) return cuts;
  const int parts = static_cast<int>(cuts.size()) - 1;
  const int n = static_cast<int>(work.size());
  std::vector<int> moved = cuts;
  for (int i = 1; i < parts; ++i) {
    const int target = nearest_boundary(prefix, total * i / parts, 1, n - 1, cuts[i]);
    moved[i] = std::clamp(target, cuts[i] - max_shift, cuts[i] + max_shift);
  }
  enforce_min_width(moved);
  return moved;
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

/// Cut area of dims through a bed of extents E: sum over axes of (dims[k] - 1) times the area
/// of the bed's cross-section across k.
double cut_area(const std::array<int, 3>& dims, Vec3 extent) {
  double area = 0;
  for (int k = 0; k < 3; ++k)
    area += (dims[k] - 1) * axis(extent, (k + 1) % 3) * axis(extent, (k + 2) % 3);
  return area;
}

/// Axis of the largest gravity component, or -1 without gravity.
int gravity_axis(Vec3 gravity) {
  int g = -1;
  Real largest = 0;
  for (int k = 0; k < 3; ++k)
    if (std::abs(axis(gravity, k)) > largest) {
      largest = std::abs(axis(gravity, k));
      g = k;
    }
  return g;
}

/// A bed is shallow when its extent along gravity axis g is below both other extents.
bool is_shallow(Vec3 extent, int g) {
  if (g < 0) return false;
  const Real e = axis(extent, g);
  return e < axis(extent, (g + 1) % 3) && e < axis(extent, (g + 2) % 3);
}

/// Every X*Y*Z = ranks with dims[k] <= n[k].
std::vector<std::array<int, 3>> fitting_factorisations(int ranks, const CoarseGrid& cells) {
  std::vector<std::array<int, 3>> result;
  for (int x = 1; x <= std::min(ranks, cells.n[0]); ++x) {
    if (ranks % x) continue;
    for (int y = 1; y <= std::min(ranks / x, cells.n[1]); ++y) {
      if ((ranks / x) % y) continue;
      const int z = ranks / x / y;
      if (z <= cells.n[2]) result.push_back({x, y, z});
    }
  }
  return result;
}

std::string dims_text(const std::array<int, 3>& d) {
  return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]);
}

std::string cells_text(const CoarseGrid& cells) {
  return dims_text({cells.n[0], cells.n[1], cells.n[2]}) +
         " coarse cells (side >= ghost width; every block needs at least one)";
}

/// Checks given dims against the rank count and the coarse cells.
void require_given_dims(int ranks, const CoarseGrid& cells, const std::array<int, 3>& given,
                        const std::string& scene_file, int dims_line) {
  const std::string key = "decomposition.dims";
  if (given[0] * given[1] * given[2] != ranks)
    throw InputError(scene_file, dims_line, key,
                     "dims " + dims_text(given) + " make " +
                         std::to_string(given[0] * given[1] * given[2]) +
                         " blocks, but the run has " + std::to_string(ranks) + " ranks");
  for (int k = 0; k < 3; ++k)
    if (given[k] < 1 || given[k] > cells.n[k])
      throw InputError(scene_file, dims_line, key,
                       "dims " + dims_text(given) + " do not fit the box's " + cells_text(cells));
}

/// True when a is the better of two dims of equal cut area: fewer cuts along gravity axis g,
/// then along x, then along y.
bool preferred_on_tie(const std::array<int, 3>& a, const std::array<int, 3>& b, int g) {
  if (g >= 0 && a[g] != b[g]) return a[g] < b[g];
  if (a[0] != b[0]) return a[0] < b[0];
  return a[1] < b[1];
}

}  // namespace

CoarseGrid CoarseGrid::over(const PeriodicBox& box, Real min_side, std::size_t max_cells) {
  if (!(min_side > 0)) throw std::invalid_argument("coarse cell side must be > 0");
  if (max_cells < 1) throw std::invalid_argument("coarse cells: at most 0 cells asked for");
  const auto cells_of_side = [&box](Real side) {
    CoarseGrid g;
    g.lo = box.lo;
    g.length = box.length;
    for (int k = 0; k < 3; ++k) {
      g.n[k] = most_cells(axis(box.length, k), side);
      g.periodic[k] = box.periodic[k];
    }
    return g;
  };
  Real natural = 1, volume = 1;  // in floating point: the natural counts may not fit an int
  for (int k = 0; k < 3; ++k) {
    natural *= std::max(Real(1), axis(box.length, k) / min_side);
    volume *= axis(box.length, k);
  }
  Real side = min_side;
  if (natural > static_cast<Real>(max_cells))
    side = std::max(min_side, std::cbrt(volume / static_cast<Real>(max_cells)));
  CoarseGrid g = cells_of_side(side);
  while (g.count() > max_cells) {
    side *= Real(1.0625);
    g = cells_of_side(side);
  }
  return g;
}

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

double imbalance(const std::vector<double>& rank_work) {
  const double total = std::accumulate(rank_work.begin(), rank_work.end(), 0.0);
  if (!(total > 0)) return 1;
  const double largest = *std::max_element(rank_work.begin(), rank_work.end());
  return largest * static_cast<double>(rank_work.size()) / total;
}

std::array<int, 3> choose_grid_dims(int ranks, Vec3 bed_lo, Vec3 bed_hi, Vec3 gravity,
                                    const CoarseGrid& cells, std::array<int, 3> given,
                                    const std::string& scene_file, int dims_line) {
  if (given != std::array<int, 3>{0, 0, 0}) {
    require_given_dims(ranks, cells, given, scene_file, dims_line);
    return given;
  }
  std::vector<std::array<int, 3>> options = fitting_factorisations(ranks, cells);
  if (options.empty())
    throw InputError(scene_file, dims_line, "decomposition.dims",
                     "no grid of " + std::to_string(ranks) + " blocks fits the box's " +
                         cells_text(cells) + ": a grid takes at most " +
                         std::to_string(cells.count()) +
                         " ranks here, in counts X*Y*Z with X, Y, Z at most " +
                         dims_text({cells.n[0], cells.n[1], cells.n[2]}));
  const Vec3 extent = bed_hi - bed_lo;
  const int g = gravity_axis(gravity);
  const auto cuts_gravity = [g](const std::array<int, 3>& d) { return d[g] > 1; };
  if (is_shallow(extent, g) && !std::all_of(options.begin(), options.end(), cuts_gravity))
    options.erase(std::remove_if(options.begin(), options.end(), cuts_gravity), options.end());
  std::array<int, 3> best = options.front();
  for (const std::array<int, 3>& d : options) {
    const double area = cut_area(d, extent), best_area = cut_area(best, extent);
    const bool tie = std::abs(area - best_area) <= 1e-9 * std::max(area, best_area);
    if (tie ? preferred_on_tie(d, best, g) : area < best_area) best = d;
  }
  return best;
}

std::array<std::vector<int>, 3> balanced_cuts(const CoarseGrid& cells, std::array<int, 3> dims,
                                              const std::vector<double>& cell_work) {
  const std::array<std::vector<double>, 3> marginal = marginal_work(cells, cell_work);
  std::array<std::vector<int>, 3> cuts;
  for (int k = 0; k < 3; ++k) {
    if (dims[k] < 1 || dims[k] > cells.n[k])
      throw std::invalid_argument(std::string("grid dims along ") + "xyz"[k] + " must lie in [1, " +
                                  std::to_string(cells.n[k]) + "]");
    const bool empty = !(std::accumulate(marginal[k].begin(), marginal[k].end(), 0.0) > 0);
    cuts[k] = min_max_partition(empty ? std::vector<double>(marginal[k].size(), 1.0) : marginal[k],
                                dims[k]);
  }
  return cuts;
}

std::array<std::vector<int>, 3> rebalance_cuts(const CoarseGrid& cells,
                                               const std::array<std::vector<int>, 3>& cuts,
                                               const std::vector<double>& cell_work,
                                               int max_shift) {
  require_valid_cuts(cells, cuts);
  if (max_shift < 0) throw std::invalid_argument("max_shift must be >= 0");
  const std::array<std::vector<double>, 3> marginal = marginal_work(cells, cell_work);
  std::array<std::vector<int>, 3> moved;
  for (int k = 0; k < 3; ++k) moved[k] = rebalance_axis(marginal[k], cuts[k], max_shift);
  return moved;
}

/// Total vertex weight METIS may sum without overflowing a 32-bit idx_t, with room for the
/// empty cells' unit weights.
constexpr double kMetisWeightBudget = 1.0e9;

std::vector<int> metis_owners(const CoarseGrid& cells, const std::vector<double>& cell_work,
                              int ranks) {
  require_cell_work(cells, cell_work);
  if (ranks < 1) throw std::invalid_argument("METIS needs at least one part");
  if (static_cast<std::size_t>(ranks) > cells.count())
    throw std::invalid_argument(std::to_string(ranks) + " ranks for only " +
                                std::to_string(cells.count()) +
                                " coarse cells: every rank needs at least one cell");
  if (ranks == 1) return std::vector<int>(cells.count(), 0);
  // METIS sums the weights in idx_t (32 bits here): large beds get a smaller scale.
  double total = 0;
  for (const double w : cell_work) total += w;
  const double scale = std::min(kMetisWorkScale, kMetisWeightBudget / std::max(total, 1.0));
  std::vector<idx_t> xadj{0}, adjncy, vwgt;
  for (std::size_t i = 0; i < cells.count(); ++i) {
    for (std::size_t j : adjacent_cells(cells, i)) adjncy.push_back(static_cast<idx_t>(j));
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
    vwgt.push_back(static_cast<idx_t>(1 + std::llround(scale * cell_work[i])));
  }
  idx_t vertices = static_cast<idx_t>(cells.count()), constraints = 1, parts = ranks, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  std::vector<idx_t> part(cells.count());
  const int status =
      METIS_PartGraphKway(&vertices, &constraints, xadj.data(), adjncy.data(), vwgt.data(), nullptr,
                          nullptr, &parts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK)
    throw std::runtime_error("METIS_PartGraphKway failed with status " + std::to_string(status));
  return std::vector<int>(part.begin(), part.end());
}

}  // namespace gpudem
