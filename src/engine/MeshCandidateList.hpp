#pragma once
/// Per-particle lists of the mesh triangles that may touch it before the next rebuild, in CSR
/// form: the triangles of particle i are triangles()[offsets()[i] .. offsets()[i + 1]), each
/// once, in increasing triangle index, so a particle's list (and every sum over it) does not
/// depend on the grid, the particle order or the rank. Triangle t is listed for particle i
/// when the distance from i's centre to t is below r_i + skin: valid while the particle and
/// the mesh each move less than skin / 2.
///
/// Search (docs/architecture.md, "Triangle meshes (STL)", plan then execute): triangles are binned
/// by their bounding boxes in a uniform grid over the mesh, cells at least as large as the largest
/// reach; a particle then scans the at most 2 × 2 × 2 cells its reach box overlaps, and takes a
/// triangle only from the lowest cell shared by the triangle's box and its own, so no triangle is
/// seen twice. A rank bins only the triangles whose boxes meet its bin region (the box, or its
/// block grown by the ghost width) grown by the largest reach. In a box with periodic axes a
/// particle meets each mesh as its periodic image nearest the mesh's image centre (MeshImages), so
/// a particle queries the grid once per mesh, and a rank bins the triangles that meet its region or
/// one of its periodic images.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/ArrayKernels.hpp"
#include "engine/BinRegion.hpp"
#include "engine/CellList.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/ParallelFor.hpp"
#include "engine/TriangleContact.hpp"

namespace gpudem {

/// Vertex ids of one triangle, indices into the mesh's vertex array.
struct TriangleCorners {
  std::uint32_t v[3];
};

/// How particles meet the meshes: on the periodic axes of `box`, mesh m meets the periodic image
/// of a particle nearest image_centre[m] (PeriodicBox::image_near). Without periodic axes, plain
/// positions and one query over all meshes.
struct MeshImages {
  PeriodicBox box;
  std::uint32_t mesh_count = 0;
  const std::uint32_t* triangle_mesh = nullptr;  ///< mesh of each triangle
  const Vec3* image_centre = nullptr;            ///< per mesh [m]
};

/// Accepts every triangle.
struct AnyTriangle {
  GPUDEM_HD bool operator()(std::uint32_t) const { return true; }
};

/// Accepts the triangles of one mesh.
struct TrianglesOfMesh {
  const std::uint32_t* triangle_mesh;
  std::uint32_t mesh;
  GPUDEM_HD bool operator()(std::uint32_t t) const { return triangle_mesh[t] == mesh; }
};

/// The uniform grid over the meshes' bounding box and the binned triangles (sorted by cell).
struct TriangleBins {
  Vec3 lo;        ///< lower corner of the grid [m]
  Real cell = 1;  ///< cell edge [m]
  int dims[3] = {1, 1, 1};
  const Vec3* vertices;
  const TriangleCorners* corners;
  const std::uint32_t* cell_begin;  ///< cell_count + 1 offsets into `binned`
  const std::uint32_t* binned;      ///< triangle indices, sorted by cell

  GPUDEM_HD int cell_of(Real x, int k) const {
    const int c = static_cast<int>(floor((x - axis(lo, k)) / cell));
    return c < 0 ? 0 : (c >= dims[k] ? dims[k] - 1 : c);
  }
  GPUDEM_HD std::uint64_t key(int x, int y, int z) const {
    return (static_cast<std::uint64_t>(z) * dims[1] + y) * dims[0] + x;
  }
  /// Lower and upper cell of triangle t's bounding box along axis k.
  GPUDEM_HD void triangle_cells(std::uint32_t t, int k, int& first, int& last) const {
    const Real a = axis(vertices[corners[t].v[0]], k), b = axis(vertices[corners[t].v[1]], k),
               c = axis(vertices[corners[t].v[2]], k);
    first = cell_of(fmin(a, fmin(b, c)), k);
    last = cell_of(fmax(a, fmax(b, c)), k);
  }
  GPUDEM_HD Real distance2(std::uint32_t t, Vec3 p) const {
    const TriangleCorners c = corners[t];
    return norm2(
        closest_triangle_feature(p, vertices[c.v[0]], vertices[c.v[1]], vertices[c.v[2]]).point -
        p);
  }

