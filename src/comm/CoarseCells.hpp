#pragma once
/// Queries of the coarse cells that the decomposition (Decomposition.cpp) and its grid cuts and
/// METIS parts (GridCuts.cpp) share.
#include <array>
#include <cstddef>
#include <vector>

#include "engine/CoarseGrid.hpp"

namespace gpudem::coarse_cells {

/// Distinct cells adjacent to `cell` (26 neighbours, periodic wrap), without `cell` itself.
std::vector<std::size_t> adjacent_cells(const CoarseGrid& cells, std::size_t cell);

/// Fails unless cuts[k] are dims[k] + 1 strictly ascending boundaries from 0 to n[k].
void require_valid_cuts(const CoarseGrid& cells, const std::array<std::vector<int>, 3>& cuts);

/// Fails unless `cell_work` has one entry per coarse cell.
void require_cell_work(const CoarseGrid& cells, const std::vector<double>& cell_work);

}  // namespace gpudem::coarse_cells
