#pragma once
/// Geometry of the domain decomposition (docs/architecture.md, "Ranks"): the coarse cells of the
/// global box (side at least the ghost width) and the map from each coarse cell to its owning rank,
/// built either as an X×Y×Z block grid or from any cell→rank map (METIS). Halo and migration ask
/// this map, so grid and METIS share one code path. Pure geometry: nothing here communicates.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/BinRegion.hpp"
#include "engine/CoarseGrid.hpp"
#include "engine/PeriodicBox.hpp"

namespace gpudem {

class Decomposition {
 public:
  /// Grid: cuts[k] holds dims[k] + 1 ascending coarse-cell boundaries, cuts[k][0] = 0,
  /// cuts[k].back() = n[k]; the rank of block (a, b, c) is a + dims0 * (b + dims1 * c).
  /// Throws std::invalid_argument for cuts that do not fit `cells`.
  static Decomposition grid(const CoarseGrid& cells, const std::array<std::vector<int>, 3>& cuts);
  /// Any cell -> rank map (METIS). owner.size() == cells.count(), values in [0, ranks); throws
  /// std::invalid_argument otherwise.
  static Decomposition from_owners(const CoarseGrid& cells, std::vector<int> owner, int ranks);

  int ranks() const { return ranks_; }
  const CoarseGrid& cells() const { return cells_; }
  bool is_grid() const { return is_grid_; }
  const std::array<std::vector<int>, 3>& cuts() const;  ///< grid only
  int owner_of_cell(std::size_t cell) const { return owner_[cell]; }
  int owner_of(Vec3 p) const { return owner_[cells_.cell_of(p)]; }

  /// Sets `out` to the ranks other than `rank` owning a coarse cell whose box lies within
  /// distance `reach` (inclusive) of p, periodic images of the cells included, ascending,
  /// without repeats. Requires reach <= the coarse cell edge along every axis of more than one
  /// cell (std::invalid_argument otherwise); p may lie outside the cell that owns it (it moved
  /// since) and outside the box, by up to reach. Cells are the
  /// boxes inside the global box: on a non-periodic axis nothing lies beyond its faces.
  void ghost_ranks(Vec3 p, int rank, Real reach, std::vector<int>& out) const;
  /// Ranks other than `rank` that own a coarse cell adjacent (26 neighbours, periodic wrap) to
  /// one of rank's cells, ascending.
  std::vector<int> neighbor_ranks(int rank) const;
  /// The map as `rank`'s engine reads it (CellOwnership): the owners, and near_other[c] = 1
  /// where a cell within kGhostReachCells of c along every axis (periodic wrap; nothing beyond
  /// a non-periodic face) belongs to another rank. ghost_ranks(p, rank, reach) is empty for
  /// every p whose cell_of(p) has near_other 0 (reach at most the cell edge, as ghost_ranks
  /// requires). version as given.
  CellOwnership ownership(int rank, std::uint64_t version) const;
  /// Where `rank` bins its particles. Per axis: the smallest interval of coarse cells holding
  /// all of rank's cells (circular on a periodic axis; of several equally short, the one
  /// starting at the lowest cell), grown by ghost_width on both sides, not clipped to the box. On a
  /// periodic axis where that grown length + cutoff >= L the region is the whole axis [lo, lo + L)
  /// and periodic. A rank with no cells gets the empty region: lo = the box's lo, length 0, not
  /// periodic.
  BinRegion region(int rank, Real ghost_width, Real cutoff) const;
  /// Per-rank sums of per-cell work (cell_work.size() == cells().count()).
  std::vector<double> rank_work(const std::vector<double>& cell_work) const;

 private:
  Decomposition(const CoarseGrid& cells, std::vector<int> owner, int ranks);

  CoarseGrid cells_;
  std::vector<int> owner_;  ///< owning rank of each coarse cell
  int ranks_ = 1;
  bool is_grid_ = false;
  std::array<std::vector<int>, 3> cuts_;
};

/// Load imbalance max / mean of rank_work: 1 when all equal, and 1 for zero total work.
double imbalance(const std::vector<double>& rank_work);

/// Grid dims for `ranks`. Given dims (non-zero) must multiply to ranks and fit the coarse cells
/// (dims[k] <= n[k]), else InputError naming scene_file, dims_line and "decomposition.dims".
/// All zero ("auto"): among all X*Y*Z = ranks with dims[k] <= n[k], the one with the least
/// internal cut area through the bed's bounding box [bed_lo, bed_hi] (each internal cut plane
/// across axis k has the area of the bed's extents along the other two axes; summed over cut
/// planes). When the bed is shallow (its extent along the dominant gravity axis is less than its
/// extents along both other axes) no factorisation cutting along gravity is taken unless none
/// other fits. Equal areas (to a relative 1e-9) go to fewer cuts along gravity, then along x,
/// then along y. No factorisation fits -> InputError saying how many ranks at most.
std::array<int, 3> choose_grid_dims(int ranks, Vec3 bed_lo, Vec3 bed_hi, Vec3 gravity,
                                    const CoarseGrid& cells, std::array<int, 3> given,
                                    const std::string& scene_file, int dims_line);

/// Grid cuts splitting the per-axis marginal sums of cell_work (per coarse cell) into dims[k]
/// contiguous parts, every block at least one coarse cell wide, with the largest part as small
/// as possible (the linear partition problem, solved exactly by dynamic programming). An axis
/// whose marginal work is all zero is split into equal cell counts.
std::array<std::vector<int>, 3> balanced_cuts(const CoarseGrid& cells, std::array<int, 3> dims,
                                              const std::vector<double>& cell_work);

/// Each internal cut plane moved toward equal marginal work by at most max_shift cells per call,
/// every block keeping at least one coarse cell (HOOMD-blue's load balancer rule: bounded moves,
/// never narrower than the ghost width = one coarse cell). Cut i of d aims at the boundary b
/// whose prefix work P(b) is nearest i/d of the axis total (ties: nearest the current cut). An
/// axis without work keeps its cuts. Returns new cuts.
std::array<std::vector<int>, 3> rebalance_cuts(const CoarseGrid& cells,
                                               const std::array<std::vector<int>, 3>& cuts,
                                               const std::vector<double>& cell_work, int max_shift);

/// Vertex weight of one unit of work in the METIS graph (an empty cell weighs 1); smaller when
/// the total work would overflow METIS's 32-bit weight sums.
constexpr double kMetisWorkScale = 64;

/// METIS_PartGraphKway of the coarse-cell graph (26-neighbour adjacency with periodic wrap, no
/// self or duplicate edges), vertex weight = 1 + round(kMetisWorkScale · cell_work): an empty
/// cell weighs as little as 1/kMetisWorkScale of a unit of work, so a bed filling a small part
/// of a large domain is still split by its work, and parts stay contiguous through empty cells;
/// deterministic (fixed METIS seed). ranks == 1: all zero. More ranks than cells:
/// std::invalid_argument. Returns the owner of each cell.
std::vector<int> metis_owners(const CoarseGrid& cells, const std::vector<double>& cell_work,
                              int ranks);

}  // namespace gpudem
