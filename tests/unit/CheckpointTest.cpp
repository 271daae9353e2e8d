// Checkpoint files: every field reads back bit-identical to what was written (at this run's
// rank count, each rank writing its own rows), for contact laws keeping 0, 4 or 7 history
// values per contact; the file is replaced atomically (a stale temporary is overwritten, a
// failed write leaves the previous checkpoint intact); damaged files, and checkpoints that do
// not fit the scene (materials, walls, another contact law's history width), are rejected with
// InputError naming the file and the problem; a snapshot table written before the rank-field
// flags existed reads as snapshots without it. Also the two resumable outputs a restart
// continues: the snapshot series (with the rank field switched on or off at the restart) and
// the time series.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "comm/Checkpoint.hpp"
#include "comm/SnapshotWriter.hpp"
#include "comm/TimeSeriesWriter.hpp"
#include "core/InputError.hpp"
#include "core/contact/ParallelBond.hpp"
#include "support/CheckpointEdits.hpp"

#include "support/MpiRank.hpp"
#include "support/SharedTempDir.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;
using test::read_values;

using test::comm_rank;
using test::comm_size;

/// Rank r's particles: none on rank 1 (a rank without particles still takes part).
std::size_t particles_of(int rank) { return rank == 1 ? 0 : 40 + 13 * rank; }

/// History values per contact of the default contact law (linear_history: spring and sliding
/// flag).
constexpr std::uint32_t kSpringWidth = 4;

/// Rank r's part of a checkpoint, random in every field, with `width` history values per
/// contact, the same for every caller. A law without history values has no records.
Checkpoint random_part(int rank, std::uint32_t width = kSpringWidth) {
  std::mt19937_64 rng(1000 + rank);
  std::uniform_real_distribution<double> value(-1e3, 1e3), positive(1e-4, 1e-2);
  const auto random_values = [&] {
    std::vector<Real> values(width);
    for (Real& v : values) v = value(rng);
    return values;
  };
  Checkpoint c;
  c.history.width = width;
  ParticleStore& p = c.particles;
  for (std::size_t i = 0; i < particles_of(rank); ++i) {
    const ParticleId id = (std::uint64_t(rank) << 40) + i * 7 + 3;
    p.add(id, {value(rng), value(rng), value(rng)}, positive(rng), static_cast<MaterialId>(i % 3),
          {value(rng), value(rng), value(rng)}, 1 / positive(rng));
    p.angular_velocity.back() = {value(rng), value(rng), value(rng)};
    p.force.back() = {value(rng), value(rng), value(rng)};
    p.torque.back() = {value(rng), value(rng), value(rng)};
    c.list_position_radius.push_back({value(rng), value(rng), value(rng), value(rng)});
    if (width == 0) continue;
    c.history.add_pair(id, id + 1, random_values().data());
    if (i % 2 == 0)
      c.history.add_wall(id, static_cast<std::uint32_t>(i % 5), random_values().data());
    if (i % 3 == 0)
      c.history.add_mesh(id, static_cast<std::uint32_t>(i * 11 % 17), random_values().data());
  }
  c.snapshots = {{"particles_000000.h5", 0.0, 123, {true, kAllSnapshotFields, false}},
                 {"particles_000001.h5", 1.0 / 3.0, 120, {false, 0b100010, true}}};
  for (int w = 0; w < 5; ++w)
    c.wall_motion.push_back({w / 3.0 * 1e-3, -w / 7.0, w == 4 ? 1e3 / 9.0 : 0.0});
  c.time = 0.1 + 1e-17;
  c.step = (std::uint64_t(1) << 35) + 5;
  c.list_build = {c.step - 3, 5, 8};
  c.substeps = 16;
  c.dt_adaptive = true;
  c.removed = 3;
  c.dt = 2.0 / 3.0 * 1e-5;
  c.dt_fraction = 0.1;
  c.skin = 1.0 / 7.0 * 1e-3;
  c.sum_force_unit = 0x1p-45;
  c.sum_torque_unit = 0x1p-52;
  return c;
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

/// Appends the particle rows and history records of `part` to those of `whole`.
void append_rows(Checkpoint& whole, const Checkpoint& part) {
  append(whole.particles.position_radius, part.particles.position_radius);
  append(whole.particles.velocity_inv_mass, part.particles.velocity_inv_mass);
  append(whole.particles.angular_velocity, part.particles.angular_velocity);
  append(whole.particles.force, part.particles.force);
  append(whole.particles.torque, part.particles.torque);
  append(whole.particles.id, part.particles.id);
  append(whole.particles.material, part.particles.material);
  append(whole.list_position_radius, part.list_position_radius);
  append(whole.history.pair_owner, part.history.pair_owner);
  append(whole.history.pair_partner, part.history.pair_partner);
  append(whole.history.pair_values, part.history.pair_values);
  append(whole.history.wall_owner, part.history.wall_owner);
  append(whole.history.wall_index, part.history.wall_index);
  append(whole.history.wall_values, part.history.wall_values);
  append(whole.history.mesh_owner, part.history.mesh_owner);
  append(whole.history.mesh_triangle, part.history.mesh_triangle);
  append(whole.history.mesh_values, part.history.mesh_values);
}

/// What the file must hold: every rank's rows in rank order, rank 0's table and attributes.
Checkpoint expected_whole(int ranks, std::uint32_t width = kSpringWidth) {
  Checkpoint whole = random_part(0, width);
  for (int r = 1; r < ranks; ++r) {
    const Checkpoint part = random_part(r, width);
    append_rows(whole, part);
  }
  return whole;
}

template <class T>
::testing::AssertionResult same_bytes(const char* name, const std::vector<T>& a,
                                      const std::vector<T>& b) {
  if (a.size() != b.size())
    return ::testing::AssertionFailure()
           << name << ": " << a.size() << " vs " << b.size() << " rows";
  if (!a.empty() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) != 0)
    return ::testing::AssertionFailure() << name << " differs";
  return ::testing::AssertionSuccess();
}

