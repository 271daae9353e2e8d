// The gpudem-mpi binary end to end: bad input exits 2 with a message naming file, line and key
// and writes nothing; a valid scene runs and writes its output; a blow-up exits 3 with the
// offending particle named and its last snapshot written.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/RunBinary.hpp"

namespace {

namespace fs = std::filesystem;

using Result = gpudem::test::RunResult;

Result run(const std::string& args) { return gpudem::test::run_binary(args); }

const char* kValidScene = R"([simulation]
end_time = 0.002
dt = 1e-4

[domain]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.1, 0.1]

[[material]]
name = "sand"
density = 2500.0
young = 1e7
poisson = 0.3
restitution = 0.5

[contact]
stiffness = 1e4

[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "sand"

[[insert]]
region = { min = [0.0, 0.0, 0.0], max = [0.1, 0.1, 0.1] }
count = 50
radius = { mean = 0.004, spread = 0.001 }
material = "sand"

[output]
every = 0.001
)";

class CommandLine : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gpudem_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Writes `text` as the scene and returns its path.
  std::string scene(const std::string& text) const {
    const fs::path p = dir_ / "scene.toml";
    std::ofstream(p) << text;
    return p.string();
  }
  std::string out() const { return (dir_ / "out").string(); }

  /// The scene with `from` replaced by `to` (which must occur).
  static std::string edit(const std::string& from, const std::string& to) {
    std::string s = kValidScene;
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  }

  /// Runs the scene expecting exit 2, `needle` in the message and no output directory.
  void expect_rejected(const std::string& scene_text, const std::string& needle,
                       const std::string& extra_args = "") {
    const Result r = run(scene(scene_text) + " --output-dir " + out() + " " + extra_args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in:\n"
                                                        << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out())) << "output written for rejected input";
  }

  fs::path dir_;
};

TEST_F(CommandLine, ValidSceneRunsAndWritesOutput) {
  const Result r = run(scene(kValidScene) + " --output-dir " + out() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(fs::path(out()) / "particles.xmf"));
  EXPECT_TRUE(fs::exists(fs::path(out()) / "particles_000000.h5"));
  EXPECT_TRUE(fs::exists(fs::path(out()) / "particles_000002.h5"));  // t = 0, 0.001, 0.002
  std::ifstream series(fs::path(out()) / "timeseries.csv");
  std::string header;
  std::getline(series, header);
  EXPECT_EQ(header.rfind("time,step,particles,contacts", 0), 0u) << header;
  EXPECT_NE(header.find("wall0_fz"), std::string::npos) << header;
}

/// The number after `name` on its line of the memory report (bytes per particle), or −1.
double bytes_per_particle(const std::string& output, const std::string& name) {
  const std::size_t at = output.find("\n  " + name + " ");
  if (at == std::string::npos) return -1;
  return std::stod(output.substr(at + 3 + name.size()));
}

/// X from the start-up summary "backend NAME[ (DEVICE)][, 8 contacts at once (AVX-512)], X bytes
/// per particle"; -1 without it.
double summary_bytes_per_particle(const std::string& output) {
  const std::size_t line = output.find("backend ");
  const std::size_t end = output.find(" bytes per particle", line);
  if (line == std::string::npos || end == std::string::npos) return -1;
  return std::stod(output.substr(output.rfind(", ", end) + 2));
}

/// On one rank (no ghosts) each particle array holds its value type per particle: Real4 for
/// position and velocity, Vec3 for spin, force and torque, an id and a material index.
TEST_F(CommandLine, VerboseReportsEachArraysBytesPerParticle) {
  const Result r = run(scene(kValidScene) + " --output-dir " + out() + " --verbose");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(bytes_per_particle(r.output, "position, radius"), 4.0 * sizeof(double));
  EXPECT_EQ(bytes_per_particle(r.output, "velocity, inverse mass"), 4.0 * sizeof(double));
  EXPECT_EQ(bytes_per_particle(r.output, "angular velocity"), 3.0 * sizeof(double));
  EXPECT_EQ(bytes_per_particle(r.output, "id, material"), 8.0 + 4.0);
  EXPECT_EQ(bytes_per_particle(r.output, "force, torque"), 6.0 * sizeof(double));
  EXPECT_EQ(bytes_per_particle(r.output, "position at list build"), 4.0 * sizeof(double));
  const char* const arrays[] = {
      "position, radius",   "velocity, inverse mass", "angular velocity",       "id, material",
      "force, torque",      "overlap ratio",          "position at list build", "neighbour list",
      "pair history",       "wall history",           "walls in reach",         "cell list",
      "history carry-over", "rebuild scratch",        "ghost buffers",          "meshes",
      "contact law"};
  double sum = 0;
  for (const char* name : arrays) {
    const double bytes = bytes_per_particle(r.output, name);
    EXPECT_GE(bytes, 0) << name << " missing from:\n" << r.output;
    sum += bytes;
  }
  const double total = bytes_per_particle(r.output, "total");
  EXPECT_NEAR(sum, total, 0.05 * std::size(arrays)) << r.output;  // lines round to 0.1
  EXPECT_EQ(summary_bytes_per_particle(r.output), total) << r.output;
}

