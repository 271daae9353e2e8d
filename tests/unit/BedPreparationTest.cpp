// Soil beds through the gpudem-mpi binary: a [preparation] run settles 300 grains, stops at the
// first time-series row whose mean kinetic energy per particle is below the threshold, removes
// the grains above a height and writes the rest, with their contact history, as a checkpoint
// file; a run that cannot settle in end_time exits 1 with no bed; a scene with
// `[[insert]] bed = ...` starts from exactly the bed's particles; a missing bed or one whose
// materials the scene lacks is refused with exit code 2 before anything is written. Resumed
// (--resume), a preparation whose bed is written has nothing left to do. A bed prepared with
// bonds keeps them, and a scene started from it continues them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "comm/Checkpoint.hpp"
#include "support/CheckpointEdits.hpp"
#include "support/RunBinary.hpp"
#include "support/SandBin.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;

/// The settle threshold [J] and the trimming height [m] of the preparation scene.
constexpr double kThreshold = 1e-9;
constexpr double kRemoveAbove = 0.012;
/// Settling is checked from √(2H/|g|) on, H = 0.1 m the domain's height.
const double kFirstCheckTime = std::sqrt(2 * 0.1 / 9.81);

/// 300 frictional grains dropped on a floor; they rest by t ≈ 0.3 s.
const std::string kPreparationScene = test::sand_bin_scene(0.6, 0.1, test::kSandGrains, R"([output]
timeseries_every = 0.005

[checkpoint]
every = 10.0

[preparation]
kinetic_energy = 1e-9
remove_above = 0.012
)");

/// The same bin and grains, started from a bed plus 20 new grains above it.
const std::string kFromBedScene = test::sand_bin_scene(0.01, 0.1, R"([[insert]]
bed = "BED"

[[insert]]
region = { min = [0.0, 0.0, 0.05], max = [0.05, 0.05, 0.08] }
count = 20
radius = 0.0025
material = "sand"
)",
                                                       "");

/// A scene whose only source is the bed file BED: each rank reads its part of the rows.
const std::string kBedAloneScene = test::sand_bin_scene(0.01, 0.1, R"([[insert]]
bed = "BED"
)",
                                                        "");

std::string replace(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

/// Rows of a CSV file as numbers, by column name.
std::map<std::string, std::vector<double>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream header(line); std::getline(header, cell, ',');) names.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    for (const std::string& name : names) {
      std::getline(row, cell, ',');
      columns[name].push_back(std::strtod(cell.c_str(), nullptr));
    }
  }
  return columns;
}

/// Mean kinetic energy per particle of time-series row k: (translational + rotational) / N.
double mean_kinetic_energy(const std::map<std::string, std::vector<double>>& series,
                           std::size_t k) {
  return (series.at("kinetic_translational")[k] + series.at("kinetic_rotational")[k]) /
         series.at("particles")[k];
}

/// The snapshot file with the highest number in `dir`.
fs::path last_snapshot(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".h5" &&
        entry.path().filename().string().rfind("particles_", 0) == 0)
      files.push_back(entry.path());
  return *std::max_element(files.begin(), files.end());
}

/// Particle positions of a snapshot by id (the snapshot's rows are in the engine's order).
std::map<ParticleId, Vec3> snapshot_positions(const fs::path& file) {
  const auto ids = test::read_values<std::uint64_t>(file.string(), "id", H5T_NATIVE_UINT64);
  const auto xyz = test::read_values<double>(file.string(), "position", H5T_NATIVE_DOUBLE);
  std::map<ParticleId, Vec3> positions;
  for (std::size_t i = 0; i < ids.size(); ++i)
    positions[ids[i]] = Vec3{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  return positions;
}

class BedPreparation : public ::testing::Test {
 protected:
  /// One preparation for the whole suite, in a folder shared by its tests.
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("gpudem_bed_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    const fs::path scene = root_ / "prepare.toml";
    std::ofstream(scene) << kPreparationScene;
    prepared_ = new test::RunResult(
        test::run_binary(scene.string() + " --quiet --output-dir " + (root_ / "prep").string()));
  }
  static void TearDownTestSuite() {
    delete prepared_;
    fs::remove_all(root_);
  }

  void SetUp() override {
    dir_ = root_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir_);
    ASSERT_EQ(prepared_->exit_code, 0) << prepared_->output;
  }

  std::string scene(const std::string& text) const {
    const fs::path p = dir_ / "scene.toml";
    std::ofstream(p) << text;
    return p.string();
  }

  static fs::path bed() { return root_ / "prep" / "bed.h5"; }

  static fs::path root_;
  static test::RunResult* prepared_;
  fs::path dir_;
};

