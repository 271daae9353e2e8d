add_library(gpudem_sim ${GPUDEM_LIBRARY_TYPE} engine/SceneSetup.cpp engine/TimeStepLimits.cpp engine/MeshReach.cpp
  engine/BondClods.cpp
  engine/MeshStartOverlap.cpp)
target_link_libraries(gpudem_sim PUBLIC gpudem_scene gpudem_particles gpudem_engine)
