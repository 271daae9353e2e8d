// Particle snapshots read back with the HDF5 C API: every dataset equals the particle store bit
// for bit at this run's rank count (each rank checks its own rows), the attributes hold time and
// step, ranks without particles take part, and the .xmf lists every file by relative name. With
// the rank field, dataset "rank" holds each row's writing rank, and the .xmf lists it for exactly
// the snapshots that hold it, also when a resumed series switches it on or off. A field set
// leaves the other datasets out of file and .xmf, single precision stores every real value
// rounded to float32 (Precision 4 in the .xmf), and a resumed series keeps each snapshot's
// fields and precision. A mesh wall
// goes into group /mesh/<name>/ of the same files, with the pressure of each triangle against
// closed forms, and into <name>.xmf, a Triangle grid per snapshot that lists exactly the
// snapshots of the particles' .xmf, also after a resume; without meshes nothing of it appears.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "comm/SnapshotWriter.hpp"

#include "support/H5Id.hpp"
#include "support/MpiRank.hpp"
#include "support/SharedTempDir.hpp"
#include "support/SnapshotReadBack.hpp"
#include "support/TestPaths.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;

using test::comm_rank;
using test::comm_size;

using test::expect_bit_identical;
using test::expect_snapshot_holds;
using test::expected_offset;
using test::global_count;
using test::H5Id;
using test::random_store;
using test::read_rows;
using test::xyz_of;

/// Default options with files named `<basename>_<index>.h5`, with or without the rank field.
SnapshotOptions named(const std::string& basename, bool rank_field = false) {
  SnapshotOptions options;
  options.basename = basename;
  options.layout.rank_field = rank_field;
  return options;
}

