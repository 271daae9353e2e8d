add_library(gpudem_comm ${GPUDEM_LIBRARY_TYPE}
  comm/CheckpointFit.cpp comm/CheckpointRead.cpp comm/CheckpointWrite.cpp
  comm/Hdf5Io.cpp
  comm/MpiContext.cpp
  comm/GpuAwareMpi.cpp
  comm/MpiDomain.cpp
  comm/MpiRankGroup.cpp
  comm/MpiWait.cpp
  comm/OutputDirectory.cpp
  comm/SnapshotQueue.cpp
  comm/SnapshotWriter.cpp
  comm/StartParts.cpp
  comm/TiledParts.cpp
  comm/TimeSeriesWriter.cpp)
target_include_directories(gpudem_comm PUBLIC ${HDF5_INCLUDE_DIRS})
target_compile_definitions(gpudem_comm PUBLIC ${HDF5_DEFINITIONS})
target_link_libraries(gpudem_comm PUBLIC gpudem_base gpudem_decomposition gpudem_particles
                      MPI::MPI_CXX
                      ${HDF5_C_LIBRARIES})
