#include "comm/SnapshotQueue.hpp"

#include <stdexcept>
#include <utility>

#include "core/Stopwatch.hpp"

namespace gpudem {
namespace {

MPI_Comm duplicate(MPI_Comm comm) {
  MPI_Comm copy = MPI_COMM_NULL;
  MPI_Comm_dup(comm, &copy);
  return copy;
}

/// Throws std::runtime_error unless the particles of all ranks of `comm` add up to `expected`.
void check_conserved(MPI_Comm comm, const ParticleStore& particles, const ParticleTally& expected) {
  std::uint64_t local[2] = {particles.size(), id_checksum(particles.id.data(), particles.size())};
  std::uint64_t total[2] = {0, 0};
  MPI_Allreduce(local, total, 2, MPI_UINT64_T, MPI_SUM, comm);  // wraps modulo 2^64
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const std::string problem = conservation_problem({total[0], total[1]}, expected, ranks);
  if (!problem.empty()) throw std::runtime_error(problem);
}

}  // namespace

bool mpi_thread_multiple() {
  int level = MPI_THREAD_SINGLE;
  MPI_Query_thread(&level);
  return level == MPI_THREAD_MULTIPLE;
}

SnapshotQueue::SnapshotQueue(MPI_Comm comm, std::string dir, SnapshotOptions options,
                             bool asynchronous)
    : comm_(duplicate(comm)), writer_(comm_, std::move(dir), std::move(options)) {
  if (asynchronous && mpi_thread_multiple()) thread_ = std::thread([this] { run_writer_thread(); });
}

SnapshotQueue::~SnapshotQueue() {
  if (thread_.joinable()) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return !pending_; });
      stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }
  MPI_Comm_free(&comm_);
}

void SnapshotQueue::write(SnapshotSource& source, double time, std::uint64_t step) {
  wait();  // the staging buffer is free again
  Job job{&source.stage_particles(), source.mesh_surfaces(),
          writer_.writes_bonds() ? source.bond_lines() : BondLines{}, time, step};
  if (!asynchronous()) return write_now(job);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = std::move(job);
  }
  changed_.notify_all();
}

void SnapshotQueue::wait() {
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return !pending_; });
    std::swap(error, error_);
  }
  if (error) std::rethrow_exception(error);
}

void SnapshotQueue::run_writer_thread() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    changed_.wait(lock, [this] { return pending_ || stopping_; });
    if (!pending_) return;
    lock.unlock();
    std::exception_ptr error;
    try {
      write_now(*pending_);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    error_ = error;
    pending_.reset();
    changed_.notify_all();
  }
}

void SnapshotQueue::write_now(const Job& job) {
  Stopwatch watch;
  job.particles->collect(particles_);
  check_conserved(comm_, particles_, job.particles->expected_tally);
  writer_.write(particles_, job.meshes, job.bonds, job.time, job.step);
  write_seconds_ += watch.lap();
}

}  // namespace gpudem
