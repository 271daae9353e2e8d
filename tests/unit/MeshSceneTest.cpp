// Mesh walls through the binary: a [[mesh]] plate pushes grains and its force and torque
// columns appear in the time series; bad meshes and bad motion, and a mesh too wide for a
// periodic axis, stop the run before any output with the scene file, line and key.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/RunBinary.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;

/// A plate in the plane x = 0 facing +x (two triangles), 0.1 m × 0.1 m around (0, 0.05, 0.05),
/// plus `extra` facets.
std::string plate_stl(const std::string& extra = "") {
  const auto facet = [](const char* a, const char* b, const char* c) {
    return std::string("facet normal 1 0 0\n outer loop\n  vertex ") + a + "\n  vertex " + b +
           "\n  vertex " + c + "\n endloop\nendfacet\n";
  };
  return "solid plate\n" + facet("0 0 0", "0 0.1 0", "0 0.1 0.1") +
         facet("0 0 0", "0 0.1 0.1", "0 0 0.1") + extra + "endsolid plate\n";
}

/// Grains resting on a floor ahead of the plate (+x), which moves at 0.2 m/s along +x from
/// t = 0.01 s. Line 27 is the mesh's `file`.
const char* kScene = R"([simulation]
end_time = 0.05
dt = 1e-5

[domain]
min = [-0.05, 0.0, 0.0]
max = [0.2, 0.1, 0.1]

[[material]]
name = "sand"
density = 2500.0
young = 1e7
restitution = 0.3
friction = 0.5

[contact]
stiffness = 2000

[[wall]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "sand"

[[mesh]]
name = "plate"
file = "MESH"
offset = [0.005, 0.0, 0.0]

[mesh.motion]
times = [0.01, 1.0]
velocities = [[0.2, 0.0, 0.0], [0.2, 0.0, 0.0]]

[[insert]]
region = { min = [0.01, 0.02, 0.0], max = [0.05, 0.08, 0.02] }
count = 40
radius = 0.003
material = "sand"

[output]
timeseries_every = 0.001
)";

class MeshScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gpudem_mesh_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Writes the scene with its mesh file (relative to the scene) and runs it.
  test::RunResult run(const std::string& stl, const std::string& scene_text = kScene,
                      const std::string& options = "") {
    std::ofstream(dir_ / "plate.stl") << stl;
    std::string text = scene_text;
    text.replace(text.find("MESH"), 4, "plate.stl");
    std::ofstream(dir_ / "scene.toml") << text;
    return test::run_binary((dir_ / "scene.toml").string() + " --output-dir " +
                            (dir_ / "out").string() + options);
  }
  void expect_refused(const test::RunResult& r, const std::string& where, const std::string& what) {
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(where), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
  }
  fs::path dir_;
};

