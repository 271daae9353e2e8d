# Domain decomposition geometry: coarse cells, the cell -> rank map, grid cuts, METIS parts.
add_library(gpudem_decomposition ${GPUDEM_LIBRARY_TYPE} comm/Decomposition.cpp comm/GridCuts.cpp)
target_link_libraries(gpudem_decomposition PUBLIC gpudem_engine METIS::METIS)
