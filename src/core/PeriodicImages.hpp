#pragma once
/// The periodic images of a sphere that a particle placed inside the domain may touch: a sphere
/// crossing a periodic face of the domain (a bed's or a CSV file's particle) also lies, shifted
/// by the domain's length, across the opposite face.
#include <array>
#include <cmath>

#include "core/Scene.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// Calls visit(image) for every image of sphere `p` that reaches into the domain: p shifted by
/// n_k L_k along each periodic axis k (domain length L_k, integer n_k, at most three per axis
/// tried around the shift that brings the centre inside), unshifted along the others.
template <class Visit>
void for_each_image_in_domain(const DomainSettings& domain, const Real4& p, Visit&& visit) {
  std::array<std::array<double, 3>, 3> shifts{};
  std::array<int, 3> counts{1, 1, 1};
  for (int k = 0; k < 3; ++k) {
    shifts[k][0] = 0;
    if (!domain.periodic[k]) continue;
    const double lo = axis(domain.min, k), length = axis(domain.max, k) - lo;
    const double c = axis(xyz(p), k);
    const double inside = -std::floor((c - lo) / length) * length;
    counts[k] = 0;
    for (const double s : {inside - length, inside, inside + length})
      if (c + s + p.w > lo && c + s - p.w < lo + length) shifts[k][counts[k]++] = s;
  }
  for (int i = 0; i < counts[0]; ++i)
    for (int j = 0; j < counts[1]; ++j)
      for (int k = 0; k < counts[2]; ++k)
        visit(Real4{p.x + shifts[0][i], p.y + shifts[1][j], p.z + shifts[2][k], p.w});
}

}  // namespace gpudem
