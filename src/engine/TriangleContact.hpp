#pragma once
/// Contact geometry of a sphere with a triangle mesh wall: the closest feature (face, edge or
/// vertex) of one triangle, and the selection, among the candidates of one particle, of the
/// contacts that count once where triangles meet. The mesh is a partner of infinite mass and
/// radius, like PlaneWall; the contact normal points from the particle centre to the contact
/// point and the overlap is δ = r − |x − p| > 0. The distance is unsigned: a centre that
/// crosses the surface is pushed out of the side it is on.
#include <cstdint>

#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// Which part of a triangle holds the closest point.
enum class FeatureKind : std::uint8_t { kFace, kEdge, kVertex };

/// Closest point of a triangle (a, b, c) to a point, and the feature it lies on. `index` is
/// the local edge (0: ab, 1: bc, 2: ca) or vertex (0: a, 1: b, 2: c); 0 for the face.
struct TriangleFeature {
  Vec3 point;
  FeatureKind kind = FeatureKind::kFace;
  std::uint8_t index = 0;
};

namespace triangle_detail {

/// (w − v)·(p − v) ≤ 0: p lies at or behind vertex v along the edge towards w. Evaluated from
/// v in the same operand order by every triangle that has the edge (v, w), so triangles that
/// share an edge always agree on it bit for bit.
GPUDEM_HD inline bool behind_vertex(Vec3 p, Vec3 v, Vec3 w) { return dot(w - v, p - v) <= 0; }

/// ((w − u) × (p − u))·n ≤ 0: p lies on the outer side of the edge u → w of a triangle with
/// normal n = (b − a) × (c − a), i.e. the side away from the third corner.
GPUDEM_HD inline bool outside_edge(Vec3 p, Vec3 u, Vec3 w, Vec3 n) {
  return dot(cross(w - u, p - u), n) <= 0;
}

/// p lies in the Voronoi region of the edge u → w: outside it and between its end planes.
GPUDEM_HD inline bool in_edge_region(Vec3 p, Vec3 u, Vec3 w, Vec3 n) {
  return outside_edge(p, u, w, n) && !behind_vertex(p, u, w) && !behind_vertex(p, w, u);
}

/// Foot of the perpendicular from p on the line through u and w: u + t (w − u),
/// t = (p − u)·(w − u) / |w − u|².
GPUDEM_HD inline Vec3 project_on_line(Vec3 p, Vec3 u, Vec3 w) {
  const Vec3 e = w - u;
  return u + (dot(p - u, e) / norm2(e)) * e;
}

/// Foot of the perpendicular from p on the plane through a with normal n: p − ((p − a)·n / n²) n.
GPUDEM_HD inline Vec3 project_on_plane(Vec3 p, Vec3 a, Vec3 n) {
  return p - (dot(p - a, n) / norm2(n)) * n;
}

}  // namespace triangle_detail

/// Closest point of the triangle (a, b, c) to p, classified by the Voronoi region of p
/// (Ericson, Real-Time Collision Detection, 2005, §5.1.5): vertex v when p lies behind v
/// along both edges from v, (w − v)·(p − v) ≤ 0; edge uw when p lies outside uw and between
/// its end planes; the face (the projection of p on the plane) otherwise. Region boundaries
/// go to the lower-dimensional feature. The triangle must have non-zero area.
GPUDEM_HD inline TriangleFeature closest_triangle_feature(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  using namespace triangle_detail;
  const Vec3 corner[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Vec3 v = corner[k], next = corner[(k + 1) % 3], previous = corner[(k + 2) % 3];
    if (behind_vertex(p, v, next) && behind_vertex(p, v, previous))
      return {v, FeatureKind::kVertex, static_cast<std::uint8_t>(k)};
  }
  const Vec3 n = cross(b - a, c - a);
  for (int k = 0; k < 3; ++k) {
    const Vec3 u = corner[k], w = corner[(k + 1) % 3];
    if (in_edge_region(p, u, w, n))
      return {project_on_line(p, u, w), FeatureKind::kEdge, static_cast<std::uint8_t>(k)};
  }
  return {project_on_plane(p, a, n), FeatureKind::kFace, 0};
}

/// Mesh topology of one triangle as the caller's mesh numbers it: its index, the global ids
/// of its welded vertices (a, b, c) and of its undirected edges (ab, bc, ca).
struct TriangleIds {
  std::uint32_t triangle = 0;
  std::uint32_t vertex[3] = {0, 0, 0};
  std::uint32_t edge[3] = {0, 0, 0};
};

