// STL meshes: ASCII and binary reading of a unit cube (welded to 8 vertices, 12 triangles and
// 18 edges, each edge on exactly two triangles, outward orientation kept), format detection,
// every input error with its file, line and triangle number, degenerate triangles, placement
// against hand-computed positions, and the load time of a 15,000-triangle torus.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/InputError.hpp"
#include "core/StlReader.hpp"
#include "core/TriangleMesh.hpp"
#include "support/SharedTempDir.hpp"

namespace gpudem {
namespace {

using Soup = std::vector<std::array<Vec3, 3>>;

constexpr double pi = 3.14159265358979323846;

// ---- meshes with known answers -----------------------------------------------------------

/// Corner i of the unit cube [0,1]³: x = bit 0, y = bit 1, z = bit 2 of i.
Vec3 cube_corner(int i) { return Vec3{double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)}; }

/// The unit cube as 12 triangles, two per face, counter-clockwise seen from outside.
Soup cube_soup() {
  const int corners[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                              {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  Soup soup;
  for (const auto& t : corners)
    soup.push_back({cube_corner(t[0]), cube_corner(t[1]), cube_corner(t[2])});
  return soup;
}

/// Torus (major radius 1, minor 0.3) on an nu × nv grid: 2·nu·nv triangles, nu·nv vertices,
/// 3·nu·nv edges, each on two triangles. Shared corners are computed once, so they are equal.
Soup torus_soup(int nu, int nv) {
  std::vector<Vec3> grid(nu * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
      const double ring = 1.0 + 0.3 * std::cos(v);
      grid[i * nv + j] = {ring * std::cos(u), ring * std::sin(u), 0.3 * std::sin(v)};
    }
  auto at = [&](int i, int j) { return grid[(i % nu) * nv + (j % nv)]; };
  Soup soup;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      soup.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      soup.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return soup;
}

// ---- STL writers -------------------------------------------------------------------------

/// ASCII STL, one keyword group per line: line 1 is "solid", triangle t (1-based) occupies
/// lines 7t − 5 ("facet") to 7t + 1 ("endfacet"), its corner k on line 7t − 4 + k.
std::vector<std::string> ascii_lines(const Soup& soup, const std::string& name = "part") {
  std::vector<std::string> lines{"solid " + name};
  for (const auto& triangle : soup) {
    lines.push_back("  facet normal 0 0 0");
    lines.push_back("    outer loop");
    for (const Vec3& p : triangle) {
      std::ostringstream s;
      s.precision(17);
      s << "      vertex " << p.x << " " << p.y << " " << p.z;
      lines.push_back(s.str());
    }
    lines.push_back("    endloop");
    lines.push_back("  endfacet");
  }
  lines.push_back("endsolid " + name);
  return lines;
}

void write_text(const std::string& path, const std::vector<std::string>& lines) {
  std::ofstream out(path, std::ios::binary);
  for (const std::string& line : lines) out << line << "\n";
}

void put_u32(std::string& bytes, std::uint32_t value) {
  for (int b = 0; b < 4; ++b) bytes.push_back(static_cast<char>((value >> (8 * b)) & 0xff));
}

void put_f32(std::string& bytes, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  put_u32(bytes, bits);
}

/// Binary STL bytes: `header` padded with NUL to 80 bytes, the count, then per triangle a zero
/// normal, three float32 corners and a zero attribute, all little-endian.
std::string binary_bytes(const Soup& soup, const std::string& header = "gpudem test mesh") {
  std::string bytes = header;
  bytes.resize(80, '\0');
  put_u32(bytes, static_cast<std::uint32_t>(soup.size()));
  for (const auto& triangle : soup) {
    for (int k = 0; k < 3; ++k) put_f32(bytes, 0.0);
    for (const Vec3& p : triangle) {
      put_f32(bytes, p.x);
      put_f32(bytes, p.y);
      put_f32(bytes, p.z);
    }
    bytes.append(2, '\0');
  }
  return bytes;
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// ---- checks ------------------------------------------------------------------------------

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// The InputError `action` throws (a failure when it throws none).
InputError input_error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "no InputError was thrown";
  return InputError("", 0, "", "");
}

bool same(const Vec3& a, const Vec3& b, double tolerance = 0) {
  return std::abs(a.x - b.x) <= tolerance && std::abs(a.y - b.y) <= tolerance &&
         std::abs(a.z - b.z) <= tolerance;
}

/// Every vertex of the mesh is used; each edge id of triangle t, slot k, is the sorted pair
/// (v_k, v_{k+1}); every edge is listed once and lies on exactly two triangles.
void expect_closed_two_manifold(const TriangleMesh& mesh) {
  std::vector<int> triangles_on_edge(mesh.edges.size(), 0);
  std::vector<bool> vertex_used(mesh.vertices.size(), false);
  ASSERT_EQ(mesh.triangle_edges.size(), mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      const std::uint32_t e = mesh.triangle_edges[t][k];
      ASSERT_LT(e, mesh.edges.size());
      const std::array<std::uint32_t, 2> sorted{std::min(a, b), std::max(a, b)};
      EXPECT_EQ(mesh.edges[e], sorted) << "triangle " << t << " slot " << k;
      ++triangles_on_edge[e];
      vertex_used[a] = true;
    }
  for (std::size_t e = 0; e < mesh.edges.size(); ++e)
    EXPECT_EQ(triangles_on_edge[e], 2) << "edge " << e;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) EXPECT_TRUE(vertex_used[v]) << v;
  auto edges = mesh.edges;
  std::sort(edges.begin(), edges.end());
  EXPECT_EQ(std::adjacent_find(edges.begin(), edges.end()), edges.end()) << "duplicate edge";
}

/// The unit cube: its 8 corners once each, 12 triangles, 18 edges, every triangle's normal
/// (v1 − v0) × (v2 − v0) pointing away from the centre, nothing skipped.
void expect_unit_cube(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_EQ(mesh.edges.size(), 18u);
  EXPECT_EQ(mesh.skipped_degenerate, 0u);
  for (int i = 0; i < 8; ++i) {
    int matches = 0;
    for (const Vec3& v : mesh.vertices) matches += same(v, cube_corner(i));
    EXPECT_EQ(matches, 1) << "corner " << i;
  }
  const Vec3 centre{0.5, 0.5, 0.5};
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    EXPECT_GT(dot(cross(b - a, c - a), (1.0 / 3.0) * (a + b + c) - centre), 0.0);
  }
  expect_closed_two_manifold(mesh);
}

class StlReaderTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::make_shared_temp_dir("gpudem_stl_"); }
  void TearDown() override { test::remove_shared_temp_dir(dir_); }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }

  std::string dir_;
};

