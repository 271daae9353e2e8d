// --preview: the wall polygons, the end pose and the path against hand-worked cases; the PNG
// decoded here (its chunks' CRCs, the zlib stream's stored blocks and Adler-32) pixel for pixel;
// and through the binary, a scene previewed without a step: the XDMF pair holds every particle,
// the mesh and the walls, and the picture shows the grains and the tool; --preview with
// --resume, --restart or --check is refused.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/PreviewGeometry.hpp"
#include "core/PreviewImage.hpp"
#include "support/PlateScene.hpp"
#include "support/RunBinary.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

TEST(PreviewGeometry, FloorOfTheBoxIsItsBottomFace) {
  const PreviewSurface s = wall_in_box({0, 0, 0}, {0, 0, 1}, {0, 0, 0}, {2, 1, 1});
  ASSERT_EQ(s.vertices.size(), 5u);  // centroid and the four corners, each once
  EXPECT_EQ(s.triangles.size(), 4u);
  EXPECT_DOUBLE_EQ(s.vertices[0].x, 1);
  EXPECT_DOUBLE_EQ(s.vertices[0].y, 0.5);
  double area = 0;
  for (const auto& t : s.triangles)
    area +=
        0.5 * norm(cross(s.vertices[t[1]] - s.vertices[t[0]], s.vertices[t[2]] - s.vertices[t[0]]));
  EXPECT_NEAR(area, 2, 1e-12);
}

TEST(PreviewGeometry, DiagonalPlaneCutsARectangleAndAMissingPlaneNothing) {
  const double s2 = std::sqrt(0.5);
  const PreviewSurface cut = wall_in_box({1, 0, 0}, {s2, s2, 0}, {0, 0, 0}, {1, 1, 1});
  ASSERT_EQ(cut.vertices.size(), 5u);
  double area = 0;
  for (const auto& t : cut.triangles)
    area += 0.5 * norm(cross(cut.vertices[t[1]] - cut.vertices[t[0]],
                             cut.vertices[t[2]] - cut.vertices[t[0]]));
  EXPECT_NEAR(area, std::sqrt(2.0), 1e-12);  // √2 long, 1 high
  EXPECT_TRUE(wall_in_box({0, 0, 5}, {0, 0, 1}, {0, 0, 0}, {1, 1, 1}).vertices.empty());
}

TEST(PreviewGeometry, EndPoseAndPathFollowTheMotion) {
  // Half a turn about z in 1 s about a centre moving 1 m along +x.
  const PrescribedMotion motion({1, 0, 0},
                                {{0, {1, 0, 0}, {0, 0, kPi}}, {1, {1, 0, 0}, {0, 0, kPi}}});
  const std::vector<Vec3> end = vertices_at({{2, 0, 0}, {1, 1, 3}}, motion, 1.0);
  EXPECT_NEAR(end[0].x, 1, 1e-12);  // 1 m ahead of the centre, turned to 1 m behind it at x = 2
  EXPECT_NEAR(end[0].y, 0, 1e-12);
  EXPECT_NEAR(end[1].x, 2, 1e-12);
  EXPECT_NEAR(end[1].y, -1, 1e-12);
  EXPECT_NEAR(end[1].z, 3, 1e-12);
  const std::vector<Vec3> path = centre_path(motion, 1.0, 5);
  ASSERT_EQ(path.size(), 5u);
  EXPECT_NEAR(path[2].x, 1.5, 1e-12);
  EXPECT_NEAR(path[4].x, 2, 1e-12);
}

// --- PNG, read back independently ------------------------------------------------------------

std::uint32_t be32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t(b[at]) << 24) | (std::uint32_t(b[at + 1]) << 16) |
         (std::uint32_t(b[at + 2]) << 8) | b[at + 3];
}

