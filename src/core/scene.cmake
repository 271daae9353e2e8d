add_library(gpudem_scene ${GPUDEM_LIBRARY_TYPE} core/SceneLoader.cpp core/SceneBodies.cpp
            core/SceneSources.cpp core/SceneBonds.cpp core/BondPairs.cpp)
target_link_libraries(gpudem_scene PUBLIC gpudem_contact_model toml11::toml11)