  /// Calls visit(t) for each triangle t within `reach` of p that `accept(t)` admits, once each.
  template <class Accept, class Visitor>
  GPUDEM_HD void for_each_near(Vec3 p, Real reach, const Accept& accept, Visitor& visit) const {
    int first[3], last[3];
    for (int k = 0; k < 3; ++k) {
      const Real x = axis(p, k);
      if (x + reach < axis(lo, k) || x - reach > axis(lo, k) + dims[k] * cell) return;
      first[k] = cell_of(x - reach, k);
      last[k] = cell_of(x + reach, k);
    }
    for (int z = first[2]; z <= last[2]; ++z)
      for (int y = first[1]; y <= last[1]; ++y)
        for (int x = first[0]; x <= last[0]; ++x) {
          const std::uint64_t cell = key(x, y, z);
          for (std::uint32_t e = cell_begin[cell]; e < cell_begin[cell + 1]; ++e) {
            const std::uint32_t t = binned[e];
            if (!accept(t) || !first_shared_cell(t, first, x, y, z)) continue;
            if (distance2(t, p) < reach * reach) visit(t);
          }
        }
  }

 private:
  /// True when (x, y, z) is the lowest cell in both t's box and the query's [first, ...].
  GPUDEM_HD bool first_shared_cell(std::uint32_t t, const int first[3], int x, int y, int z) const {
    const int at[3] = {x, y, z};
    for (int k = 0; k < 3; ++k) {
      int lo_cell, hi_cell;
      triangle_cells(t, k, lo_cell, hi_cell);
      if (at[k] != (lo_cell > first[k] ? lo_cell : first[k])) return false;
    }
    return true;
  }
};

namespace mesh_candidate_kernels {

/// True when the interval [a, b] meets [lo, hi] shifted by some multiple of the period L: with
/// the smallest n for which hi + nL >= a, when b >= lo + nL.
GPUDEM_HD inline bool meets_periodic_interval(Real a, Real b, Real lo, Real hi, Real L) {
  const Real n = ceil((a - hi) / L);
  return b >= lo + n * L;
}

/// True when triangle t's bounding box meets `region` on every axis the region does not span
/// whole; on such an axis periodic in `box`, when it meets the region or a periodic image of it.
GPUDEM_HD inline bool meets_region(const TriangleBins& bins, std::uint32_t t,
                                   const BinRegion& region, const PeriodicBox& box) {
  for (int k = 0; k < 3; ++k) {
    if (region.periodic[k]) continue;
    const TriangleCorners c = bins.corners[t];
    const Real u = axis(bins.vertices[c.v[0]], k), v = axis(bins.vertices[c.v[1]], k),
               w = axis(bins.vertices[c.v[2]], k);
    const Real a = fmin(u, fmin(v, w)), b = fmax(u, fmax(v, w));
    const Real lo = axis(region.lo, k), hi = lo + axis(region.length, k);
    const bool meets = box.periodic[k] ? meets_periodic_interval(a, b, lo, hi, axis(box.length, k))
                                       : !(b < lo || a > hi);
    if (!meets) return false;
  }
  return true;
}

/// Number of cells triangle t's bounding box covers; 0 for a triangle outside `region`.
struct CountCells {
  TriangleBins bins;
  BinRegion region;
  PeriodicBox box;
  std::uint32_t* count;
  GPUDEM_HD void operator()(std::size_t t) const {
    if (!meets_region(bins, static_cast<std::uint32_t>(t), region, box)) {
      count[t] = 0;
      return;
    }
    std::uint32_t cells = 1;
    for (int k = 0; k < 3; ++k) {
      int first, last;
      bins.triangle_cells(static_cast<std::uint32_t>(t), k, first, last);
      cells *= static_cast<std::uint32_t>(last - first + 1);
    }
    count[t] = cells;
  }
};

/// 1 for a triangle that covers some cell, else 0 (from CountCells).
struct IsBinned {
  const std::uint32_t* count;
  GPUDEM_HD Real operator()(std::size_t t) const { return count[t] > 0 ? Real(1) : Real(0); }
};

/// (cell, triangle) pairs of triangle t from slot offset[t] on (none outside `region`).
struct WriteCells {
  TriangleBins bins;
  BinRegion region;
  PeriodicBox box;
  const std::uint32_t* offset;
  std::uint64_t* key;
  std::uint32_t* triangle;
  GPUDEM_HD void operator()(std::size_t t) const {
    if (!meets_region(bins, static_cast<std::uint32_t>(t), region, box)) return;
    int first[3], last[3];
    for (int k = 0; k < 3; ++k)
      bins.triangle_cells(static_cast<std::uint32_t>(t), k, first[k], last[k]);
    std::uint32_t slot = offset[t];
    for (int z = first[2]; z <= last[2]; ++z)
      for (int y = first[1]; y <= last[1]; ++y)
        for (int x = first[0]; x <= last[0]; ++x) {
          key[slot] = bins.key(x, y, z);
          triangle[slot++] = static_cast<std::uint32_t>(t);
        }
  }
};

/// Coordinate k of vertex i, times `sign` (+1 for the largest, −1 for minus the smallest).
struct VertexCoordinate {
  const Vec3* vertices;
  int k;
  Real sign;
  GPUDEM_HD Real operator()(std::size_t i) const { return sign * axis(vertices[i], k); }
};

struct CountVisitor {
  std::uint32_t count = 0;
  GPUDEM_HD void operator()(std::uint32_t) { ++count; }
};

struct WriteVisitor {
  std::uint32_t* out;
  GPUDEM_HD void operator()(std::uint32_t t) { *out++ = t; }
};

/// Sorts the `count` values from `first` on in increasing order (insertion sort: a particle's
/// list holds a few triangles).
GPUDEM_HD inline void sort_short(std::uint32_t* first, std::uint32_t count) {
  for (std::uint32_t a = 1; a < count; ++a) {
    const std::uint32_t value = first[a];
    std::uint32_t b = a;
    for (; b > 0 && first[b - 1] > value; --b) first[b] = first[b - 1];
    first[b] = value;
  }
}

/// Triangles within r_i + skin of particle i (of each mesh, of i's image nearest the mesh's
/// image centre): counted, or written from offsets[i] on in increasing index.
template <bool kWrite, class P>
struct ParticleTriangles {
  TriangleBins bins;
  MeshImages images;
  const Vec4T<P>* position_radius;  ///< in the engine's state scalar P
  Real skin;
  std::uint32_t* offsets;
  std::uint32_t* triangles;
  template <class Visitor>
  GPUDEM_HD void visit_near(Vec3 x, Real reach, Visitor& visit) const {
    if (!images.box.any_periodic()) {
      bins.for_each_near(x, reach, AnyTriangle{}, visit);
      return;
    }
    for (std::uint32_t m = 0; m < images.mesh_count; ++m)
      bins.for_each_near(images.box.image_near(x, images.image_centre[m]), reach,
                         TrianglesOfMesh{images.triangle_mesh, m}, visit);
  }
  GPUDEM_HD void operator()(std::size_t i) const {
    const Real4 p = vec4_cast<Real>(position_radius[i]);
    if constexpr (kWrite) {
      WriteVisitor write{triangles + offsets[i]};
      visit_near(xyz(p), p.w + skin, write);
      sort_short(triangles + offsets[i], offsets[i + 1] - offsets[i]);
    } else {
      CountVisitor count;
      visit_near(xyz(p), p.w + skin, count);
      offsets[i] = count.count;
    }
  }
};

}  // namespace mesh_candidate_kernels

template <class Space>
class MeshCandidateList {
 public:
  /// Bins the `triangle_count` triangles (corners into `vertices`, both in Space memory) that
  /// meet `region` grown by the largest reach max_radius + skin (or, along a periodic axis of
  /// images.box, a periodic image of it: a triangle just outside the box or the block can touch
  /// a particle inside) and lists,
  /// for each of the n particles (inside the region, each at least r_i + skin from its faces),
  /// the triangles within r_i + skin, each mesh seen from the particle's image that `images`
  /// gives. `max_radius` is the largest particle radius: cells are at least
  /// 2 (max_radius + skin) wide, and no wider than needed to keep the grid under `max_cells`.
  template <class P>
  void build(const Vec3* vertices, std::size_t vertex_count, const TriangleCorners* corners,
             std::size_t triangle_count, const BinRegion& region, const MeshImages& images,
             const Vec4T<P>* position_radius, std::size_t n, Real max_radius, Real skin,
             std::size_t max_cells = std::size_t(1) << 22) {
    n_ = n;
    offsets_.resize(n + 1);
    plan_grid(vertices, vertex_count, max_radius + skin, max_cells);
    bins_.vertices = vertices;
    bins_.corners = corners;
    bin_triangles(triangle_count, grown(region, max_radius + skin), images.box);
    using namespace mesh_candidate_kernels;
    parallel_for(Space{}, n,
                 ParticleTriangles<false, P>{bins_, images, position_radius, skin, offsets_.data(),
                                             nullptr});
    const std::uint64_t total = counts_to_offsets<Space>(
        offsets_.data(), n, "MeshCandidateList: more than 2^32 - 1 particle-triangle pairs");
    triangles_.resize(total);
    parallel_for(Space{}, n,
                 ParticleTriangles<true, P>{bins_, images, position_radius, skin, offsets_.data(),
                                            triangles_.data()});
    pairs_ = total;
  }

