add_executable(gpudem-mpi app/main.cpp)
target_link_libraries(gpudem-mpi PRIVATE gpudem_sim CLI11::CLI11)
