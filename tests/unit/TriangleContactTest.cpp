// Sphere–triangle-mesh contact geometry: the closest feature of one triangle against an
// independent closest-point computation and closed forms, and the selection of contacts where
// triangles meet (coplanar pairs, flat fans, convex and concave folds, a convex polyhedron)
// against the analytic surfaces they represent. Tolerances: 1e-12 on lengths and unit normals
// of order 0.1–1 (coordinates of order 1, rounding ≈ 1e-16); 1e-9 between the two
// closest-point methods on random, possibly thin triangles; 1 % on forces.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "engine/TriangleContact.hpp"

namespace gpudem {
namespace {

constexpr Real kPi = 3.14159265358979323846;
constexpr Real kTight = 1e-12;

Vec3 unit(Vec3 v) { return (1 / norm(v)) * v; }

/// Rotation by `angle` about the unit `axis` (Rodrigues' formula).
Vec3 rotate(Vec3 v, Vec3 axis, Real angle) {
  return std::cos(angle) * v + std::sin(angle) * cross(axis, v) +
         (1 - std::cos(angle)) * dot(axis, v) * axis;
}

/// A generic placement so that no test relies on axis-aligned, exactly representable geometry.
struct Placement {
  Vec3 axis = unit({0.3, -0.5, 0.8});
  Real angle = 0.7;
  Vec3 shift = {0.37, -1.21, 2.05};
  Vec3 operator()(Vec3 v) const { return rotate(v, axis, angle) + shift; }
  Vec3 direction(Vec3 v) const { return rotate(v, axis, angle); }
};

/// Indexed mesh with edge ids numbered here, independently of any mesh reader.
struct TestMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;

  std::vector<TriangleIds> topology() const {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_id;
    std::vector<TriangleIds> ids(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      ids[t].triangle = static_cast<std::uint32_t>(t);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = triangles[t][k], w = triangles[t][(k + 1) % 3];
        const auto key = std::make_pair(std::min(u, w), std::max(u, w));
        const auto found = edge_id.emplace(key, static_cast<std::uint32_t>(edge_id.size())).first;
        ids[t].vertex[k] = u;
        ids[t].edge[k] = found->second;
      }
    }
    return ids;
  }

  std::uint32_t edge_of(std::uint32_t u, std::uint32_t w) const {
    const std::vector<TriangleIds> ids = topology();
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
        if ((a == u && b == w) || (a == w && b == u)) return ids[t].edge[k];
      }
    return std::numeric_limits<std::uint32_t>::max();
  }
};

/// The contacts the selection marks, in triangle order.
struct SelectedContacts {
  std::vector<MeshContactCandidate> items;
  int count = 0;
};

/// Every triangle a candidate of the sphere (centre, r), as the engine keeps one per listed
/// triangle, reduced to its contacts.
SelectedContacts contacts(const TestMesh& mesh, Vec3 centre, Real r) {
  const std::vector<TriangleIds> ids = mesh.topology();
  std::vector<MeshContactCandidate> candidates(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    evaluate_mesh_candidate(candidates[t], centre, r, mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                            mesh.vertices[tri[2]], ids[t]);
  }
  const MeshCandidateSpan span{candidates.data(), static_cast<std::uint32_t>(candidates.size()),
                               ids.data()};
  const int selected = select_mesh_contacts(span, r);
  SelectedContacts set;
  for (const MeshContactCandidate& c : candidates)
    if (c.status == CandidateStatus::kContact) set.items.push_back(c);
  set.count = static_cast<int>(set.items.size());
  EXPECT_EQ(set.count, selected);
  return set;
}

