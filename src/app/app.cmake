add_executable(gpudem-mpi app/main.cpp app/Runner.cpp app/BedPreparation.cpp app/DomainSetup.cpp
  app/LoadBalance.cpp app/MemoryReport.cpp app/Preview.cpp app/Resume.cpp app/ThreadCores.cpp
  app/TimeLoop.cpp)
target_link_libraries(gpudem-mpi PRIVATE gpudem_sim gpudem_comm CLI11::CLI11)
# The executable sits at the top of the build tree: build/gpudem-mpi.
set_target_properties(gpudem-mpi PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR})
