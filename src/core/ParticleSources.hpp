#pragma once
/// Particle creation from the scene's [[insert]] sources: random non-overlapping insertion in a
/// box (by count or by volume fraction) with a radius distribution, or CSV import.
#include <cstdint>
#include <random>
#include <vector>

#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"

namespace gpudem {

/// Creates the particles of every source, in scene order, appending to `store` with
/// consecutive global ids starting at store.size(). New particles never overlap each other or
/// those already present. Throws InputError (file, line, key) for unreadable CSV files, bad
/// rows, or a region that cannot hold the requested particles.
void create_particles(const Scene& scene, ParticleStore& store);

/// Draws `count` radii from `dist` [m]; all are > 0.
std::vector<double> sample_radii(const RadiusDistribution& dist, std::size_t count,
                                 std::mt19937_64& rng);

/// Smallest and largest radius `dist` can produce [m].
double min_radius(const RadiusDistribution& dist);
double max_radius(const RadiusDistribution& dist);

}  // namespace gpudem
