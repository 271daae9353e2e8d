// How the programs start MPI (comm/MpiInit.hpp): a file opens for parallel I/O even when a job
// killed while opening a file of the same base name has left Open MPI's node-wide semaphore of
// that name taken (/dev/shm/sem.OMPIO_<name>), as a checkpoint cut short by kill -9 leaves it.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <mpi.h>
#include <semaphore.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace gpudem {
namespace {

namespace fs = std::filesystem;

TEST(MpiInit, AFileOpensWhileAKilledJobHoldsTheSemaphoreOfItsName) {
  const std::string base = "gpudem-taken-" + std::to_string(::getpid()) + ".h5";
  const std::string semaphore = "/OMPIO_" + base;
  sem_t* taken = sem_open(semaphore.c_str(), O_CREAT | O_EXCL, 0600, 0);  // held, never posted
  ASSERT_NE(taken, SEM_FAILED);
  const std::string path = (fs::temp_directory_path() / base).string();
  MPI_File file;
  EXPECT_EQ(MPI_File_open(MPI_COMM_SELF, path.c_str(), MPI_MODE_CREATE | MPI_MODE_RDWR,
                          MPI_INFO_NULL, &file),
            MPI_SUCCESS);  // without init_mpi's setting this waits forever (the test's timeout)
  MPI_File_close(&file);
  sem_close(taken);
  sem_unlink(semaphore.c_str());
  fs::remove(path);
}

}  // namespace
}  // namespace gpudem
