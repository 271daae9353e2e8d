// [[bond]] tables and fixed materials (held, or moved at a velocity) in a scene: every key
// read, defaults, refusals that name file, line and key, a gap the skin cannot hold refused at
// set-up, and the bond vibration and a grip's speed in the time-step limits.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/BondPairs.hpp"
#include "core/InputError.hpp"
#include "core/SceneLoader.hpp"
#include "engine/BondClods.hpp"
#include "engine/SceneSetup.hpp"
#include "engine/TimeStepLimits.hpp"

namespace gpudem::test {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

/// Lines 1-18 fixed; the [[bond]] table from line 19 on.
const char* const kScene = R"([simulation]
end_time = 1.0
[domain]
min = [0, 0, 0]
max = [1, 1, 1]
[[material]]
name = "soil"
density = 1850
young = 2e6
[[material]]
name = "clamp"
density = 1850
young = 2e6
fixed = true
[contact]
normal = "hertz"
[neighbor]
skin = 0.001
)";

class BondScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gpudem-bond-scene-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path() const { return (dir_ / "scene.toml").string(); }

  Scene load(const std::string& bond) {
    std::ofstream(path()) << kScene << bond;
    return load_scene(path(), {});
  }

  /// The InputError of loading the scene with `bond`, checked to name the file, `line`, `key`
  /// and `phrase`.
  void expect_refused(const std::string& bond, int line, const std::string& key,
                      const std::string& phrase) {
    try {
      load(bond);
      ADD_FAILURE() << "loaded:\n" << bond;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(e.file(), path()) << message;
      EXPECT_EQ(e.line(), line) << message;
      EXPECT_EQ(e.key(), key) << message;
      EXPECT_NE(message.find(phrase), std::string::npos) << message;
    }
  }

  fs::path dir_;
};

TEST_F(BondScene, ReadsEveryKeyAndTheFixedFlag) {
  const Scene s = load(
      "[[bond]]\nmaterials = [\"clamp\", \"soil\"]\ngap = 2e-4\nyoung = 3e7\npoisson = 0.2\n"
      "radius_factor = 0.7\ntensile_strength = 1e5\nshear_strength = 2e5\ndamping_ratio = 0.3\n"
      "[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\n");
  ASSERT_EQ(s.bonds.size(), 2u);
  const BondSettings& b = s.bonds[0];
  EXPECT_EQ(b.a, 1u);
  EXPECT_EQ(b.b, 0u);
  EXPECT_EQ(b.gap, 2e-4);
  EXPECT_EQ(b.young, 3e7);
  EXPECT_EQ(b.poisson, 0.2);
  EXPECT_EQ(b.radius_factor, 0.7);
  EXPECT_EQ(b.tensile_strength, 1e5);
  EXPECT_EQ(b.shear_strength, 2e5);
  EXPECT_EQ(b.damping_ratio, 0.3);
  const BondSettings& d = s.bonds[1];
  EXPECT_EQ(d.gap, 0.0);
  EXPECT_EQ(d.poisson, 0.25);
  EXPECT_EQ(d.radius_factor, 1.0);
  EXPECT_TRUE(std::isinf(d.tensile_strength));
  EXPECT_TRUE(std::isinf(d.shear_strength));
  EXPECT_EQ(d.damping_ratio, 0.0);
  EXPECT_FALSE(s.materials[0].fixed);
  EXPECT_TRUE(s.materials[1].fixed);
}

TEST_F(BondScene, RefusalsNameTheKey) {
  expect_refused("[[bond]]\nmaterials = [\"soil\", \"sand\"]\nyoung = 1e6\n", 20,
                 "bond[0].materials", "unknown material 'sand'");
  expect_refused("[[bond]]\nmaterials = [\"soil\", \"soil\"]\n", 19, "bond[0].young",
                 "missing required key 'young'");
  expect_refused("[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\ntensile_strength = -1\n",
                 22, "bond[0].tensile_strength", "> 0");
  expect_refused("[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\nstrength = 1\n", 22,
                 "bond[0].strength", "unknown key");
}