/// Default options with the rank field.
SnapshotOptions with_rank_field() { return named(kParticlesBasename, true); }

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Every rank's particle count, in rank order.
std::vector<std::uint64_t> counts_of_all_ranks(std::uint64_t count) {
  std::vector<std::uint64_t> counts(comm_size());
  MPI_Allgather(&count, 1, MPI_UINT64_T, counts.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  return counts;
}

bool file_has_dataset(const std::string& path, const char* name) {
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  EXPECT_GE(file.id, 0) << "cannot open " << path;
  return file.id >= 0 && H5Lexists(file.id, name, H5P_DEFAULT) > 0;
}

/// Checks that dataset "rank" holds this rank's number in each of its rows, and (on rank 0,
/// reading the whole dataset) that the file is every rank's count of rows of its number, in
/// rank order.
void expect_rank_field_holds_the_writing_ranks(const std::string& path, std::uint64_t count) {
  MPI_Barrier(MPI_COMM_WORLD);
  const std::vector<std::uint64_t> counts = counts_of_all_ranks(count);
  const hsize_t n = std::accumulate(counts.begin(), counts.end(), std::uint64_t(0));
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  ASSERT_GE(file.id, 0) << "cannot open " << path;
  expect_bit_identical(std::vector<std::uint32_t>(count, comm_rank()),
                       read_rows<std::uint32_t>(file.id, "rank", H5T_STD_U32LE, H5T_NATIVE_UINT32,
                                                {n}, expected_offset(count), count),
                       "rank");
  if (comm_rank() != 0) return;
  std::vector<std::uint32_t> whole;
  for (int r = 0; r < comm_size(); ++r)
    whole.insert(whole.end(), counts[r], static_cast<std::uint32_t>(r));
  expect_bit_identical(
      whole, read_rows<std::uint32_t>(file.id, "rank", H5T_STD_U32LE, H5T_NATIVE_UINT32, {n}, 0, n),
      "rank (whole file)");
}

/// The value of XML attribute `key` in the tag text `tag` ("" when absent).
std::string xml_attribute(const std::string& tag, const std::string& key) {
  const std::string opening = " " + key + "=\"";
  const std::size_t start = tag.find(opening);
  if (start == std::string::npos) return "";
  const std::size_t first = start + opening.size();
  return tag.substr(first, tag.find('"', first) - first);
}

/// An element of an .xmf: the text of its opening tag, and its content up to its closing tag
/// (the document's elements of one name do not nest, except Grid, which is cut at its first
/// "</Grid>": the uniform grids hold none).
struct XmlElement {
  std::string tag;
  std::string content;
};

/// Every element named `name` in `text`, in document order (each has a closing tag).
std::vector<XmlElement> xml_elements(const std::string& text, const std::string& name) {
  std::vector<XmlElement> elements;
  const std::string opening = "<" + name + " ", closing = "</" + name + ">";
  for (std::size_t at = text.find(opening); at != std::string::npos;
       at = text.find(opening, at + 1)) {
    const std::size_t tag_end = text.find('>', at);
    const std::size_t end = text.find(closing, tag_end);
    elements.push_back(
        {text.substr(at, tag_end + 1 - at), text.substr(tag_end + 1, end - tag_end - 1)});
  }
  return elements;
}

/// One uniform grid of an .xmf: the HDF5 file its geometry reads, and its attributes by name
/// with the opening tag and text of each attribute's DataItem.
struct ListedGrid {
  std::string h5_file;
  std::vector<std::pair<std::string, XmlElement>> attributes;
};

std::vector<ListedGrid> uniform_grids(const std::string& xmf) {
  std::vector<ListedGrid> grids;
  for (const XmlElement& grid : xml_elements(xmf, "Grid")) {
    if (xml_attribute(grid.tag, "GridType") != "Uniform") continue;
    ListedGrid listed;
    const std::vector<XmlElement> geometry = xml_elements(grid.content, "DataItem");
    const std::string source = geometry.empty() ? "" : geometry.front().content;
    listed.h5_file = source.substr(0, source.find(':'));
    for (const XmlElement& attribute : xml_elements(grid.content, "Attribute")) {
      const std::vector<XmlElement> items = xml_elements(attribute.content, "DataItem");
      listed.attributes.emplace_back(xml_attribute(attribute.tag, "Name"),
                                     items.empty() ? XmlElement{} : items.front());
    }
    grids.push_back(listed);
  }
  return grids;
}

/// Checks that the .xmf lists one grid per snapshot, in order, with attribute "rank" (Scalar
/// UInt of 4 bytes, one per particle, read from that file's dataset "rank") exactly for the
/// snapshots whose `with_rank` entry is set, which must also be the files holding the dataset.
void expect_rank_listed_for(const SnapshotWriter& writer, const std::vector<bool>& with_rank) {
  MPI_Barrier(MPI_COMM_WORLD);
  const std::vector<ListedGrid> grids = uniform_grids(read_text(writer.xmf_path()));
  ASSERT_EQ(grids.size(), with_rank.size());
  ASSERT_EQ(writer.files().size(), with_rank.size());
  for (std::size_t k = 0; k < grids.size(); ++k) {
    const std::string file = fs::path(writer.files()[k]).filename().string();
    EXPECT_EQ(grids[k].h5_file, file);
    EXPECT_EQ(file_has_dataset(writer.files()[k], "rank"), with_rank[k]) << file;
    EXPECT_EQ(writer.table()[k].layout.rank_field, with_rank[k]) << file;
    const auto rank = std::find_if(grids[k].attributes.begin(), grids[k].attributes.end(),
                                   [](const auto& a) { return a.first == "rank"; });
    ASSERT_EQ(rank != grids[k].attributes.end(), with_rank[k]) << "grid of " << file;
    ASSERT_EQ(grids[k].attributes.size(), with_rank[k] ? 7u : 6u) << "grid of " << file;
    if (!with_rank[k]) continue;
    const XmlElement& item = rank->second;
    EXPECT_EQ(item.content, file + ":/rank");
    EXPECT_EQ(xml_attribute(item.tag, "NumberType"), "UInt");
    EXPECT_EQ(xml_attribute(item.tag, "Precision"), "4");
    EXPECT_EQ(xml_attribute(item.tag, "Dimensions"), std::to_string(writer.table()[k].count));
  }
}

/// A fresh directory, the same on every rank, removed after the test.
class SnapshotWriterTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::make_shared_temp_dir("gpudem_snapshot_"); }
  void TearDown() override { test::remove_shared_temp_dir(dir_); }

  std::string dir_;
};

/// A few hundred particles per rank; rank 1 has none when there are several ranks.
std::size_t particles_on_this_rank() { return comm_rank() == 1 ? 0 : 300 + 37 * comm_rank(); }

TEST_F(SnapshotWriterTest, EveryDatasetReadsBackBitIdenticalToTheStore) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_);
  const ParticleStore first = random_store(particles_on_this_rank(), 100 + comm_rank());
  const ParticleStore second = random_store(particles_on_this_rank() + 5, 200 + comm_rank());
  writer.write(first, 0.1234567890123456789, 7);
  writer.write(second, 2.5e-3 / 3.0, (std::uint64_t(1) << 40) + 3);

  ASSERT_EQ(writer.files().size(), 2u);
  EXPECT_EQ(writer.files()[0], (fs::path(dir_) / "particles_000000.h5").string());
  EXPECT_EQ(writer.files()[1], (fs::path(dir_) / "particles_000001.h5").string());
  expect_snapshot_holds(writer.files()[0], first, 0.1234567890123456789, 7);
  expect_snapshot_holds(writer.files()[1], second, 2.5e-3 / 3.0, (std::uint64_t(1) << 40) + 3);
}

TEST_F(SnapshotWriterTest, SnapshotWithoutAnyParticleHasEmptyDatasets) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, named("empty"));
  writer.write(ParticleStore{}, 1.5, 42);
  ASSERT_EQ(writer.files().size(), 1u);
  expect_snapshot_holds(writer.files()[0], ParticleStore{}, 1.5, 42);
  EXPECT_NE(read_text(writer.xmf_path()).find("NumberOfElements=\"0\""), std::string::npos);
}

