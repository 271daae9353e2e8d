// Per-particle triangle candidates from the binned mesh grid against a brute-force search over
// every triangle: the same set for every particle, each triangle once, in increasing index. In a
// periodic box the brute force takes, per triangle, the nearest of all periodic images of the
// particle, so it does not depend on the image centres the list uses.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "core/StlReader.hpp"
#include "engine/MeshCandidateList.hpp"
#include "support/TestPaths.hpp"

namespace gpudem {
namespace {

/// One or more meshes: triangle t belongs to mesh triangle_mesh[t]; image_centre[m] is the
/// centre of mesh m's bounding box.
struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<TriangleCorners> corners;
  std::vector<std::uint32_t> triangle_mesh;
  std::vector<Vec3> image_centre;
};

Mesh from(const TriangleMesh& m) {
  Mesh out{m.vertices, {}, std::vector<std::uint32_t>(m.triangles.size(), 0), {}};
  for (const auto& t : m.triangles) out.corners.push_back({{t[0], t[1], t[2]}});
  return out;
}

/// Centre of the bounding box of the points.
Vec3 bounding_box_centre(const std::vector<Vec3>& points) {
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return 0.5 * (lo + hi);
}

/// A wavy sheet of 2·k² triangles over [x_lo, x_hi] × [0, 1], z = 0.05 sin(6x) cos(5y): small
/// triangles.
Mesh wavy_sheet(int k, double x_lo = 0, double x_hi = 1) {
  Mesh m;
  for (int j = 0; j <= k; ++j)
    for (int i = 0; i <= k; ++i) {
      const double x = x_lo + (x_hi - x_lo) * i / k, y = double(j) / k;
      m.vertices.push_back({x, y, 0.05 * std::sin(6 * x) * std::cos(5 * y)});
    }
  const auto id = [k](int i, int j) { return static_cast<std::uint32_t>(j * (k + 1) + i); };
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      m.corners.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      m.corners.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  m.triangle_mesh.assign(m.corners.size(), 0);
  m.image_centre.push_back(bounding_box_centre(m.vertices));
  return m;
}

/// The meshes a and b as meshes 0 and 1 of one set.
Mesh join(const Mesh& a, Mesh b) {
  Mesh out = a;
  const auto base = static_cast<std::uint32_t>(a.vertices.size());
  out.vertices.insert(out.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (TriangleCorners c : b.corners) {
    out.corners.push_back({{c.v[0] + base, c.v[1] + base, c.v[2] + base}});
    out.triangle_mesh.push_back(1);
  }
  out.image_centre.push_back(b.image_centre[0]);
  return out;
}

/// The unit box [0, 1) periodic along x (y, z over [−1, 2], not periodic).
PeriodicBox box_periodic_in_x() {
  PeriodicBox box;
  box.lo = {0, -1, -1};
  box.length = {1, 3, 3};
  box.periodic[0] = true;
  return box;
}

/// How the list sees the meshes in `box`.
MeshImages images_of(const Mesh& mesh, const PeriodicBox& box) {
  return MeshImages{box, static_cast<std::uint32_t>(mesh.image_centre.size()),
                    mesh.triangle_mesh.data(), mesh.image_centre.data()};
}

/// |closest point of triangle t − p|².
Real distance2_to_triangle(const Mesh& mesh, std::uint32_t t, Vec3 p) {
  const TriangleCorners c = mesh.corners[t];
  const Vec3 q = closest_triangle_feature(p, mesh.vertices[c.v[0]], mesh.vertices[c.v[1]],
                                          mesh.vertices[c.v[2]])
                     .point;
  return norm2(q - p);
}

/// Smallest squared distance from triangle t to p shifted by −L, 0 or +L along each periodic
/// axis of the box (p alone without periodic axes).
Real nearest_image_distance2(const Mesh& mesh, std::uint32_t t, Vec3 p, const PeriodicBox& box) {
  Real best = std::numeric_limits<Real>::max();
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) {
        const int shift[3] = {i, j, k};
        Vec3 image = p;
        bool allowed = true;
        for (int a = 0; a < 3; ++a) {
          allowed = allowed && (box.periodic[a] || shift[a] == 0);
          axis(image, a) += shift[a] * axis(box.length, a);
        }
        if (allowed) best = std::min(best, distance2_to_triangle(mesh, t, image));
      }
  return best;
}

/// n spheres of radius 5–10 mm at random in the box [lo, hi].
std::vector<Real4> random_spheres(std::size_t n, Vec3 lo, Vec3 hi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), r(0.005, 0.010);
  std::vector<Real4> p(n);
  for (Real4& s : p)
    s = {lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y),
         lo.z + u(rng) * (hi.z - lo.z), r(rng)};
  return p;
}

/// A region that spans everything (a run on one rank).
BinRegion everywhere() {
  BinRegion r;
  for (bool& whole : r.periodic) whole = true;
  return r;
}

