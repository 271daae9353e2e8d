// Per-particle triangle candidates from the binned mesh grid against a brute-force search over
// every triangle: the same set for every particle, each triangle once, in increasing index.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/StlReader.hpp"
#include "kernels/MeshCandidateList.hpp"

namespace gpudem {
namespace {

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<TriangleCorners> corners;
};

Mesh from(const TriangleMesh& m) {
  Mesh out{m.vertices, {}};
  for (const auto& t : m.triangles) out.corners.push_back({{t[0], t[1], t[2]}});
  return out;
}

/// A wavy sheet of 2·k² triangles over [0, 1]², z = 0.05 sin(6x) cos(5y): small triangles.
Mesh wavy_sheet(int k) {
  Mesh m;
  for (int j = 0; j <= k; ++j)
    for (int i = 0; i <= k; ++i) {
      const double x = double(i) / k, y = double(j) / k;
      m.vertices.push_back({x, y, 0.05 * std::sin(6 * x) * std::cos(5 * y)});
    }
  const auto id = [k](int i, int j) { return static_cast<std::uint32_t>(j * (k + 1) + i); };
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      m.corners.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      m.corners.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  return m;
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

/// Compares the list with the brute-force set of triangles within r + skin of each particle,
/// in increasing index; returns the number of particle-triangle pairs.
std::size_t expect_same_as_brute_force(const Mesh& mesh, const std::vector<Real4>& spheres,
                                       Real skin, std::size_t max_cells,
                                       const BinRegion& region = everywhere()) {
  MeshCandidateList<HostSpace> list;
  list.build(mesh.vertices.data(), mesh.vertices.size(), mesh.corners.data(), mesh.corners.size(),
             region, spheres.data(), spheres.size(), 0.010, skin, max_cells);
  EXPECT_EQ(list.size(), spheres.size());
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const Vec3 p = xyz(spheres[i]);
    const Real reach = spheres[i].w + skin;
    std::vector<std::uint32_t> expected;
    for (std::uint32_t t = 0; t < mesh.corners.size(); ++t) {
      const TriangleCorners c = mesh.corners[t];
      const Vec3 q = closest_triangle_feature(p, mesh.vertices[c.v[0]], mesh.vertices[c.v[1]],
                                              mesh.vertices[c.v[2]])
                         .point;
      if (norm2(q - p) < reach * reach) expected.push_back(t);
    }
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
  const Mesh sweep = from(
      load_mesh(std::string(GPUDEM_SOURCE_DIR) + "/inputs/tillage/sweep.stl", MeshPlacement{}));
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
  list.build(sheet.vertices.data(), sheet.vertices.size(), sheet.corners.data(),
             sheet.corners.size(), everywhere(), far.data(), far.size(), 0.01, 0.001);
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
  list.build(sheet.vertices.data(), sheet.vertices.size(), sheet.corners.data(),
             sheet.corners.size(), region, spheres.data(), spheres.size(), 0.010, skin);
  std::uint64_t meeting = 0;  // triangles whose x range meets [−0.1, 0.3]
  for (const TriangleCorners& c : sheet.corners) {
    const Real lo =
        std::min({sheet.vertices[c.v[0]].x, sheet.vertices[c.v[1]].x, sheet.vertices[c.v[2]].x});
    meeting += lo <= 0.3 ? 1 : 0;
  }
  EXPECT_EQ(list.binned_triangles(), meeting);
  EXPECT_LT(meeting, sheet.corners.size() / 2);
}

}  // namespace
}  // namespace gpudem
