#pragma once
/// The radius distributions of box sources (docs/input.md, "[[insert]]"): sampling and bounds.
#include <random>
#include <string>
#include <vector>

#include "core/Scene.hpp"

namespace gpudem {

/// Why `dist` cannot be sampled (no value of positive weight, or bounds holding less than 1e-6 of
/// the normal's probability), or empty when it can.
std::string sampling_problem(const RadiusDistribution& dist);

/// Draws `count` radii from `dist` [m]: uniform on [mean - spread, mean + spread]; normal
/// (mean, stddev) redrawn until within [min, max]; or values[k] with probability
/// weights[k] / sum(weights) (equal weights when none are given). Throws
/// std::invalid_argument for a distribution that cannot be sampled (sampling_problem).
std::vector<double> sample_radii(const RadiusDistribution& dist, std::size_t count,
                                 std::mt19937_64& rng);

/// Smallest and largest radius `dist` can produce [m].
double min_radius(const RadiusDistribution& dist);
double max_radius(const RadiusDistribution& dist);

}  // namespace gpudem