void expect_identical(const Checkpoint& a, const Checkpoint& b) {
  EXPECT_TRUE(
      same_bytes("position_radius", a.particles.position_radius, b.particles.position_radius));
  EXPECT_TRUE(same_bytes("velocity_inv_mass", a.particles.velocity_inv_mass,
                         b.particles.velocity_inv_mass));
  EXPECT_TRUE(
      same_bytes("angular_velocity", a.particles.angular_velocity, b.particles.angular_velocity));
  EXPECT_TRUE(same_bytes("force", a.particles.force, b.particles.force));
  EXPECT_TRUE(same_bytes("torque", a.particles.torque, b.particles.torque));
  EXPECT_TRUE(same_bytes("id", a.particles.id, b.particles.id));
  EXPECT_TRUE(same_bytes("material", a.particles.material, b.particles.material));
  EXPECT_TRUE(same_bytes("list_position_radius", a.list_position_radius, b.list_position_radius));
  EXPECT_TRUE(same_bytes("pair_owner", a.history.pair_owner, b.history.pair_owner));
  EXPECT_TRUE(same_bytes("pair_partner", a.history.pair_partner, b.history.pair_partner));
  EXPECT_EQ(a.history.width, b.history.width);
  EXPECT_TRUE(same_bytes("pair_values", a.history.pair_values, b.history.pair_values));
  EXPECT_TRUE(same_bytes("wall_owner", a.history.wall_owner, b.history.wall_owner));
  EXPECT_TRUE(same_bytes("wall_index", a.history.wall_index, b.history.wall_index));
  EXPECT_TRUE(same_bytes("wall_values", a.history.wall_values, b.history.wall_values));
  EXPECT_TRUE(same_bytes("mesh_owner", a.history.mesh_owner, b.history.mesh_owner));
  EXPECT_TRUE(same_bytes("mesh_triangle", a.history.mesh_triangle, b.history.mesh_triangle));
  EXPECT_TRUE(same_bytes("mesh_values", a.history.mesh_values, b.history.mesh_values));
  ASSERT_EQ(a.snapshots.size(), b.snapshots.size());
  for (std::size_t k = 0; k < a.snapshots.size(); ++k) {
    EXPECT_EQ(a.snapshots[k].h5_file, b.snapshots[k].h5_file);
    EXPECT_EQ(a.snapshots[k].time, b.snapshots[k].time);
    EXPECT_EQ(a.snapshots[k].count, b.snapshots[k].count);
    EXPECT_EQ(a.snapshots[k].layout.rank_field, b.snapshots[k].layout.rank_field)
        << a.snapshots[k].h5_file;
    EXPECT_EQ(a.snapshots[k].layout.fields, b.snapshots[k].layout.fields) << a.snapshots[k].h5_file;
    EXPECT_EQ(a.snapshots[k].layout.single_precision, b.snapshots[k].layout.single_precision)
        << a.snapshots[k].h5_file;
  }
  ASSERT_EQ(a.wall_motion.size(), b.wall_motion.size());
  for (std::size_t k = 0; k < a.wall_motion.size(); ++k) {
    EXPECT_EQ(a.wall_motion[k].displacement, b.wall_motion[k].displacement) << "wall " << k;
    EXPECT_EQ(a.wall_motion[k].velocity, b.wall_motion[k].velocity) << "wall " << k;
    EXPECT_EQ(a.wall_motion[k].push, b.wall_motion[k].push) << "wall " << k;
  }
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.list_build.step, b.list_build.step);
  EXPECT_EQ(a.list_build.substep, b.list_build.substep);
  EXPECT_EQ(a.list_build.substeps, b.list_build.substeps);
  EXPECT_EQ(a.substeps, b.substeps);
  EXPECT_EQ(a.dt_adaptive, b.dt_adaptive);
  EXPECT_EQ(a.removed, b.removed);
  EXPECT_EQ(a.dt, b.dt);
  EXPECT_EQ(a.dt_fraction, b.dt_fraction);
  EXPECT_EQ(a.skin, b.skin);
  EXPECT_EQ(a.sum_force_unit, b.sum_force_unit);
  EXPECT_EQ(a.sum_torque_unit, b.sum_torque_unit);
}