void expect_near(Vec3 actual, Vec3 expected, Real tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

/// Closest point of a triangle by another method: the plane projection when its barycentric
/// coordinates (solved from the 2×2 normal equations) are all non-negative, else the closest
/// of the three clamped segment projections.
Vec3 reference_closest_point(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 e0 = b - a, e1 = c - a, d = p - a;
  const Real g00 = dot(e0, e0), g01 = dot(e0, e1), g11 = dot(e1, e1);
  const Real r0 = dot(d, e0), r1 = dot(d, e1), det = g00 * g11 - g01 * g01;
  const Real s = (g11 * r0 - g01 * r1) / det, t = (g00 * r1 - g01 * r0) / det;
  if (s >= 0 && t >= 0 && s + t <= 1) return a + s * e0 + t * e1;
  Vec3 best{};
  Real best2 = std::numeric_limits<Real>::infinity();
  const Vec3 corner[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Vec3 u = corner[k], e = corner[(k + 1) % 3] - u;
    const Real along = std::clamp(dot(p - u, e) / dot(e, e), Real(0), Real(1));
    const Vec3 x = u + along * e;
    if (norm2(p - x) < best2) best2 = norm2(p - x), best = x;
  }
  return best;
}

// --- closest feature of one triangle -------------------------------------------------------

TEST(ClosestTriangleFeature, MatchesIndependentClosestPointAndFeatureForRandomPoints) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> coordinate(-1, 1);
  auto random_vec = [&] { return Vec3{coordinate(rng), coordinate(rng), coordinate(rng)}; };
  int counts[3] = {0, 0, 0};
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 a = random_vec(), b = random_vec(), c = random_vec(), p = 2 * random_vec();
    const TriangleFeature f = closest_triangle_feature(p, a, b, c);
    expect_near(f.point, reference_closest_point(p, a, b, c), 1e-9);
    const Vec3 corner[3] = {a, b, c};
    if (f.kind == FeatureKind::kVertex) expect_near(f.point, corner[f.index], 0);
    if (f.kind == FeatureKind::kEdge) {
      const Vec3 u = corner[f.index], w = corner[(f.index + 1) % 3];
      EXPECT_NEAR(norm(cross(f.point - u, w - u)) / norm2(w - u), 0, kTight);
    }
    ++counts[static_cast<int>(f.kind)];
  }
  EXPECT_GT(counts[0], 500);  // every region is exercised
  EXPECT_GT(counts[1], 500);
  EXPECT_GT(counts[2], 500);
}

// --- single triangle: face, edge, vertex ---------------------------------------------------

struct SingleTriangle {
  Placement place;
  Vec3 a = place({0, 0, 0}), b = place({1, 0, 0}), c = place({0.3, 0.9, 0});
  Vec3 normal = place.direction({0, 0, 1});
  TestMesh mesh{{a, b, c}, {{0, 1, 2}}};
};

TEST(MeshContact, FaceContactHasFaceNormalTowardsTheMeshAndOverlapRMinusDistance) {
  const SingleTriangle s;
  const Real r = 0.1, height = 0.07;
  const Vec3 foot = 0.2 * s.a + 0.3 * s.b + 0.5 * s.c;
  for (Real side : {1.0, -1.0}) {
    const Vec3 centre = foot + side * height * s.normal;
    const SelectedContacts set = contacts(s.mesh, centre, r);
    ASSERT_EQ(set.count, 1);
    EXPECT_EQ(set.items[0].kind, FeatureKind::kFace);
    EXPECT_EQ(set.items[0].feature_id, 0u);
    expect_near(set.items[0].point, foot, kTight);
    expect_near(mesh_contact_normal(set.items[0], centre), -side * s.normal, kTight);
    EXPECT_NEAR(mesh_contact_overlap(set.items[0], r), r - height, kTight);
  }
}

TEST(MeshContact, EdgeContactIsAtTheDistanceToTheSegment) {
  const SingleTriangle s;
  const Real r = 0.1, along = 0.3, out = 0.04, height = 0.05;
  const Vec3 edge = s.b - s.a, outward = unit(cross(edge, s.normal));  // away from c
  ASSERT_LT(dot(outward, s.c - s.a), 0);
  const Vec3 foot = s.a + along * edge;
  const Vec3 centre = foot + out * outward + height * s.normal;
  const SelectedContacts set = contacts(s.mesh, centre, r);
  ASSERT_EQ(set.count, 1);
  EXPECT_EQ(set.items[0].kind, FeatureKind::kEdge);
  EXPECT_EQ(set.items[0].feature_id, s.mesh.edge_of(0, 1));
  expect_near(set.items[0].point, foot, kTight);
  EXPECT_NEAR(mesh_contact_overlap(set.items[0], r), r - std::hypot(out, height), kTight);
  expect_near(mesh_contact_normal(set.items[0], centre),
              (-1 / std::hypot(out, height)) * (out * outward + height * s.normal), kTight);
}

