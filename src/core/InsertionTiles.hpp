#pragma once
/// The grid of tiles over a box region that tiled insertion fills (core/TiledInsertion.hpp).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/Vec3.hpp"

namespace gpudem {

/// The tile grid over a box region [lo, hi]: n[k] equal tiles along axis k, numbered fastest
/// along axis (slab + 1) % 3 and slowest along the slab axis, the one with the most tiles.
class InsertionTiles {
 public:
  using Coords = std::array<std::int64_t, 3>;

  /// Tiles of edge at least `min_edge` (fewer than 2^31 of them); one tile along an axis
  /// shorter than `min_edge`.
  InsertionTiles(Vec3 lo, Vec3 hi, double min_edge);

  std::size_t count() const { return layer_size() * static_cast<std::size_t>(n_[slab_]); }
  /// Tiles in one layer across the slab axis.
  std::size_t layer_size() const {
    return static_cast<std::size_t>(n_[(slab_ + 1) % 3]) *
           static_cast<std::size_t>(n_[(slab_ + 2) % 3]);
  }
  int slab_axis() const { return slab_; }
  std::int64_t along(int k) const { return n_[k]; }
  Coords coords(std::size_t tile) const;
  std::size_t index(const Coords& c) const;
  bool contains(const Coords& c) const;
  Vec3 tile_lo(const Coords& c) const;
  Vec3 tile_hi(const Coords& c) const;
  Vec3 lo() const { return lo_; }
  Vec3 hi() const { return hi_; }
  /// Index along axis k of the tiles whose slab holds coordinate x, ⌊(x − lo_k) / edge_k⌋
  /// (outside [0, along(k)) for x outside the region).
  std::int64_t index_along(int k, double x) const {
    return static_cast<std::int64_t>(std::floor((x - axis(lo_, k)) / axis(edge_, k)));
  }
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

}  // namespace gpudem
