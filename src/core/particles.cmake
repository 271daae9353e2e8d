add_library(gpudem_particles ${GPUDEM_LIBRARY_TYPE} core/ParticleSources.cpp core/RadiusSampling.cpp
            core/InsertionTiles.cpp core/TiledInsertion.cpp)
target_link_libraries(gpudem_particles PUBLIC gpudem_base)