TEST(MeshContact, VertexContactIsAtTheDistanceToThePoint) {
  const SingleTriangle s;
  const Real r = 0.1;
  const Vec3 away = -0.03 * (unit(s.b - s.a) + unit(s.c - s.a)) + 0.04 * s.normal;
  const Vec3 centre = s.a + away;
  const SelectedContacts set = contacts(s.mesh, centre, r);
  ASSERT_EQ(set.count, 1);
  EXPECT_EQ(set.items[0].kind, FeatureKind::kVertex);
  EXPECT_EQ(set.items[0].feature_id, 0u);
  expect_near(set.items[0].point, s.a, 0);
  EXPECT_NEAR(mesh_contact_overlap(set.items[0], r), r - norm(away), kTight);
  expect_near(mesh_contact_normal(set.items[0], centre), -unit(away), kTight);
}

TEST(MeshContact, TriangleOutOfReachIsNoCandidate) {
  const SingleTriangle s;
  MeshContactCandidate item;
  const Real distance = 0.1;
  const Vec3 centre = (1.0 / 3) * (s.a + s.b + s.c) + distance * s.normal;
  const TriangleIds ids = s.mesh.topology()[0];
  EXPECT_FALSE(evaluate_mesh_candidate(item, centre, distance * (1 - 1e-9), s.a, s.b, s.c, ids));
  EXPECT_EQ(item.status, CandidateStatus::kOutOfReach);
  EXPECT_EQ(contacts(s.mesh, centre, distance * (1 - 1e-9)).count, 0);
  EXPECT_TRUE(evaluate_mesh_candidate(item, centre, distance * (1 + 1e-9), s.a, s.b, s.c, ids));
  EXPECT_EQ(item.status, CandidateStatus::kInReach);
  EXPECT_EQ(contacts(s.mesh, centre, distance * (1 + 1e-9)).count, 1);
}

// --- where triangles meet ------------------------------------------------------------------

/// Hertz-like force on the particle, −k δ^{3/2} n, summed over its contacts (k = 1).
Vec3 contact_force(const SelectedContacts& set, Vec3 centre, Real r) {
  Vec3 force{};
  for (int i = 0; i < set.count; ++i)
    force -= std::pow(mesh_contact_overlap(set.items[i], r), 1.5) *
             mesh_contact_normal(set.items[i], centre);
  return force;
}

TEST(MeshContact, CoplanarSquareGivesThePlaneContactAcrossTheSharedDiagonal) {
  const Placement place;
  // Unit square (v0, v1, v2, v3) split along the diagonal v0–v2.
  const TestMesh square{{place({0, 0, 0}), place({1, 0, 0}), place({1, 1, 0}), place({0, 1, 0})},
                        {{0, 1, 2}, {0, 2, 3}}};
  const Vec3 normal = place.direction({0, 0, 1});
  const Real r = 0.1, height = 0.08;
  const Real expected_overlap = r - height;
  const Vec3 expected_force = std::pow(expected_overlap, 1.5) * normal;
  // Across the diagonal at its middle, perpendicular to it, in steps of 1e-4 and with offsets
  // down to rounding size right at the diagonal.
  std::vector<Real> offsets;
  for (int step = -200; step <= 200; ++step) offsets.push_back(step * 1e-4);
  for (Real tiny : {1e-9, 1e-12, 1e-15, 1e-17}) offsets.insert(offsets.end(), {tiny, -tiny});
  for (Real offset : offsets) {
    const Vec3 centre = place({0.5 + offset, 0.5 - offset, 0}) + height * normal;
    const SelectedContacts set = contacts(square, centre, r);
    ASSERT_EQ(set.count, 1) << "offset " << offset;
    EXPECT_NEAR(mesh_contact_overlap(set.items[0], r), expected_overlap, kTight);
    expect_near(mesh_contact_normal(set.items[0], centre), -normal, kTight);
    const Vec3 force = contact_force(set, centre, r);
    EXPECT_LT(norm(force - expected_force), 0.01 * norm(expected_force));
  }
}

/// Six triangles around vertex 0 in the plane z = 0 (placed), outer vertices at radius 1.
TestMesh flat_fan(const Placement& place) {
  TestMesh fan{{place({0, 0, 0})}, {}};
  for (int k = 0; k < 6; ++k) {
    fan.vertices.push_back(place({std::cos(k * kPi / 3), std::sin(k * kPi / 3), 0}));
    fan.triangles.push_back({0, std::uint32_t(1 + k), std::uint32_t(1 + (k + 1) % 6)});
  }
  return fan;
}