TEST_F(SnapshotWriterTest, XmfListsEverySnapshotByRelativeFileName) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, named("bed"));
  EXPECT_EQ(writer.xmf_path(), (fs::path(dir_) / "bed.xmf").string());
  writer.write(random_store(particles_on_this_rank(), 300 + comm_rank()), 0.0, 0);
  writer.write(random_store(particles_on_this_rank(), 400 + comm_rank()), 0.01, 100);
  MPI_Barrier(MPI_COMM_WORLD);

  const std::string xmf = read_text(writer.xmf_path());
  const std::string total = std::to_string(global_count(particles_on_this_rank()));
  EXPECT_NE(xmf.find(">bed_000000.h5:/position<"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find(">bed_000001.h5:/position<"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find("NumberOfElements=\"" + total + "\""), std::string::npos) << xmf;
  EXPECT_NE(xmf.find("<Time Value=\"0.01\"/>"), std::string::npos) << xmf;
  EXPECT_EQ(xmf.find(dir_), std::string::npos) << "file names must be relative";
  EXPECT_FALSE(fs::exists(writer.xmf_path() + ".tmp"));
}

TEST_F(SnapshotWriterTest, RankFieldHoldsTheWritingRankOfEveryRow) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, with_rank_field());
  const ParticleStore particles = random_store(particles_on_this_rank(), 900 + comm_rank());
  writer.write(particles, 0.25, 25);
  writer.write(ParticleStore{}, 0.5, 50);
  expect_snapshot_holds(writer.files()[0], particles, 0.25, 25);
  expect_rank_field_holds_the_writing_ranks(writer.files()[0], particles.size());
  expect_rank_field_holds_the_writing_ranks(writer.files()[1], 0);
  expect_rank_listed_for(writer, {true, true});
}

TEST_F(SnapshotWriterTest, WithoutTheOptionThereIsNoRankField) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_);
  writer.write(random_store(particles_on_this_rank(), 1000 + comm_rank()), 0.0, 0);
  expect_rank_listed_for(writer, {false});
  EXPECT_EQ(read_text(writer.xmf_path()).find("rank"), std::string::npos);
}

TEST_F(SnapshotWriterTest, ResumedSeriesKeepsEachSnapshotsRankField) {
  const ParticleStore particles = random_store(particles_on_this_rank(), 1100 + comm_rank());
  std::vector<XdmfSnapshot> table;
  {
    SnapshotWriter with_rank(MPI_COMM_WORLD, dir_, with_rank_field());
    with_rank.write(particles, 0.0, 0);
    with_rank.write(particles, 0.1, 10);
    table = with_rank.table();
  }
  {
    SnapshotWriter without_rank(MPI_COMM_WORLD, dir_);
    without_rank.resume(table);
    expect_rank_listed_for(without_rank, {true, true});
    without_rank.write(particles, 0.2, 20);
    expect_rank_listed_for(without_rank, {true, true, false});
    table = without_rank.table();
  }
  SnapshotWriter with_rank_again(MPI_COMM_WORLD, dir_, with_rank_field());
  with_rank_again.resume(table);
  with_rank_again.write(particles, 0.3, 30);
  expect_rank_listed_for(with_rank_again, {true, true, false, true});
  expect_rank_field_holds_the_writing_ranks(with_rank_again.files()[3], particles.size());
}

/// For each uniform grid of the writer's .xmf, its geometry and attributes as
/// "name=Precision", in order, the geometry ("position") first.
std::vector<std::vector<std::string>> listed_precisions(const SnapshotWriter& writer) {
  MPI_Barrier(MPI_COMM_WORLD);
  std::vector<std::vector<std::string>> listed;
  for (const XmlElement& grid : xml_elements(read_text(writer.xmf_path()), "Grid")) {
    if (xml_attribute(grid.tag, "GridType") != "Uniform") continue;
    const XmlElement geometry = xml_elements(grid.content, "Geometry").at(0);
    std::vector<std::string> entries{
        "position=" +
        xml_attribute(xml_elements(geometry.content, "DataItem").at(0).tag, "Precision")};
    for (const XmlElement& attribute : xml_elements(grid.content, "Attribute"))
      entries.push_back(
          xml_attribute(attribute.tag, "Name") + "=" +
          xml_attribute(xml_elements(attribute.content, "DataItem").at(0).tag, "Precision"));
    listed.push_back(entries);
  }
  return listed;
}

constexpr std::uint32_t field_bit(std::size_t k) { return std::uint32_t(1) << k; }

