# Tools: triangle meshes from STL files and their prescribed rigid motion.
add_library(gpudem_mesh ${GPUDEM_LIBRARY_TYPE} core/StlReader.cpp core/PrescribedMotion.cpp)
target_link_libraries(gpudem_mesh PUBLIC gpudem_base)