TEST(MeshContact, FlatFanGivesOneContactNearItsSharedVertex) {
  const Placement place;
  const TestMesh fan = flat_fan(place);
  const Vec3 normal = place.direction({0, 0, 1});
  const Real r = 0.1, height = 0.099;  // reach in the plane √(r² − h²) ≈ 0.014
  for (Real distance : {0.0, 1e-17, 1e-13, 1e-10, 1e-6, 1e-3, 0.005, 0.012, 0.05}) {
    for (int sector_step = 0; sector_step < 24; ++sector_step) {
      const Real angle = sector_step * kPi / 12 + (sector_step % 3 == 1 ? 0.01 : 0);
      const Vec3 foot = place({distance * std::cos(angle), distance * std::sin(angle), 0});
      const Vec3 centre = foot + height * normal;
      const SelectedContacts set = contacts(fan, centre, r);
      ASSERT_EQ(set.count, 1) << "distance " << distance << " angle " << angle;
      EXPECT_NEAR(mesh_contact_overlap(set.items[0], r), r - height, kTight);
      expect_near(mesh_contact_normal(set.items[0], centre), -normal, kTight);
    }
  }
}

/// Two triangles sharing the edge (0,−1,0)–(0,1,0) (placed): a horizontal one towards −x and
/// one folded down or up towards ±z, like the edge of a box (down) or an inside corner (up).
TestMesh fold(const Placement& place, Real second_face_z) {
  return {{place({0, -1, 0}), place({0, 1, 0}), place({-1, 0, 0}), place({0, 0, second_face_z})},
          {{0, 1, 2}, {1, 0, 3}}};
}

TEST(MeshContact, ConvexFoldGivesOneEdgeContactFromOutside) {
  const Placement place;
  const TestMesh box_edge = fold(place, -1);
  const Real r = 0.1, distance = 0.09;
  for (Real angle : {0.01, kPi / 4, kPi / 2 - 0.01}) {  // in the wedge x > 0, z > 0
    const Vec3 centre = place({distance * std::cos(angle), 0.1, distance * std::sin(angle)});
    const SelectedContacts set = contacts(box_edge, centre, r);
    ASSERT_EQ(set.count, 1) << "angle " << angle;
    EXPECT_EQ(set.items[0].kind, FeatureKind::kEdge);
    EXPECT_EQ(set.items[0].feature_id, box_edge.edge_of(0, 1));
    EXPECT_NEAR(mesh_contact_overlap(set.items[0], r), r - distance, kTight);
  }
}

TEST(MeshContact, ConvexFoldContactIsContinuousAroundTheEdge) {
  const Placement place;
  const TestMesh box_edge = fold(place, -1);
  const Real r = 0.1, distance = 0.09;
  // From above the horizontal face (x < 0), around the edge, to beside the vertical face
  // (z < 0), staying off both planes. The closed form is the nearest point of the surface: the
  // edge in the wedge x, z > 0, else the foot on the plane the centre is over.
  for (int step = 0; step <= 1000; ++step) {
    const Real angle = (kPi - 0.2) - step * ((1.5 * kPi - 0.4) / 1000);
    const Real x = distance * std::cos(angle), z = distance * std::sin(angle);
    const Vec3 nearest = {std::min(x, Real(0)), 0.1, std::min(z, Real(0))};
    const Vec3 to_surface = nearest - Vec3{x, 0.1, z};
    const Vec3 centre = place({x, 0.1, z});
    const SelectedContacts set = contacts(box_edge, centre, r);
    ASSERT_EQ(set.count, 1) << "angle " << angle;
    EXPECT_NEAR(mesh_contact_overlap(set.items[0], r), r - norm(to_surface), kTight);
    expect_near(mesh_contact_normal(set.items[0], centre), place.direction(unit(to_surface)),
                kTight);
  }
}