TEST_F(SnapshotWriterTest, FieldsOutsideTheSetAreLeftOutOfFileAndXmf) {
  SnapshotOptions options;
  options.layout.fields = field_bit(0) | field_bit(5);  // radius and id
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, options);
  const ParticleStore p = random_store(particles_on_this_rank(), 1500 + comm_rank());
  writer.write(p, 0.5, 5);
  const std::string& path = writer.files()[0];
  MPI_Barrier(MPI_COMM_WORLD);
  for (const char* name : {"position", "radius", "id", "connectivity"})
    EXPECT_TRUE(file_has_dataset(path, name)) << name;
  for (const char* name : {"velocity", "angular_velocity", "force", "material"})
    EXPECT_FALSE(file_has_dataset(path, name)) << name;
  const hsize_t n = global_count(p.size()), offset = expected_offset(p.size());
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  expect_bit_identical(test::radii_of(p),
                       read_rows<double>(file.id, "radius", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n},
                                         offset, p.size()),
                       "radius");
  expect_bit_identical(p.id,
                       read_rows<std::uint64_t>(file.id, "id", H5T_STD_U64LE, H5T_NATIVE_UINT64,
                                                {n}, offset, p.size()),
                       "id");
  const std::vector<std::vector<std::string>> expected{{"position=8", "radius=8", "id=8"}};
  EXPECT_EQ(listed_precisions(writer), expected);
  EXPECT_EQ(writer.table()[0].layout.fields, options.layout.fields);
}

TEST_F(SnapshotWriterTest, SinglePrecisionStoresEachRealValueRoundedToFloat) {
  SnapshotOptions options;
  options.layout.single_precision = true;
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, options);
  const ParticleStore p = random_store(particles_on_this_rank(), 1600 + comm_rank());
  writer.write(p, 0.25, 3);
  test::expect_snapshot_holds<float>(writer.files()[0], p, 0.25, 3);
  const std::vector<std::vector<std::string>> expected{{"position=4", "radius=4", "velocity=4",
                                                        "angular_velocity=4", "force=4",
                                                        "material=4", "id=8"}};
  EXPECT_EQ(listed_precisions(writer), expected);
}

TEST_F(SnapshotWriterTest, ResumedSeriesKeepsEachSnapshotsFieldsAndPrecision) {
  const ParticleStore particles = random_store(particles_on_this_rank(), 1700 + comm_rank());
  std::vector<XdmfSnapshot> table;
  {
    SnapshotWriter full(MPI_COMM_WORLD, dir_);
    full.write(particles, 0.0, 0);
    table = full.table();
  }
  SnapshotOptions lean;
  lean.layout.fields = field_bit(1);  // velocity
  lean.layout.single_precision = true;
  SnapshotWriter resumed(MPI_COMM_WORLD, dir_, lean);
  resumed.resume(table);
  resumed.write(particles, 0.1, 10);
  const std::vector<std::vector<std::string>> expected{
      {"position=8", "radius=8", "velocity=8", "angular_velocity=8", "force=8", "material=4",
       "id=8"},
      {"position=4", "velocity=4"}};
  EXPECT_EQ(listed_precisions(resumed), expected);
  ASSERT_EQ(resumed.table().size(), 2u);
  EXPECT_FALSE(resumed.table()[0].layout.single_precision);
  EXPECT_TRUE(resumed.table()[1].layout.single_precision);
  EXPECT_EQ(resumed.table()[1].layout.fields, lean.layout.fields);
  expect_snapshot_holds(resumed.files()[0], particles, 0.0, 0);
  EXPECT_FALSE(file_has_dataset(resumed.files()[1], "force"));
}

TEST_F(SnapshotWriterTest, LeavesNoHdf5ObjectOpen) {
  ASSERT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);
  SnapshotWriter writer(MPI_COMM_WORLD, dir_);
  for (int k = 0; k < 3; ++k) writer.write(random_store(10, 500 + comm_rank()), k, k);
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL), 0);
}

TEST_F(SnapshotWriterTest, FailureNamesTheFileAndTheHdf5Call) {
  const std::string missing_dir = (fs::path(dir_) / "missing").string();
  SnapshotWriter writer(MPI_COMM_WORLD, missing_dir);
  H5E_auto2_t print = nullptr;
  void* print_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &print, &print_data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the expected failure need not print a trace
  try {
    writer.write(random_store(5, 600 + comm_rank()), 0.0, 0);
    ADD_FAILURE() << "writing into a missing directory did not throw";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(missing_dir + "/particles_000000.h5"), std::string::npos) << message;
    EXPECT_NE(message.find("H5Fcreate"), std::string::npos) << message;
  }
  H5Eset_auto2(H5E_DEFAULT, print, print_data);
  EXPECT_TRUE(writer.files().empty());
}

