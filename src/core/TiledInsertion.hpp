#pragma once
/// Tiled random sequential insertion: a box source filled tile by tile, in parallel, giving the
/// same particles on any number of ranks and threads, each rank placing only its part.
///
/// The region is cut into a grid of equal tiles whose edges are at least the largest diameter
/// 2 r_max (sized for about kSpheresPerTile spheres each; core/InsertionTiles.hpp). A tile's
/// spheres have their centres in it, so they reach at most r_max beyond it: two tiles with a
/// tile between them never hold overlapping spheres. The tiles are coloured by the parities of
/// their three indices (8 colours, no two neighbours alike). Each tile draws its radii from its
/// own random stream and sorts them, largest first; then in each of kRounds rounds the tiles
/// of each colour in turn (one phase) place the round's run of their radii at random free
/// centres (random sequential insertion), avoiding the spheres already in the tile and its 26
/// neighbours and the earlier sources' particles. Tiles of one colour are independent, so a
/// phase fills them in any order, on any thread.
///
/// A part (rank `index` of `count`) owns a near-equal share of the layers of tiles across the
/// axis with the most tiles, and mirrors the layer next to its own on either side: after each
/// phase, the spheres that phase placed in a part's first and last layers go to the parts
/// beside it (TiledFill::boundary, TiledFill::receive). Every tile is thus filled with its
/// neighbours exactly as they are in the whole region at that phase.
///
/// The tile faces leave a faint mark: the large spheres keep a little away from them (about 2 %
/// less solid volume of centres within 1/16 of a tile of a face, validation.md). A tile's quota
/// cannot move to a neighbour with room, so the densest fill is a little below the sequential
/// placement's (0.38 by count for radii 1 ± 0.5 mm; tiles of 128 spheres failed at 0.36).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/InsertionTiles.hpp"
#include "core/ParticleStore.hpp"
#include "core/RowShare.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// Spheres a tile is sized for (its edges are at least 2 r_max).
inline constexpr double kSpheresPerTile = 512;
/// Rounds of the 8 colours; in round k every tile places the k-th of kRounds near-equal runs
/// of its radii, so the large spheres go first everywhere, as in the sequential placement.
inline constexpr int kRounds = 8;
/// Phases of a tiled placement: round p / 8, colour p % 8.
inline constexpr int kTilePhases = 8 * kRounds;

/// The tiles of box source `i` of `scene`: edges of at least 2 r_max and about kSpheresPerTile
/// spheres each (its count, or its volume to fill over the mean volume of 4096 radii drawn
/// from a stream of its own).
InsertionTiles insertion_tiles(const Scene& scene, std::size_t i);

/// A sphere placed in tile `tile` (its index in the grid) of a part's first or last layer.
struct BoundarySphere {
  std::uint64_t tile;
  Real4 sphere;
};

enum class LayerSide { Below, Above };

/// The layers of tiles (across the slab axis) that part `index` of `count` holds: its own
/// near-equal share, and the layer beside it on either side, mirrored from the nearest part
/// with layers there.
struct HeldLayers {
  RowRange own;                    ///< own layers (none for a part with fewer layers than parts)
  int neighbour[2] = {-1, -1};     ///< the parts owning the layers below and above; -1 for none
  std::size_t first = 0, end = 0;  ///< layers held, own and mirrored: [first, end)
};

/// The tiled placement of box source `i` by one part: its own layers of tiles and the layer
/// beside them on either side (mirrored from the parts that own them). Run the kTilePhases
/// phases in order on every part, passing each part's boundary spheres to its neighbours after
/// each phase, then take the particles with append_to.
class TiledFill {
 public:
  /// Part `part` of box source i of `scene` (checked by check_box_source); `earlier` holds the
  /// spheres to avoid (those of earlier sources), of which it copies the ones, and the periodic
  /// images in the domain (core/PeriodicImages.hpp), that reach a held tile widened by r_max
  /// (all of them that matter, when `earlier` holds every earlier sphere of which some image's
  /// box widened by r_max meets the held tiles).
  TiledFill(const Scene& scene, std::size_t i, FilePart part, const std::vector<Real4>& earlier);

  const InsertionTiles& tiles() const { return tiles_; }
  /// The part owning the layer beside this part's own on `side`; -1 for none (the region's end
  /// or a part without layers).
  int neighbour(LayerSide side) const { return held_.neighbour[static_cast<int>(side)]; }

  /// Phase `phase` (< kTilePhases, in order): the own tiles of its colour place its round's run
  /// of their radii, on all OpenMP threads.
  void fill_phase(int phase);
  /// The spheres the last phase placed in the own layer on `side` (for neighbour(side)).
  std::vector<BoundarySphere> boundary(LayerSide side) const;
  /// Adds to the mirrored layer on `side` the spheres that neighbour(side) placed there.
  void receive(LayerSide side, const std::vector<BoundarySphere>& spheres);

  /// Appends the own tiles' particles, tile by tile, with ids from `next_id`; velocity the
  /// source's, mass from its material. Throws InputError naming the source and the first own
  /// tile whose spheres found no room.
  void append_to(ParticleStore& store, ParticleId& next_id) const;

 private:
  struct Tile {
    std::vector<double> radii;         ///< largest first
    std::vector<Real4> spheres;        ///< placed so far
    std::vector<Real4> earlier;        ///< earlier sources' spheres that reach it
    std::size_t last_phase_first = 0;  ///< spheres placed before the tile's last phase
    bool stuck = false;                ///< a sphere found no free centre: it takes no more
  };

  void fill_tile(std::size_t t, int round);
  std::vector<Real4> neighbour_spheres_near(std::size_t t, Vec3 lo, Vec3 hi) const;
  void copy_earlier_spheres(const std::vector<Real4>& earlier);
  /// Adds sphere p to the earlier spheres of each held tile that it, widened by r_max, meets.
  void copy_to_tiles(const Real4& p);
  Tile& tile(std::size_t t) { return tiles_held_[t - first_held_]; }
  const Tile& tile(std::size_t t) const { return tiles_held_[t - first_held_]; }
  bool holds(std::size_t t) const {
    return t >= first_held_ && t < first_held_ + tiles_held_.size();
  }
  /// First tile of the own layer on `side`.
  std::size_t boundary_layer_first(LayerSide side) const;

  const Scene& scene_;
  const ParticleSource& src_;
  std::size_t index_;
  InsertionTiles tiles_;
  double r_min_, r_max_;
  HeldLayers held_;
  std::size_t own_first_ = 0, own_count_ = 0;  ///< own tiles (whole layers)
  std::size_t first_held_ = 0;                 ///< first tile held (own or mirrored)
  std::vector<Tile> tiles_held_;
  int last_colour_ = -1;
};

/// Tiled placement of box source `i` over its whole region, appending its particles to `out`
/// with ids from `next_id`, avoiding the spheres `avoid` (copied before any is appended): one
/// part, all phases.
void insert_tiled_box(const Scene& scene, std::size_t i, const std::vector<Real4>& avoid,
                      ParticleStore& out, ParticleId& next_id);

}  // namespace gpudem