/// A fresh directory, the same on every rank, removed after the test.
class CheckpointFile : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::make_shared_temp_dir("gpudem_checkpoint_"); }
  void TearDown() override { test::remove_shared_temp_dir(dir_); }

  std::string path() const { return checkpoint_path(dir_); }

  /// Writes this rank's random part; rank 0 then reads the whole file back.
  void write_random(std::uint32_t width = kSpringWidth) const {
    write_checkpoint(MPI_COMM_WORLD, dir_, random_part(comm_rank(), width));
  }

  /// The message of the InputError that reading `file` raises ("" and a failure if none).
  static std::string rejection(const std::string& file) {
    try {
      read_checkpoint(file);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "'" << file << "' was accepted";
    return "";
  }

  void expect_rejected(const std::string& needle) const {
    const std::string message = rejection(path());
    EXPECT_NE(message.find(path()), std::string::npos) << message;
    EXPECT_NE(message.find(needle), std::string::npos)
        << "expected '" << needle << "' in: " << message;
  }

  std::string dir_;
};

TEST_F(CheckpointFile, RoundTripIsBitIdenticalAtThisRankCount) {
  write_random();
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm_rank() == 0) expect_identical(read_checkpoint(path()), expected_whole(comm_size()));
}

/// The parts {0, parts} .. {parts - 1, parts} of `path`, concatenated in order; the table and
/// attributes of part 0.
Checkpoint concatenated_parts(const std::string& path, int parts) {
  Checkpoint whole = read_checkpoint(path, FilePart{0, parts});
  for (int k = 1; k < parts; ++k) {
    const Checkpoint part = read_checkpoint(path, FilePart{k, parts});
    EXPECT_EQ(part.snapshots.size(), whole.snapshots.size()) << "part " << k << " of " << parts;
    EXPECT_EQ(part.step, whole.step) << "part " << k << " of " << parts;
    append_rows(whole, part);
  }
  return whole;
}

TEST_F(CheckpointFile, PartsReadInOrderMakeTheWholeFile) {
  write_random();
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm_rank() != 0) return;
  const Checkpoint whole = expected_whole(comm_size());
  for (const int parts : {1, 2, 3, 5, 64}) {
    SCOPED_TRACE(std::to_string(parts) + " parts");
    expect_identical(concatenated_parts(path(), parts), whole);
  }
  const Checkpoint first = read_checkpoint(path(), FilePart{0, 3});
  const RowRange rows = share_of_rows(whole.particles.size(), 0, 3);
  ASSERT_EQ(first.particles.size(), rows.count);
  EXPECT_LT(first.particles.size(), whole.particles.size());
}

TEST_F(CheckpointFile, RoundTripWithoutHistoryValuesStoresNoValueDatasets) {
  write_random(0);
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm_rank() != 0) return;
  EXPECT_FALSE(test::has_dataset(path(), "pair_history"));
  EXPECT_FALSE(test::has_dataset(path(), "wall_history"));
  EXPECT_TRUE(test::has_dataset(path(), "pair_owner"));
  const Checkpoint c = read_checkpoint(path());
  EXPECT_EQ(c.history.width, 0u);
  EXPECT_TRUE(c.history.pair_owner.empty());
  EXPECT_TRUE(c.history.wall_owner.empty());
  expect_identical(c, expected_whole(comm_size(), 0));
}