fs::path BedPreparation::root_;
test::RunResult* BedPreparation::prepared_ = nullptr;

TEST_F(BedPreparation, StopsAtTheFirstSettledRow) {
  const auto series = read_csv(root_ / "prep" / "timeseries.csv");
  const std::vector<double>& time = series.at("time");
  ASSERT_GE(time.size(), 2u);
  const std::size_t last = time.size() - 1;
  EXPECT_LT(mean_kinetic_energy(series, last), kThreshold) << "stopped at t = " << time[last];
  EXPECT_LT(time[last], 0.6 - 1e-9) << "settled before end_time";
  for (std::size_t k = 1; k < last; ++k) {
    if (time[k] < kFirstCheckTime) continue;
    EXPECT_GE(mean_kinetic_energy(series, k), kThreshold)
        << "an earlier row settled: t = " << time[k];
  }
  EXPECT_DOUBLE_EQ(read_checkpoint(bed().string()).time, time[last]);
  EXPECT_NE(prepared_->output.find("settled at t = "), std::string::npos) << prepared_->output;
}

TEST_F(BedPreparation, KeepsExactlyTheParticlesBelowThePlane) {
  const Checkpoint b = read_checkpoint(bed().string());
  const std::map<ParticleId, Vec3> before = snapshot_positions(last_snapshot(root_ / "prep"));
  ASSERT_EQ(before.size(), 300u);
  std::size_t below = 0;
  for (const auto& [id, x] : before) below += x.z <= kRemoveAbove;
  EXPECT_EQ(b.particles.size(), below);
  EXPECT_GT(before.size() - below, 0u) << "some particles lie above the plane";
  for (std::size_t i = 0; i < b.particles.size(); ++i) {
    const Real4 p = b.particles.position_radius[i];
    EXPECT_LE(p.z, kRemoveAbove) << "id " << b.particles.id[i];
    ASSERT_EQ(before.count(b.particles.id[i]), 1u);
    const Vec3 x = before.at(b.particles.id[i]);
    EXPECT_TRUE(x.x == p.x && x.y == p.y && x.z == p.z) << "id " << b.particles.id[i];
  }
  EXPECT_EQ(b.list_position_radius.size(), b.particles.size());
  EXPECT_FALSE(fs::exists(bed().string() + ".staging"));
  const std::string kept =
      std::to_string(below) + " particles kept, " + std::to_string(300 - below) + " removed";
  EXPECT_NE(prepared_->output.find(kept), std::string::npos) << prepared_->output;
}