/// Two touching spheres of radius r, one of each material.
ParticleStore two_spheres(double r) {
  ParticleStore p;
  const double inv_mass = 1 / sphere_mass(1850, r);
  p.add(0, {0.5, 0.5, 0.5}, r, 0, {0, 0, 0}, inv_mass);
  p.add(1, {0.5 + 2 * r, 0.5, 0.5}, r, 0, {0, 0, 0}, inv_mass);
  return p;
}

TEST_F(BondScene, AGapBeyondHalfTheSkinIsRefusedAtSetUp) {
  const Scene s = load("[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\ngap = 6e-4\n");
  try {
    make_engine_setup(s, two_spheres(0.005));
    ADD_FAILURE() << "a gap of 0.6 skin was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "bond[0].gap");
    EXPECT_NE(std::string(e.what()).find("neighbor.skin >= 0.0012"), std::string::npos) << e.what();
  }
  const Scene held = load("[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\ngap = 5e-4\n");
  EXPECT_EQ(make_engine_setup(held, two_spheres(0.005)).bonds.size(), 1u);
}

TEST_F(BondScene, ClodsAreDrawnInTheirRegionWithoutOverlapTheSameEveryTime) {
  const std::string clods =
      "[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\n"
      "clods = { count = 40, radius = { mean = 0.05, spread = 0.02 }, "
      "region = { min = [0.1, 0.1, 0.1], max = [0.9, 0.9, 0.4] } }\n";
  const Scene s = load(clods);
  ASSERT_EQ(s.bonds[0].clods.count, 40u);
  const std::vector<std::vector<Real4>> drawn = draw_clods(s);
  ASSERT_EQ(drawn.size(), 1u);
  ASSERT_EQ(drawn[0].size(), 40u);
  for (std::size_t a = 0; a < drawn[0].size(); ++a) {
    const Real4 c = drawn[0][a];
    EXPECT_GE(c.w, 0.03);
    EXPECT_LE(c.w, 0.07);
    EXPECT_TRUE(c.x >= 0.1 && c.x <= 0.9 && c.y >= 0.1 && c.y <= 0.9 && c.z >= 0.1 && c.z <= 0.4);
    for (std::size_t b = a + 1; b < drawn[0].size(); ++b)
      EXPECT_GE(norm(xyz(c) - xyz(drawn[0][b])), c.w + drawn[0][b].w) << a << " and " << b;
  }
  const std::vector<std::vector<Real4>> again = draw_clods(s);
  EXPECT_EQ(again[0][17].x, drawn[0][17].x);
  const Scene crowded = load(
      "[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\n"
      "clods = { count = 400, radius = 0.1 }\n");
  try {
    draw_clods(crowded);
    ADD_FAILURE() << "400 clods of 0.1 m fitted in a 1 m box";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "bond[0].clods.count");
  }
}

TEST_F(BondScene, PairsAreReadOrderedAndBadRowsNamed) {
  const auto write = [&](const std::string& name, const std::string& text) {
    const std::string file = (dir_ / name).string();
    std::ofstream(file) << text;
    return file;
  };
  const std::vector<ListedBond> pairs =
      read_bond_pairs(write("pairs.csv", "id_b,id_a\n7,3\n2,9\n\n3,5\n"));
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0].lower, 2u);
  EXPECT_EQ(pairs[0].higher, 9u);
  EXPECT_EQ(pairs[0].line, 3);
  EXPECT_EQ(pairs[1].lower, 3u);
  EXPECT_EQ(pairs[1].higher, 5u);
  EXPECT_EQ(pairs[2].higher, 7u);
  const auto refused = [&](const std::string& text, int line, const std::string& phrase) {
    const std::string file = write("bad.csv", text);
    try {
      read_bond_pairs(file);
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file);
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
    }
  };
  refused("a,b\n1,2\n", 1, "missing column 'id_a'");
  refused("id_a,id_b\n1,2.5\n", 2, "not a particle id");
  refused("id_a,id_b\n1,-2\n", 2, "not a particle id");
  refused("id_a,id_b\n4,4\n", 2, "paired with itself");
  refused("id_a,id_b\n1,2\n3,4\n2,1\n", 4, "listed twice (also on line 2)");
  refused("id_a,id_b\n", 1, "lists no pair");
}