// ---- reading -----------------------------------------------------------------------------

TEST_F(StlReaderTest, AsciiCubeWeldsToEightVerticesTwelveTrianglesEighteenEdges) {
  write_text(path("cube.stl"), ascii_lines(cube_soup()));
  expect_unit_cube(load_mesh(path("cube.stl"), MeshPlacement{}));
}

TEST_F(StlReaderTest, BinaryCubeWeldsToEightVerticesTwelveTrianglesEighteenEdges) {
  write_bytes(path("cube.stl"), binary_bytes(cube_soup()));
  expect_unit_cube(load_mesh(path("cube.stl"), MeshPlacement{}));
}

TEST_F(StlReaderTest, ReadsCornersExactlyAsWrittenInFileOrder) {
  const Soup cube = cube_soup();
  write_bytes(path("cube.stl"), binary_bytes(cube));
  const Soup read = read_stl(path("cube.stl"));
  ASSERT_EQ(read.size(), cube.size());
  for (std::size_t t = 0; t < cube.size(); ++t)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(same(read[t][k], cube[t][k])) << t << " " << k;
}

TEST_F(StlReaderTest, BinaryWhoseHeaderStartsWithSolidIsReadAsBinary) {
  write_bytes(path("cube.stl"), binary_bytes(cube_soup(), "solid cube exported by a CAD tool"));
  expect_unit_cube(load_mesh(path("cube.stl"), MeshPlacement{}));
}

TEST_F(StlReaderTest, AsciiKeywordsInUpperCaseAndSeveralSolidsAreRead) {
  const Soup cube = cube_soup();
  std::vector<std::string> lines = ascii_lines(Soup(cube.begin(), cube.begin() + 5), "front");
  for (const std::string& line : ascii_lines(Soup(cube.begin() + 5, cube.end()), "back"))
    lines.push_back(line);
  for (std::string& line : lines)
    for (char& c : line) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  write_text(path("cube.stl"), lines);
  expect_unit_cube(load_mesh(path("cube.stl"), MeshPlacement{}));
}

// ---- errors ------------------------------------------------------------------------------