TEST_F(BedPreparation, KeepsTheHistoryOfTheRemainingContacts) {
  const Checkpoint b = read_checkpoint(bed().string());
  const Checkpoint settled = read_checkpoint((root_ / "prep" / "checkpoint.h5").string());
  ASSERT_EQ(settled.step, b.step) << "the settled step is checkpointed";
  std::set<ParticleId> kept(b.particles.id.begin(), b.particles.id.end());
  const ContactHistory& all = settled.history;
  ContactHistory expected;
  expected.width = all.width;
  for (std::size_t k = 0; k < all.pair_owner.size(); ++k)
    if (kept.count(all.pair_owner[k]) && kept.count(all.pair_partner[k]))
      expected.add_pair(all.pair_owner[k], all.pair_partner[k], &all.pair_values[k * all.width]);
  for (std::size_t k = 0; k < all.wall_owner.size(); ++k)
    if (kept.count(all.wall_owner[k]))
      expected.add_wall(all.wall_owner[k], all.wall_index[k], &all.wall_values[k * all.width]);
  EXPECT_EQ(b.history.width, 4u);
  EXPECT_GT(expected.pair_owner.size(), 100u) << "the bed holds loaded springs";
  EXPECT_LT(expected.pair_owner.size(), all.pair_owner.size()) << "contacts above were dropped";
  EXPECT_EQ(b.history.pair_owner, expected.pair_owner);
  EXPECT_EQ(b.history.pair_partner, expected.pair_partner);
  EXPECT_EQ(b.history.pair_values, expected.pair_values);
  EXPECT_EQ(b.history.wall_owner, expected.wall_owner);
  EXPECT_EQ(b.history.wall_index, expected.wall_index);
  EXPECT_EQ(b.history.wall_values, expected.wall_values);
}

/// --resume on a preparation: with its bed written the run is complete and nothing changes;
/// with the settle step's checkpoint but no bed (killed before the bed was written) it goes on
/// from that checkpoint and writes the bed.
TEST_F(BedPreparation, ResumedPreparationIsCompleteOnceItsBedIsWritten) {
  const fs::path prep = dir_ / "prep";
  fs::copy(root_ / "prep", prep, fs::copy_options::recursive);
  ASSERT_TRUE(fs::exists(prep / "checkpoint.h5")) << "the settle step writes a checkpoint";
  const std::string job = scene(kPreparationScene) + " --resume --output-dir " + prep.string();
  const auto written = fs::last_write_time(prep / "bed.h5");
  const test::RunResult done = test::run_binary(job);
  EXPECT_EQ(done.exit_code, 0) << done.output;
  EXPECT_NE(done.output.find("run complete: the bed " + (prep / "bed.h5").string() +
                             " is written; nothing to do"),
            std::string::npos)
      << done.output;
  EXPECT_EQ(fs::last_write_time(prep / "bed.h5"), written);

  fs::remove(prep / "bed.h5");
  const test::RunResult resumed = test::run_binary(job + " --quiet");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("bed: "), std::string::npos) << resumed.output;
  ASSERT_TRUE(fs::exists(prep / "bed.h5"));
  EXPECT_GT(read_checkpoint((prep / "bed.h5").string()).step,
            read_checkpoint((root_ / "prep" / "bed.h5").string()).step)
      << "the resumed preparation settles again after the checkpoint's step";
}

