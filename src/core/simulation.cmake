add_library(gpudem_sim STATIC core/SceneSetup.cpp)
target_link_libraries(gpudem_sim PUBLIC gpudem_scene gpudem_particles gpudem_kernels)
