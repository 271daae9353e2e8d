#pragma once
/// The decomposition's cell map in the engine's memory space (docs/architecture.md, "One time
/// step"–5), so that a rebuild finds on the device the owned particles that leave for another rank
/// and the few that may be another rank's ghosts; only those travel to the host.
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/ArrayKernels.hpp"
#include "engine/CoarseGrid.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/ParallelFor.hpp"
#include "engine/PeriodicBox.hpp"
#include "engine/Permute.hpp"

namespace gpudem {

/// CellOwnership as kernels read it (pointers into Space memory); owner null on one rank.
struct RankCellsView {
  CoarseGrid grid;
  const int* owner = nullptr;
  const std::uint8_t* near_other = nullptr;
  int rank = 0;  ///< this rank
};

namespace rank_cell_kernels {

/// The relocation key of owned particle i at a rebuild: `removed` when it lies outside the
/// non-periodic box, else 0 when this rank owns its position and 1 + its owner otherwise;
/// index[i] = i. `removed` is the rank count + 1, above every owner's key, so a stable sort by
/// these keys keeps the staying particles first in their order, groups the leaving ones by
/// destination after them and puts the removed ones last. A view without an owner map (one
/// rank) owns every cell.
template <class P>
struct RelocationKey {
  RankCellsView cells;
  PeriodicBox box;
  std::uint64_t removed;
  const Vec4T<P>* position_radius;
  std::uint64_t* key;
  std::uint32_t* index;
  GPUDEM_HD void operator()(std::size_t i) const {
    const Vec3 x = vec_cast<Real>(xyz(position_radius[i]));
    std::uint64_t k = 0;
    if (box.outside(x)) {
      k = removed;
    } else if (cells.owner != nullptr) {
      const int owner = cells.owner[cells.grid.cell_of(x)];
      k = owner == cells.rank ? 0 : 1 + static_cast<std::uint64_t>(owner);
    }
    key[i] = k;
    index[i] = static_cast<std::uint32_t>(i);
  }
};

/// 1 for a key at least `least`, else 0, for reduce_sum.
struct KeyAtLeast {
  const std::uint64_t* key;
  std::uint64_t least;
  GPUDEM_HD Real operator()(std::size_t i) const { return key[i] >= least ? Real(1) : Real(0); }
};

/// flag[i] = 1 when particle i (i < n) lies in a cell near another rank's, else 0; flag[n] = 0.
template <class P>
struct NearOtherRank {
  RankCellsView cells;
  const Vec4T<P>* position_radius;
  std::size_t n;
  std::uint32_t* flag;
  GPUDEM_HD void operator()(std::size_t i) const {
    flag[i] =
        i < n && cells.near_other[cells.grid.cell_of(vec_cast<Real>(xyz(position_radius[i])))] != 0
            ? 1
            : 0;
  }
};

/// out[before[i]] = i where before[i + 1] != before[i] (the exclusive scan of 0/1 flags).
struct ScatterFlagged {
  const std::uint32_t* before;
  std::uint32_t* out;
  GPUDEM_HD void operator()(std::size_t i) const {
    if (before[i + 1] != before[i]) out[before[i]] = static_cast<std::uint32_t>(i);
  }
};

}  // namespace rank_cell_kernels

/// A device copy of a DomainLink's CellOwnership, uploaded again only when its version changes.
template <class Space>
class RankCells {
 public:
  void update(const CellOwnership& map, int rank) {
    if (map.version == version_ && rank == rank_) return;
    grid_ = map.grid;
    owner_.upload(map.owner);
    near_other_.upload(map.near_other);
    version_ = map.version;
    rank_ = rank;
  }

  RankCellsView view() const {
    return RankCellsView{grid_, owner_.data(), near_other_.data(), rank_};
  }

  /// Host copies of the positions of the particles among [0, n) that lie in a cell near another
  /// rank's, with their indices, ascending.
  template <class P>
  void near_other_rank(const Vec4T<P>* position_radius, std::size_t n,
                       std::vector<std::uint32_t>& index, std::vector<Vec4T<P>>& position) const {
    DeviceArray<std::uint32_t, Space> before(n + 1);
    parallel_for(Space{}, n + 1,
                 rank_cell_kernels::NearOtherRank<P>{view(), position_radius, n, before.data()});
    const std::size_t count = exclusive_scan(Space{}, before.data(), before.data(), n + 1);
    DeviceArray<std::uint32_t, Space> selected(count);
    parallel_for(Space{}, n, rank_cell_kernels::ScatterFlagged{before.data(), selected.data()});
    DeviceArray<Vec4T<P>, Space> gathered(count);
    parallel_for(Space{}, count,
                 GatherByOrder<Vec4T<P>>{selected.data(), position_radius, gathered.data()});
    selected.download(index);
    gathered.download(position);
  }

  /// Bytes held in Space memory.
  std::size_t memory_bytes() const { return owner_.bytes() + near_other_.bytes(); }

 private:
  CoarseGrid grid_;
  DeviceArray<int, Space> owner_;
  DeviceArray<std::uint8_t, Space> near_other_;
  std::uint64_t version_ = std::numeric_limits<std::uint64_t>::max();  ///< none yet
  int rank_ = -1;
};

}  // namespace gpudem