/// Builds `list` for `spheres` (radii at most 0.010 m) against `mesh`.
void build_list(MeshCandidateList<HostSpace>& list, const Mesh& mesh,
                const std::vector<Real4>& spheres, Real skin, const BinRegion& region,
                const PeriodicBox& box, std::size_t max_cells = std::size_t(1) << 22) {
  list.build(mesh.vertices.data(), mesh.vertices.size(), mesh.corners.data(), mesh.corners.size(),
             region, images_of(mesh, box), spheres.data(), spheres.size(), 0.010, skin, max_cells);
}

/// Compares the list with the brute-force set of triangles within r + skin of each particle
/// (of its nearest periodic image in `box`), in increasing index; returns the number of
/// particle-triangle pairs.
std::size_t expect_same_as_brute_force(const Mesh& mesh, const std::vector<Real4>& spheres,
                                       Real skin, std::size_t max_cells,
                                       const BinRegion& region = everywhere(),
                                       const PeriodicBox& box = PeriodicBox{}) {
  MeshCandidateList<HostSpace> list;
  build_list(list, mesh, spheres, skin, region, box, max_cells);
  EXPECT_EQ(list.size(), spheres.size());
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const Vec3 p = xyz(spheres[i]);
    const Real reach = spheres[i].w + skin;
    std::vector<std::uint32_t> expected;
    for (std::uint32_t t = 0; t < mesh.corners.size(); ++t)
      if (nearest_image_distance2(mesh, t, p, box) < reach * reach) expected.push_back(t);
    const std::vector<std::uint32_t> got(list.triangles() + list.offsets()[i],
                                         list.triangles() + list.offsets()[i + 1]);
    EXPECT_EQ(got, expected) << "particle " << i;
    if (got != expected) break;
    pairs += got.size();
  }
  EXPECT_EQ(list.pairs(), pairs);
  return pairs;
}

TEST(MeshCandidateList, SweepToolMatchesBruteForce) {
  const Mesh sweep =
      from(load_mesh(test::source_dir() + "/inputs/tillage/sweep.stl", MeshPlacement{}));
  const auto spheres = random_spheres(20000, {-0.3, -0.2, -0.05}, {0.05, 0.2, 0.65}, 1);
  const std::size_t pairs = expect_same_as_brute_force(sweep, spheres, 0.002, 1u << 22);
  EXPECT_GT(pairs, 500u);  // the test sees contacts, not an empty neighbourhood
}

/// 20,000 small triangles; also with a grid capped at 64 cells, whose cells then hold many
/// triangles each (the same set must come out).
TEST(MeshCandidateList, FineSheetMatchesBruteForceAtAnyCellSize) {
  const Mesh sheet = wavy_sheet(100);
  const auto spheres = random_spheres(5000, {-0.02, -0.02, -0.07}, {1.02, 1.02, 0.07}, 2);
  const std::size_t fine = expect_same_as_brute_force(sheet, spheres, 0.001, 1u << 22);
  EXPECT_GT(fine, 1000u);
  EXPECT_EQ(expect_same_as_brute_force(sheet, spheres, 0.001, 64), fine);
}

TEST(MeshCandidateList, ParticlesFarFromTheMeshHaveNoCandidates) {
  const Mesh sheet = wavy_sheet(4);
  const std::vector<Real4> far{{5, 5, 5, 0.01}, {-3, 0.5, 0.5, 0.01}, {0.5, 0.5, 0.5, 0.01}};
  MeshCandidateList<HostSpace> list;
  build_list(list, sheet, far, 0.001, everywhere(), PeriodicBox{});
  EXPECT_EQ(list.pairs(), 0u);
}

/// A rank whose region holds the part x < 0.3 of the sheet bins only the triangles that meet
/// it, and its particles (inside the region, at least a reach from its face) still find every
/// triangle within reach.
TEST(MeshCandidateList, ARegionBinsOnlyItsTrianglesAndMissesNoneItsParticlesReach) {
  const Mesh sheet = wavy_sheet(40);  // 3200 triangles over the unit square
  BinRegion region = everywhere();
  region.periodic[0] = false;
  region.lo.x = -0.1;
  region.length.x = 0.4;
  const Real skin = 0.001, reach = 0.010 + skin;
  const auto spheres = random_spheres(3000, {-0.02, -0.02, -0.07}, {0.3 - reach, 1.02, 0.07}, 3);
  EXPECT_GT(expect_same_as_brute_force(sheet, spheres, skin, 1u << 22, region), 300u);

  MeshCandidateList<HostSpace> list;
  build_list(list, sheet, spheres, skin, region, PeriodicBox{});
  std::uint64_t meeting = 0;  // triangles whose x range meets [−0.1, 0.3] grown by the reach
  for (const TriangleCorners& c : sheet.corners) {
    const Real lo =
        std::min({sheet.vertices[c.v[0]].x, sheet.vertices[c.v[1]].x, sheet.vertices[c.v[2]].x});
    meeting += lo <= 0.3 + reach ? 1 : 0;
  }
  EXPECT_EQ(list.binned_triangles(), meeting);
  EXPECT_LT(meeting, sheet.corners.size() / 2);
}