/// Two triangles sharing the edge of vertices 1 and 2: (0, 1, 2) in the plane z = 0, with
/// normal +z (right-hand rule) and area 6, and (1, 2, 3) through the axis points x = 3, y = 4,
/// z = 5, with n = (−3, 4, 0) × (−3, 0, 5) = (20, 15, 12) and area |n| / 2 = √769 / 2.
MeshSurface two_triangles() {
  MeshSurface mesh;
  mesh.vertices = {{0, 0, 0}, {3, 0, 0}, {0, 4, 0}, {0, 0, 5}};
  mesh.triangles = {{0, 1, 2}, {1, 2, 3}};
  mesh.triangle_force = {{7, -1, -9}, {1, 2, 3}};
  return mesh;
}

/// −(F · n̂) / A of two_triangles(): 9 / 6 on the first, −(1, 2, 3) · (20, 15, 12) / √769
/// over √769 / 2 = −2 · 86 / 769 on the second [Pa].
const std::vector<double> kTwoTrianglePressures = {1.5, -172.0 / 769.0};

SnapshotOptions options_with_plate(const std::string& basename) {
  SnapshotOptions options;
  options.basename = basename;
  options.meshes = {{"plate", 4, 2}};
  return options;
}

std::vector<std::uint32_t> flat_ids(const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  std::vector<std::uint32_t> out;
  for (const auto& t : triangles) out.insert(out.end(), t.begin(), t.end());
  return out;
}

/// Reads group /mesh/plate/ of `path` whole on every rank and compares it with `mesh`.
void expect_plate_holds(const std::string& path, const MeshSurface& mesh,
                        const std::vector<double>& pressures) {
  MPI_Barrier(MPI_COMM_WORLD);
  H5Id<H5Fclose> file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  ASSERT_GE(file.id, 0) << "cannot open " << path;
  const hid_t f64 = H5T_IEEE_F64LE, f64_mem = H5T_NATIVE_DOUBLE;
  const hsize_t v = mesh.vertices.size(), t = mesh.triangles.size();
  expect_bit_identical(
      xyz_of(mesh.vertices),
      read_rows<double>(file.id, "mesh/plate/vertices", f64, f64_mem, {v, 3}, 0, v), "vertices");
  expect_bit_identical(flat_ids(mesh.triangles),
                       read_rows<std::uint32_t>(file.id, "mesh/plate/triangles", H5T_STD_U32LE,
                                                H5T_NATIVE_UINT32, {t, 3}, 0, t),
                       "triangles");
  expect_bit_identical(xyz_of(mesh.triangle_force),
                       read_rows<double>(file.id, "mesh/plate/force", f64, f64_mem, {t, 3}, 0, t),
                       "force");
  const std::vector<double> stored =
      read_rows<double>(file.id, "mesh/plate/pressure", f64, f64_mem, {t}, 0, t);
  ASSERT_EQ(stored.size(), pressures.size());
  for (std::size_t k = 0; k < stored.size(); ++k)  // closed forms, to 4 ulp
    EXPECT_NEAR(stored[k], pressures[k], 4e-16 * std::abs(pressures[k])) << "triangle " << k;
}

TEST_F(SnapshotWriterTest, MeshGroupHoldsTheSurfaceTheForcesAndTheTrianglePressures) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, options_with_plate("particles"));
  const ParticleStore particles = random_store(particles_on_this_rank(), 1400 + comm_rank());
  writer.write(particles, {two_triangles()}, 0.5, 5);
  expect_snapshot_holds(writer.files()[0], particles, 0.5, 5);
  expect_plate_holds(writer.files()[0], two_triangles(), kTwoTrianglePressures);
}

/// The (file, time value) of each uniform grid of an .xmf, in order.
std::vector<std::pair<std::string, std::string>> listed_snapshots(const std::string& xmf) {
  std::vector<std::pair<std::string, std::string>> listed;
  for (const XmlElement& grid : xml_elements(xmf, "Grid")) {
    if (xml_attribute(grid.tag, "GridType") != "Uniform") continue;
    const std::string time = grid.content.substr(grid.content.find("<Time "));
    const std::vector<XmlElement> items = xml_elements(grid.content, "DataItem");
    const std::string source = items.empty() ? "" : items.front().content;
    listed.emplace_back(source.substr(0, source.find(':')),
                        xml_attribute(time.substr(0, time.find('>')), "Value"));
  }
  return listed;
}

/// The only element named `name` in `text`.
XmlElement only_element(const std::string& text, const std::string& name) {
  const std::vector<XmlElement> found = xml_elements(text, name);
  EXPECT_EQ(found.size(), 1u) << name << " in\n" << text;
  return found.empty() ? XmlElement{} : found.front();
}

/// Checks a DataItem: `file`:/mesh/plate/`dataset` of the given type and Dimensions.
void expect_plate_item(const XmlElement& item, const std::string& file, const std::string& dataset,
                       const std::string& number_type, const std::string& precision,
                       const std::string& dims) {
  EXPECT_EQ(item.content, file + ":/mesh/plate/" + dataset);
  EXPECT_EQ(xml_attribute(item.tag, "Format"), "HDF") << dataset;
  EXPECT_EQ(xml_attribute(item.tag, "NumberType"), number_type) << dataset;
  EXPECT_EQ(xml_attribute(item.tag, "Precision"), precision) << dataset;
  EXPECT_EQ(xml_attribute(item.tag, "Dimensions"), dims) << dataset;
}

