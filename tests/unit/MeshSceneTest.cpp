// Mesh walls through the binary: a [[mesh]] plate pushes grains and its force and torque
// columns appear in the time series; the summary says where each mesh is; bad meshes and bad
// motion, a mesh that never meets the domain, starts inside the grains or is smaller than a
// grain, and a mesh too wide for a periodic axis, stop the run before any output with the scene
// file, line and key.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/PlateScene.hpp"
#include "support/RunBinary.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;

using test::plate_stl;

/// Grains resting on a floor ahead of the plate (+x), which moves at 0.2 m/s along +x from
/// t = 0.01 s. Line 27 is the mesh's `file`.
const std::string kScene = test::plate_scene_head("0.05") + R"([[mesh]]
name = "plate"
file = "MESH"
offset = [0.005, 0.0, 0.0]

[mesh.motion]
times = [0.01, 1.0]
velocities = [[0.2, 0.0, 0.0], [0.2, 0.0, 0.0]]

)" + test::kPlateGrains + R"(
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

/// kScene with `line` added after the mesh's offset (line 29).
std::string with_placement(const std::string& line) {
  std::string scene = kScene;
  const std::string offset = "offset = [0.005, 0.0, 0.0]\n";
  return scene.insert(scene.find(offset) + offset.size(), line + "\n");
}

/// The start-up summary says where each mesh is at t = 0 and what it sweeps until the end.
TEST_F(MeshScene, SummaryGivesTheMeshsStartAndSweptBoxes) {
  const test::RunResult r = run(plate_stl(), kScene, " --check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // 0.2 m/s from t = 0.01 s to the end at 0.05 s: 8 mm along +x.
  EXPECT_NE(r.output.find("mesh plate: 2 triangles, 4 vertices; at t = 0 within x [0.005, 0.005], "
                          "y [0, 0.1], z [0, 0.1] m; until t = 0.05 s within x [0.005, 0.013], "
                          "y [0, 0.1], z [0, 0.1] m"),
            std::string::npos)
      << r.output;
}

/// A tool placed 5 m beyond the bin's x range (the mistake of a unit or a sign) never meets a
/// particle: refused before any output, naming its offset (line 28).
TEST_F(MeshScene, MeshThatNeverMeetsTheDomainIsRefused) {
  std::string scene = kScene;
  scene.replace(scene.find("offset = [0.005, 0.0, 0.0]"), 26, "offset = [5.0, 0.0, 0.0]");
  expect_refused(run(plate_stl(), scene), "scene.toml:28: key 'mesh[0].offset'",
                 "mesh 'plate' never meets the domain: at t = 0 it spans x [5, 5] m and until the "
                 "end of the run [5, 5.008] m, outside the domain's [-0.05, 0.2] m");
}

/// A tool placed in the middle of the grains at t = 0 (a sign or an offset mistaken) is
/// refused before any output, with the count and the deepest overlap, naming its offset.
TEST_F(MeshScene, MeshPlacedInsideTheGrainsIsRefused) {
  std::string scene = kScene;
  scene.replace(scene.find("offset = [0.005, 0.0, 0.0]"), 26, "offset = [0.03, 0.0, 0.0]");
  const test::RunResult r = run(plate_stl(), scene);
  expect_refused(r, "scene.toml:28: key 'mesh[0].offset'", "mesh 'plate' overlaps ");
  EXPECT_NE(r.output.find("% of its radius) at ("), std::string::npos) << r.output;
}

/// A tool that starts outside and moves in is accepted: 10 m/s for 0.04 s carries it 0.4 m
/// (into grains ten times stiffer than kScene's, which hold a 10 m/s impact).
TEST_F(MeshScene, MeshThatEntersTheDomainLaterIsAccepted) {
  std::string scene = kScene;
  scene.replace(scene.find("stiffness = 2000"), 16, "stiffness = 20000");
  scene.replace(scene.find("offset = [0.005, 0.0, 0.0]"), 26, "offset = [-0.3, 0.0, 0.0]");
  scene.replace(scene.find("[[0.2, 0.0, 0.0], [0.2, 0.0, 0.0]]"), 34,
                "[[10.0, 0.0, 0.0], [10.0, 0.0, 0.0]]");
  const test::RunResult r = run(plate_stl(), scene, " --check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("until t = 0.05 s within x [-0.3, 0.1]"), std::string::npos) << r.output;
}

/// A scale that shrinks the 0.1 m plate to 1 mm, below the 6 mm grains, is refused naming it.
TEST_F(MeshScene, MeshSmallerThanAParticleIsRefused) {
  expect_refused(run(plate_stl(), with_placement("scale = 0.01")),
                 "scene.toml:29: key 'mesh[0].scale'",
                 "mesh 'plate' spans only 0.001 m at scale 0.01, less than the smallest "
                 "particle's diameter (0.006 m)");
}

/// The summary line of mesh `name` in `output`.
std::string mesh_line(const std::string& output, const std::string& name) {
  const std::size_t at = output.find("mesh " + name + ":");
  return at == std::string::npos ? "" : output.substr(at, output.find('\n', at) - at);
}

/// A quarter turn about z given in degrees places the plate as the same turn in radians: it then
/// spans x [-0.095, 0.005] (the plate's y extent turned onto −x).
TEST_F(MeshScene, RotationInDegreesEqualsRotationInRadians) {
  const test::RunResult degrees =
      run(plate_stl(), with_placement("rotation_degrees = 90"), " --check");
  EXPECT_EQ(degrees.exit_code, 0) << degrees.output;
  EXPECT_NE(mesh_line(degrees.output, "plate").find("at t = 0 within x [-0.095, 0.005], y ["),
            std::string::npos)
      << degrees.output;
  const test::RunResult radians =
      run(plate_stl(), with_placement("rotation_angle = 1.5707963267948966"), " --check");
  EXPECT_EQ(mesh_line(radians.output, "plate"), mesh_line(degrees.output, "plate"));
  EXPECT_EQ(radians.output.find("warning"), std::string::npos) << radians.output;
}

/// An angle of 10 "rad" is degrees meant most likely: warned of (the run goes on as written);
/// giving the angle twice is refused.
TEST_F(MeshScene, AngleBeyondAFullTurnIsWarnedOfAndTwoAnglesAreRefused) {
  const test::RunResult r = run(plate_stl(), with_placement("rotation_angle = 10"), " --check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: " + (dir_ / "scene.toml").string() +
                          ":29: key 'mesh[0].rotation_angle': an angle of 10 rad is more than a "
                          "full turn; for degrees write rotation_degrees instead"),
            std::string::npos)
      << r.output;
  fs::remove_all(dir_ / "out");
  expect_refused(run(plate_stl(), with_placement("rotation_angle = 1.0\nrotation_degrees = 57.3")),
                 "key 'mesh[0].rotation_degrees'", "give the angle once");
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
