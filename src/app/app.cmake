add_executable(gpudem-mpi app/main.cpp app/Runner.cpp)
target_link_libraries(gpudem-mpi PRIVATE gpudem_sim gpudem_comm CLI11::CLI11)