  std::size_t size() const { return n_; }
  const std::uint32_t* offsets() const { return offsets_.data(); }
  const std::uint32_t* triangles() const { return triangles_.data(); }
  std::uint64_t pairs() const { return pairs_; }
  /// Triangles binned at the last build: those that meet the region.
  std::uint64_t binned_triangles() const { return binned_count_; }
  std::size_t memory_bytes() const {
    return offsets_.bytes() + triangles_.bytes() + cell_begin_.bytes() + binned_.bytes() +
           keys_.bytes();
  }

 private:
  /// Grid over the vertices' bounding box grown by `reach`, cells of at least 2·reach (so a
  /// reach box overlaps at most two cells per axis), grown until the grid has <= max_cells.
  void plan_grid(const Vec3* vertices, std::size_t vertex_count, Real reach,
                 std::size_t max_cells) {
    Vec3 lo, hi;  // bounding box of the vertices, reduced where they live
    const Real lowest = -std::numeric_limits<Real>::max();
    for (int k = 0; k < 3; ++k) {
      using mesh_candidate_kernels::VertexCoordinate;
      axis(hi, k) = reduce_max(Space{}, vertex_count, lowest, VertexCoordinate{vertices, k, 1});
      axis(lo, k) = -reduce_max(Space{}, vertex_count, lowest, VertexCoordinate{vertices, k, -1});
    }
    const Vec3 margin{reach, reach, reach};
    bins_.lo = lo - margin;
    const Vec3 extent = (hi + margin) - bins_.lo;
    Real cell = 2 * reach;
    for (;;) {
      std::size_t cells = 1;
      for (int k = 0; k < 3; ++k) {
        bins_.dims[k] = std::max(1, static_cast<int>(std::ceil(axis(extent, k) / cell)));
        cells *= static_cast<std::size_t>(bins_.dims[k]);
      }
      if (cells <= max_cells) break;
      cell *= 2;
    }
    bins_.cell = cell;
  }

