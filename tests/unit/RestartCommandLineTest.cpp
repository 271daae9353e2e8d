// gpudem-mpi --restart end to end: a run of 2T equals, snapshot for snapshot and bit for bit,
// a run of T continued from its checkpoint (same .xmf, same time series), summing its loads in
// the units the checkpoint records; continued with other snapshot fields and precision, the .xmf
// describes each snapshot as written; a run killed with SIGKILL while writing a checkpoint every
// step always leaves a checkpoint that reads back and continues; a bad checkpoint or a restart that
// cannot continue (another time step, a contact law keeping another number of history values per
// contact) exits 2 with a message naming the problem and writes nothing. With --resume a chain of
// jobs on the same command line starts the run, continues it from its own checkpoint and stops once
// it is complete.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "comm/Checkpoint.hpp"
#include "core/InputError.hpp"
#include "support/CheckpointEdits.hpp"

extern char** environ;

#include "support/RunBinary.hpp"
#include "support/SandBin.hpp"

namespace gpudem {
namespace {

namespace fs = std::filesystem;
using test::read_values;

using Result = test::RunResult;

Result run(const std::string& args) { return test::run_binary(args); }

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// 300 frictional grains falling onto a floor: by T = 0.1 s they rest on it and on each other
/// with loaded tangential springs. Snapshots every 0.05 s, checkpoints every T.
const std::string kBedScene = test::sand_bin_scene(0.2, 0.2, test::kSandGrains, R"([output]
every = 0.05
timeseries_every = 0.005

[checkpoint]
every = 0.1
)");

class RestartCommandLine : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gpudem_restart_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string scene(const std::string& text) const {
    const fs::path p = dir_ / "scene.toml";
    std::ofstream(p) << text;
    return p.string();
  }