TEST_F(StlReaderTest, TruncatedBinaryNamesDeclaredAndActualSize) {
  std::string bytes = binary_bytes(cube_soup(), "solid cube");
  bytes.resize(bytes.size() - 25);  // 84 + 50·12 − 25 = 659 bytes
  write_bytes(path("cut.stl"), bytes);
  const InputError error = input_error_of([&] { read_stl(path("cut.stl")); });
  EXPECT_EQ(error.file(), path("cut.stl"));
  EXPECT_TRUE(contains(error.what(),
                       "truncated binary STL: the header declares 12 triangles, "
                       "which need 84 + 50 × 12 = 684 bytes, but the file has "
                       "659 bytes"))
      << error.what();
}

TEST_F(StlReaderTest, TrailingBytesAfterBinaryTrianglesAreCounted) {
  write_bytes(path("long.stl"), binary_bytes(cube_soup()) + "1234567");
  const InputError error = input_error_of([&] { read_stl(path("long.stl")); });
  EXPECT_TRUE(contains(error.what(),
                       "binary STL with 7 trailing bytes: the header declares 12 "
                       "triangles, which need 84 + 50 × 12 = 684 bytes, but the "
                       "file has 691 bytes"))
      << error.what();
}

TEST_F(StlReaderTest, FileShorterThanBinaryHeaderIsNotAnStl) {
  write_text(path("note.stl"), {"hello"});
  const InputError error = input_error_of([&] { read_stl(path("note.stl")); });
  EXPECT_TRUE(contains(error.what(), "not an STL file: only 6 bytes")) << error.what();
}

TEST_F(StlReaderTest, TextNotStartingWithSolidIsReportedAsSuch) {
  std::vector<std::string> lines = ascii_lines(cube_soup());
  lines.front() = "mesh cube";
  write_text(path("other.stl"), lines);
  const InputError error = input_error_of([&] { read_stl(path("other.stl")); });
  EXPECT_TRUE(contains(error.what(), "the file looks like text, but ASCII STL starts with 'solid'"))
      << error.what();
}

TEST_F(StlReaderTest, NonFiniteBinaryCoordinateNamesTriangleAndCorner) {
  Soup soup = cube_soup();
  soup[4][1].y = std::numeric_limits<double>::quiet_NaN();
  write_bytes(path("nan.stl"), binary_bytes(soup));
  const InputError error = input_error_of([&] { read_stl(path("nan.stl")); });
  EXPECT_EQ(error.line(), 0);
  EXPECT_TRUE(contains(error.what(), "triangle 5 of 12: corner 2 has a non-finite coordinate"))
      << error.what();
}

TEST_F(StlReaderTest, NonFiniteAsciiCoordinateNamesLineTriangleAndCorner) {
  for (const std::string bad : {"nan", "inf", "-inf", "1e400"}) {
    std::vector<std::string> lines = ascii_lines(cube_soup());
    lines[32] = "      vertex 0 " + bad + " 1";  // line 7·5 − 4 + 2 = 33: triangle 5, corner 2
    write_text(path("nan.stl"), lines);
    const InputError error = input_error_of([&] { read_stl(path("nan.stl")); });
    EXPECT_EQ(error.line(), 33) << bad;
    EXPECT_TRUE(contains(error.what(),
                         "triangle 5: corner 2: coordinate '" + bad + "' is not a finite number"))
        << error.what();
  }
}

TEST_F(StlReaderTest, MisspelledAsciiKeywordNamesItsLine) {
  std::vector<std::string> lines = ascii_lines(cube_soup());
  lines[16] = "    outer lop";  // line 7·3 − 4 = 17: triangle 3's "outer loop"
  write_text(path("typo.stl"), lines);
  const InputError error = input_error_of([&] { read_stl(path("typo.stl")); });
  EXPECT_EQ(error.line(), 17);
  EXPECT_TRUE(contains(error.what(), "typo.stl:17: expected 'loop' but found 'lop'"))
      << error.what();
}

TEST_F(StlReaderTest, NonNumericAsciiCoordinateNamesItsLine) {
  std::vector<std::string> lines = ascii_lines(cube_soup());
  lines[3] = "      vertex 0 zero 0";  // line 7·1 − 4 + 1 = 4: triangle 1, corner 1
  write_text(path("word.stl"), lines);
  const InputError error = input_error_of([&] { read_stl(path("word.stl")); });
  EXPECT_EQ(error.line(), 4);
  EXPECT_TRUE(
      contains(error.what(), "triangle 1: corner 1: expected a coordinate but found 'zero'"))
      << error.what();
}

