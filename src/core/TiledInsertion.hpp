#pragma once
/// Tiled random sequential insertion: a box source filled tile by tile, in parallel, giving the
/// same particles on any number of ranks and threads, each rank creating only its part.
///
/// The region is cut into a grid of equal tiles whose edges are at least the largest diameter
/// 2 r_max (sized for about kSpheresPerTile spheres each). A tile's spheres have their centres
/// in it, so they reach at most r_max beyond it: two tiles with a tile between them can never
/// hold overlapping spheres. The tiles are coloured by the parity of their three indices
/// (8 colours, no two tiles of one colour adjacent). Each tile draws its radii from its own
/// random stream and sorts them, largest first; then, in each of kRounds rounds, the tiles of
/// each colour in turn place the round's run of their radii at random free centres (random
/// sequential insertion), avoiding the spheres already placed in the tile and its 26
/// neighbours and the store's earlier particles. Tiles of one colour are independent, so they
/// fill in any order on any thread.
///
/// A part (rank `index` of `count`) owns a near-equal share of the tiles in their order, which
/// runs slowest along the axis with the most tiles (layers across that slab axis). A tile
/// depends on the lower-coloured neighbours of its round and on all neighbours of earlier
/// rounds. The slab axis' parity is the colour's highest bit, so along a chain of dependencies
/// it drops at most once within a round, and a chain crosses at most 2 kRounds - 1 layers:
/// a part fills its own layers and that many either side, and its own tiles come out exactly
/// as in the whole region.
///
/// The tile faces leave a mark: over 4 × 10^5 spheres of radius 1 ± 0.5 mm at a solid
/// fraction of 0.3, the solid volume of the centres lying within 1/16 of a tile of its faces
/// is 1.5 % below the mean (8 % with one round). Tiles sized for 512 spheres reach a solid
/// fraction of 0.38, as the sequential placement does (tiles of 128: below 0.34).
#include <array>
#include <cstddef>
#include <cstdint>

#include "core/ParticleStore.hpp"
#include "core/RowShare.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// Spheres a tile is sized for (its edges are at least 2 r_max).
inline constexpr double kSpheresPerTile = 512;
/// Rounds of the 8 colours; in round k every tile places the k-th of kRounds near-equal runs
/// of its radii, largest first, so large spheres go first everywhere, as in the sequential
/// placement.
inline constexpr int kRounds = 8;
/// Layers of tiles a part fills beyond its own on either side (see above).
inline constexpr int kTileMarginLayers = 2 * kRounds - 1;

/// The tile grid over a box region [lo, hi]: n[k] equal tiles along axis k, in the order that
/// runs fastest along axis (slab + 1) % 3 and slowest along `slab`.
class InsertionTiles {
 public:
  using Coords = std::array<std::int64_t, 3>;

  /// Tiles of edge at least `min_edge` (fewer than 2^31 of them); one tile along an axis
  /// shorter than `min_edge`.
  InsertionTiles(Vec3 lo, Vec3 hi, double min_edge);

  std::size_t count() const { return layer_size() * static_cast<std::size_t>(n_[slab_]); }
  /// Tiles in one layer across the slab axis.
  std::size_t layer_size() const {
    return static_cast<std::size_t>(n_[(slab_ + 1) % 3]) * static_cast<std::size_t>(n_[(slab_ + 2) % 3]);
  }
  int slab_axis() const { return slab_; }
  std::int64_t along(int k) const { return n_[k]; }
  Coords coords(std::size_t tile) const;
  std::size_t index(const Coords& c) const;
  bool contains(const Coords& c) const;
  Vec3 tile_lo(const Coords& c) const;
  Vec3 tile_hi(const Coords& c) const;
  Vec3 lo() const { return lo_; }
  Vec3 edge() const { return edge_; }
  double tile_volume() const { return edge_.x * edge_.y * edge_.z; }
  /// Colour 0..7 of a tile: the parities of its indices, the slab axis' the highest bit.
  int colour(const Coords& c) const {
    return static_cast<int>((c[(slab_ + 1) % 3] & 1) | (c[(slab_ + 2) % 3] & 1) << 1 |
                            (c[slab_] & 1) << 2);
  }

 private:
  Vec3 lo_, hi_, edge_;
  Coords n_{};
  int slab_ = 2;
};

/// The tiles of box source `i` of `scene`: edges of at least 2 r_max and about kSpheresPerTile
/// spheres each (its count, or its volume to fill over the mean volume of 4096 radii drawn from
/// a stream of its own).
InsertionTiles insertion_tiles(const Scene& scene, std::size_t i);

/// Tiled placement of box source `i` of `scene` (checked by the caller: material, distribution,
/// size): appends the particles of `part`'s tiles, tile by tile, with ids from `next_id`.
/// The particles of all parts in order are those of the whole region (part {0, 1}), whatever
/// the number of parts and threads. A tile's radii are `count` shared out over the tiles
/// (⌊N (t+1)/T⌋ − ⌊N t/T⌋ for tile t of T) or drawn until their volume reaches
/// volume_fraction × the tile's volume, placed largest first. Spheres of `store` that reach
/// into the region are avoided. Throws InputError naming the source and the first tile of the
/// part that could not hold its spheres.
void insert_tiled_box(const Scene& scene, std::size_t i, FilePart part, ParticleStore& store,
                      ParticleId& next_id);

}  // namespace gpudem
