// Implements: the frame components of a force and a torque against hand-worked cases; through
// the binary, two plates grouped as one implement move exactly as the same plates given the
// same motion each, the implement's columns are the sums of its meshes' and its frame columns
// their components, and bad [[implement]] tables are refused before any output with the scene
// file, line and key.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/ImplementLoads.hpp"
#include "core/Rotation.hpp"
#include "support/PlateScene.hpp"
#include "support/RunBinary.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

TEST(FrameLoads, AlongPlusXDraftIsMinusFxAndLateralIsY) {
  const FrameLoads f = frame_loads({-10, 2, 5}, {1, 2, 3}, Rotation{}, {1, 0, 0}, {0, 0, 1});
  EXPECT_DOUBLE_EQ(f.draft, 10);
  EXPECT_DOUBLE_EQ(f.vertical, 5);
  EXPECT_DOUBLE_EQ(f.lateral, 2);  // l = u × f = z × x = y
  EXPECT_DOUBLE_EQ(f.moment_forward, 1);
  EXPECT_DOUBLE_EQ(f.moment_lateral, 2);
  EXPECT_DOUBLE_EQ(f.moment_vertical, 3);
}

TEST(FrameLoads, AlongMinusXDraftIsFxAndLateralIsMinusY) {
  const FrameLoads f = frame_loads({10, 2, 5}, {1, 2, 3}, Rotation{}, {-1, 0, 0}, {0, 0, 1});
  EXPECT_DOUBLE_EQ(f.draft, 10);
  EXPECT_DOUBLE_EQ(f.vertical, 5);
  EXPECT_DOUBLE_EQ(f.lateral, -2);
  EXPECT_DOUBLE_EQ(f.moment_forward, -1);
  EXPECT_DOUBLE_EQ(f.moment_lateral, -2);
  EXPECT_DOUBLE_EQ(f.moment_vertical, 3);
}

/// Turned a quarter turn about z, the frame that travelled along +x travels along +y.
TEST(FrameLoads, TheFrameTurnsWithTheImplement) {
  const Rotation quarter = rotation_by_vector({0, 0, kPi / 2});
  const FrameLoads f = frame_loads({3, -7, 1}, {0, 0, 0}, quarter, {1, 0, 0}, {0, 0, 1});
  EXPECT_NEAR(f.draft, 7, 1e-12);
  EXPECT_NEAR(f.vertical, 1, 1e-12);
  EXPECT_NEAR(f.lateral, -3, 1e-12);  // l turns from +y to −x
}

/// Two plates facing +x, one above the other (0.1 m × 0.05 m each, two triangles), so that
/// together they are the 0.1 m square plate of MeshSceneTest.
std::string half_plate_stl(double z0) {
  const auto v = [](double y, double z) {
    return "  vertex 0 " + std::to_string(y) + " " + std::to_string(z) + "\n";
  };
  const auto facet = [](const std::string& a, const std::string& b, const std::string& c) {
    return "facet normal 1 0 0\n outer loop\n" + a + b + c + " endloop\nendfacet\n";
  };
  const double z1 = z0 + 0.05;
  return "solid half\n" + facet(v(0, z0), v(0.1, z0), v(0.1, z1)) +
         facet(v(0, z0), v(0.1, z1), v(0, z1)) + "endsolid half\n";
}

/// Grains on a floor ahead of the two plates, which move at 0.2 m/s along +x from t = 0.01 s,
/// either each by its own [mesh.motion] (MOTION_LOW, MOTION_HIGH) or as one implement (IMPLEMENT).
const std::string kScene = test::plate_scene_head("0.05") + R"([[mesh]]
name = "low"
file = "low.stl"
offset = [0.005, 0.0, 0.0]
MOTION_LOW
[[mesh]]
name = "high"
file = "high.stl"
offset = [0.005, 0.0, 0.0]
MOTION_HIGH
IMPLEMENT
)" + test::kPlateGrains + R"(
[output]
timeseries_every = 0.001
)";

const char* kOwnMotion = R"([mesh.motion]
centre = [0.0, 0.05, 0.1]
times = [0.01, 1.0]
velocities = [[0.2, 0.0, 0.0], [0.2, 0.0, 0.0]]
)";

const char* kImplement = R"([[implement]]
name = "frame"
meshes = ["low", "high"]
reference = [0.0, 0.05, 0.1]

[implement.motion]
times = [0.01, 1.0]
velocities = [[0.2, 0.0, 0.0], [0.2, 0.0, 0.0]]
)";

/// The time series as columns by name.
std::map<std::string, std::vector<double>> read_columns(const fs::path& csv_path) {
  std::ifstream csv(csv_path);
  std::string line, cell;
  std::getline(csv, line);
  std::vector<std::string> names;
  for (std::stringstream header(line); std::getline(header, cell, ',');) names.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(csv, line)) {
    std::stringstream row(line);
    for (std::size_t k = 0; k < names.size() && std::getline(row, cell, ','); ++k)
      columns[names[k]].push_back(std::stod(cell));
  }
  return columns;
}

class ImplementScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gpudem_implement_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "low.stl") << half_plate_stl(0);
    std::ofstream(dir_ / "high.stl") << half_plate_stl(0.05);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Writes kScene with the three placeholders replaced and runs it into out_<name>.
  test::RunResult run(const std::string& name, const std::string& low, const std::string& high,
                      const std::string& implement, const std::string& options = " --quiet") {
    std::string text = kScene;
    for (auto [key, value] :
         {std::pair{"MOTION_LOW", &low}, {"MOTION_HIGH", &high}, {"IMPLEMENT", &implement}})
      text.replace(text.find(key), std::string(key).size(), *value);
    std::ofstream(dir_ / (name + ".toml")) << text;
    return test::run_binary((dir_ / (name + ".toml")).string() + " --output-dir " +
                            (dir_ / ("out_" + name)).string() + options);
  }
  void expect_refused(const test::RunResult& r, const std::string& where, const std::string& what) {
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(where), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out_bad"));
  }
  /// kImplement with `from` replaced by `to`.
  static std::string implement_with(const std::string& from, const std::string& to) {
    std::string text = kImplement;
    return text.replace(text.find(from), from.size(), to);
  }
  fs::path dir_;
};

TEST_F(ImplementScene, MovesItsMeshesAsTheirOwnMotionsAndSumsTheirLoads) {
  ASSERT_EQ(run("own", kOwnMotion, kOwnMotion, "").exit_code, 0);
  const test::RunResult r = run("grouped", "", "", kImplement);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto own = read_columns(dir_ / "out_own" / "timeseries.csv");
  auto grouped = read_columns(dir_ / "out_grouped" / "timeseries.csv");
  for (const char* mesh : {"low", "high"})
    for (const char* axis : {"_fx", "_fy", "_fz", "_tx", "_ty", "_tz"})
      EXPECT_EQ(own[std::string(mesh) + axis], grouped[std::string(mesh) + axis]) << mesh << axis;
  double most_draft = 0;
  for (std::size_t k = 0; k < grouped["time"].size(); ++k) {
    for (const char* axis : {"_fx", "_fy", "_fz", "_tx", "_ty", "_tz"}) {
      const std::string a = axis;
      EXPECT_DOUBLE_EQ(grouped["frame" + a][k], grouped["low" + a][k] + grouped["high" + a][k]);
    }
    EXPECT_DOUBLE_EQ(grouped["frame_draft"][k], -grouped["frame_fx"][k]);
    EXPECT_DOUBLE_EQ(grouped["frame_vertical"][k], grouped["frame_fz"][k]);
    EXPECT_DOUBLE_EQ(grouped["frame_lateral"][k], grouped["frame_fy"][k]);
    EXPECT_DOUBLE_EQ(grouped["frame_m_lateral"][k], grouped["frame_ty"][k]);
    EXPECT_DOUBLE_EQ(grouped["low_draft"][k], -grouped["low_fx"][k]);
    EXPECT_DOUBLE_EQ(grouped["high_m_vertical"][k], grouped["high_tz"][k]);
    most_draft = std::max(most_draft, grouped["frame_draft"][k]);
  }
  EXPECT_GT(most_draft, 1e-3);  // the grains resist the travel
  const test::RunResult summary = run("summary", "", "", kImplement, " --check");
  EXPECT_NE(
      summary.output.find("implement frame: meshes low, high; reference point (0, 0.05, 0.1) m; "
                          "forward (1, 0, 0), up (0, 0, 1)"),
      std::string::npos)
      << summary.output;
}

TEST_F(ImplementScene, BadTablesAreRefused) {
  const std::string where = "key 'implement[0].meshes'";
  expect_refused(run("bad", "", "", implement_with("\"high\"]", "\"blade\"]"), " --check"), where,
                 "no [[mesh]] is named 'blade' (meshes: 'low', 'high')");
  expect_refused(run("bad", "", kOwnMotion, kImplement, " --check"), where,
                 "mesh 'high' has its own [mesh.motion]");
  expect_refused(run("bad", "", "",
                     std::string(kImplement) + "\n" + implement_with("frame", "other"), " --check"),
                 "key 'implement[1].meshes'", "mesh 'low' is already in implement 'frame'");
  expect_refused(run("bad", "", "", implement_with("\"frame\"", "\"floor\""), " --check"),
                 "key 'implement[0].name'", "already used by a wall, mesh or implement");
  expect_refused(
      run("bad", "", "", implement_with("reference", "up = [1, 0, 0]\nreference"), " --check"),
      "key 'implement[0].forward'", "not along up");
  expect_refused(run("bad", "", "", implement_with("\"frame\"", "\"low_m\""), " --check"),
                 "key 'implement[0].name'", "two columns 'low_m_lateral'");
  const std::string still =
      "[implement.motion]\ntimes = [0.01, 1.0]\n"
      "velocities = [[0.2, 0.0, 0.0], [0.2, 0.0, 0.0]]\n";
  expect_refused(run("bad", "", "", implement_with(still, ""), " --check"),
                 "key 'implement[0].forward'", "give the implement's travel direction");
}

}  // namespace
}  // namespace gpudem