/// Checks one uniform grid of plate.xmf: 2 triangles over 4 vertices read from `file`, with
/// force (Vector) and pressure (Scalar) per triangle.
void expect_plate_grid(const XmlElement& grid, const std::string& file) {
  const XmlElement topology = only_element(grid.content, "Topology");
  EXPECT_EQ(xml_attribute(topology.tag, "TopologyType"), "Triangle");
  EXPECT_EQ(xml_attribute(topology.tag, "NumberOfElements"), "2");
  expect_plate_item(only_element(topology.content, "DataItem"), file, "triangles", "UInt", "4",
                    "2 3");
  const XmlElement geometry = only_element(grid.content, "Geometry");
  EXPECT_EQ(xml_attribute(geometry.tag, "GeometryType"), "XYZ");
  expect_plate_item(only_element(geometry.content, "DataItem"), file, "vertices", "Float", "8",
                    "4 3");
  const std::vector<XmlElement> attributes = xml_elements(grid.content, "Attribute");
  ASSERT_EQ(attributes.size(), 2u);
  const char* const names[] = {"force", "pressure"};
  const char* const types[] = {"Vector", "Scalar"};
  const char* const dims[] = {"2 3", "2"};
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(xml_attribute(attributes[k].tag, "Name"), names[k]);
    EXPECT_EQ(xml_attribute(attributes[k].tag, "AttributeType"), types[k]);
    EXPECT_EQ(xml_attribute(attributes[k].tag, "Center"), "Cell");
    expect_plate_item(only_element(attributes[k].content, "DataItem"), file, names[k], "Float", "8",
                      dims[k]);
  }
}

TEST_F(SnapshotWriterTest, MeshXmfHasATriangleGridPerSnapshotOfTheParticlesXmf) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, options_with_plate("run"));
  writer.write(random_store(particles_on_this_rank(), 1500 + comm_rank()), {two_triangles()}, 0.0,
               0);
  writer.write(random_store(particles_on_this_rank(), 1600 + comm_rank()), {two_triangles()}, 0.02,
               200);
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string plate_xmf = read_text((fs::path(dir_) / "plate.xmf").string());
  const XmlElement collection = xml_elements(plate_xmf, "Grid").front();
  EXPECT_EQ(xml_attribute(collection.tag, "Name"), "plate");
  EXPECT_EQ(xml_attribute(collection.tag, "CollectionType"), "Temporal");
  const std::vector<std::pair<std::string, std::string>> expected = {{"run_000000.h5", "0"},
                                                                     {"run_000001.h5", "0.02"}};
  EXPECT_EQ(listed_snapshots(plate_xmf), expected);
  EXPECT_EQ(listed_snapshots(read_text(writer.xmf_path())), expected);
  std::vector<XmlElement> grids = xml_elements(plate_xmf, "Grid");
  grids.erase(grids.begin());  // the collection
  ASSERT_EQ(grids.size(), 2u);
  for (std::size_t k = 0; k < grids.size(); ++k) expect_plate_grid(grids[k], expected[k].first);
  EXPECT_EQ(plate_xmf.find(dir_), std::string::npos) << "file names must be relative";
  EXPECT_FALSE(fs::exists((fs::path(dir_) / "plate.xmf.tmp")));
}

TEST_F(SnapshotWriterTest, ResumedSeriesKeepsTheMeshXmfInStepWithTheParticles) {
  const ParticleStore particles = random_store(particles_on_this_rank(), 1700 + comm_rank());
  MeshSurface moved = two_triangles();
  for (Vec3& x : moved.vertices) x = x + Vec3{0.25, -0.5, 1};  // a translation keeps p
  std::vector<XdmfSnapshot> at_checkpoint;
  {
    SnapshotWriter before(MPI_COMM_WORLD, dir_, options_with_plate("particles"));
    before.write(particles, {two_triangles()}, 0.0, 0);
    before.write(particles, {two_triangles()}, 0.1, 10);
    at_checkpoint = before.table();
    before.write(particles, {two_triangles()}, 0.2, 20);  // lost: after the checkpoint
  }
  const std::string plate_xmf = (fs::path(dir_) / "plate.xmf").string();
  SnapshotWriter after(MPI_COMM_WORLD, dir_, options_with_plate("particles"));
  after.resume(at_checkpoint);
  MPI_Barrier(MPI_COMM_WORLD);
  const std::vector<std::pair<std::string, std::string>> resumed = {{"particles_000000.h5", "0"},
                                                                    {"particles_000001.h5", "0.1"}};
  EXPECT_EQ(listed_snapshots(read_text(plate_xmf)), resumed);
  EXPECT_EQ(listed_snapshots(read_text(after.xmf_path())), resumed);
  after.write(particles, {moved}, 0.15, 15);
  MPI_Barrier(MPI_COMM_WORLD);
  std::vector<std::pair<std::string, std::string>> continued = resumed;
  continued.emplace_back("particles_000002.h5", "0.15");
  EXPECT_EQ(listed_snapshots(read_text(plate_xmf)), continued);
  EXPECT_EQ(listed_snapshots(read_text(after.xmf_path())), continued);
  expect_plate_holds(after.files()[2], moved, kTwoTrianglePressures);
}