/// Seconds the end-of-run time split gives `part` ("integration", "forces", ...); -1 when the
/// split or the part is missing.
double split_seconds(const std::string& output, const std::string& part) {
  const std::size_t line = output.find("\ntime split (slowest rank): ");
  if (line == std::string::npos) return -1;
  const std::size_t at = output.find(" " + part + " ", line);
  if (at == std::string::npos || at > output.find('\n', line + 1)) return -1;
  return std::stod(output.substr(at + part.size() + 2));
}

/// Integration and forces are clocked apart; with --exact-time-split (which on the host changes
/// nothing but the waits) the run is the same.
TEST_F(CommandLine, TimeSplitClocksIntegrationApartFromForces) {
  for (const char* flag : {"", " --exact-time-split"}) {
    const Result r = run(scene(kValidScene) + " --output-dir " + out() + flag);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* part : {"integration", "forces", "neighbour lists"})
      EXPECT_GT(split_seconds(r.output, part), 0) << part << flag << ":\n" << r.output;
    fs::remove_all(out());
  }
}

/// A rank whose affinity mask holds fewer cores than its OpenMP threads is warned, with the
/// mpirun options that give each thread a core; one with a core per thread is not.
TEST_F(CommandLine, MoreThreadsThanCoresIsWarnedOf) {
#if !defined(GPUDEM_HAVE_OPENMP)
  GTEST_SKIP() << "built without OpenMP";
#endif
  const std::string args = " " + scene(kValidScene) + " --output-dir " + out() + " 2>&1";
  const Result crowded = gpudem::test::run_command("OMP_NUM_THREADS=2 taskset -c 0 " +
                                                   gpudem::test::binary_path() + args);
  ASSERT_EQ(crowded.exit_code, 0) << crowded.output;
  EXPECT_NE(crowded.output.find("warning: 1 of 1 rank(s) run more OpenMP threads than the cores "
                                "they may use (rank 0: 2 threads on 1 core(s))"),
            std::string::npos)
      << crowded.output;
  EXPECT_NE(crowded.output.find("--bind-to none (or --map-by slot:PE=2)"), std::string::npos);
  fs::remove_all(out());
  const Result one = gpudem::test::run_command("OMP_NUM_THREADS=1 taskset -c 0 " +
                                               gpudem::test::binary_path() + args);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_EQ(one.output.find("OpenMP threads than the cores"), std::string::npos) << one.output;
}

/// With OMP_NUM_THREADS unset a lone rank takes every core of its mask, and ranks that share
/// their cores split them: three ranks on one core take one thread each and are told that the
/// node has fewer cores than ranks, and that their MPI waits sleep.
TEST_F(CommandLine, RanksShareTheirCoresWhenNoThreadCountIsSet) {
#if !defined(GPUDEM_HAVE_OPENMP)
  GTEST_SKIP() << "built without OpenMP";
#endif
  const std::string args = scene(kValidScene) + " --output-dir " + out();
  const Result alone =
      gpudem::test::run_command("env -u OMP_NUM_THREADS taskset -c 0,1 " +
                                gpudem::test::binary_path() + " " + args + " 2>&1");
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  EXPECT_NE(alone.output.find("host backend: 2 OpenMP thread(s) on rank 0 (OMP_NUM_THREADS unset"),
            std::string::npos)
      << alone.output;
  EXPECT_EQ(alone.output.find("take turns"), std::string::npos) << alone.output;
  fs::remove_all(out());
  const Result three = gpudem::test::run_command(
      "unset OMP_NUM_THREADS; " + gpudem::test::ranks_command(3, args, "taskset -c 0 "));
  ASSERT_EQ(three.exit_code, 0) << three.output;
  EXPECT_NE(three.output.find("host backend: 1 OpenMP thread(s) on rank 0 (OMP_NUM_THREADS unset"),
            std::string::npos)
      << three.output;
  EXPECT_NE(three.output.find("warning: 3 ranks on one node run 3 OpenMP threads in all on its 1 "
                              "core(s), so they take turns; run at most 1 rank(s) per node"),
            std::string::npos)
      << three.output;
  EXPECT_NE(three.output.find("(mpirun -np 1 on one node); meanwhile a rank that waits for "
                              "another's messages sleeps between its tests"),
            std::string::npos)
      << three.output;
}

