#pragma once
/// Asynchronous snapshot output: a writer thread collects the particles an engine staged
/// (SnapshotSource, StepEngine.hpp), checks that no particle was lost or duplicated between
/// ranks and writes them through a SnapshotWriter, while the time loop steps on. The writer
/// thread talks MPI on a duplicate of the run's communicator, which needs the thread level
/// MPI_THREAD_MULTIPLE; without it, or when asked, the queue writes in write() itself. The files
/// are the same either way. One write is in flight at a time, so a write first waits for the one
/// before it.
#include <mpi.h>

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "comm/SnapshotWriter.hpp"

namespace gpudem {

/// True when MPI runs at the thread level MPI_THREAD_MULTIPLE, which a writer thread needs.
bool mpi_thread_multiple();

class SnapshotQueue {
 public:
  /// A SnapshotWriter (same arguments) on a duplicate of `comm`, written on a thread of its own
  /// when `asynchronous` and mpi_thread_multiple(). Collective.
  SnapshotQueue(MPI_Comm comm, std::string dir, SnapshotOptions options, bool asynchronous);
  /// Waits for the write in flight (dropping its error: call wait() first to see it) and frees
  /// the duplicate communicator. Collective.
  ~SnapshotQueue();
  SnapshotQueue(const SnapshotQueue&) = delete;
  SnapshotQueue& operator=(const SnapshotQueue&) = delete;

  /// Waits for the write before (rethrowing its error), stages the particles of `source` and
  /// takes its mesh surfaces, then writes them as the snapshot at `time` and `step`: collects
  /// the particles, checks them against their expected tally over all ranks (std::runtime_error
  /// saying what differs) and writes them with the meshes. With a writer thread it returns
  /// once the write is queued; `source` must outlive the write. Collective.
  void write(SnapshotSource& source, double time, std::uint64_t step);
  /// Waits until the last write is done; rethrows its error (once). Collective when a write is
  /// in flight.
  void wait();

  /// The writer, for its table and paths; wait() first so they include the last write.
  const SnapshotWriter& writer() const { return writer_; }
  /// SnapshotWriter::resume, before any write. Collective.
  void resume(const std::vector<XdmfSnapshot>& table) { writer_.resume(table); }
  bool asynchronous() const { return thread_.joinable(); }
  /// Time spent collecting, checking and writing snapshots, on whichever thread [s]; wait()
  /// first so it includes the last write.
  double write_seconds() const { return write_seconds_; }

 private:
  /// One snapshot to write: the particles staged at its step, the meshes, its time and step.
  struct Job {
    StagedParticles* particles = nullptr;
    std::vector<MeshSurface> meshes;
    BondLines bonds;
    double time = 0;
    std::uint64_t step = 0;
  };

  void run_writer_thread();
  /// Collects, checks and writes `job` on the calling thread; adds its time to write_seconds_.
  void write_now(const Job& job);

  MPI_Comm comm_;  ///< the duplicate the writer uses
  SnapshotWriter writer_;
  ParticleStore particles_;  ///< the collected particles of the write in flight
  std::thread thread_;       ///< the writer thread; not joinable when writing synchronously
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<Job> pending_;  ///< handed to the writer thread, not yet done
  bool stopping_ = false;
  std::exception_ptr error_;  ///< of the last write, until wait() rethrows it
  double write_seconds_ = 0;
};

}  // namespace gpudem
