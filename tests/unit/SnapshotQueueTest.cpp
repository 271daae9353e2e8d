// Snapshots written through the queue: on the writer thread write() returns while the particles
// are still being collected; the files of asynchronous and synchronous queues hold the staged
// particles bit for bit, at any rank count; a tally that does not add up over the ranks fails
// the write with a message saying what differs, which reaches the time loop at wait() (or at
// write() itself when writing synchronously), once.
#include <gtest/gtest.h>
#include <mpi.h>

#include <chrono>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "comm/SnapshotQueue.hpp"
#include "support/MpiRank.hpp"
#include "support/SharedTempDir.hpp"
#include "support/SnapshotReadBack.hpp"

namespace gpudem {
namespace {

using test::comm_rank;
using test::expect_snapshot_holds;

/// A copy of a particle store whose collect() can be held back until release() (for at most
/// two seconds, after which it records that it timed out and goes on).
class HeldStaging final : public StagedParticles {
 public:
  void collect(ParticleStore& particles) override {
    std::unique_lock<std::mutex> lock(mutex_);
    if (held_ && !released_.wait_for(lock, std::chrono::seconds(2), [this] { return !held_; }))
      timed_out_ = true;
    particles = copy;
  }
  void hold() { held_ = true; }
  void release() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      held_ = false;
    }
    released_.notify_all();
  }
  bool timed_out() {
    std::lock_guard<std::mutex> lock(mutex_);
    return timed_out_;
  }

  ParticleStore copy;

 private:
  std::mutex mutex_;
  std::condition_variable released_;
  bool held_ = false;
  bool timed_out_ = false;
};

/// A stand-in for an engine: stages a copy of `state` with its tally over all ranks, shifted
/// by `tally_error` to fake a lost or duplicated particle.
class FakeSource final : public SnapshotSource {
 public:
  StagedParticles& stage_particles() override {
    staging.copy = state;
    std::uint64_t local[2] = {state.size(), id_checksum(state.id.data(), state.size())};
    std::uint64_t total[2] = {0, 0};
    MPI_Allreduce(local, total, 2, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    staging.expected_tally = {total[0] + tally_error.count, total[1] + tally_error.id_sum};
    return staging;
  }
  std::vector<MeshSurface> mesh_surfaces() const override { return {}; }
  BondLines bond_lines() const override { return {}; }

  ParticleStore state;
  ParticleTally tally_error;
  HeldStaging staging;
};

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class SnapshotQueueTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!mpi_thread_multiple()) GTEST_SKIP() << "MPI offers no MPI_THREAD_MULTIPLE";
    dir_ = test::make_shared_temp_dir("gpudem_snapshot_queue_");
  }
  void TearDown() override {
    if (!dir_.empty()) test::remove_shared_temp_dir(dir_);
  }
  std::string subdir(const std::string& name) {
    const std::string path = dir_ + "/" + name;
    if (comm_rank() == 0) std::filesystem::create_directories(path);
    MPI_Barrier(MPI_COMM_WORLD);
    return path;
  }

  std::string dir_;
};

TEST_F(SnapshotQueueTest, WriterThreadWritesWhileTheCallerGoesOn) {
  SnapshotQueue queue(MPI_COMM_WORLD, subdir("async"), {}, true);
  ASSERT_TRUE(queue.asynchronous());
  FakeSource source;
  source.state = test::random_store(50 + 7 * comm_rank(), 11 + comm_rank());
  const ParticleStore staged = source.state;
  source.staging.hold();
  queue.write(source, 0.25, 40);  // a synchronous write would wait here for the release
  source.state = test::random_store(9, 99 + comm_rank());  // the engine steps on
  source.staging.release();
  queue.wait();
  EXPECT_FALSE(source.staging.timed_out()) << "write() waited for the particles to be collected";
  ASSERT_EQ(queue.writer().files().size(), 1u);
  expect_snapshot_holds(queue.writer().files()[0], staged, 0.25, 40);
}

TEST_F(SnapshotQueueTest, SynchronousQueueCollectsInsideWrite) {
  SnapshotQueue queue(MPI_COMM_WORLD, subdir("sync"), {}, false);
  EXPECT_FALSE(queue.asynchronous());
  FakeSource source;
  source.state = test::random_store(5, 3 + comm_rank());
  source.staging.hold();
  queue.write(source, 0, 0);
  EXPECT_TRUE(source.staging.timed_out());
}

TEST_F(SnapshotQueueTest, AsynchronousAndSynchronousSeriesAreTheSame) {
  const std::string async_dir = subdir("async"), sync_dir = subdir("sync");
  SnapshotQueue async_queue(MPI_COMM_WORLD, async_dir, {}, true);
  SnapshotQueue sync_queue(MPI_COMM_WORLD, sync_dir, {}, false);
  FakeSource source;
  std::vector<ParticleStore> states;
  for (int k = 0; k < 3; ++k) {
    source.state = test::random_store(comm_rank() == 1 ? 0 : 30 + k, 100 * k + comm_rank());
    states.push_back(source.state);
    async_queue.write(source, 0.5 * k, 10 * k);
    async_queue.wait();  // the source's single staging buffer is free again
    sync_queue.write(source, 0.5 * k, 10 * k);
  }
  ASSERT_EQ(async_queue.writer().files().size(), 3u);
  ASSERT_EQ(sync_queue.writer().files().size(), 3u);
  for (int k = 0; k < 3; ++k) {
    expect_snapshot_holds(async_queue.writer().files()[k], states[k], 0.5 * k, 10 * k);
    expect_snapshot_holds(sync_queue.writer().files()[k], states[k], 0.5 * k, 10 * k);
  }
  EXPECT_EQ(read_text(async_queue.writer().xmf_path()), read_text(sync_queue.writer().xmf_path()));
}

/// What wait() throws, or "" when it returns.
std::string wait_error(SnapshotQueue& queue) {
  try {
    queue.wait();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return {};
}

TEST_F(SnapshotQueueTest, LostParticleFailsTheWriteOnceAtWait) {
  SnapshotQueue queue(MPI_COMM_WORLD, subdir("lost"), {}, true);
  FakeSource source;
  source.state = test::random_store(20, 5 + comm_rank());
  source.tally_error = {1, 0};
  queue.write(source, 0, 0);
  const std::string error = wait_error(queue);
  EXPECT_NE(error.find("particles were lost or duplicated between ranks"), std::string::npos)
      << error;
  EXPECT_EQ(error.find("ids differ"), std::string::npos) << error;
  EXPECT_TRUE(queue.writer().files().empty());
  EXPECT_EQ(wait_error(queue), "");
}

TEST_F(SnapshotQueueTest, ForeignIdFailsTheWriteNamingTheIds) {
  SnapshotQueue queue(MPI_COMM_WORLD, subdir("foreign"), {}, false);
  FakeSource source;
  source.state = test::random_store(20, 5 + comm_rank());
  source.tally_error = {0, 12345};
  try {
    queue.write(source, 0, 0);
    ADD_FAILURE() << "a tally with other ids was written";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("their ids differ from the expected set"),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(queue.writer().files().empty());
}

}  // namespace
}  // namespace gpudem
