#include "core/InsertionTiles.hpp"

#include <algorithm>
#include <cmath>

namespace gpudem {

InsertionTiles::InsertionTiles(Vec3 lo, Vec3 hi, double min_edge) : lo_(lo), hi_(hi) {
  constexpr double kMaxTiles = 2147483647.0;
  double edge = min_edge;
  for (;;) {
    double tiles = 1;
    for (int k = 0; k < 3; ++k) {
      n_[k] =
          std::max<std::int64_t>(1, static_cast<std::int64_t>((axis(hi, k) - axis(lo, k)) / edge));
      tiles *= static_cast<double>(n_[k]);
    }
    if (tiles < kMaxTiles) break;
    edge *= std::cbrt(2 * tiles / kMaxTiles);
  }
  for (int k = 0; k < 3; ++k)
    axis(edge_, k) = (axis(hi, k) - axis(lo, k)) / static_cast<double>(n_[k]);
  slab_ = 0;
  for (int k = 1; k < 3; ++k)
    if (n_[k] > n_[slab_]) slab_ = k;
}

InsertionTiles::Coords InsertionTiles::coords(std::size_t tile) const {
  const int a = (slab_ + 1) % 3, b = (slab_ + 2) % 3;
  const auto na = static_cast<std::size_t>(n_[a]), nb = static_cast<std::size_t>(n_[b]);
  Coords c{};
  c[a] = static_cast<std::int64_t>(tile % na);
  c[b] = static_cast<std::int64_t>(tile / na % nb);
  c[slab_] = static_cast<std::int64_t>(tile / (na * nb));
  return c;
}

std::size_t InsertionTiles::index(const Coords& c) const {
  const int a = (slab_ + 1) % 3, b = (slab_ + 2) % 3;
  return static_cast<std::size_t>(c[a] + n_[a] * (c[b] + n_[b] * c[slab_]));
}

bool InsertionTiles::contains(const Coords& c) const {
  for (int k = 0; k < 3; ++k)
    if (c[k] < 0 || c[k] >= n_[k]) return false;
  return true;
}

Vec3 InsertionTiles::tile_lo(const Coords& c) const {
  Vec3 p;
  for (int k = 0; k < 3; ++k)
    axis(p, k) = axis(lo_, k) + static_cast<double>(c[k]) * axis(edge_, k);
  return p;
}

Vec3 InsertionTiles::tile_hi(const Coords& c) const {
  Vec3 p;
  for (int k = 0; k < 3; ++k)  // the last tile ends on the region's face exactly
    axis(p, k) = c[k] + 1 == n_[k] ? axis(hi_, k)
                                   : axis(lo_, k) + static_cast<double>(c[k] + 1) * axis(edge_, k);
  return p;
}

}  // namespace gpudem