TEST(MeshContact, ConcaveFoldGivesTwoFaceContacts) {
  const Placement place;
  const TestMesh corner = fold(place, 1);
  const Real r = 0.1;
  // Inside the corner x < 0, z > 0 at (−to_vertical, y, to_horizontal).
  for (auto [to_vertical, to_horizontal] : {std::pair{0.06, 0.07}, std::pair{0.03, 0.03}}) {
    const Vec3 centre = place({-to_vertical, 0.1, to_horizontal});
    const SelectedContacts set = contacts(corner, centre, r);
    ASSERT_EQ(set.count, 2);
    for (int i = 0; i < 2; ++i) {
      const MeshContactCandidate& c = set.items[i];
      EXPECT_EQ(c.kind, FeatureKind::kFace);
      const bool horizontal = c.feature_id == 0;
      const Real expected = horizontal ? to_horizontal : to_vertical;
      const Vec3 expected_normal = place.direction(horizontal ? Vec3{0, 0, -1} : Vec3{1, 0, 0});
      EXPECT_NEAR(mesh_contact_overlap(c, r), r - expected, kTight);
      expect_near(mesh_contact_normal(c, centre), expected_normal, kTight);
    }
    EXPECT_NE(set.items[0].feature_id, set.items[1].feature_id);
  }
}

/// Regular icosahedron with circumradius 1 (20 faces, 5 around each vertex).
TestMesh icosahedron() {
  const Real g = (1 + std::sqrt(Real(5))) / 2, s = 1 / std::sqrt(1 + g * g);
  TestMesh m;
  for (Real u : {-1.0, 1.0})
    for (Real v : {-1.0, 1.0}) {
      m.vertices.push_back({0, s * u, s * g * v});
      m.vertices.push_back({s * u, s * g * v, 0});
      m.vertices.push_back({s * g * v, 0, s * u});
    }
  // Faces: the triples of mutually nearest vertices (edge length 2s).
  const Real edge2 = 4 * s * s;
  auto adjacent = [&](std::uint32_t i, std::uint32_t j) {
    return std::abs(norm2(m.vertices[i] - m.vertices[j]) - edge2) < 1e-9;
  };
  for (std::uint32_t i = 0; i < 12; ++i)
    for (std::uint32_t j = i + 1; j < 12; ++j)
      for (std::uint32_t k = j + 1; k < 12; ++k)
        if (adjacent(i, j) && adjacent(j, k) && adjacent(k, i)) m.triangles.push_back({i, j, k});
  return m;
}

/// The squared distance from `centre` to the mesh, by the reference closest point.
Real closest_distance2(const TestMesh& mesh, Vec3 centre) {
  Real closest2 = std::numeric_limits<Real>::infinity();
  for (const auto& t : mesh.triangles)
    closest2 =
        std::min(closest2, norm2(reference_closest_point(centre, mesh.vertices[t[0]],
                                                         mesh.vertices[t[1]], mesh.vertices[t[2]]) -
                                 centre));
  return closest2;
}

/// Whether a point lies outside a convex mesh around the origin: beyond one face plane.
bool outside_convex(const TestMesh& mesh, Vec3 point) {
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]];
    const Vec3 n = cross(mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a);
    if (dot(point - a, n) * dot(a, n) > 0) return true;
  }
  return false;
}

TEST(MeshContact, ConvexPolyhedronGivesExactlyOneContactAtTheClosestPoint) {
  const TestMesh mesh = icosahedron();
  ASSERT_EQ(mesh.triangles.size(), 20u);
  const Real r = 0.1;
  std::mt19937_64 rng(11);
  std::normal_distribution<Real> gaussian;
  std::uniform_real_distribution<Real> fraction(0.0, 1.0);
  int tested = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    // A surface point on a vertex, an edge or a face (where the features compete), moved off
    // the surface by up to 1.2 r in a random outward-leaning direction.
    const auto& tri = mesh.triangles[trial % 20];
    const Vec3 a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
    const Real u = fraction(rng), v = (1 - u) * fraction(rng);
    const Vec3 on_surface =
        trial % 3 == 0 ? a : (trial % 3 == 1 ? a + u * (b - a) : a + u * (b - a) + v * (c - a));
    const Vec3 lean = {gaussian(rng), gaussian(rng), gaussian(rng)};
    const Vec3 centre = on_surface + 1.2 * r * fraction(rng) * unit(on_surface + 0.6 * lean);
    if (!outside_convex(mesh, centre)) continue;
    const Real closest2 = closest_distance2(mesh, centre);
    if (closest2 >= r * r) continue;
    ++tested;
    const SelectedContacts set = contacts(mesh, centre, r);
    ASSERT_EQ(set.count, 1) << "trial " << trial;
    EXPECT_NEAR(std::sqrt(set.items[0].distance2), std::sqrt(closest2), kTight);
  }
  EXPECT_GT(tested, 1000);
}