/// On one rank the region is the box itself: a sheet over x ∈ [−0.05, 0.5] reaches out of the
/// box [0, 1]³ through x = 0, and particles just inside it still find the triangles that lie
/// wholly outside the box within their reach.
TEST(MeshCandidateList, TrianglesJustOutsideTheBoxAreFoundFromInside) {
  const Mesh sheet = wavy_sheet(100, -0.05, 0.5);
  PeriodicBox box;
  box.lo = {0, -0.1, -0.1};
  box.length = {1, 1.2, 0.2};
  const auto spheres = random_spheres(2000, {0.0, -0.02, -0.07}, {0.012, 1.02, 0.07}, 6);
  std::size_t outside = 0;  // particles whose reach crosses x = 0
  for (const Real4& p : spheres) outside += p.x < p.w + 0.001 ? 1 : 0;
  ASSERT_GT(outside, 100u);
  EXPECT_GT(expect_same_as_brute_force(sheet, spheres, 0.001, 1u << 22, whole_box_region(box), box),
            500u);
}

/// Smallest and largest x of triangle t.
void x_range(const Mesh& mesh, std::uint32_t t, Real& lo, Real& hi) {
  const TriangleCorners c = mesh.corners[t];
  const Real a = mesh.vertices[c.v[0]].x, b = mesh.vertices[c.v[1]].x, d = mesh.vertices[c.v[2]].x;
  lo = std::min({a, b, d});
  hi = std::max({a, b, d});
}

/// In a box periodic along x (L = 1), a sheet over x ∈ [0.75, 1.25] sticks out through the face
/// x = 1 (its part beyond 1 stands for x ∈ [0, 0.25]) beside a second sheet over [0.3, 0.5];
/// particles on both sides of the face, wrapped into [0, 1), find the same triangles as the
/// brute force over all their images, many of them through the face.
TEST(MeshCandidateList, SheetAcrossAPeriodicFaceMatchesBruteForceOverImages) {
  const Mesh meshes = join(wavy_sheet(50, 0.75, 1.25), wavy_sheet(20, 0.3, 0.5));
  const PeriodicBox box = box_periodic_in_x();
  const BinRegion region = whole_box_region(box);
  const Real skin = 0.001;
  const auto spheres = random_spheres(6000, {0, -0.02, -0.07}, {1, 1.02, 0.07}, 4);
  EXPECT_GT(expect_same_as_brute_force(meshes, spheres, skin, 1u << 22, region, box), 1000u);

  MeshCandidateList<HostSpace> list;
  build_list(list, meshes, spheres, skin, region, box);
  std::size_t through_face = 0;  // particles at x < 0.25 listing triangles beyond x = 1
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    if (spheres[i].x >= 0.25) continue;
    for (std::uint32_t e = list.offsets()[i]; e < list.offsets()[i + 1]; ++e) {
      Real lo, hi;
      x_range(meshes, list.triangles()[e], lo, hi);
      through_face += hi > 1 ? 1 : 0;
    }
  }
  RecordProperty("pairs_through_the_face", static_cast<int>(through_face));
  EXPECT_GT(through_face, 200u);
}

/// A rank whose region is the high end of a periodic x axis, [0.8, 1.05] (its block [0.85, 1)
/// grown by 0.05), with a sheet over [−0.1, 0.4] at the low end and one over [0.6, 0.9]: it bins
/// the first sheet's triangles that meet the region's image [−0.2, 0.05] grown by the reach and
/// the second's that meet [0.8, 1.05] so grown, and its particles find, through the face, all
/// the triangles they reach.
TEST(MeshCandidateList, ARegionAtTheHighEndReachesTrianglesAtTheLowEndThroughTheFace) {
  const Mesh meshes = join(wavy_sheet(40, -0.1, 0.4), wavy_sheet(40, 0.6, 0.9));
  const PeriodicBox box = box_periodic_in_x();
  BinRegion region = whole_box_region(box);
  region.periodic[0] = false;
  region.lo.x = 0.8;
  region.length.x = 0.25;
  const Real skin = 0.001;
  const auto spheres = random_spheres(3000, {0.85, -0.02, -0.07}, {1, 1.02, 0.07}, 5);
  EXPECT_GT(expect_same_as_brute_force(meshes, spheres, skin, 1u << 22, region, box), 200u);

  MeshCandidateList<HostSpace> list;
  build_list(list, meshes, spheres, skin, region, box);
  std::uint64_t meeting = 0, low_end = 0;
  for (std::uint32_t t = 0; t < meshes.corners.size(); ++t) {
    Real lo, hi;
    x_range(meshes, t, lo, hi);
    const Real reach = 0.010 + skin;
    const bool at_low_end = meshes.triangle_mesh[t] == 0 && lo <= 0.05 + reach;
    low_end += at_low_end ? 1 : 0;
    meeting += at_low_end || (meshes.triangle_mesh[t] == 1 && hi >= 0.8 - reach) ? 1 : 0;
  }
  RecordProperty("binned_triangles", static_cast<int>(list.binned_triangles()));
  EXPECT_EQ(list.binned_triangles(), meeting);
  EXPECT_GT(low_end, 0u);
  EXPECT_LT(meeting, meshes.corners.size() / 2);
}

}  // namespace
}  // namespace gpudem