TEST_F(CheckpointFile, RoundTripOfSevenHistoryValuesPerContact) {
  write_random(7);  // tangential spring and sliding flag, and an EPSD rolling spring
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm_rank() != 0) return;
  const std::size_t pairs = expected_whole(comm_size(), 7).history.pair_owner.size();
  EXPECT_EQ(test::read_values<double>(path(), "pair_history", H5T_NATIVE_DOUBLE).size(), 7 * pairs);
  expect_identical(read_checkpoint(path()), expected_whole(comm_size(), 7));
}

TEST_F(CheckpointFile, RanksHoldingHistoriesOfDifferentWidthsAreRefused) {
  if (comm_size() < 2) GTEST_SKIP() << "needs two ranks";
  const std::uint32_t width = comm_rank() == 0 ? kSpringWidth : 7;
  EXPECT_THROW(write_random(width), std::logic_error) << "on rank " << comm_rank();
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_FALSE(fs::exists(path() + ".tmp"));
  EXPECT_FALSE(fs::exists(path()));
}

TEST_F(CheckpointFile, EmptyCheckpointRoundTrips) {
  Checkpoint empty;
  empty.dt = 1e-4;
  write_checkpoint(MPI_COMM_WORLD, dir_, empty);
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm_rank() == 0) expect_identical(read_checkpoint(path()), empty);
}

TEST_F(CheckpointFile, StaleTemporaryFromAKilledWriterIsReplaced) {
  if (comm_rank() == 0) std::ofstream(path() + ".tmp") << "half a checkpoint from a killed run";
  MPI_Barrier(MPI_COMM_WORLD);
  write_random();
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm_rank() != 0) return;
  EXPECT_FALSE(fs::exists(path() + ".tmp"));
  expect_identical(read_checkpoint(path()), expected_whole(comm_size()));
}

TEST_F(CheckpointFile, FailedWriteLeavesThePreviousCheckpointIntact) {
  if (comm_size() > 1) GTEST_SKIP() << "one-rank case";
  write_random();
  fs::create_directory(path() + ".tmp");  // the temporary file cannot be created
  Checkpoint other = random_part(0);
  other.step += 1;
  H5E_auto2_t print = nullptr;
  void* print_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &print, &print_data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the expected failure need not print a trace
  try {
    write_checkpoint(MPI_COMM_WORLD, dir_, other);
    ADD_FAILURE() << "writing over a directory did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path() + ".tmp"), std::string::npos) << e.what();
  }
  H5Eset_auto2(H5E_DEFAULT, print, print_data);
  expect_identical(read_checkpoint(path()), random_part(0));
}

TEST_F(CheckpointFile, MissingFileIsRejected) {
  if (comm_rank() != 0) return;
  expect_rejected("no such checkpoint file");
}

TEST_F(CheckpointFile, FileThatIsNotHdf5IsRejected) {
  if (comm_rank() != 0) return;
  std::ofstream(path()) << "time,step\n0,0\n";
  expect_rejected("not a readable HDF5 file");
}

class DamagedCheckpoint : public CheckpointFile {
 protected:
  void SetUp() override {
    CheckpointFile::SetUp();
    if (comm_size() > 1) GTEST_SKIP() << "one-rank case";
    write_random();
  }
};

TEST_F(DamagedCheckpoint, OtherFormatVersionIsRejected) {
  test::set_u32_attribute(path(), "format_version", kCheckpointFormatVersion + 1);
  expect_rejected("format version " + std::to_string(kCheckpointFormatVersion + 1));
}

TEST_F(DamagedCheckpoint, MissingDatasetIsRejected) {
  test::remove_dataset(path(), "pair_history");
  expect_rejected("missing dataset 'pair_history'");
}

TEST_F(DamagedCheckpoint, MissingHistoryWidthIsRejected) {
  test::remove_attribute(path(), "history_width");
  expect_rejected("missing attribute 'history_width'");
}

TEST_F(DamagedCheckpoint, HistoryOfAnotherNumberOfColumnsIsRejected) {
  const std::size_t walls = random_part(0).history.wall_owner.size();
  test::replace_f64_dataset(path(), "wall_history", walls, 3, std::vector<double>(walls * 3, 1));
  expect_rejected("dataset 'wall_history' must have 4 columns");
}

TEST_F(DamagedCheckpoint, HistoryOfAnotherNumberOfRowsIsRejected) {
  test::replace_f64_dataset(path(), "pair_history", 2, kSpringWidth,
                            std::vector<double>(2 * kSpringWidth, 1));
  expect_rejected("dataset 'pair_history' has 2 rows but 'pair_owner' has " +
                  std::to_string(particles_of(0)));
}

TEST_F(DamagedCheckpoint, DatasetsOfDifferentLengthsAreRejected) {
  test::replace_u32_dataset(path(), "material", {0, 1, 2});
  expect_rejected("dataset 'material' has 3 rows but 'id' has " + std::to_string(particles_of(0)));
}