// --- finely tessellated surfaces: many triangles within reach at once -----------------------

/// Each triangle split into four at its edge midpoints (welded), the new vertices pushed onto
/// the unit sphere.
TestMesh subdivide_on_unit_sphere(const TestMesh& coarse) {
  TestMesh fine{coarse.vertices, {}};
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
  auto middle = [&](std::uint32_t u, std::uint32_t w) {
    const auto key = std::make_pair(std::min(u, w), std::max(u, w));
    const auto found = midpoint.find(key);
    if (found != midpoint.end()) return found->second;
    fine.vertices.push_back(unit(fine.vertices[u] + fine.vertices[w]));
    const auto index = static_cast<std::uint32_t>(fine.vertices.size() - 1);
    midpoint.emplace(key, index);
    return index;
  };
  for (const auto& t : coarse.triangles) {
    const std::uint32_t ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
    fine.triangles.push_back({t[0], ab, ca});
    fine.triangles.push_back({ab, t[1], bc});
    fine.triangles.push_back({ca, bc, t[2]});
    fine.triangles.push_back({ab, bc, ca});
  }
  return fine;
}

/// Triangles of the mesh within reach of the sphere (centre, r).
int triangles_within_reach(const TestMesh& mesh, Vec3 centre, Real r) {
  int within = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3 x = reference_closest_point(centre, mesh.vertices[t[0]], mesh.vertices[t[1]],
                                           mesh.vertices[t[2]]);
    if (norm2(x - centre) < r * r) ++within;
  }
  return within;
}

TEST(MeshContact, GeodesicSphereGivesOneContactWithHundredsOfTrianglesWithinReach) {
  TestMesh mesh = icosahedron();
  for (int level = 0; level < 4; ++level) mesh = subdivide_on_unit_sphere(mesh);
  ASSERT_EQ(mesh.triangles.size(), 5120u);  // edges ≈ 0.03, against a particle radius of 0.3
  const Real r = 0.3;
  std::mt19937_64 rng(5);
  std::normal_distribution<Real> gaussian;
  std::uniform_real_distribution<Real> gap(0.02, 0.25);
  int most_within = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec3 direction = unit({gaussian(rng), gaussian(rng), gaussian(rng)});
    const Vec3 centre = (1 + gap(rng)) * direction;
    const Real closest2 = closest_distance2(mesh, centre);
    most_within = std::max(most_within, triangles_within_reach(mesh, centre, r));
    const SelectedContacts set = contacts(mesh, centre, r);
    ASSERT_EQ(set.count, 1) << "trial " << trial;
    EXPECT_NEAR(std::sqrt(set.items[0].distance2), std::sqrt(closest2), kTight);
  }
  EXPECT_GT(most_within, 100);
}

/// The square [0, 1]² (placed) as an n × n grid of cells, each split into two triangles.
TestMesh tessellated_square(const Placement& place, int n) {
  TestMesh square;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) square.vertices.push_back(place({Real(i) / n, Real(j) / n, 0}));
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      square.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      square.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return square;
}

TEST(MeshContact, FinelyTessellatedPlaneGivesThePlaneContactAnywhere) {
  const Placement place;
  const TestMesh square = tessellated_square(place, 60);  // 7,200 triangles, cells of 1/60
  const Vec3 normal = place.direction({0, 0, 1});
  const Real r = 0.1, height = 0.03;  // about 200 triangles within reach
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<Real> inner(0.2, 0.8);
  for (int trial = 0; trial < 30; ++trial) {
    // Random feet, and feet exactly on grid vertices and edges, where the features compete.
    const Real x = trial % 3 == 0 ? std::round(60 * inner(rng)) / 60 : inner(rng);
    const Real y = trial % 3 == 2 ? x : inner(rng);
    const Vec3 centre = place({x, y, 0}) + height * normal;
    ASSERT_GT(triangles_within_reach(square, centre, r), 150);
    const SelectedContacts set = contacts(square, centre, r);
    ASSERT_EQ(set.count, 1) << "trial " << trial;
    EXPECT_NEAR(mesh_contact_overlap(set.items[0], r), r - height, kTight);
    expect_near(mesh_contact_normal(set.items[0], centre), -normal, kTight);
  }
}

}  // namespace
}  // namespace gpudem