/// CRC-32 (ISO 3309) from a table, as the PNG specification's sample code computes it.
std::uint32_t table_crc(const std::uint8_t* data, std::size_t n) {
  static std::uint32_t table[256];
  static bool made = false;
  if (!made) {
    for (std::uint32_t k = 0; k < 256; ++k) {
      std::uint32_t c = k;
      for (int bit = 0; bit < 8; ++bit) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      table[k] = c;
    }
    made = true;
  }
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) c = table[(c ^ data[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

struct DecodedPng {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< rows without their filter byte
  Rgb at(std::uint32_t x, std::uint32_t y) const {
    const std::size_t k = 3 * (std::size_t(y) * width + x);
    return {rgb[k], rgb[k + 1], rgb[k + 2]};
  }
};

/// The image of an 8-bit RGB PNG of stored deflate blocks; fails the test on any defect.
DecodedPng decode_png(const std::vector<std::uint8_t>& png) {
  DecodedPng out;
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  EXPECT_TRUE(png.size() > 8 && std::equal(signature, signature + 8, png.begin()));
  std::vector<std::uint8_t> zlib;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = be32(png, at);
    const std::string type(png.begin() + at + 4, png.begin() + at + 8);
    EXPECT_EQ(be32(png, at + 8 + length), table_crc(&png[at + 4], length + 4)) << type;
    if (type == "IHDR") {
      out.width = be32(png, at + 8);
      out.height = be32(png, at + 12);
      EXPECT_EQ(png[at + 16], 8);  // bit depth
      EXPECT_EQ(png[at + 17], 2);  // RGB
    }
    if (type == "IDAT")
      zlib.insert(zlib.end(), png.begin() + at + 8, png.begin() + at + 8 + length);
    at += 12 + length;
  }
  std::vector<std::uint8_t> raw;
  std::size_t at = 2;
  for (bool last = false; !last;) {
    last = zlib.at(at) & 1;
    EXPECT_EQ(zlib[at] >> 1, 0);  // stored block
    const std::size_t n = zlib[at + 1] | (zlib[at + 2] << 8);
    raw.insert(raw.end(), zlib.begin() + at + 5, zlib.begin() + at + 5 + n);
    at += 5 + n;
  }
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t byte : raw) a = (a + byte) % 65521, b = (b + a) % 65521;
  EXPECT_EQ(be32(zlib, at), (b << 16) | a);
  EXPECT_EQ(raw.size(), out.height * (1 + 3 * std::size_t(out.width)));
  for (std::uint32_t y = 0; y < out.height; ++y) {
    EXPECT_EQ(raw[y * (1 + 3 * std::size_t(out.width))], 0);  // filter: none
    auto row = raw.begin() + y * (1 + 3 * std::size_t(out.width)) + 1;
    out.rgb.insert(out.rgb.end(), row, row + 3 * out.width);
  }
  return out;
}

TEST(PreviewImage, PngHoldsTheCanvasPixelForPixel) {
  Canvas canvas(300, 250, {255, 255, 255});  // rows longer than one stored block in all
  const double a[2] = {10, 10}, b[2] = {100, 10}, c[2] = {10, 100};
  canvas.fill_triangle(a, b, c, {200, 0, 0}, 1);
  canvas.fill_circle(200, 150, 30, {0, 0, 250});
  const DecodedPng png = decode_png(canvas.png());
  ASSERT_EQ(png.width, 300u);
  ASSERT_EQ(png.height, 250u);
  EXPECT_EQ(png.at(20, 20), (Rgb{200, 0, 0}));      // inside the triangle
  EXPECT_EQ(png.at(90, 90), (Rgb{255, 255, 255}));  // beyond its hypotenuse
  EXPECT_EQ(png.at(200, 150), (Rgb{0, 0, 250}));    // the circle's centre
  EXPECT_EQ(png.at(200, 178), (Rgb{0, 0, 250}));    // 28.5 px from the centre
  EXPECT_EQ(png.at(200, 181), (Rgb{255, 255, 255}));
}

// --- through the binary ----------------------------------------------------------------------

/// 40 grains on a floor and a plate facing +x ahead of them that moves 0.19 m along +x.
const std::string kScene = test::plate_scene_head("1.0") + R"([[mesh]]
name = "plate"
file = "plate.stl"
offset = [-0.01, 0.0, 0.0]

[mesh.motion]
times = [0.01, 1.0]
velocities = [[0.2, 0.0, 0.0], [0.2, 0.0, 0.0]]

)" + test::kPlateGrains;

TEST(PreviewScene, WritesTheSceneAtTimeZeroWithoutAStep) {
  const fs::path dir = fs::temp_directory_path() / ("gpudem_preview_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "plate.stl") << test::plate_stl();
  std::ofstream(dir / "scene.toml") << kScene;
  const fs::path out = dir / "out";
  const test::RunResult r =
      test::run_binary((dir / "scene.toml").string() + " --preview --output-dir " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("preview of t = 0 written to"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "timeseries.csv"));
  EXPECT_FALSE(fs::exists(out / "particles_000000.h5"));
  const test::RunResult listing = test::run_command("h5ls -r " + (out / "preview.h5").string());
  for (const char* dataset :
       {"/particles/position      Dataset {40, 3}", "/mesh/plate/triangles    Dataset {2, 3}",
        "/mesh_end/plate/vertices Dataset {4, 3}", "/path/plate"})
    EXPECT_NE(listing.output.find(dataset), std::string::npos) << dataset << "\n" << listing.output;
  std::ifstream xmf(out / "preview.xmf");
  const std::string xml{std::istreambuf_iterator<char>(xmf), {}};
  for (const char* grid : {"Name=\"particles\"", "Name=\"plate\"", "Name=\"plate_end\"",
                           "Name=\"plate_path\"", "Name=\"floor\""})
    EXPECT_NE(xml.find(grid), std::string::npos) << grid;
  std::ifstream png_file(out / "preview.png", std::ios::binary);
  const DecodedPng png = decode_png({std::istreambuf_iterator<char>(png_file), {}});
  ASSERT_EQ(png.width, 1800u);
  std::size_t grain = 0, tool = 0;
  for (std::uint32_t y = 0; y < png.height; ++y)
    for (std::uint32_t x = 0; x < png.width; ++x) {
      const Rgb p = png.at(x, y);
      grain += p == Rgb{150, 110, 70};  // the first material's colour
      tool += p.r > 2 * p.b + 60 && p.g > 40 && p.r > 120 && p.g < p.r;  // orange, shaded
    }
  EXPECT_GT(grain, 100u);
  EXPECT_GT(tool, 1000u);  // the plate face-on in the side view, 0.1 m square
  for (const char* other : {" --resume", " --restart x.h5", " --check"}) {
    const test::RunResult refused =
        test::run_binary((dir / "scene.toml").string() + " --preview --output-dir " +
                         (dir / "other").string() + other);
    EXPECT_EQ(refused.exit_code, 2) << other << refused.output;
    EXPECT_NE(refused.output.find("excludes"), std::string::npos) << refused.output;
    EXPECT_FALSE(fs::exists(dir / "other"));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gpudem