TEST_F(BondScene, ATableOfPairsTakesNoMaterialsGapOrClods) {
  std::ofstream(dir_ / "pairs.csv") << "id_a,id_b\n0,1\n";
  const Scene s = load("[[bond]]\npairs = \"pairs.csv\"\nyoung = 1e6\n");
  EXPECT_EQ(s.bonds[0].pairs, (dir_ / "pairs.csv").string());
  expect_refused("[[bond]]\npairs = \"pairs.csv\"\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\n",
                 21, "bond[0].materials", "takes no materials");
  expect_refused("[[bond]]\npairs = \"pairs.csv\"\ngap = 0.001\nyoung = 1e6\n", 21, "bond[0].gap",
                 "takes no gap");
}

TEST_F(BondScene, NoMeshMayTakeTheBondsOutputName) {
  std::ofstream(dir_ / "plate.stl") << "solid p\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                       "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                                       "endsolid p\n";
  const std::string mesh =
      "[[mesh]]\nname = \"bonds\"\nfile = \"plate.stl\"\nmaterial = \"soil\"\n";
  EXPECT_NO_THROW(load(mesh));
  expect_refused("[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e6\n" + mesh, 23,
                 "mesh[0].name", "bonds.xmf");
}

TEST_F(BondScene, TheStiffestBondBoundsTheStep) {
  const double r = 0.005, young = 1e9;  // ν = 0.25 (the default): G = E/2.5
  const Scene s = load("[[bond]]\nmaterials = [\"soil\", \"soil\"]\nyoung = 1e9\n");
  const ParticleStore p = two_spheres(r);
  const TimeStepLimits limits = time_step_limits(s, p, {});
  // Equal spheres, L₀ = 2r, r_b = r: ω² = 2 [(k_n + 2k_s)/m + (k_t + 2k_b + 2k_s r²)/I].
  const double m = sphere_mass(1850, r), inertia = 0.4 * m * r * r, shear = young / 2.5;
  const double area = kPi * r * r, second = 0.25 * kPi * std::pow(r, 4), length = 2 * r;
  const double kn = young * area / length, ks = shear * area / length;
  const double kt = shear * 2 * second / length, kb = young * second / length;
  const double omega2 = 2 * ((kn + 2 * ks) / m + (kt + 2 * kb + 2 * ks * r * r) / inertia);
  EXPECT_NEAR(limits.bond, kPi / std::sqrt(omega2), 1e-12 * limits.bond);
  EXPECT_LE(limits.stable, 2 / std::sqrt(omega2));
  EXPECT_EQ(limits.critical(), limits.bond);  // far stiffer than the soil's contacts
  const Scene unbonded = load("");
  EXPECT_TRUE(std::isinf(time_step_limits(unbonded, p, {}).bond));
}

TEST_F(BondScene, AFixedMaterialMovesAtItsVelocityWhichBoundsTheStep) {
  std::string text = kScene;
  text.replace(text.find("fixed = true\n"), 13, "fixed = true\nvelocity = [0, 0, 0.5]\n");
  std::ofstream(path()) << text;
  const Scene moving = load_scene(path(), {});
  EXPECT_EQ(moving.materials[1].velocity.z, 0.5);
  EXPECT_EQ(norm(moving.materials[0].velocity), 0.0);
  const ParticleStore p = two_spheres(0.005);
  const double held = max_speed(load(""), p, {});
  EXPECT_NEAR(max_speed(moving, p, {}), held + 0.5, 1e-12);

  text = kScene;
  text.replace(text.find("young = 2e6\n"), 12, "young = 2e6\nvelocity = [1, 0, 0]\n");
  std::ofstream(path()) << text;
  try {
    load_scene(path(), {});
    ADD_FAILURE() << "a velocity without fixed = true was taken";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 10) << e.what();
    EXPECT_EQ(e.key(), "material[0].velocity") << e.what();
    EXPECT_NE(std::string(e.what()).find("fixed = true"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gpudem::test