/// Without the floor the 50 spheres fall out through the bottom over many time-series rows: one
/// warning at the first removal, then the count in the progress lines (the last says all 50).
TEST_F(CommandLine, ParticlesLeavingTheDomainAreWarnedOfOnceThenCounted) {
  const std::string no_floor = edit(
      "[[wall]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nmaterial = \"sand\"\n", "");
  const Result r = run(scene(no_floor) + " --output-dir " + out() +
                       " --set simulation.end_time=0.2 --set output.timeseries_every=0.005");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string warning = "left the domain and were removed";
  const std::size_t first = r.output.find(warning);
  ASSERT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(warning, first + 1), std::string::npos) << r.output;
  std::ifstream series(fs::path(out()) / "timeseries.csv");
  std::string row;
  std::set<std::string> removed_counts;
  std::getline(series, row);
  while (std::getline(series, row)) {
    std::stringstream fields(row);
    std::string field;
    for (int column = 0; column <= 9; ++column) std::getline(fields, field, ',');
    removed_counts.insert(field);  // column 9: removed
  }
  EXPECT_GT(removed_counts.size(), 3u) << "the removals should span several rows";
  const std::size_t last_progress = r.output.rfind("\nt = ");
  ASSERT_NE(last_progress, std::string::npos) << r.output;
  const std::string line =
      r.output.substr(last_progress + 1, r.output.find('\n', last_progress + 1) - last_progress);
  EXPECT_NE(line.find("  removed 50"), std::string::npos) << line;
  EXPECT_NE(r.output.find("50 particles removed (left the domain)"), std::string::npos) << r.output;
}

TEST_F(CommandLine, VerboseAndQuietExcludeEachOther) {
  const Result r = run(scene(kValidScene) + " --output-dir " + out() + " --verbose --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--quiet excludes --verbose"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CommandLine, CheckValidatesWithoutWriting) {
  const Result r = run(scene(kValidScene) + " --check --output-dir " + out());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("50 particles"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CommandLine, SetOverridesAKey) {
  const Result r =
      run(scene(kValidScene) + " --check --set insert.0.count=20 --output-dir " + out());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("20 particles"), std::string::npos) << r.output;
}

TEST_F(CommandLine, VersionAndHelp) {
  EXPECT_EQ(run("--version").exit_code, 0);
  const Result help = run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("--set"), std::string::npos);
}

