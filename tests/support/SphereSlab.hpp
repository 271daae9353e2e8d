#pragma once
// Solid volume of spheres cut by horizontal planes, for packing fractions of slabs.
#include <algorithm>

namespace gpudem::test {

/// Volume of a sphere (centre height z, radius r) between the planes z = a and z = b (a <= b).
inline double sphere_volume_between(double z, double r, double a, double b) {
  constexpr double kPi = 3.14159265358979323846;
  auto below = [&](double plane) {  // volume of the sphere below `plane`: a cap of height h
    const double h = std::clamp(plane - (z - r), 0.0, 2 * r);
    return kPi * h * h * (3 * r - h) / 3;
  };
  return below(b) - below(a);
}

}  // namespace gpudem::test