TEST_F(BedPreparation, UnsettledRunExitsOneWithoutBed) {
  const fs::path out = dir_ / "out";
  const test::RunResult r = test::run_binary(scene(kPreparationScene) +
                                             " --quiet --set simulation.end_time=0.15 "
                                             "--output-dir " +
                                             out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_FALSE(fs::exists(out / "bed.h5"));
  const auto series = read_csv(out / "timeseries.csv");
  const std::size_t last = series.at("time").size() - 1;
  EXPECT_NEAR(series.at("time")[last], 0.15, 1e-12);
  const double energy = mean_kinetic_energy(series, last);
  ASSERT_GT(energy, kThreshold);
  const std::string message = "did not settle: mean kinetic energy ";
  const std::size_t at = r.output.find(message);
  ASSERT_NE(at, std::string::npos) << r.output;
  const double reported = std::strtod(r.output.c_str() + at + message.size(), nullptr);
  EXPECT_NEAR(reported, energy, 1e-5 * energy) << "printed with 6 significant digits";
  EXPECT_NE(r.output.find("J per particle at t = 0.15 s, threshold 1e-09 J"), std::string::npos)
      << r.output;
}

TEST_F(BedPreparation, SceneStartsFromTheBedParticles) {
  const fs::path out = dir_ / "out";
  const test::RunResult r = test::run_binary(scene(replace(kFromBedScene, "BED", bed().string())) +
                                             " --quiet --output-dir " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("zero contact history"), std::string::npos) << r.output;
  const Checkpoint b = read_checkpoint(bed().string());
  const std::map<ParticleId, Vec3> start = snapshot_positions(out / "particles_000000.h5");
  ASSERT_EQ(start.size(), b.particles.size() + 20);
  const ParticleId largest = *std::max_element(b.particles.id.begin(), b.particles.id.end());
  for (ParticleId id = largest + 1; id <= largest + 20; ++id)
    EXPECT_EQ(start.count(id), 1u) << "new grains take ids after the bed's largest, " << id;
  for (std::size_t i = 0; i < b.particles.size(); ++i) {
    const Real4 p = b.particles.position_radius[i];
    ASSERT_EQ(start.count(b.particles.id[i]), 1u) << "id " << b.particles.id[i];
    const Vec3 x = start.at(b.particles.id[i]);
    EXPECT_TRUE(x.x == p.x && x.y == p.y && x.z == p.z) << "id " << b.particles.id[i];
  }
  EXPECT_EQ(read_csv(out / "timeseries.csv").at("time").front(), 0.0);
}

TEST_F(BedPreparation, LawOfAnotherHistoryWidthStartsWithoutHistory) {
  const fs::path out = dir_ / "out";
  const test::RunResult r =
      test::run_binary(scene(replace(kFromBedScene, "BED", bed().string())) +
                       " --quiet --set contact.tangential='\"none\"' --output-dir " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("keeps 4 values per contact but this contact law keeps 0; the bed "
                          "starts with zero contact history"),
            std::string::npos)
      << r.output;
}

/// The bed's Hooke law keeps 4 values per contact (linear_history); Hertz–Mindlin with JKR keeps
/// those 4 and the formed flag.
TEST_F(BedPreparation, JkrLawKeepsTheSpringsOfABedWithoutAdhesion) {
  const fs::path out = dir_ / "out";
  const std::string sticky =
      replace(replace(kFromBedScene, "BED", bed().string()), "[contact]\nstiffness = 2000\n",
              "[contact]\nnormal = \"hertz\"\ncohesion = \"jkr\"\n");
  const test::RunResult r =
      test::run_binary(scene(sticky) + " --quiet --set material.0.surface_energy=0.01" +
                       " --output-dir " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("keeps 4 values per contact, this law's without JKR's formed flag; its "
                          "contacts keep their springs and start formed"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("zero contact history"), std::string::npos) << r.output;
}

TEST(BedHistory, AValueAppendedToEveryRecord) {
  ContactHistory h;
  h.width = 2;
  const Real a[] = {1, 2}, b[] = {3, 4}, c[] = {5, 6};
  h.add_pair(7, 8, a);
  h.add_pair(8, 7, b);
  h.add_wall(7, 0, c);
  const ContactHistory out = with_value_appended(h, 1);
  EXPECT_EQ(out.width, 3u);
  EXPECT_EQ(out.pair_values, (std::vector<Real>{1, 2, 1, 3, 4, 1}));
  EXPECT_EQ(out.wall_values, (std::vector<Real>{5, 6, 1}));
  EXPECT_TRUE(out.mesh_values.empty());
  EXPECT_EQ(out.pair_partner, h.pair_partner);
  EXPECT_TRUE(out.lengths_agree());
}

/// Grains cemented where their surfaces lie within 0.5 mm when they are poured (bonds that never
/// break), with a skin that holds such a gap.
const std::string kCement = R"([neighbor]
skin = 0.002

[[bond]]
materials = ["sand", "sand"]
gap = 0.0005
young = 1e6
)";

/// A bed prepared with bonds keeps those between kept grains (each end's record, as the settle
/// step's checkpoint holds them); a scene with the same [[bond]] table starts with exactly
/// those bonds instead of making its own; one without [[bond]] tables is refused.
TEST_F(BedPreparation, ABedKeepsItsBondsAndTheSceneContinuesThem) {
  const fs::path prep = dir_ / "prep";
  const test::RunResult made = test::run_binary(
      scene(test::sand_bin_scene(0.6, 0.1, test::kSandGrains,
                                 kCement + "[checkpoint]\nevery = 10.0\n\n[preparation]\n"
                                           "kinetic_energy = 1e-9\nremove_above = 0.012\n")) +
      " --quiet --output-dir " + prep.string());
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const Checkpoint b = read_checkpoint((prep / "bed.h5").string());
  const Checkpoint settled = read_checkpoint((prep / "checkpoint.h5").string());
  const std::set<ParticleId> kept(b.particles.id.begin(), b.particles.id.end());
  std::vector<std::pair<ParticleId, ParticleId>> expected, held;
  std::vector<Real> expected_values;
  const ContactHistory& all = settled.bonds;
  for (std::size_t k = 0; k < all.pair_owner.size(); ++k)
    if (kept.count(all.pair_owner[k]) && kept.count(all.pair_partner[k])) {
      expected.emplace_back(all.pair_owner[k], all.pair_partner[k]);
      expected_values.insert(expected_values.end(), all.pair_values.begin() + k * all.width,
                             all.pair_values.begin() + (k + 1) * all.width);
    }
  for (std::size_t k = 0; k < b.bonds.pair_owner.size(); ++k)
    held.emplace_back(b.bonds.pair_owner[k], b.bonds.pair_partner[k]);
  ASSERT_GT(expected.size(), 10u) << "the poured grains were cemented";
  EXPECT_LT(expected.size(), all.pair_owner.size()) << "bonds of grains above were dropped";
  EXPECT_EQ(held, expected);
  EXPECT_EQ(b.bonds.pair_values, expected_values);
  EXPECT_EQ(b.bonds_made, expected.size() / 2);

  const std::string from_bed = replace(kFromBedScene, "BED", (prep / "bed.h5").string());
  const fs::path out = dir_ / "out";
  const test::RunResult r =
      test::run_binary(scene(from_bed + kCement) + " --output-dir " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("its " + std::to_string(b.bonds_made) +
                          " bonds hold; the [[bond]] tables make no others"),
            std::string::npos)
      << r.output;
  const auto series = read_csv(out / "timeseries.csv");
  EXPECT_EQ(series.at("bonds").front(), double(b.bonds_made));
  EXPECT_EQ(series.at("broken_bonds").front(), 0.0);
  const fs::path split = dir_ / "split";  // each of 2 ranks reads half the bed's bond records
  const test::RunResult two = test::run_binary_on_ranks(
      2, scene(from_bed + kCement) + " --quiet --output-dir " + split.string());
  ASSERT_EQ(two.exit_code, 0) << two.output;
  const auto split_series = read_csv(split / "timeseries.csv");
  for (const char* column : {"bonds", "broken_bonds", "kinetic_translational", "potential_elastic"})
    EXPECT_EQ(split_series.at(column), series.at(column)) << column;

  const fs::path refused = dir_ / "refused";
  const test::RunResult bare =
      test::run_binary(scene(from_bed) + " --output-dir " + refused.string());
  EXPECT_EQ(bare.exit_code, 2) << bare.output;
  EXPECT_NE(
      bare.output.find("key 'insert[0].bed': cannot read the bed: " + (prep / "bed.h5").string() +
                       ": holds parallel bonds but the scene defines no [[bond]] table"),
      std::string::npos)
      << bare.output;
  EXPECT_FALSE(fs::exists(refused));
}

/// A bed prepared under a [[bond]] table that bonded nothing (grains poured apart, gap 0) holds
/// no bonds: a scene from it lets its own table cement the settled grains.
TEST_F(BedPreparation, ABedWithoutBondsLetsTheTablesMakeThem) {
  const fs::path prep = dir_ / "prep";
  std::string cement = replace(kCement, "gap = 0.0005", "gap = 0.0");
  const test::RunResult made =
      test::run_binary(scene(test::sand_bin_scene(0.6, 0.1, test::kSandGrains,
                                                  cement + "[preparation]\nkinetic_energy = 1e-9\n"
                                                           "remove_above = 0.012\n")) +
                       " --quiet --output-dir " + prep.string());
  ASSERT_EQ(made.exit_code, 0) << made.output;
  ASSERT_EQ(read_checkpoint((prep / "bed.h5").string()).bonds_made, 0u);
  const fs::path out = dir_ / "out";
  const test::RunResult r =
      test::run_binary(scene(replace(kFromBedScene, "BED", (prep / "bed.h5").string()) + kCement) +
                       " --output-dir " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("bonds hold"), std::string::npos) << r.output;
  EXPECT_GT(read_csv(out / "timeseries.csv").at("bonds").front(), 10.0)
      << "the table cemented the settled grains";
}

TEST_F(BedPreparation, MissingBedIsRefused) {
  const fs::path out = dir_ / "out";
  const std::string missing = (dir_ / "nowhere.h5").string();
  const test::RunResult r = test::run_binary(scene(replace(kFromBedScene, "BED", missing)) +
                                             " --output-dir " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("scene.toml:27: key 'insert[0].bed': cannot read the bed: " + missing +
                          ": no such checkpoint file"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(BedPreparation, BedMaterialIndexBeyondTheFilesNamesIsRefused) {
  const fs::path copy = dir_ / "bed.h5";
  fs::copy_file(bed(), copy);
  const std::size_t n = read_checkpoint(copy.string()).particles.size();
  std::vector<std::uint32_t> materials(n, 0);
  materials[n / 2] = 1;
  test::replace_u32_dataset(copy.string(), "material", materials);
  const ParticleId id = read_checkpoint(copy.string()).particles.id[n / 2];
  const fs::path out = dir_ / "out";
  const test::RunResult r = test::run_binary(scene(replace(kFromBedScene, "BED", copy.string())) +
                                             " --output-dir " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("key 'insert[0].bed': cannot read the bed: " + copy.string() +
                          ": particle id " + std::to_string(id) +
                          " has material index 1 but the file names 1 material(s)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
}

/// The bed records its materials by name: a scene that calls its material otherwise does not
/// take the bed's grains for another material; it is refused, naming both files and the name.
TEST_F(BedPreparation, BedMaterialTheSceneLacksIsRefusedNamingBothFiles) {
  std::string text = replace(kFromBedScene, "BED", bed().string());
  for (std::size_t at = text.find("\"sand\""); at != std::string::npos;
       at = text.find("\"sand\"", at))
    text.replace(at, 6, "\"loam\"");
  const fs::path out = dir_ / "out";
  const test::RunResult r = test::run_binary(scene(text) + " --output-dir " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("key 'insert[0].bed': cannot read the bed: " + bed().string() +
                          ": its particles are of material 'sand', which the scene " +
                          (dir_ / "scene.toml").string() + " does not define (it defines 'loam')"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(BedPreparation, ProblemInAnotherRanksPartOfABedAloneIsRefusedOnEveryRank) {
  // Two ranks read the first and the second half of the rows; only the last particle names a
  // material beyond the scene, so only rank 1 finds it, and rank 0 must report it.
  const fs::path copy = dir_ / "bed.h5";
  fs::copy_file(bed(), copy);
  const std::size_t n = read_checkpoint(copy.string()).particles.size();
  std::vector<std::uint32_t> materials(n, 0);
  materials.back() = 1;
  test::replace_u32_dataset(copy.string(), "material", materials);
  const ParticleId id = read_checkpoint(copy.string()).particles.id.back();
  const fs::path out = dir_ / "out";
  const test::RunResult r = test::run_binary_on_ranks(
      2, scene(replace(kBedAloneScene, "BED", copy.string())) + " --output-dir " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string needle = "key 'insert[0].bed': cannot read the bed: " + copy.string() +
                             ": particle id " + std::to_string(id) + " has material index 1";
  const std::size_t first = r.output.find(needle);
  EXPECT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(needle, first + 1), std::string::npos) << "reported twice:\n" << r.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace gpudem
