// Grid dims and cuts balanced by work, the load imbalance, and METIS parts.
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