TEST_F(CommandLine, MissingFile) {
  const Result r = run((dir_ / "nope.toml").string() + " --output-dir " + out());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("nope.toml"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CommandLine, SyntaxErrorNamesLine) {
  expect_rejected(edit("young = 1e7", "young = = 1e7"), "scene.toml:12");
}

TEST_F(CommandLine, UnknownKeySuggestsNearest) {
  expect_rejected(edit("density = 2500.0", "densty = 2500.0"), "density");
}

TEST_F(CommandLine, WrongType) { expect_rejected(edit("young = 1e7", "young = \"big\""), "young"); }

TEST_F(CommandLine, MissingRequiredKey) {
  expect_rejected(edit("end_time = 0.002", ""), "end_time");
}

TEST_F(CommandLine, NegativeRadius) {
  expect_rejected(edit("mean = 0.004, spread = 0.001", "mean = -0.004, spread = 0.001"), "radius");
}

TEST_F(CommandLine, ZeroRadius) {
  expect_rejected(edit("{ mean = 0.004, spread = 0.001 }", "0.0"), "radius");
}

TEST_F(CommandLine, PoissonOutOfRange) {
  expect_rejected(edit("poisson = 0.3", "poisson = 0.5"), "poisson");
}

TEST_F(CommandLine, RestitutionOutOfRange) {
  expect_rejected(edit("restitution = 0.5", "restitution = 0.0"), "restitution");
  expect_rejected(edit("restitution = 0.5", "restitution = 1.5"), "restitution");
}

TEST_F(CommandLine, NonPositiveDensity) {
  expect_rejected(edit("density = 2500.0", "density = 0.0"), "density");
}

TEST_F(CommandLine, EmptyDomain) {
  expect_rejected(edit("max = [0.1, 0.1, 0.1]", "max = [0.1, 0.0, 0.1]"), "domain");
}

TEST_F(CommandLine, SourceOutsideDomain) {
  expect_rejected(edit("max = [0.1, 0.1, 0.1] }", "max = [0.1, 0.1, 0.3] }"), "insert[0]");
}

TEST_F(CommandLine, CsvRowThatDoesNotParseNamesItsLine) {
  std::ofstream(dir_ / "bed.csv") << "x,y,z,r\n0.05,0.05,0.05,0.004\n0.02,0.02,zero,0.004\n";
  const std::string insert = "[[insert]]\ncsv = \"bed.csv\"\nmaterial = \"sand\"\n\n[output]";
  std::string s = kValidScene;
  s = s.substr(0, s.find("[[insert]]")) + insert + s.substr(s.find("[output]") + 8);
  expect_rejected(s, "bed.csv:3");
}

TEST_F(CommandLine, OutputDirectoryThatCannotBeCreated) {
  std::ofstream(dir_ / "blocker") << "a file where a directory should go";
  const Result r = run(scene(kValidScene) + " --output-dir " + (dir_ / "blocker" / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("output.dir"), std::string::npos) << r.output;
}

TEST_F(CommandLine, BadOptionValue) {
  expect_rejected(kValidScene, "--backend", "--backend quantum");
  expect_rejected(kValidScene, "--set", "--set simulation.end_time");
}

/// The values of dataset `name` of an HDF5 file, in file order (h5dump).
std::vector<double> dataset_values(const fs::path& file, const std::string& name) {
  const Result r = gpudem::test::run_command(
      "h5dump -d " + name + " -y -w 0 -m %.17g -o /dev/stdout -O /dev/null " + file.string());
  std::vector<double> values;
  std::stringstream text(r.output);
  std::string field;
  while (std::getline(text, field, ','))
    if (field.find_first_of("0123456789") != std::string::npos) values.push_back(std::stod(field));
  return values;
}

/// A CSV source's wx, wy, wz columns give the spin: an alumina sphere (r = 10 mm, μ = 0.3,
/// e = 0.5) spinning at 500 rad/s about y meets the floor at 1 m/s and slides throughout
/// (ω r > 3.5 μ (1 + e) v): it leaves with v_x = μ (1 + e) v and ω = 500 − 2.5 μ (1 + e) v / r
/// rad/s (Maw, Barber & Fawcett 1976), within 2 % of the change.
TEST_F(CommandLine, SpinColumnsOfACsvSourceSetTheSpin) {
  std::ofstream(dir_ / "spinning.csv") << "x,y,z,r,vz,wy\n0.05,0.05,0.0101,0.01,-1,500\n";
  const std::string scene_text = R"([simulation]
end_time = 4e-4
gravity = [0.0, 0.0, 0.0]

[domain]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.1, 0.1]

[[material]]
name = "alumina"
density = 4000.0
young = 3.8e11
poisson = 0.23
restitution = 0.5
friction = 0.3

[contact]
normal = "hertz"
damping = "restitution"
tangential = "mindlin"

[[wall]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "alumina"

[[insert]]
csv = "spinning.csv"

[output]
every = 4e-4
)";
  const Result r = run(scene(scene_text) + " --output-dir " + out());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path last = fs::path(out()) / "particles_000001.h5";
  const std::vector<double> v = dataset_values(last, "velocity");
  const std::vector<double> w = dataset_values(last, "angular_velocity");
  ASSERT_EQ(v.size(), 3u) << r.output;
  ASSERT_EQ(w.size(), 3u);
  const double slide = 0.3 * 1.5 * 1.0, spin_change = 2.5 * slide / 0.01;
  EXPECT_NEAR(v[0], slide, 0.02 * slide);
  EXPECT_NEAR(w[1], 500 - spin_change, 0.02 * spin_change);
  EXPECT_GT(v[2], 0);  // rebounding
}

TEST_F(CommandLine, UnstableRunStopsNamingTheParticle) {
  // Two particles placed 60 % of a radius into each other: the health check stops at step 1.
  std::ofstream(dir_ / "pair.csv") << "x,y,z,r\n0.05,0.05,0.05,0.01\n0.062,0.05,0.05,0.01\n";
  std::string s = kValidScene;
  s = s.substr(0, s.find("[[insert]]")) + "[[insert]]\ncsv = \"pair.csv\"\n\n[output]" +
      s.substr(s.find("[output]") + 8);
  const Result r = run(scene(s) + " --output-dir " + out());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("step 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle id"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(fs::path(out()) / "particles_000001.h5")) << r.output;
}

}  // namespace
