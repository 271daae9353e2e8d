#pragma once
/// The clods of the scene's [[bond]] tables (docs/input.md, "[[bond]]"): spheres within which
/// alone a table bonds particles, drawn once where a new run starts.
#include <vector>

#include "core/Config.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// The clod spheres (x, y, z, radius) of every [[bond]] table, none for a table without clods:
/// centres uniform in the table's region, radii from its distribution, none overlapping another
/// of the same table, from std::mt19937_64 seeded by simulation.seed and the table's index, so
/// every rank draws the same. Throws InputError naming bond[k].clods when 1000 draws in a row
/// find no room for the next clod, or its radius distribution cannot be sampled.
std::vector<std::vector<Real4>> draw_clods(const Scene& scene);

}  // namespace gpudem
