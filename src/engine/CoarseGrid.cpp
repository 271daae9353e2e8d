// The coarse cells over a box.
#include "engine/CoarseGrid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gpudem {
namespace {

/// max(1, floor(L / s)), corrected where the quotient rounds across an integer so that the
/// cell edge L / n, as computed, is >= s and L / (n + 1) is not.
int most_cells(Real L, Real s) {
  int n = std::max(1, static_cast<int>(std::floor(L / s)));
  if (n > 1 && L / n < s) --n;
  if (L / (n + 1) >= s) ++n;
  return n;
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

}  // namespace gpudem