TEST_F(DamagedCheckpoint, DatasetsOfDifferentLengthsAreRejectedWhenTheirPartsAgree) {
  // 40 ids and 41 materials: the first of two parts has 20 rows of each.
  const std::size_t n = particles_of(0);
  test::replace_u32_dataset(path(), "material", std::vector<std::uint32_t>(n + 1, 0));
  try {
    read_checkpoint(path(), FilePart{0, 2});
    ADD_FAILURE() << "a part of datasets of different lengths was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dataset 'material' has " + std::to_string(n + 1) +
                                         " rows but 'id' has " + std::to_string(n)),
              std::string::npos)
        << e.what();
  }
}

TEST_F(DamagedCheckpoint, DatasetOfTheWrongTypeIsRejected) {
  test::replace_u32_dataset(path(), "id", std::vector<std::uint32_t>(particles_of(0), 1));
  expect_rejected("dataset 'id' has the wrong value type");
}

TEST_F(DamagedCheckpoint, RankFieldFlagsAreStoredAsOneByteEach) {
  EXPECT_EQ(test::raw_bytes(path(), "snapshot_rank_field"),
            (std::vector<unsigned char>{1, 0}));  // random_part's table: with, without
}

/// A checkpoint written before mesh springs, the list-build step, adaptive steps and the units of
/// the integer sums were stored: no mesh records, the list built at the checkpoint's step, one
/// step per base step, no units (the run's own).
TEST_F(DamagedCheckpoint, CheckpointWithoutMeshRecordsOrBuildStepReadsAsNoneAndTheStep) {
  for (const char* name : {"mesh_owner", "mesh_triangle", "mesh_history"})
    test::remove_dataset(path(), name);
  for (const char* name : {"list_build_step", "list_build_substep", "list_build_substeps",
                           "substeps", "dt_adaptive", "sum_force_unit", "sum_torque_unit"})
    test::remove_attribute(path(), name);
  Checkpoint expected = random_part(0);
  expected.history.mesh_owner.clear();
  expected.history.mesh_triangle.clear();
  expected.history.mesh_values.clear();
  expected.list_build = {expected.step, 0, 1};
  expected.substeps = 1;
  expected.dt_adaptive = false;
  expected.sum_force_unit = 0;
  expected.sum_torque_unit = 0;
  expect_identical(read_checkpoint(path()), expected);
}

TEST_F(DamagedCheckpoint, SumUnitsOtherThanTwoPositivePowersOfTwoAreRejected) {
  test::set_f64_attribute(path(), "sum_force_unit", 3e-14);
  expect_rejected("attribute 'sum_force_unit' is not a positive power of two");
  test::set_f64_attribute(path(), "sum_force_unit", 0x1p-45);
  test::set_f64_attribute(path(), "sum_torque_unit", -0x1p-52);
  expect_rejected("attribute 'sum_torque_unit' is not a positive power of two");
  test::set_f64_attribute(path(), "sum_torque_unit", std::numeric_limits<double>::infinity());
  expect_rejected("attribute 'sum_torque_unit' is not a positive power of two");
  test::remove_attribute(path(), "sum_torque_unit");
  expect_rejected("attributes 'sum_force_unit' and 'sum_torque_unit' are not both there");
}

TEST_F(DamagedCheckpoint, SubstepsOutsideTheirRangeAreRejected) {
  test::set_u32_attribute(path(), "list_build_substep", 8);
  expect_rejected(
      "attribute 'list_build_substep' (8) is not below attribute "
      "'list_build_substeps' (8)");
  test::set_u32_attribute(path(), "list_build_substep", 5);
  test::set_u32_attribute(path(), "substeps", kMaxSubsteps + 1);
  expect_rejected("attribute 'substeps' (1025) is not in 1..1024");
}

TEST_F(DamagedCheckpoint, MeshRecordsOfDifferentLengthsAreRejected) {
  test::replace_u32_dataset(path(), "mesh_triangle", {1, 2});
  expect_rejected("dataset 'mesh_triangle' has 2 rows but 'mesh_owner' has");
}

TEST_F(DamagedCheckpoint, TableWithoutRankFieldFlagsHasNoSnapshotWithTheRankField) {
  test::remove_dataset(path(), "snapshot_rank_field");
  Checkpoint expected = random_part(0);
  for (XdmfSnapshot& snapshot : expected.snapshots) snapshot.layout.rank_field = false;
  expect_identical(read_checkpoint(path()), expected);
}