TEST_F(StlReaderTest, AsciiCutAfterAFacetReportsTheEndOfTheFile) {
  std::vector<std::string> lines = ascii_lines(cube_soup());
  lines.resize(15);  // through line 15, triangle 2's "endfacet"
  write_text(path("cut.stl"), lines);
  const InputError error = input_error_of([&] { read_stl(path("cut.stl")); });
  EXPECT_EQ(error.line(), 16);  // the empty line after the last newline
  EXPECT_TRUE(
      contains(error.what(), "expected 'facet' or 'endsolid' but found the end of the file"))
      << error.what();
}

TEST_F(StlReaderTest, MissingFileAndDirectoryAreNamed) {
  const InputError missing = input_error_of([&] { read_stl(path("absent.stl")); });
  EXPECT_EQ(missing.file(), path("absent.stl"));
  EXPECT_TRUE(contains(missing.what(), "STL file not found")) << missing.what();
  const InputError directory = input_error_of([&] { read_stl(dir_); });
  EXPECT_TRUE(contains(directory.what(), "is a directory, not an STL file")) << directory.what();
}

TEST_F(StlReaderTest, FilesWithoutTrianglesAreRejected) {
  write_bytes(path("empty_binary.stl"), binary_bytes({}));
  write_text(path("empty_ascii.stl"), {"solid nothing", "endsolid nothing"});
  for (const std::string name : {"empty_binary.stl", "empty_ascii.stl"}) {
    const InputError error = input_error_of([&] { read_stl(path(name)); });
    EXPECT_TRUE(contains(error.what(), name + ": STL file contains no triangles")) << error.what();
  }
}

TEST_F(StlReaderTest, InvalidPlacementIsRejectedBeforeReading) {
  write_bytes(path("cube.stl"), binary_bytes(cube_soup()));
  MeshPlacement flat;
  flat.scale = 0;
  EXPECT_TRUE(contains(input_error_of([&] { load_mesh(path("cube.stl"), flat); }).what(),
                       "scale must be positive and finite"));
  MeshPlacement no_axis;
  no_axis.rotation_axis = {0, 0, 0};
  EXPECT_TRUE(contains(input_error_of([&] { load_mesh(path("cube.stl"), no_axis); }).what(),
                       "rotation axis must be a finite non-zero vector"));
}

// ---- welding and degenerate triangles ----------------------------------------------------

TEST(BuildMeshTest, IdsCountUpInOrderOfFirstUseAndKeepPositionsExactly) {
  const Soup cube = cube_soup();
  const TriangleMesh mesh = build_mesh(cube);
  const std::array<std::uint32_t, 3> first{0, 1, 2};
  EXPECT_EQ(mesh.triangles[0], first);
  EXPECT_EQ(mesh.triangle_edges[0], first);
  for (std::size_t t = 0; t < cube.size(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(same(mesh.vertices[mesh.triangles[t][k]], cube[t][k])) << t << " " << k;
}

TEST(BuildMeshTest, NegativeAndPositiveZeroWeld) {
  const Soup soup{{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}},
                  {Vec3{-0.0, 1, 0}, Vec3{1, 0, -0.0}, Vec3{1, 1, 0}}};
  const TriangleMesh mesh = build_mesh(soup);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.edges.size(), 5u);
}

TEST_F(StlReaderTest, ZeroAreaTrianglesAreSkippedCountedAndLeaveNoVertex) {
  Soup soup{{Vec3{0, 0, 0}, Vec3{0.5, 0, 0}, Vec3{1, 0, 0}},       // collinear: area 0
            {Vec3{1, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 1}},         // repeated corner
            {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0.5, 1e-12, 0}}};  // 5e-13 ≤ 1e-12 · 3
  for (const auto& triangle : cube_soup()) soup.push_back(triangle);
  write_text(path("slivers.stl"), ascii_lines(soup));
  const TriangleMesh mesh = load_mesh(path("slivers.stl"), MeshPlacement{});
  EXPECT_EQ(mesh.skipped_degenerate, 3u);
  ASSERT_EQ(mesh.vertices.size(), 8u);  // not (0.5, 0, 0) nor (0.5, 1e-12, 0)
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_EQ(mesh.edges.size(), 18u);
  expect_closed_two_manifold(mesh);
}

TEST(BuildMeshTest, DegenerateThresholdScalesWithTheBoundingBox) {
  // Bounding box diagonal² = 2, so the threshold area is 2e-12; the slivers have base 1 and
  // heights 3e-12 (area 1.5e-12, dropped) and 5e-12 (area 2.5e-12, kept).
  for (const double scale : {1.0, 1e-3, 1e3}) {
    const Soup soup{{Vec3{0, 0, 0}, Vec3{scale, 0, 0}, Vec3{0, scale, 0}},
                    {Vec3{0, 0, 0}, Vec3{scale, 0, 0}, Vec3{0.5 * scale, 3e-12 * scale, 0}},
                    {Vec3{0, 0, 0}, Vec3{scale, 0, 0}, Vec3{0.5 * scale, 5e-12 * scale, 0}}};
    const TriangleMesh mesh = build_mesh(soup);
    EXPECT_EQ(mesh.skipped_degenerate, 1u) << scale;
    EXPECT_EQ(mesh.triangles.size(), 2u) << scale;
  }
}

