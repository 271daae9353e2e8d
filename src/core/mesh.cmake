add_library(gpudem_mesh STATIC core/StlReader.cpp)
target_link_libraries(gpudem_mesh PUBLIC gpudem_base)