  fs::path dir_;
};

/// Every dataset of two snapshot files holds the same bytes.
void expect_same_snapshot(const fs::path& a, const fs::path& b) {
  for (const char* name : {"position", "radius", "velocity", "angular_velocity", "force", "id"}) {
    const auto in_a = test::raw_bytes(a.string(), name);
    const auto in_b = test::raw_bytes(b.string(), name);
    EXPECT_FALSE(in_a.empty()) << a << ": " << name;
    EXPECT_TRUE(in_a == in_b) << name << " differs between " << a << " and " << b;
  }
}

TEST_F(RestartCommandLine, RestartedRunEqualsStraightRun) {
  const std::string bed = scene(kBedScene);
  const fs::path straight = dir_ / "straight", legs = dir_ / "legs";
  const Result whole =
      run(bed + " --quiet --set checkpoint.every=0 --output-dir " + straight.string());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  EXPECT_FALSE(fs::exists(straight / "checkpoint.h5")) << "checkpoint.every = 0 writes none";

  const Result first =
      run(bed + " --quiet --set simulation.end_time=0.1 --output-dir " + legs.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string checkpoint = (legs / "checkpoint.h5").string();
  ASSERT_GT(read_values<std::uint64_t>(checkpoint, "pair_owner", H5T_NATIVE_UINT64).size(), 100u)
      << "the bed must hold tangential springs at the checkpoint";
  EXPECT_EQ(read_checkpoint(checkpoint).history.width, 4u) << "linear_history: spring and flag";
  const Result second =
      run(bed + " --quiet --restart " + checkpoint + " --output-dir " + legs.string());
  ASSERT_EQ(second.exit_code, 0) << second.output;

  for (const char* file : {"particles_000003.h5", "particles_000004.h5"})
    expect_same_snapshot(straight / file, legs / file);
  EXPECT_FALSE(fs::exists(legs / "particles_000005.h5"));
  EXPECT_EQ(read_text(legs / "particles.xmf"), read_text(straight / "particles.xmf"));
  EXPECT_EQ(read_text(legs / "timeseries.csv"), read_text(straight / "timeseries.csv"));
  EXPECT_EQ(read_checkpoint(checkpoint).step, 4000u) << "a checkpoint ends the run";
}

/// A restart sums the contact loads in the units its checkpoint records, not in those of the
/// particles it starts from (which may have lost the lightest grain by then): the units written
/// are the run's, and a checkpoint whose units are edited continues into another run.
TEST_F(RestartCommandLine, RestartSumsLoadsInTheUnitsOfItsCheckpoint) {
  const std::string bed = scene(kBedScene);
  const fs::path legs = dir_ / "legs", edited = dir_ / "edited";
  const Result first =
      run(bed + " --quiet --set simulation.end_time=0.1 --output-dir " + legs.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const fs::path checkpoint = legs / "checkpoint.h5";
  const Checkpoint c = read_checkpoint(checkpoint.string());
  // the run's units: the power of two at or below 2^-40 of its lightest grain's weight, and
  // that times its smallest radius (no grain leaves the bin)
  double lightest = std::numeric_limits<double>::infinity(), smallest = lightest;
  for (std::size_t i = 0; i < c.particles.size(); ++i) {
    lightest = std::min(lightest, 9.80665 / c.particles.velocity_inv_mass[i].w);
    smallest = std::min(smallest, c.particles.position_radius[i].w);
  }
  EXPECT_LE(c.sum_force_unit, lightest * 0x1p-40);
  EXPECT_GT(c.sum_force_unit, lightest * 0x1p-41);
  EXPECT_LE(c.sum_torque_unit, c.sum_force_unit * smallest);
  EXPECT_GT(c.sum_torque_unit, c.sum_force_unit * smallest / 2);
  fs::create_directories(edited);
  fs::copy_file(checkpoint, edited / "checkpoint.h5");
  test::set_f64_attribute((edited / "checkpoint.h5").string(), "sum_force_unit", 0x1p-30);
  const Result own =
      run(bed + " --quiet --restart " + checkpoint.string() + " --output-dir " + legs.string());
  ASSERT_EQ(own.exit_code, 0) << own.output;
  const Result other = run(bed + " --quiet --restart " + (edited / "checkpoint.h5").string() +
                           " --output-dir " + edited.string());
  ASSERT_EQ(other.exit_code, 0) << other.output;
  EXPECT_NE(test::raw_bytes((legs / "particles_000004.h5").string(), "position"),
            test::raw_bytes((edited / "particles_000004.h5").string(), "position"));
}

/// A chain of jobs that all run the same command line with --resume: the first starts the
/// scene (here cut short at T, as by a batch time limit), the second continues from the
/// output directory's checkpoint to 2T and equals a straight run, and the third finds the run
/// complete and changes nothing.
TEST_F(RestartCommandLine, ResumedJobsContinueTheRunUntilItIsComplete) {
  const std::string bed = scene(kBedScene);
  const fs::path straight = dir_ / "straight", chain = dir_ / "chain";
  const Result whole = run(bed + " --quiet --output-dir " + straight.string());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const std::string job = bed + " --resume --output-dir " + chain.string();

  const Result first = run(job + " --quiet --set simulation.end_time=0.1");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_EQ(read_checkpoint((chain / "checkpoint.h5").string()).step, 2000u);
  const Result second = run(job);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(
      second.output.find("restart from " + (chain / "checkpoint.h5").string() + " at t = 0.1 s"),
      std::string::npos)
      << second.output;
  for (const char* file : {"particles_000003.h5", "particles_000004.h5"})
    expect_same_snapshot(straight / file, chain / file);
  EXPECT_EQ(read_text(chain / "timeseries.csv"), read_text(straight / "timeseries.csv"));

  const auto written = fs::last_write_time(chain / "timeseries.csv");
  const Result third = run(job);
  EXPECT_EQ(third.exit_code, 0) << third.output;
  EXPECT_NE(third.output.find("run complete: " + (chain / "checkpoint.h5").string() +
                              " is at t = 0.2 s, end_time = 0.2 s; nothing to do"),
            std::string::npos)
      << third.output;
  EXPECT_EQ(fs::last_write_time(chain / "timeseries.csv"), written);
  EXPECT_FALSE(fs::exists(chain / "particles_000005.h5"));
  EXPECT_EQ(read_checkpoint((chain / "checkpoint.h5").string()).step, 4000u);
}

/// --resume without checkpoints in the scene, or together with --restart, exits 2 before
/// anything is written.
TEST_F(RestartCommandLine, ResumeIsRefusedWithoutCheckpointsOrWithRestart) {
  const std::string bed = scene(kBedScene);
  const fs::path out = dir_ / "out";
  const Result none = run(bed + " --resume --set checkpoint.every=0 --output-dir " + out.string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("key 'checkpoint.every': --resume needs checkpoints"),
            std::string::npos)
      << none.output;
  const Result both = run(bed + " --resume --restart " + (dir_ / "x.h5").string() +
                          " --output-dir " + out.string());
  EXPECT_EQ(both.exit_code, 2) << both.output;
  EXPECT_NE(both.output.find("--restart excludes --resume"), std::string::npos) << both.output;
  EXPECT_FALSE(fs::exists(out)) << "output written for a refused --resume";
}

/// Whether file `path` holds dataset `name`, stored as `type`.
bool stored_as(const fs::path& path, const char* name, hid_t type) {
  test::H5Id<H5Fclose> file(H5Fopen(path.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (file.id < 0 || H5Lexists(file.id, name, H5P_DEFAULT) <= 0) return false;
  test::H5Id<H5Dclose> dataset(H5Dopen2(file.id, name, H5P_DEFAULT));
  test::H5Id<H5Tclose> stored(H5Dget_type(dataset.id));
  return H5Tequal(stored.id, type) > 0;
}

TEST_F(RestartCommandLine, RestartWithOtherFieldsAndPrecisionKeepsEachSnapshotDescribed) {
  const std::string bed = scene(kBedScene);
  const fs::path legs = dir_ / "legs";
  const std::string lean =
      " --set 'output.fields=[\"velocity\"]' --set 'output.precision=\"float\"'";
  const Result first =
      run(bed + " --quiet --set simulation.end_time=0.1" + lean + " --output-dir " + legs.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const Result second = run(bed + " --quiet --restart " + (legs / "checkpoint.h5").string() +
                            " --output-dir " + legs.string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  // Snapshots 0-2 (t = 0, 0.05, 0.1) come from the lean first leg, 3-4 from the second, which
  // writes every field in double.
  const std::string xmf = read_text(legs / "particles.xmf");
  for (const char* file : {"particles_000000", "particles_000002"}) {
    const fs::path h5 = legs / (std::string(file) + ".h5");
    EXPECT_TRUE(stored_as(h5, "position", H5T_IEEE_F32LE)) << file;
    EXPECT_TRUE(stored_as(h5, "velocity", H5T_IEEE_F32LE)) << file;
    EXPECT_FALSE(stored_as(h5, "radius", H5T_IEEE_F32LE)) << file << " holds a radius";
    EXPECT_FALSE(stored_as(h5, "radius", H5T_IEEE_F64LE)) << file << " holds a radius";
    EXPECT_NE(xmf.find(std::string(file) + ".h5:/velocity"), std::string::npos) << file;
    EXPECT_EQ(xmf.find(std::string(file) + ".h5:/radius"), std::string::npos) << file;
  }
  for (const char* file : {"particles_000003", "particles_000004"}) {
    EXPECT_TRUE(stored_as(legs / (std::string(file) + ".h5"), "position", H5T_IEEE_F64LE));
    EXPECT_NE(xmf.find(std::string(file) + ".h5:/radius"), std::string::npos) << file;
    EXPECT_NE(xmf.find(std::string(file) + ".h5:/force"), std::string::npos) << file;
  }
  // Geometry in float for the first three grids, double for the last two.
  std::size_t doubles = 0, floats = 0;
  for (std::size_t at = xmf.find("<Geometry"); at != std::string::npos;
       at = xmf.find("<Geometry", at + 1)) {
    const std::size_t item = xmf.find("Precision=\"", at) + 11;
    (xmf[item] == '8' ? doubles : floats) += 1;
  }
  EXPECT_EQ(floats, 3u);
  EXPECT_EQ(doubles, 2u);
}

// ---- a writer killed at random moments -------------------------------------------------------

/// An 8000-particle lattice written as CSV: large enough that a checkpoint takes a good part
/// of each step, so kills land inside writes. The lattice settles into columns; its stiffness
/// keeps dt = 1e-4 s below a column's stable step √(m/k) = 2.0e-4 s for 15,000 steps (at
/// k = 1e4 a column goes unstable near step 460, within reach of the kills).
void write_lattice(const fs::path& csv) {
  std::ofstream out(csv);
  out << "x,y,z,r\n";
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 20; ++k)
        out << 0.0025 + 0.005 * i << ',' << 0.0025 + 0.005 * j << ',' << 0.0025 + 0.005 * k
            << ",0.002\n";
}

const char* kLatticeScene = R"([simulation]
end_time = 10.0
dt = 1e-4

[domain]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.1, 0.2]

[[material]]
name = "sand"
density = 2500.0
young = 1e7
poisson = 0.3

[contact]
stiffness = 2e3

[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "sand"

[[insert]]
csv = "lattice.csv"

[output]
every = 10.0

[checkpoint]
every = 1e-4
)";

/// Starts gpudem-mpi with `args` (output discarded) and returns its pid.
pid_t spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  std::string binary = test::binary_path();
  argv.push_back(binary.data());
  std::vector<std::string> copies = args;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return failed ? -1 : pid;
}

/// Reads the checkpoint (every read must succeed) until `stop` has passed or it holds a step
/// beyond `beyond`; returns the last step read (0 while there is none).
std::uint64_t read_repeatedly(const std::string& path, std::chrono::steady_clock::time_point stop,
                              std::uint64_t beyond = std::numeric_limits<std::uint64_t>::max()) {
  std::uint64_t step = 0;
  do {
    if (fs::exists(path)) {
      try {
        step = read_checkpoint(path).step;
      } catch (const InputError& e) {
        ADD_FAILURE() << "checkpoint observed broken while the writer runs: " << e.what();
        return 0;
      }
    }
    if (step > beyond) return step;
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
  } while (std::chrono::steady_clock::now() < stop);
  return step;
}

TEST_F(RestartCommandLine, KilledWriterNeverLeavesAHalfWrittenCheckpoint) {
  write_lattice(dir_ / "lattice.csv");
  const std::string lattice = scene(kLatticeScene);
  const fs::path out = dir_ / "out";
  const std::string checkpoint = (out / "checkpoint.h5").string();
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> extra_ms(0, 400);
  int killed_inside_a_write = 0;
  std::uint64_t step = 0;
  for (int round = 0; round < 4; ++round) {
    std::vector<std::string> args = {lattice, "--quiet", "--output-dir", out.string()};
    if (round > 0) args.insert(args.end(), {"--restart", checkpoint});
    const pid_t pid = spawn(args);
    ASSERT_GT(pid, 0);
    // Once this run has written a checkpoint (start-up time varies with the backend), it is
    // killed at a random moment of the next 400 ms, often inside a write.
    const auto start = std::chrono::steady_clock::now();
    const std::uint64_t first = read_repeatedly(checkpoint, start + std::chrono::seconds(20), step);
    read_repeatedly(checkpoint,
                    std::chrono::steady_clock::now() + std::chrono::milliseconds(extra_ms(rng)));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_GT(first, step) << "round " << round << " wrote no checkpoint in 20 s"
                           << (WIFEXITED(status) ? " (it exited with status " +
                                                       std::to_string(WEXITSTATUS(status)) + ")"
                                                 : std::string());
    killed_inside_a_write += fs::exists(checkpoint + ".tmp") ? 1 : 0;
    ASSERT_TRUE(fs::exists(checkpoint)) << "round " << round;
    const std::uint64_t now = read_checkpoint(checkpoint).step;  // throws if damaged
    EXPECT_GE(now, first) << "round " << round;
    step = now;
  }
  RecordProperty("kills_inside_a_write", killed_inside_a_write);

  // A last restart runs to its end over whatever temporary file the last kill left.
  const Result last =
      run(lattice + " --quiet --output-dir " + out.string() + " --restart " + checkpoint +
          " --set simulation.end_time=" + std::to_string((step + 3) * 1e-4));
  ASSERT_EQ(last.exit_code, 0) << last.output;
  EXPECT_EQ(read_checkpoint(checkpoint).step, step + 3);
  EXPECT_FALSE(fs::exists(checkpoint + ".tmp"));
}

// ---- restarts that are refused ---------------------------------------------------------------

/// A valid checkpoint of a small run (50 grains, 20 steps), made once for the refusals.
class RefusedRestart : public RestartCommandLine {
 protected:
  static void SetUpTestSuite() {
    source_dir_ = fs::temp_directory_path() / ("gpudem_refused_" + std::to_string(::getpid()));
    fs::remove_all(source_dir_);
    fs::create_directories(source_dir_);
    std::string text = kBedScene;
    std::ofstream(source_dir_ / "scene.toml") << text;
    const Result r = run((source_dir_ / "scene.toml").string() +
                         " --quiet --set insert.0.count=50 --set simulation.end_time=0.001 "
                         "--set checkpoint.every=0.001 --output-dir " +
                         (source_dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() { fs::remove_all(source_dir_); }

  void SetUp() override {
    RestartCommandLine::SetUp();
    fs::copy_file(source_dir_ / "out" / "checkpoint.h5", bad());
  }

  std::string bad() const { return (dir_ / "bad.h5").string(); }

  /// Restarting from bad() exits 2, names `file` and `needle`, and writes nothing.
  void expect_refused(const std::string& needle, const std::string& extra_args = "",
                      const std::string& file = "") const {
    const fs::path out = dir_ / "out";
    const Result r = run(scene(kBedScene) + " --set insert.0.count=50 --restart " + bad() +
                         " --output-dir " + out.string() + " " + extra_args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(file.empty() ? bad() : file), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in:\n"
                                                        << r.output;
    EXPECT_FALSE(fs::exists(out)) << "output written for a refused restart";
  }

  static fs::path source_dir_;
};

fs::path RefusedRestart::source_dir_;

TEST_F(RefusedRestart, TheValidCheckpointIsAccepted) {
  const Result r = run(scene(kBedScene) + " --quiet --restart " + bad() + " --output-dir " +
                       (dir_ / "out").string() + " --set simulation.end_time=0.0015");
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST_F(RefusedRestart, MissingFile) {
  fs::remove(bad());
  expect_refused("no such checkpoint file");
}

TEST_F(RefusedRestart, NotHdf5) {
  std::ofstream(bad(), std::ios::trunc) << "not a checkpoint\n";
  expect_refused("not a readable HDF5 file");
}

TEST_F(RefusedRestart, OtherFormatVersion) {
  test::set_u32_attribute(bad(), "format_version", 99);
  expect_refused("format version 99");
}

TEST_F(RefusedRestart, MissingDataset) {
  test::remove_dataset(bad(), "torque");
  expect_refused("missing dataset 'torque'");
}

TEST_F(RefusedRestart, InconsistentLengths) {
  test::replace_u32_dataset(bad(), "material", {0, 0});
  expect_refused("dataset 'material' has 2 rows but 'id' has 50");
}

TEST_F(RefusedRestart, MaterialIndexBeyondTheFilesNames) {
  test::replace_u32_dataset(bad(), "material", std::vector<std::uint32_t>(50, 3));
  expect_refused("material index 3 but the file names 1 material");
}

TEST_F(RefusedRestart, ProblemInAnotherRanksPartIsRefusedOnEveryRank) {
  // Two ranks read rows 0-24 and 25-49; only the last particle names a material beyond the
  // scene, so only rank 1 finds it, and rank 0 must report it.
  std::vector<std::uint32_t> materials(50, 0);
  materials.back() = 3;
  test::replace_u32_dataset(bad(), "material", materials);
  const fs::path out = dir_ / "out";
  const Result r =
      test::run_binary_on_ranks(2, scene(kBedScene) + " --set insert.0.count=50 " + "--restart " +
                                       bad() + " --output-dir " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string needle = "has material index 3 but the file names 1 material";
  const std::size_t first = r.output.find(needle);
  EXPECT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(needle, first + 1), std::string::npos) << "reported twice:\n" << r.output;
  EXPECT_NE(r.output.find(bad()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "output written for a refused restart";
}

TEST_F(RefusedRestart, OtherTimeStep) {
  expect_refused("dt = 5e-05 s but the scene gives 1e-04 s", "--set simulation.dt=1e-4",
                 "scene.toml");
}

TEST_F(RefusedRestart, ContactLawKeepingAnotherHistoryWidth) {
  expect_refused("contact history of 4 values per contact, but the scene's contact law keeps 0",
                 "--set 'contact.tangential=\"none\"'");
  fs::remove_all(dir_ / "out");  // in case the first restart was not refused
  expect_refused("contact history of 4 values per contact, but the scene's contact law keeps 7",
                 "--set 'contact.rolling=\"epsd\"'");
}

TEST_F(RefusedRestart, CheckpointAtTheEndTime) {
  expect_refused("nothing to continue", "--set simulation.end_time=0.001", "scene.toml");
}

}  // namespace
}  // namespace gpudem