/// The plate pushes the grains along +x: they exert a force along −x on it.
TEST_F(MeshScene, PlatePushesGrainsAndReportsItsForce) {
  const test::RunResult r = run(plate_stl(), kScene, " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream csv(dir_ / "out" / "timeseries.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_NE(header.find("plate_fx,plate_fy,plate_fz,plate_tx,plate_ty,plate_tz"), std::string::npos)
      << header;
  std::size_t column = 0;
  for (std::size_t at = 0; at < header.find("plate_fx"); ++at) column += header[at] == ',';
  double most_negative = 0;
  while (std::getline(csv, line)) {
    std::stringstream row(line);
    std::string cell;
    for (std::size_t k = 0; k <= column; ++k) std::getline(row, cell, ',');
    most_negative = std::min(most_negative, std::stod(cell));
  }
  EXPECT_LT(most_negative, -1e-3);  // at least a millinewton against the motion
}

TEST_F(MeshScene, SummaryCountsZeroAreaTriangles) {
  const test::RunResult r =
      run(plate_stl("facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 0 0.05 0\n"
                    "  vertex 0 0.1 0\n endloop\nendfacet\n"),
          kScene, " --check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("mesh plate: 2 triangles, 4 vertices (1 zero-area triangles skipped)"),
            std::string::npos)
      << r.output;
}

TEST_F(MeshScene, MissingMeshFileIsRefused) {
  std::string scene = kScene;
  scene.replace(scene.find("MESH"), 4, "nowhere.stl");
  std::ofstream(dir_ / "scene.toml") << scene;
  const test::RunResult r =
      test::run_binary((dir_ / "scene.toml").string() + " --output-dir " + (dir_ / "out").string());
  expect_refused(r, "scene.toml:27: key 'mesh[0].file'", "STL file not found");
}

TEST_F(MeshScene, TruncatedBinaryMeshIsRefused) {
  std::string binary(80, ' ');
  binary += std::string("\x02\x00\x00\x00", 4) + std::string(60, '\0');  // 2 facets, 1.2 written
  expect_refused(run(binary), "scene.toml:27: key 'mesh[0].file'", "truncated binary STL");
}

TEST_F(MeshScene, NonFiniteVertexIsRefused) {
  std::string stl = plate_stl();
  stl.replace(stl.find("0 0.1 0.1"), 9, "0 nan 0.1");
  expect_refused(run(stl), "scene.toml:27: key 'mesh[0].file'", "is not a finite number");
}

TEST_F(MeshScene, MotionTimesMustIncrease) {
  std::string scene = kScene;
  scene.replace(scene.find("times = [0.01, 1.0]"), 19, "times = [1.0, 0.01]");
  expect_refused(run(plate_stl(), scene), "key 'mesh[0].motion.times'", "increase strictly");
}

TEST_F(MeshScene, MotionNeedsOneVelocityPerTime) {
  std::string scene = kScene;
  scene.replace(scene.find("times = [0.01, 1.0]"), 19, "times = [0.0, 0.01, 1.0]");
  expect_refused(run(plate_stl(), scene), "key 'mesh[0].motion.velocities'",
                 "an array of 3 vectors");
}

TEST_F(MeshScene, MeshNameMustDifferFromWallNames) {
  std::string scene = kScene;
  scene.replace(scene.find("name = \"plate\""), 14, "name = \"floor\"");
  expect_refused(run(plate_stl(), scene), "key 'mesh[0].name'", "already used by a wall");
}

/// A mesh's name names its output file <name>.xmf beside particles.xmf.
TEST_F(MeshScene, MeshNameMustNameAFileBesideTheParticles) {
  for (const char* name : {"particles", "..", "tool/blade"}) {
    SCOPED_TRACE(name);
    std::string scene = kScene;
    scene.replace(scene.find("name = \"plate\""), 14, std::string("name = \"") + name + "\"");
    expect_refused(run(plate_stl(), scene), "key 'mesh[0].name'", "names the mesh's output file");
  }
}

/// kScene with the domain periodic along y, of length L (from y = 0).
std::string periodic_in_y(double length) {
  std::string scene = kScene;
  const std::string old_max = "max = [0.2, 0.1, 0.1]\n";
  scene.replace(
      scene.find(old_max), old_max.size(),
      "max = [0.2, " + std::to_string(length) + ", 0.1]\nperiodic = [false, true, false]\n");
  return scene;
}

/// The plate spans 0.1 m along y. Radii 3 mm and the automatic skin (half the smallest radius,
/// 1.5 mm) leave L − 2 (r_max + 2 skin) = L − 0.012 m for it: a period of 0.1 m is too short.
TEST_F(MeshScene, MeshWiderThanAPeriodAllowsIsRefused) {
  expect_refused(run(plate_stl(), periodic_in_y(0.1)), "scene.toml:28: key 'mesh[0].file'",
                 "mesh 'plate' spans 0.1 m along periodic axis y (L = 0.1 m); a mesh must fit "
                 "within L - 2 (r_max + 2 skin) = 0.088 m");
}

/// With a period of 0.15 m (room 0.138 m) the translating plate fits; once it also turns, it
/// reaches up to half its diagonal, 0.05 √2 m, from its centre in any pose, so it counts as
/// spanning 0.1 √2 = 0.1414 m and is refused.
TEST_F(MeshScene, TurningMeshCountsItsWholeDiagonal) {
  const std::string scene = periodic_in_y(0.15);
  EXPECT_EQ(run(plate_stl(), scene, " --check").exit_code, 0);
  fs::remove_all(dir_ / "out");
  std::string turning = scene;
  const std::string velocities = "velocities = [[0.2, 0.0, 0.0], [0.2, 0.0, 0.0]]\n";
  turning.insert(turning.find(velocities) + velocities.size(),
                 "angular_velocities = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n");
  expect_refused(run(plate_stl(), turning), "key 'mesh[0].file'",
                 "spans 0.1414 m along periodic axis y (L = 0.15 m); a mesh must fit within "
                 "L - 2 (r_max + 2 skin) = 0.138 m to meet each particle as one periodic image");
}

}  // namespace
}  // namespace gpudem