/// Whether a candidate-list entry's triangle is within reach of the particle, and whether the
/// selection kept it as a contact.
enum class CandidateStatus : std::uint8_t { kOutOfReach, kInReach, kContact };

/// Closest point of one listed triangle to a particle centre. `feature_id` names the feature
/// globally: the triangle index for a face, the edge id for an edge, the vertex id for a vertex.
struct MeshContactCandidate {
  Vec3 point;          ///< closest point on the triangle [m]
  Real distance2 = 0;  ///< |point − centre|² [m²]
  std::uint32_t feature_id = 0;
  std::uint32_t triangle = 0;  ///< global triangle index, into the topology
  FeatureKind kind = FeatureKind::kFace;
  CandidateStatus status = CandidateStatus::kOutOfReach;
};

/// The candidates of one particle: one per listed triangle, in list order, in memory the caller
/// owns (the mesh candidate list's per-entry working array), so a particle may touch any number
/// of triangles. `topology` holds every triangle's welded vertex and edge ids.
struct MeshCandidateSpan {
  MeshContactCandidate* items;
  std::uint32_t count;
  const TriangleIds* topology;
  GPUDEM_HD const TriangleIds& ids(std::uint32_t k) const { return topology[items[k].triangle]; }
  GPUDEM_HD bool in_reach(std::uint32_t k) const {
    return items[k].status != CandidateStatus::kOutOfReach;
  }
  GPUDEM_HD bool is_contact(std::uint32_t k) const {
    return items[k].status == CandidateStatus::kContact;
  }
};

/// Global id of the feature of a triangle: its index, edge id or vertex id.
GPUDEM_HD inline std::uint32_t global_feature_id(const TriangleFeature& f, const TriangleIds& ids) {
  if (f.kind == FeatureKind::kEdge) return ids.edge[f.index];
  if (f.kind == FeatureKind::kVertex) return ids.vertex[f.index];
  return ids.triangle;
}

/// Fills `item` with the closest point of triangle (a, b, c) to the sphere (centre, radius)
/// and marks it within reach when 0 < |x − centre| < radius (a centre exactly on the surface
/// has no contact direction). Returns whether the triangle is within reach.
GPUDEM_HD inline bool evaluate_mesh_candidate(MeshContactCandidate& item, Vec3 centre, Real radius,
                                              Vec3 a, Vec3 b, Vec3 c, const TriangleIds& ids) {
  const TriangleFeature f = closest_triangle_feature(centre, a, b, c);
  const Real distance2 = norm2(f.point - centre);
  const bool within = distance2 > 0 && distance2 < radius * radius;
  item = {
      f.point,      distance2, global_feature_id(f, ids),
      ids.triangle, f.kind,    within ? CandidateStatus::kInReach : CandidateStatus::kOutOfReach};
  return within;
}

/// Two triangles find the same closest point when their points lie within this fraction of
/// the particle radius: far above the rounding of coordinates (≈ 1e-16 of their magnitude,
/// so for meshes within 1e6 radii of the origin), far below any contact geometry.
constexpr Real kMeshAgreementTolerance = Real(1e-9);

/// Kept contacts closer than this fraction of the radius are one contact. It exceeds the
/// agreement tolerance a thousandfold, more than the triangles that meet at any vertex of a
/// sound mesh, so that a chain of candidates, each agreeing with the next, around a vertex
/// collapses into one contact.
constexpr Real kMeshMergeTolerance = Real(1e-6);

