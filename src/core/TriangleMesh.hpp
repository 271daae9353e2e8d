#pragma once
/// Indexed triangle mesh of a wall or tool (host data), built from a triangle soup by welding
/// corners with exactly equal coordinates and numbering the undirected edges.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "core/Vec3.hpp"

namespace gpudem {

struct TriangleMesh {
  /// Each distinct corner position once, numbered by first use in `triangles`.
  std::vector<Vec3> vertices;
  /// Vertex ids of each triangle, in the order (orientation) of the input.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Edge ids of the edges (v0,v1), (v1,v2), (v2,v0) of each triangle.
  std::vector<std::array<std::uint32_t, 3>> triangle_edges;
  /// Each undirected edge once as {smaller vertex id, larger vertex id}, numbered by first use
  /// in `triangle_edges`.
  std::vector<std::array<std::uint32_t, 2>> edges;
  /// Input triangles dropped for zero area.
  std::size_t skipped_degenerate = 0;
};

/// A triangle whose area is at most this fraction of the squared bounding-box diagonal of the
/// whole input counts as having zero area.
constexpr double degenerate_area_fraction = 1e-12;

namespace mesh_detail {

/// Id of each of `count` items such that equal items share one id and ids count up in the
/// order of first appearance. `less(i, j)` is a strict weak order on the item indices and
/// `same(i, j)` its equivalence. O(count log count).
template <class Less, class Same>
std::vector<std::uint32_t> first_appearance_ids(std::size_t count, Less less, Same same) {
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> group(count);
  std::uint32_t groups = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (k > 0 && !same(order[k - 1], order[k])) ++groups;
    group[order[k]] = groups;
  }
  constexpr auto unset = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> renumber(count == 0 ? 0 : groups + 1, unset);
  std::vector<std::uint32_t> ids(count);
  std::uint32_t distinct = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t& id = renumber[group[i]];
    if (id == unset) id = distinct++;
    ids[i] = id;
  }
  return ids;
}

inline bool lexicographic_less(const Vec3& a, const Vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

inline bool same_position(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

/// Squared diagonal of the axis-aligned bounding box of all corners.
inline double squared_diagonal(const std::vector<std::array<Vec3, 3>>& soup) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for (const auto& triangle : soup)
    for (const Vec3& p : triangle) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
  return soup.empty() ? 0.0 : norm2(hi - lo);
}

/// Area |(b − a) × (c − a)| / 2 of the triangle (a, b, c).
inline double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * norm(cross(b - a, c - a));
}

inline void require_finite_and_indexable(const std::vector<std::array<Vec3, 3>>& soup) {
  if (soup.size() > std::numeric_limits<std::uint32_t>::max() / 3)
    throw std::length_error("build_mesh: too many triangles for 32-bit vertex ids");
  for (const auto& triangle : soup)
    for (const Vec3& p : triangle)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw std::invalid_argument("build_mesh: non-finite corner coordinate");
}

/// Welded id of every corner 3t + k of the soup (ids of all corners, before any drop).
inline std::vector<std::uint32_t> weld_corners(const std::vector<std::array<Vec3, 3>>& soup) {
  auto corner = [&soup](std::uint32_t c) -> const Vec3& { return soup[c / 3][c % 3]; };
  return first_appearance_ids(
      3 * soup.size(),
      [&](std::uint32_t i, std::uint32_t j) { return lexicographic_less(corner(i), corner(j)); },
      [&](std::uint32_t i, std::uint32_t j) { return same_position(corner(i), corner(j)); });
}

/// Fills mesh.triangles and mesh.vertices with the non-degenerate triangles of the soup,
/// renumbering the welded corner ids so that only used vertices remain.
inline void keep_nondegenerate(const std::vector<std::array<Vec3, 3>>& soup,
                               const std::vector<std::uint32_t>& welded, TriangleMesh& mesh) {
  const double min_area = degenerate_area_fraction * squared_diagonal(soup);
  constexpr auto unset = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> vertex_id(welded.size(), unset);
  for (std::size_t t = 0; t < soup.size(); ++t) {
    const std::uint32_t a = welded[3 * t], b = welded[3 * t + 1], c = welded[3 * t + 2];
    if (a == b || b == c || c == a ||
        triangle_area(soup[t][0], soup[t][1], soup[t][2]) <= min_area) {
      ++mesh.skipped_degenerate;
      continue;
    }
    std::array<std::uint32_t, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& id = vertex_id[welded[3 * t + k]];
      if (id == unset) {
        id = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.push_back(soup[t][k]);
      }
      triangle[k] = id;
    }
    mesh.triangles.push_back(triangle);
  }
}

/// Fills mesh.edges and mesh.triangle_edges from mesh.triangles.
inline void number_edges(TriangleMesh& mesh) {
  const std::size_t count = 3 * mesh.triangles.size();
  std::vector<std::uint64_t> key(count);
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint64_t a = mesh.triangles[c / 3][c % 3];
    const std::uint64_t b = mesh.triangles[c / 3][(c + 1) % 3];
    key[c] = (std::min(a, b) << 32) | std::max(a, b);
  }
  const std::vector<std::uint32_t> ids = first_appearance_ids(
      count, [&key](std::uint32_t i, std::uint32_t j) { return key[i] < key[j]; },
      [&key](std::uint32_t i, std::uint32_t j) { return key[i] == key[j]; });
  mesh.triangle_edges.resize(mesh.triangles.size());
  for (std::size_t c = 0; c < count; ++c) {
    mesh.triangle_edges[c / 3][c % 3] = ids[c];
    if (ids[c] == mesh.edges.size())  // first use: ids count up in this order
      mesh.edges.push_back({static_cast<std::uint32_t>(key[c] >> 32),
                            static_cast<std::uint32_t>(key[c] & 0xffffffffu)});
  }
}

}  // namespace mesh_detail

/// Indexed mesh of a triangle soup (three corners per triangle, coordinates finite).
///
/// Corners with exactly equal coordinates become one vertex: no tolerance is applied, because
/// an STL exporter writes the shared corners of neighbouring facets bit-identically. A
/// triangle is dropped (and counted in skipped_degenerate) when two of its corners weld to one
/// vertex or its area is at most degenerate_area_fraction × the squared bounding-box diagonal
/// of the whole soup; vertices used only by dropped triangles are not kept. Vertex and edge
/// ids count up in order of first use, so the same soup always gives the same mesh.
/// O(n log n) in the number of triangles. Throws std::invalid_argument for a non-finite
/// coordinate and std::length_error beyond 32-bit ids.
inline TriangleMesh build_mesh(const std::vector<std::array<Vec3, 3>>& soup) {
  mesh_detail::require_finite_and_indexable(soup);
  TriangleMesh mesh;
  mesh_detail::keep_nondegenerate(soup, mesh_detail::weld_corners(soup), mesh);
  mesh_detail::number_edges(mesh);
  return mesh;
}

}  // namespace gpudem
