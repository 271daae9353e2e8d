#pragma once
/// The [[source]] tables of a scene (SceneSources.cpp), read by the scene loader after the
/// domain and materials.
#include <vector>

#include "core/Scene.hpp"
#include "core/TomlReader.hpp"

namespace gpudem::scene_reading {

/// Every [[source]] table of `root`, checked against the scene read so far.
std::vector<ParticleSource> read_sources(const TableReader& root, const Scene& scene);

}  // namespace gpudem::scene_reading
