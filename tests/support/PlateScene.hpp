#pragma once
// The grains-and-plate scenes that the mesh, implement and preview tests run through the binary.
#include <string>

namespace gpudem::test {

/// A domain from (−0.05, 0, 0) to (0.2, 0.1, 0.1) m with sand (ρ = 2500 kg/m³, e = 0.3,
/// μ = 0.5), Hooke k_n = 2000 N/m, dt = 1e-5 s and a floor wall "floor", to `end_time` (the
/// text given): lines 1–24, ending with a blank line, before the caller's tables.
inline std::string plate_scene_head(const std::string& end_time) {
  return "[simulation]\nend_time = " + end_time +
         "\ndt = 1e-5\n\n"
         "[domain]\nmin = [-0.05, 0.0, 0.0]\nmax = [0.2, 0.1, 0.1]\n\n"
         "[[material]]\nname = \"sand\"\ndensity = 2500.0\nyoung = 1e7\nrestitution = 0.3\n"
         "friction = 0.5\n\n"
         "[contact]\nstiffness = 2000\n\n"
         "[[wall]]\nname = \"floor\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n"
         "material = \"sand\"\n\n";
}

/// 40 grains of r = 3 mm on the floor between x = 0.01 and 0.05 m, as an [[insert]] table.
inline const std::string kPlateGrains = R"([[insert]]
region = { min = [0.01, 0.02, 0.0], max = [0.05, 0.08, 0.02] }
count = 40
radius = 0.003
material = "sand"
)";

/// A plate in the plane x = 0 facing +x (two triangles), 0.1 m × 0.1 m around (0, 0.05, 0.05),
/// as ASCII STL, plus `extra` facets.
inline std::string plate_stl(const std::string& extra = "") {
  const auto facet = [](const char* a, const char* b, const char* c) {
    return std::string("facet normal 1 0 0\n outer loop\n  vertex ") + a + "\n  vertex " + b +
           "\n  vertex " + c + "\n endloop\nendfacet\n";
  };
  return "solid plate\n" + facet("0 0 0", "0 0.1 0", "0 0.1 0.1") +
         facet("0 0 0", "0 0.1 0.1", "0 0 0.1") + extra + "endsolid plate\n";
}

}  // namespace gpudem::test