TEST_F(DamagedCheckpoint, RankFieldFlagsOtherThanZeroOrOneAreRejected) {
  test::replace_u8_dataset(path(), "snapshot_rank_field", {0, 2});
  expect_rejected("dataset 'snapshot_rank_field' holds 2; expected 0 or 1");
  test::replace_u8_dataset(path(), "snapshot_rank_field", {1});
  expect_rejected("dataset 'snapshot_rank_field' has 1 rows but 'snapshot_file' has 2");
  test::replace_u32_dataset(path(), "snapshot_rank_field", {0, 1});
  expect_rejected("dataset 'snapshot_rank_field' has the wrong value type");
}

TEST_F(DamagedCheckpoint, TableWithoutFieldSetsOrPrecisionsHasEveryFieldInDouble) {
  test::remove_dataset(path(), "snapshot_fields");
  test::remove_dataset(path(), "snapshot_precision");
  Checkpoint expected = random_part(0);
  for (XdmfSnapshot& snapshot : expected.snapshots) {
    snapshot.layout.fields = kAllSnapshotFields;
    snapshot.layout.single_precision = false;
  }
  expect_identical(read_checkpoint(path()), expected);
}

TEST_F(DamagedCheckpoint, FieldSetsBeyondTheFieldsAndOtherPrecisionsAreRejected) {
  test::replace_u32_dataset(path(), "snapshot_fields", {63, 64});
  expect_rejected("dataset 'snapshot_fields' holds 64; expected a set of 6 fields, below 64");
  test::replace_u32_dataset(path(), "snapshot_fields", {63});
  expect_rejected("dataset 'snapshot_fields' has 1 rows but 'snapshot_file' has 2");
  test::replace_u32_dataset(path(), "snapshot_fields", {63, 34});
  test::replace_u8_dataset(path(), "snapshot_precision", {8, 2});
  expect_rejected("dataset 'snapshot_precision' holds 2; expected 4 or 8");
}

/// A file from before the walls' motion was kept reads with none; a value that is not finite
/// is refused; a scene with another number of walls cannot continue the motion.
TEST_F(DamagedCheckpoint, WallMotionIsOptionalFiniteAndOfTheScenesWalls) {
  Checkpoint c = read_checkpoint(path());
  ASSERT_EQ(c.wall_motion.size(), 5u);
  Scene scene;
  scene.materials.resize(3);
  scene.meshes.resize(1);
  scene.walls.resize(6);
  try {
    fit_checkpoint_to_scene(c, path(), scene);
    ADD_FAILURE() << "the motion of 5 walls was accepted by a scene of 6";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds the motion of 5 wall(s) but the scene defines 6"),
              std::string::npos)
        << e.what();
  }
  std::vector<double> motion(15, 0.0);
  motion[7] = std::numeric_limits<double>::quiet_NaN();
  test::replace_f64_dataset(path(), "wall_motion", 5, 3, motion);
  expect_rejected("dataset 'wall_motion' holds a value that is not finite");
  test::remove_dataset(path(), "wall_motion");
  c = read_checkpoint(path());
  EXPECT_TRUE(c.wall_motion.empty());
  EXPECT_NO_THROW(fit_checkpoint_to_scene(c, path(), scene));
}

/// Bonds continue only with the scene's [[bond]] tables: a file without bonds refuses a scene
/// with tables, a file with bonds a scene without, and a bond of a table the scene does not
/// have (or of no whole table index) is refused.
TEST_F(DamagedCheckpoint, BondsContinueOnlyWithTheScenesBondTables) {
  Checkpoint c = read_checkpoint(path());
  Scene scene;
  scene.materials.resize(3);
  scene.walls.resize(5);
  scene.meshes.resize(1);
  EXPECT_NO_THROW(fit_checkpoint_to_scene(c, path(), scene));
  scene.bonds.resize(1);
  const auto refused = [&](const std::string& phrase) {
    try {
      fit_checkpoint_to_scene(c, path(), scene);
      ADD_FAILURE() << "accepted; expected: " << phrase;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
    }
  };
  refused("holds no bonds but the scene defines [[bond]] tables");
  c.bonds.width = bond_value::width;
  std::vector<Real> record(bond_value::width, 0.0);
  record[bond_value::rest_length] = 2e-3;
  c.bonds.add_pair(1, 2, record.data());
  EXPECT_NO_THROW(fit_checkpoint_to_scene(c, path(), scene));
  c.bonds.pair_values[bond_value::type] = 1;
  refused("is of [[bond]] table 1");
  c.bonds.pair_values[bond_value::type] = 0.5;
  refused("is of [[bond]] table 0.5");
  scene.bonds.clear();
  refused("holds parallel bonds but the scene defines no [[bond]] table");
}

