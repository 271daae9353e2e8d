// Particles a mesh overlaps where a new run starts (engine/MeshStartOverlap.hpp): counted, the
// deepest measured by the fraction of its radius, over several ranks as on one; a tool placed
// inside the particles is refused naming its offset, resting contacts are warned of.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/InputError.hpp"
#include "engine/MeshStartOverlap.hpp"
#include "support/FakeRanks.hpp"

namespace gpudem {
namespace {

/// A 1 m square in the plane z = 0 (two triangles).
TriangleMesh floor_square() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

/// Particles of radius 0.01 m at heights z above the square (x, y = 0.5), or beside it.
ParticleStore particles_at(const std::vector<double>& heights) {
  ParticleStore p;
  for (std::size_t k = 0; k < heights.size(); ++k) p.add(k, {0.5, 0.5, heights[k]}, 0.01, 0, {}, 1);
  return p;
}

TEST(MeshStartOverlap, CountsOverlapsAndFindsTheDeepest) {
  ParticleStore p = particles_at({0.0095, -0.006, 0.02, 0.0101});
  p.add(9, {1.009, 0.5, 0.0}, 0.01, 0, {}, 1);  // beside an edge: 1 mm into its reach
  const MeshStartOverlap o = mesh_start_overlap(floor_square(), p);
  EXPECT_EQ(o.particles, 3u);  // 0.5 mm, 4 mm (below the square) and 1 mm; not 10 mm or 10.1 mm
  EXPECT_NEAR(o.deepest, 0.004, 1e-12);
  EXPECT_NEAR(o.deepest_ratio, 0.4, 1e-10);
  EXPECT_EQ(o.deepest_at.z, -0.006);
}

TEST(MeshStartOverlap, NoParticleNearTheMeshIsNoOverlap) {
  const MeshStartOverlap o = mesh_start_overlap(floor_square(), particles_at({0.5, 2.0, -0.3}));
  EXPECT_EQ(o.particles, 0u);
  EXPECT_EQ(o.deepest_ratio, 0.0);
}

/// A scene with one mesh named "tool" whose offset is on line 12.
Scene tool_scene() {
  Scene s;
  s.file = "till.toml";
  MeshSettings m;
  m.name = "tool";
  m.offset_line = 12;
  s.meshes.push_back(m);
  return s;
}

std::vector<MeshWallSetup> square_wall() {
  MeshWallSetup w;
  w.mesh = floor_square();
  return {w};
}

TEST(MeshStartOverlap, ToolInsideTheParticlesIsRefusedNamingItsOffset) {
  SingleRank one;
  try {
    check_mesh_start_overlaps(tool_scene(), square_wall(), particles_at({0.0095, 0.005}), one);
    FAIL() << "not refused";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("till.toml:12: key 'mesh[0].offset'"), std::string::npos) << what;
    EXPECT_NE(what.find("mesh 'tool' overlaps 2 particle(s) at t = 0, the deepest by 0.005 m "
                        "(50 % of its radius) at (0.5, 0.5, 0.005) m"),
              std::string::npos)
        << what;
  }
}

TEST(MeshStartOverlap, RestingContactsAreWarnedOf) {
  SingleRank one;
  const std::vector<std::string> warnings =
      check_mesh_start_overlaps(tool_scene(), square_wall(), particles_at({0.0099, 0.5}), one);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("mesh 'tool' overlaps 1 particle(s) at t = 0, the deepest by 0.0001 m "
                             "(1 % of its radius)"),
            std::string::npos)
      << warnings[0];
}

/// Three ranks, each with a share: the count sums and the deepest comes from the rank that
/// holds it, on every rank alike.
TEST(MeshStartOverlap, RanksAgreeOnTheCountAndTheDeepest) {
  const std::vector<std::vector<double>> shares = {{0.0099}, {0.5}, {0.0098, 0.0092}};
  std::vector<std::vector<std::string>> warnings(3);
  test::run_on_fake_ranks(3, [&](test::FakeRankLink& link) {
    warnings[link.rank()] = check_mesh_start_overlaps(
        tool_scene(), square_wall(), particles_at(shares[link.rank()]), link.group());
  });
  ASSERT_EQ(warnings[0].size(), 1u);
  EXPECT_NE(warnings[0][0].find("mesh 'tool' overlaps 3 particle(s) at t = 0, the deepest by "
                                "0.0008 m (8 % of its radius) at (0.5, 0.5, 0.0092) m"),
            std::string::npos)
      << warnings[0][0];
  EXPECT_EQ(warnings[1], warnings[0]);
  EXPECT_EQ(warnings[2], warnings[0]);
}

}  // namespace
}  // namespace gpudem
