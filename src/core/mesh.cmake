# Tools: triangle meshes from STL files, their prescribed rigid motion and the loads of the
# implements they form.
add_library(gpudem_mesh ${GPUDEM_LIBRARY_TYPE} core/StlReader.cpp core/PrescribedMotion.cpp
            core/ImplementLoads.cpp core/PreviewGeometry.cpp core/PreviewImage.cpp)
target_link_libraries(gpudem_mesh PUBLIC gpudem_base)
