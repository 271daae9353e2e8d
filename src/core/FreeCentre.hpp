#pragma once
/// The draws of random sequential insertion (Widom 1966; Feder 1980): uniform deviates and a
/// free centre for one sphere, shared by the sequential and the tiled placement of box sources.
#include <cstdint>
#include <optional>
#include <random>

#include "core/SphereHash.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// Random centres tried for one sphere before its box counts as full.
inline constexpr int kMaxAttemptsPerSphere = 1000;

/// Uniform on [0, 1) from the top 53 bits (identical on every standard library).
inline double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// A centre c with c_k = first_k + width_k u_k, u_k uniform on [0, 1), at which a sphere of
/// radius r overlaps no sphere of `hash`; none after kMaxAttemptsPerSphere overlapping tries
/// or when a width is negative (no centre fits).
inline std::optional<Vec3> free_centre(Vec3 first, Vec3 width, double r, const SphereHash& hash,
                                       std::mt19937_64& rng) {
  for (int k = 0; k < 3; ++k)
    if (axis(width, k) < 0) return std::nullopt;
  for (int attempt = 0; attempt < kMaxAttemptsPerSphere; ++attempt) {
    Vec3 c;
    for (int k = 0; k < 3; ++k) axis(c, k) = axis(first, k) + axis(width, k) * uniform01(rng);
    if (!hash.overlaps(c, r)) return c;
  }
  return std::nullopt;
}

}  // namespace gpudem
