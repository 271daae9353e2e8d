#pragma once
// The small frictional sand bin the command-line tests run through the binary.
#include <string>

#include "core/ExactDecimal.hpp"

namespace gpudem::test {

/// 300 grains of r = 2.5 ± 0.5 mm in the lower 0.05 m of the bin, as an [[insert]] table.
inline const std::string kSandGrains = R"([[insert]]
region = { min = [0.0, 0.0, 0.0], max = [0.05, 0.05, 0.05] }
count = 300
radius = { mean = 0.0025, spread = 0.0005 }
material = "sand"
)";

/// A 0.05 m × 0.05 m × `height` bin, periodic in x and y, with a floor; sand (ρ = 2500 kg/m³,
/// e = 0.2, μ = 0.8), Hooke k_n = 2000 N/m, dt = 5e-5 s. Lines 1–25 are the same for every
/// bin; `inserts` (the [[insert]] tables) starts at line 26, followed by `sections`.
inline std::string sand_bin_scene(double end_time, double height, const std::string& inserts,
                                  const std::string& sections) {
  return "[simulation]\nend_time = " + exact_decimal(end_time) +
         "\ndt = 5e-5\n\n"
         "[domain]\nmin = [0.0, 0.0, 0.0]\nmax = [0.05, 0.05, " + exact_decimal(height) +
         "]\nperiodic = [true, true, false]\n\n"
         "[[material]]\nname = \"sand\"\ndensity = 2500.0\nyoung = 1e7\npoisson = 0.3\n"
         "restitution = 0.2\nfriction = 0.8\n\n"
         "[contact]\nstiffness = 2000\n\n"
         "[[wall]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nmaterial = \"sand\"\n\n" +
         inserts + "\n" + sections;
}

}  // namespace gpudem::test