TEST_F(DamagedCheckpoint, MaterialWallOrMeshBeyondTheSceneIsRejected) {
  Checkpoint c = read_checkpoint(path());  // materials 0..2, walls 0..4, mesh records
  Scene scene;
  scene.materials.resize(3);
  scene.walls.resize(5);
  try {
    fit_checkpoint_to_scene(c, path(), scene);
    ADD_FAILURE() << "particle-mesh springs were accepted by a scene without meshes";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("but the scene defines no mesh"), std::string::npos)
        << e.what();
  }
  scene.meshes.resize(1);
  EXPECT_NO_THROW(fit_checkpoint_to_scene(c, path(), scene));
  scene.materials.resize(2);
  try {
    fit_checkpoint_to_scene(c, path(), scene);
    ADD_FAILURE() << "a material index beyond the scene was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material index 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path()), std::string::npos) << e.what();
  }
  scene.materials.resize(3);
  scene.walls.resize(4);
  EXPECT_THROW(fit_checkpoint_to_scene(c, path(), scene), InputError);
}

/// A checkpoint records its materials' names; a scene that lists them in another order reads
/// each particle's material by name, and one that lacks a name is refused naming both files.
TEST_F(CheckpointFile, MaterialsAreMatchedByName) {
  Checkpoint part = random_part(comm_rank());
  part.material_names = {"steel", "soil", "clay"};
  write_checkpoint(MPI_COMM_WORLD, dir_, part);
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm_rank() != 0) return;
  Checkpoint c = read_checkpoint(path());
  EXPECT_EQ(c.material_names, part.material_names);
  const std::vector<MaterialId> written = c.particles.material;
  ASSERT_NE(std::count(written.begin(), written.end(), 2u), 0) << "no particle of clay";
  Scene scene;
  scene.file = "till.toml";
  for (const char* name : {"clay", "soil", "steel"}) {
    scene.materials.emplace_back();
    scene.materials.back().name = name;
  }
  map_materials_by_name(c, path(), scene);
  for (std::size_t i = 0; i < written.size(); ++i)
    EXPECT_EQ(c.particles.material[i], 2 - written[i]) << "particle " << i;
  scene.materials.erase(scene.materials.begin());
  Checkpoint again = read_checkpoint(path());
  try {
    map_materials_by_name(again, path(), scene);
    ADD_FAILURE() << "a material the scene lacks was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path() + ": its particles are of material 'clay', which the scene "
                                    "till.toml does not define (it defines 'soil', 'steel')"),
              std::string::npos)
        << message;
  }
}