  /// `region` grown by `reach` on each axis it does not span whole.
  static BinRegion grown(BinRegion region, Real reach) {
    for (int k = 0; k < 3; ++k) {
      if (region.periodic[k]) continue;
      axis(region.lo, k) -= reach;
      axis(region.length, k) += 2 * reach;
    }
    return region;
  }

  void bin_triangles(std::size_t triangle_count, const BinRegion& region, const PeriodicBox& box) {
    using namespace mesh_candidate_kernels;
    DeviceArray<std::uint32_t, Space> count(triangle_count + 1);
    parallel_for(Space{}, triangle_count, CountCells{bins_, region, box, count.data()});
    binned_count_ = static_cast<std::uint64_t>(
        std::llround(reduce_sum(Space{}, triangle_count, IsBinned{count.data()})));
    const std::uint64_t pairs = exclusive_scan(Space{}, count.data(), count.data(), triangle_count);
    keys_.resize(pairs);
    binned_.resize(pairs);
    parallel_for(Space{}, triangle_count,
                 WriteCells{bins_, region, box, count.data(), keys_.data(), binned_.data()});
    const std::size_t cells =
        static_cast<std::size_t>(bins_.dims[0]) * bins_.dims[1] * bins_.dims[2];
    sort_by_key(Space{}, keys_.data(), binned_.data(), pairs, bits_for(cells - 1));
    cell_begin_.resize(cells + 1);
    parallel_for(Space{}, cells + 1,
                 cell_list_kernels::FindCellBegin{keys_.data(), static_cast<std::uint32_t>(pairs),
                                                  cell_begin_.data()});
    bins_.cell_begin = cell_begin_.data();
    bins_.binned = binned_.data();
  }

  TriangleBins bins_;
  std::size_t n_ = 0;
  std::uint64_t pairs_ = 0;
  std::uint64_t binned_count_ = 0;
  DeviceArray<std::uint32_t, Space> offsets_;
  DeviceArray<std::uint32_t, Space> triangles_;
  DeviceArray<std::uint32_t, Space> cell_begin_;
  DeviceArray<std::uint32_t, Space> binned_;
  DeviceArray<std::uint64_t, Space> keys_;
};

}  // namespace gpudem