TEST_F(SnapshotWriterTest, WithoutMeshesTheFolderHoldsOnlyTheParticleFiles) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_);
  writer.write(random_store(particles_on_this_rank(), 1800 + comm_rank()), {}, 0.0, 0);
  MPI_Barrier(MPI_COMM_WORLD);
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"particles.xmf", "particles_000000.h5"}));
  EXPECT_FALSE(file_has_dataset(writer.files()[0], "mesh"));
}

TEST_F(SnapshotWriterTest, RejectsMeshNamesThatCannotNameAFileAndSurfacesOfOtherCounts) {
  for (const char* name : {"", "a/b", ".", "..", "particles"}) {
    SnapshotOptions options;
    options.meshes = {{name, 4, 2}};
    EXPECT_THROW(SnapshotWriter(MPI_COMM_WORLD, dir_, options), std::invalid_argument) << name;
  }
  SnapshotOptions twice;
  twice.meshes = {{"plate", 4, 2}, {"plate", 4, 2}};
  EXPECT_THROW(SnapshotWriter(MPI_COMM_WORLD, dir_, twice), std::invalid_argument);
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, options_with_plate("particles"));
  MeshSurface extra_vertex = two_triangles();
  extra_vertex.vertices.push_back({1, 1, 1});
  MeshSurface bad_index = two_triangles();
  bad_index.triangles[1][2] = 4;
  for (const std::vector<MeshSurface>& surfaces : {std::vector<MeshSurface>{},
                                                   {extra_vertex},
                                                   {bad_index},
                                                   {two_triangles(), two_triangles()}})
    EXPECT_THROW(writer.write(ParticleStore{}, surfaces, 0.0, 0), std::invalid_argument);
  EXPECT_TRUE(writer.files().empty());
}

/// rank + 1 bonds on each rank: bond k of rank r joins ids 100 r + k and 100 r + k + 1, from
/// (r, k, 0) to (r, k, 1), with normal force 10 r + k and strength used k / 4.
BondLines bonds_of_this_rank() {
  BondLines lines;
  const int r = comm_rank();
  for (int k = 0; k <= r; ++k) {
    const ParticleId a = 100 * r + k;
    lines.ids.insert(lines.ids.end(), {a, a + 1});
    lines.points.insert(lines.points.end(),
                        {Vec3{double(r), double(k), 0}, Vec3{double(r), double(k), 1}});
    lines.normal_force.push_back(10.0 * r + k);
    lines.strength_used.push_back(k / 4.0);
  }
  return lines;
}

SnapshotOptions with_bonds(const std::string& basename) {
  SnapshotOptions options = named(basename);
  options.bonds = true;
  return options;
}