TEST_F(DamagedCheckpoint, HistoryOfAnotherContactLawIsRejected) {
  Checkpoint c = read_checkpoint(path());  // 4 values per contact
  Scene scene;
  scene.materials.resize(3);
  scene.walls.resize(5);
  scene.meshes.resize(1);
  for (const TangentialLaw tangential : {TangentialLaw::LinearHistory, TangentialLaw::Mindlin}) {
    scene.contact.model.tangential = tangential;
    EXPECT_NO_THROW(fit_checkpoint_to_scene(c, path(), scene));
  }
  const auto expect_refused_for = [&](TangentialLaw tangential, RollingLaw rolling,
                                      const std::string& keeps) {
    scene.contact.model.tangential = tangential;
    scene.contact.model.rolling = rolling;
    try {
      fit_checkpoint_to_scene(c, path(), scene);
      ADD_FAILURE() << "a history of 4 values per contact fitted a law keeping " << keeps;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path()), std::string::npos) << message;
      EXPECT_NE(message.find("history of 4 values per contact"), std::string::npos) << message;
      EXPECT_NE(message.find("keeps " + keeps), std::string::npos) << message;
      EXPECT_NE(message.find("written with another contact law"), std::string::npos) << message;
    }
  };
  expect_refused_for(TangentialLaw::None, RollingLaw::None, "0");
  expect_refused_for(TangentialLaw::LinearHistory, RollingLaw::Epsd, "7");
  expect_refused_for(TangentialLaw::None, RollingLaw::Epsd, "3");
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST_F(CheckpointFile, SnapshotSeriesResumesAfterTheCheckpointsTable) {
  ParticleStore two;
  two.add(1, {0, 0, 0}, 1e-3, 0, {}, 1);
  two.add(2, {1, 0, 0}, 1e-3, 0, {}, 1);
  std::vector<XdmfSnapshot> table;
  {
    SnapshotWriter first(MPI_COMM_WORLD, dir_);
    first.write(two, 0.0, 0);
    first.write(two, 0.5, 50);
    table = first.table();
    first.write(two, 1.0, 100);  // after the checkpoint: dropped on resume
  }
  SnapshotWriter resumed(MPI_COMM_WORLD, dir_);
  resumed.resume(table);
  resumed.write(two, 0.75, 75);
  MPI_Barrier(MPI_COMM_WORLD);
  ASSERT_EQ(resumed.files().size(), 3u);
  EXPECT_EQ(resumed.files()[2], (fs::path(dir_) / "particles_000002.h5").string());
  const std::string xmf = read_text(resumed.xmf_path());
  EXPECT_NE(xmf.find("<Time Value=\"0.5\"/>"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find("<Time Value=\"0.75\"/>"), std::string::npos) << xmf;
  EXPECT_EQ(xmf.find("<Time Value=\"1\"/>"), std::string::npos) << xmf;
  if (comm_rank() == 0) {
    EXPECT_EQ(read_values<double>(resumed.files()[2], "position", H5T_NATIVE_DOUBLE).size(),
              6u * static_cast<std::size_t>(comm_size()));
  }
}

/// Whether each grid of the .xmf text, in order, lists attribute "rank" (grids are cut at
/// their closing tag; the uniform grids hold no grid).
std::vector<bool> grids_listing_rank(const std::string& xmf) {
  std::vector<bool> listing;
  const std::string opening = "GridType=\"Uniform\"";
  for (std::size_t at = xmf.find(opening); at != std::string::npos;
       at = xmf.find(opening, at + 1)) {
    const std::string grid = xmf.substr(at, xmf.find("</Grid>", at) - at);
    listing.push_back(grid.find("<Attribute Name=\"rank\"") != std::string::npos);
  }
  return listing;
}

/// Writes two snapshots with the rank field `before`, checkpoints the series, reads the
/// checkpoint back and resumes the series from it with the rank field `after`.
std::string xmf_after_restart(const std::string& dir, bool before, bool after) {
  ParticleStore two;
  two.add(1, {0, 0, 0}, 1e-3, 0, {}, 1);
  two.add(2, {1, 0, 0}, 1e-3, 0, {}, 1);
  Checkpoint checkpoint;
  checkpoint.dt = 1e-4;
  {
    SnapshotWriter first(MPI_COMM_WORLD, dir, {before});
    first.write(two, 0.0, 0);
    first.write(two, 0.5, 50);
    checkpoint.snapshots = first.table();
  }
  write_checkpoint(MPI_COMM_WORLD, dir, checkpoint);
  MPI_Barrier(MPI_COMM_WORLD);
  SnapshotWriter resumed(MPI_COMM_WORLD, dir, {after});
  resumed.resume(read_checkpoint(checkpoint_path(dir)).snapshots);
  resumed.write(two, 0.75, 75);
  MPI_Barrier(MPI_COMM_WORLD);
  return read_text(resumed.xmf_path());
}

TEST_F(CheckpointFile, SnapshotRankFieldSwitchedOnOrOffAtARestart) {
  EXPECT_EQ(grids_listing_rank(xmf_after_restart(dir_, true, false)),
            (std::vector<bool>{true, true, false}));
  EXPECT_EQ(grids_listing_rank(xmf_after_restart(dir_, false, true)),
            (std::vector<bool>{false, false, true}));
  EXPECT_TRUE(test::has_dataset((fs::path(dir_) / "particles_000002.h5").string(), "rank"));
  EXPECT_FALSE(test::has_dataset((fs::path(dir_) / "particles_000001.h5").string(), "rank"));
}

TEST_F(CheckpointFile, TimeSeriesResumesAfterTheCheckpointStep) {
  if (comm_rank() != 0) return;
  const std::string file = (fs::path(dir_) / "series.csv").string();
  {
    TimeSeriesWriter first(file, {"time", "step"}, true);
    for (int step = 0; step <= 5; ++step) first.append({0.5 * step, double(step)});
  }
  TimeSeriesWriter resumed(file, {"time", "step"}, true, SeriesResume{"step", 3});
  resumed.append({2.0, 4});
  EXPECT_EQ(read_text(file), "time,step\n0,0\n0.5,1\n1,2\n1.5,3\n2,4\n");
  EXPECT_FALSE(fs::exists(file + ".tmp"));

  TimeSeriesWriter other_columns(file, {"time", "step", "energy"}, true, SeriesResume{"step", 3});
  EXPECT_EQ(read_text(file), "time,step,energy\n") << "another header starts a new file";
}

}  // namespace
}  // namespace gpudem