TEST_F(StlReaderTest, FileOfOnlyZeroAreaTrianglesIsRejected) {
  write_text(path("flat.stl"), ascii_lines({{Vec3{0, 0, 0}, Vec3{1, 1, 1}, Vec3{2, 2, 2}}}));
  const InputError error = input_error_of([&] { load_mesh(path("flat.stl"), MeshPlacement{}); });
  EXPECT_TRUE(contains(error.what(), "all 1 triangles have zero area")) << error.what();
}

// ---- placement ---------------------------------------------------------------------------

TEST_F(StlReaderTest, PlacementScalesThenRotatesThenOffsets) {
  write_bytes(path("cube.stl"), binary_bytes(cube_soup()));
  MeshPlacement placement;
  placement.scale = 2;
  placement.rotation_axis = {0, 0, 1};
  placement.rotation_angle = pi / 2;
  placement.offset = {1, 2, 3};
  const TriangleMesh mesh = load_mesh(path("cube.stl"), placement);
  // (x, y, z) → 2(x, y, z) → (−2y, 2x, 2z) → (1 − 2y, 2 + 2x, 3 + 2z); e.g. (1,0,0) → (1,4,3).
  const double tolerance = 1e-12;  // cos(π/2) rounds to 6.1e-17, not 0
  EXPECT_TRUE(same(mesh.vertices[mesh.triangles[10][0]], Vec3{1, 4, 3}, tolerance));   // (1,0,0)
  EXPECT_TRUE(same(mesh.vertices[mesh.triangles[10][2]], Vec3{-1, 4, 5}, tolerance));  // (1,1,1)
  ASSERT_EQ(mesh.vertices.size(), 8u);
  for (int i = 0; i < 8; ++i) {
    const Vec3 c = cube_corner(i);
    int matches = 0;
    for (const Vec3& v : mesh.vertices)
      matches += same(v, Vec3{1 - 2 * c.y, 2 + 2 * c.x, 3 + 2 * c.z}, tolerance);
    EXPECT_EQ(matches, 1) << "corner " << i;
  }
  EXPECT_EQ(mesh.edges.size(), 18u);
}

TEST_F(StlReaderTest, RotationAboutTheDiagonalPermutesCoordinates) {
  // A third of a turn about (1,1,1) (not normalised) maps (x, y, z) to (z, x, y).
  write_bytes(path("cube.stl"), binary_bytes(cube_soup()));
  MeshPlacement placement;
  placement.rotation_axis = {1, 1, 1};
  placement.rotation_angle = 2 * pi / 3;
  const TriangleMesh mesh = load_mesh(path("cube.stl"), placement);
  const Soup cube = cube_soup();
  for (std::size_t t = 0; t < cube.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = cube[t][k];
      EXPECT_TRUE(same(mesh.vertices[mesh.triangles[t][k]], Vec3{p.z, p.x, p.y}, 1e-12))
          << t << " " << k;
    }
}

// ---- size --------------------------------------------------------------------------------

TEST_F(StlReaderTest, FifteenThousandTriangleTorusLoadsQuickly) {
  const Soup torus = torus_soup(100, 75);
  ASSERT_EQ(torus.size(), 15000u);
  write_bytes(path("torus_binary.stl"), binary_bytes(torus));
  write_text(path("torus_ascii.stl"), ascii_lines(torus));
  for (const std::string name : {"torus_binary.stl", "torus_ascii.stl"}) {
    const auto start = std::chrono::steady_clock::now();
    const TriangleMesh mesh = load_mesh(path(name), MeshPlacement{});
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    std::printf("[ timing   ] %s: 15000 triangles loaded in %.4f s\n", name.c_str(),
                elapsed.count());
    EXPECT_EQ(mesh.vertices.size(), 7500u) << name;
    EXPECT_EQ(mesh.triangles.size(), 15000u) << name;
    EXPECT_EQ(mesh.edges.size(), 22500u) << name;  // Euler: V − E + F = 0 for a torus
    expect_closed_two_manifold(mesh);
  }
}

}  // namespace
}  // namespace gpudem
