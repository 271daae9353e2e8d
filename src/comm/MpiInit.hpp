#pragma once
/// How every program of the project starts MPI.
#include <mpi.h>

#include <cstdlib>

namespace gpudem {

/// MPI_Init_thread at MPI_THREAD_MULTIPLE (snapshots are written on a thread of their own),
/// after keeping Open MPI's parallel I/O from its "sm" shared-file-pointer component. That
/// component guards each file open with a POSIX semaphore named after the file's base name
/// (/dev/shm/sem.OMPIO_<name>), shared by every job on the node: a job killed while it opens a
/// file (a checkpoint cut short by kill -9 or a time limit) leaves the semaphore taken, and
/// every later open of a file of that name on that node, checkpoint.h5.tmp say, then waits
/// forever. HDF5 uses no shared file pointer, so nothing is lost; a value the user has set for
/// OMPI_MCA_sharedfp is kept.
inline void init_mpi(int& argc, char**& argv) {
  ::setenv("OMPI_MCA_sharedfp", "^sm", /*overwrite=*/0);
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
}

}  // namespace gpudem