TEST_F(SnapshotWriterTest, BondGroupHoldsEachRanksBondsAtItsOffset) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, with_bonds("particles"));
  const BondLines bonds = bonds_of_this_rank();
  writer.write(random_store(particles_on_this_rank(), 2100 + comm_rank()), {}, bonds, 0.5, 5);
  MPI_Barrier(MPI_COMM_WORLD);
  const hsize_t n = global_count(bonds.size()), at = expected_offset(bonds.size());
  const hsize_t rows = bonds.size();
  H5Id<H5Fclose> file(H5Fopen(writer.files()[0].c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  ASSERT_GE(file.id, 0);
  const hid_t u64 = H5T_STD_U64LE, u64_mem = H5T_NATIVE_UINT64;
  const hid_t f64 = H5T_IEEE_F64LE, f64_mem = H5T_NATIVE_DOUBLE;
  expect_bit_identical(bonds.ids,
                       read_rows<ParticleId>(file.id, "bonds/ids", u64, u64_mem, {n, 2}, at, rows),
                       "ids");
  std::vector<std::uint64_t> connectivity;
  for (hsize_t k = 0; k < 2 * rows; ++k) connectivity.push_back(2 * at + k);
  expect_bit_identical(
      connectivity,
      read_rows<std::uint64_t>(file.id, "bonds/connectivity", u64, u64_mem, {n, 2}, at, rows),
      "connectivity");
  expect_bit_identical(
      xyz_of(bonds.points),
      read_rows<double>(file.id, "bonds/points", f64, f64_mem, {2 * n, 3}, 2 * at, 2 * rows),
      "points");
  expect_bit_identical(
      bonds.normal_force,
      read_rows<double>(file.id, "bonds/normal_force", f64, f64_mem, {n}, at, rows), "force");
  expect_bit_identical(
      bonds.strength_used,
      read_rows<double>(file.id, "bonds/strength_used", f64, f64_mem, {n}, at, rows), "used");
  const std::string xmf = read_text((fs::path(dir_) / "bonds.xmf").string());
  EXPECT_NE(xmf.find("TopologyType=\"Polyline\" NumberOfElements=\"" + std::to_string(n) +
                     "\" NodesPerElement=\"2\""),
            std::string::npos)
      << xmf;
  EXPECT_EQ(writer.table().back().bond_count, n);
}

TEST_F(SnapshotWriterTest, WithoutTheBondsOptionThereIsNoBondGroup) {
  SnapshotWriter writer(MPI_COMM_WORLD, dir_, named("particles"));
  writer.write(random_store(particles_on_this_rank(), 2200 + comm_rank()), {}, bonds_of_this_rank(),
               0.5, 5);
  MPI_Barrier(MPI_COMM_WORLD);
  H5Id<H5Fclose> file(H5Fopen(writer.files()[0].c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  EXPECT_EQ(H5Lexists(file.id, "bonds", H5P_DEFAULT), 0);
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "bonds.xmf"));
}

#ifdef GPUDEM_SNAPSHOT_FIXTURE_DIR
// Output folder kept for tests/scripts/check_snapshot.py (every .xmf) and
// tests/scripts/paraview_open.py (particles.xmf and plate.xmf). particles.xmf: two random
// snapshots and one without any particle; ranked.xmf: the same with the rank field;
// resumed.xmf: a series resumed with the rank field switched on after a snapshot without it;
// lean.xmf: velocity and id only, in single precision; meshed.xmf and plate.xmf: two
// snapshots with the mesh "plate" (two triangles) in them; bonded.xmf and bonds.xmf: two
// snapshots with bonds, the second with none.
TEST(SnapshotFixture, WritesOutputFolderForTheXdmfCheck) {
  const std::string dir =
      test::path_from_environment("GPUDEM_SNAPSHOT_FIXTURE_DIR", GPUDEM_SNAPSHOT_FIXTURE_DIR);
  if (comm_rank() == 0) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  SnapshotWriter plain(MPI_COMM_WORLD, dir);
  SnapshotWriter ranked(MPI_COMM_WORLD, dir, named("ranked", true));
  for (SnapshotWriter* writer : {&plain, &ranked}) {
    writer->write(random_store(particles_on_this_rank(), 700 + comm_rank()), 0.0, 0);
    writer->write(random_store(particles_on_this_rank() + 11, 800 + comm_rank()), 0.005, 50);
    writer->write(ParticleStore{}, 0.01, 100);
  }
  SnapshotWriter before_restart(MPI_COMM_WORLD, dir, named("resumed"));
  before_restart.write(random_store(particles_on_this_rank(), 1200 + comm_rank()), 0.0, 0);
  SnapshotWriter after_restart(MPI_COMM_WORLD, dir, named("resumed", true));
  after_restart.resume(before_restart.table());
  after_restart.write(random_store(particles_on_this_rank() + 3, 1300 + comm_rank()), 0.01, 100);
  SnapshotOptions lean_options = named("lean");
  lean_options.layout.fields = field_bit(1) | field_bit(5);  // velocity and id
  lean_options.layout.single_precision = true;
  SnapshotWriter lean(MPI_COMM_WORLD, dir, lean_options);
  lean.write(random_store(particles_on_this_rank(), 1400 + comm_rank()), 0.0, 0);
  lean.write(ParticleStore{}, 0.01, 100);
  SnapshotWriter meshed(MPI_COMM_WORLD, dir, options_with_plate("meshed"));
  meshed.write(random_store(particles_on_this_rank(), 1900 + comm_rank()), {two_triangles()}, 0.0,
               0);
  meshed.write(ParticleStore{}, {two_triangles()}, 0.01, 100);
  SnapshotWriter bonded(MPI_COMM_WORLD, dir, with_bonds("bonded"));
  bonded.write(random_store(particles_on_this_rank(), 2000 + comm_rank()), {}, bonds_of_this_rank(),
               0.0, 0);
  bonded.write(ParticleStore{}, {}, BondLines{}, 0.01, 100);
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_TRUE(fs::exists(fs::path(dir) / "plate.xmf"));
  EXPECT_TRUE(fs::exists(fs::path(dir) / "bonds.xmf"));
  for (const SnapshotWriter* writer : {&plain, &ranked, &after_restart, &lean, &meshed, &bonded}) {
    for (const std::string& file : writer->files()) EXPECT_TRUE(fs::exists(file)) << file;
    EXPECT_TRUE(fs::exists(writer->xmf_path()));
  }
}
#endif

}  // namespace
}  // namespace gpudem
