#pragma once
/// Overlap queries against a growing set of spheres, for random sequential insertion.
///
/// A hierarchical grid: level l has cubic cells of edge h_l = h_0 2^l with h_0 the smallest
/// diameter, and a sphere lives in the cell of its centre on the lowest level whose cell edge
/// is at least its diameter, so every cell holds a few spheres whatever the radius ratio. Cells
/// of all levels share one hash table of linked lists (Teschner et al., "Optimized spatial
/// hashing for collision detection of deformable objects", VMV 2003); a hash collision only
/// adds candidates, never hides one. A query visits, on each non-empty level, the cells within
/// r + R_l of the centre, R_l being the largest radius stored on that level.
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/Vec3.hpp"

namespace gpudem {

class SphereHash {
 public:
  /// Largest number of spheres one hash holds (indices are 32-bit).
  static constexpr std::size_t max_size = std::numeric_limits<std::uint32_t>::max() - 1;

  /// `min_radius` [m] > 0 sets the finest cell; `capacity` is the expected number of spheres
  /// (the table has at least twice as many buckets).
  SphereHash(double min_radius, std::size_t capacity) : finest_cell_(2 * min_radius) {
    if (!(min_radius > 0)) throw std::invalid_argument("SphereHash: min_radius must be > 0");
    if (capacity > max_size) throw std::length_error("SphereHash: capacity too large");
    std::size_t buckets = 1024;
    while (buckets < 2 * capacity) buckets *= 2;
    head_.assign(buckets, empty_);
    nodes_.reserve(capacity);
  }

  std::size_t size() const { return nodes_.size(); }

  void insert(Vec3 centre, double radius) {
    if (size() >= max_size) throw std::length_error("SphereHash: full");
    const int l = level_of(radius);
    level_count_[l] += 1;
    if (radius > level_max_radius_[l]) level_max_radius_[l] = radius;
    const double h = cell_edge(l);
    const std::size_t bucket =
        bucket_of(l, cell_of(centre.x, h), cell_of(centre.y, h), cell_of(centre.z, h));
    nodes_.push_back({centre.x, centre.y, centre.z, radius, head_[bucket]});
    head_[bucket] = static_cast<std::uint32_t>(nodes_.size() - 1);
  }

  /// True when a sphere at `centre` with `radius` would overlap a stored one:
  /// |x_i - x_j| < r_i + r_j (touching spheres do not overlap).
  bool overlaps(Vec3 centre, double radius) const {
    for (int l = levels_ - 1; l >= 0; --l)  // large spheres first: they reject most often
      if (level_count_[l] > 0 && overlaps_on_level(l, centre, radius)) return true;
    return false;
  }

 private:
  static constexpr int levels_ = 48;
  static constexpr std::uint32_t empty_ = std::numeric_limits<std::uint32_t>::max();

  double cell_edge(int l) const { return std::ldexp(finest_cell_, l); }

  /// Lowest level whose cell edge is at least the diameter (the top level takes the rest).
  int level_of(double radius) const {
    int l = 0;
    while (l + 1 < levels_ && cell_edge(l) < 2 * radius) ++l;
    return l;
  }

  static std::int64_t cell_of(double x, double h) {
    return static_cast<std::int64_t>(std::floor(x / h));
  }

  /// Bucket of cell (i, j, k) on level l. Cells next to each other along x get adjacent
  /// buckets, so a query reads each row of cells from one or two cache lines.
  std::size_t bucket_of(int l, std::int64_t i, std::int64_t j, std::int64_t k) const {
    std::uint64_t key = static_cast<std::uint64_t>(j) * 0x9E3779B97F4A7C15ull ^
                        static_cast<std::uint64_t>(k) * 0xC2B2AE3D27D4EB4Full ^
                        static_cast<std::uint64_t>(l) * 0x165667B19E3779F9ull;
    key ^= key >> 32;  // the table size is a power of two: fold the high bits in
    key *= 0xD6E8FEB86659FD93ull;
    key ^= key >> 29;
    return static_cast<std::size_t>((key + static_cast<std::uint64_t>(i)) & (head_.size() - 1));
  }

  bool overlaps_on_level(int l, Vec3 c, double radius) const {
    const double h = cell_edge(l);
    const double reach = radius + level_max_radius_[l];
    const std::int64_t x0 = cell_of(c.x - reach, h), x1 = cell_of(c.x + reach, h);
    const std::int64_t y0 = cell_of(c.y - reach, h), y1 = cell_of(c.y + reach, h);
    const std::int64_t z0 = cell_of(c.z - reach, h), z1 = cell_of(c.z + reach, h);
    // The candidate's own cell first: it holds the likeliest overlap.
    if (bucket_overlaps(bucket_of(l, cell_of(c.x, h), cell_of(c.y, h), cell_of(c.z, h)), c, radius))
      return true;
    for (std::int64_t k = z0; k <= z1; ++k)
      for (std::int64_t j = y0; j <= y1; ++j)
        for (std::int64_t i = x0; i <= x1; ++i)
          if (bucket_overlaps(bucket_of(l, i, j, k), c, radius)) return true;
    return false;
  }

  bool bucket_overlaps(std::size_t bucket, Vec3 c, double radius) const {
    for (std::uint32_t n = head_[bucket]; n != empty_; n = nodes_[n].next) {
      const Node& s = nodes_[n];
      const double dx = s.x - c.x, dy = s.y - c.y, dz = s.z - c.z;
      const double contact = s.radius + radius;
      if (dx * dx + dy * dy + dz * dz < contact * contact) return true;
    }
    return false;
  }

  /// A stored sphere and the next one in its bucket (one cache miss per candidate).
  struct Node {
    double x, y, z, radius;
    std::uint32_t next;
  };

  double finest_cell_;
  std::vector<std::uint32_t> head_;  ///< first sphere of each bucket
  std::vector<Node> nodes_;
  std::size_t level_count_[levels_] = {};
  double level_max_radius_[levels_] = {};
};

}  // namespace gpudem