namespace triangle_detail {

/// Whether a triangle with these ids has the edge or vertex `id` of the given kind.
GPUDEM_HD inline bool has_feature(const TriangleIds& t, FeatureKind kind, std::uint32_t id) {
  const std::uint32_t* ids = kind == FeatureKind::kEdge ? t.edge : t.vertex;
  return ids[0] == id || ids[1] == id || ids[2] == id;
}

/// Whether candidate i's point is a local minimum of the distance to the centre over the mesh:
/// always for a face; for an edge or vertex when every candidate triangle within reach that has
/// it finds its own closest point there (within the agreement tolerance, squared).
GPUDEM_HD inline bool is_local_minimum(const MeshCandidateSpan& set, std::uint32_t i,
                                       Real tolerance2) {
  const MeshContactCandidate& c = set.items[i];
  if (c.kind == FeatureKind::kFace) return true;
  for (std::uint32_t j = 0; j < set.count; ++j) {
    if (!set.in_reach(j) || !has_feature(set.ids(j), c.kind, c.feature_id)) continue;
    if (norm2(set.items[j].point - c.point) > tolerance2) return false;
  }
  return true;
}

/// Whether candidate i's point coincides (within the merge tolerance, squared) with a point
/// already kept as a contact.
GPUDEM_HD inline bool duplicates_kept(const MeshCandidateSpan& set, std::uint32_t i,
                                      Real tolerance2) {
  for (std::uint32_t j = 0; j < set.count; ++j)
    if (set.is_contact(j) && norm2(set.items[j].point - set.items[i].point) <= tolerance2)
      return true;
  return false;
}

}  // namespace triangle_detail

/// Marks, among the candidates of a particle of the given radius within reach, its contacts,
/// each once (status kContact), and returns their number. O(k²) in the candidate count k, with
/// no bound on k: the candidates live in the caller's memory, one per listed triangle.
///
/// A contact is a local minimum of the distance from the centre over the mesh surface
/// (Kremmer & Favier 2001, IJNME 51; Su, Gu & Xu 2011, Chem. Eng. Sci. 66; Hu et al. 2013,
/// IJNME 94). A face candidate is always one. An edge or vertex candidate is one only when
/// every candidate triangle that has that edge or vertex finds its closest point there: a
/// triangle with a closer point beside it shows that the distance still decreases into that
/// triangle. A triangle that has the feature is never farther than the feature, so it is
/// always among the candidates within reach. Faces are kept first, then edges, then vertices,
/// each in list order and only if its point is not already kept, so a point reported by
/// several triangles (a shared edge or vertex, or a point on a boundary that rounding assigns
/// to two faces) counts once, as its highest-dimensional feature. The candidate closest to the
/// centre always passes the test, so a particle within reach of the mesh keeps at least one
/// contact.
///
/// This contains the feature-priority rule (keep faces; an edge only if no kept face has it;
/// a vertex only if no kept face or edge touches it; each edge and vertex once) and also
/// removes the edge of a non-adjacent triangle that that rule keeps near a vertex, e.g. in a
/// flat fan. Consequences:
/// - Coplanar triangles: a centre just off a shared edge gets the face of the triangle it is
///   above; the other triangle's edge candidate is dropped (that face has a closer point). On
///   the edge both report the edge, kept once. Overlap and normal equal those of the plane.
/// - Convex edge (tool edge, fold angle > 180° on the particle side): a centre in the wedge
///   between the two face normals gets one edge contact whose normal turns continuously from
///   one face normal to the other; beside the wedge, one face contact.
/// - Concave fold (angle < 180°): a centre inside the fold touching both sides gets two face
///   contacts, one per side, as from two planes; the fold edge is not reported from inside.
GPUDEM_HD inline int select_mesh_contacts(MeshCandidateSpan set, Real radius) {
  using namespace triangle_detail;
  const Real agreement2 = (kMeshAgreementTolerance * radius) * (kMeshAgreementTolerance * radius);
  const Real merge2 = (kMeshMergeTolerance * radius) * (kMeshMergeTolerance * radius);
  const FeatureKind order[3] = {FeatureKind::kFace, FeatureKind::kEdge, FeatureKind::kVertex};
  int contacts = 0;
  for (FeatureKind kind : order)
    for (std::uint32_t i = 0; i < set.count; ++i) {
      if (!set.in_reach(i) || set.items[i].kind != kind) continue;
      if (!is_local_minimum(set, i, agreement2) || duplicates_kept(set, i, merge2)) continue;
      set.items[i].status = CandidateStatus::kContact;
      ++contacts;
    }
  return contacts;
}

/// Unit contact normal of a selected contact, from the centre to the contact point.
GPUDEM_HD inline Vec3 mesh_contact_normal(const MeshContactCandidate& c, Vec3 centre) {
  return (Real(1) / sqrt(c.distance2)) * (c.point - centre);
}

/// Overlap δ = r − |x − centre| of a selected contact.
GPUDEM_HD inline Real mesh_contact_overlap(const MeshContactCandidate& c, Real radius) {
  return radius - sqrt(c.distance2);
}

}  // namespace gpudem
