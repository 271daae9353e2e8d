// Writes the benchmarks' settled bed (SettledBed.hpp) of 10^4, 10^5 or 10^6 spheres as a
// particle CSV (x, y, z, r, vx, vy, vz) for scenes run through gpudem-mpi, and prints the
// periodic extents of the tiled bed: "lx ly".
//   gpudem-bench-write-bed EXPONENT OUT.csv
#include <cstdio>
#include <stdexcept>
#include <string>

#include "SettledBed.hpp"

int main(int argc, char** argv) {
  using namespace gpudem;
  if (argc != 3) {
    std::fprintf(stderr, "usage: gpudem-bench-write-bed EXPONENT(4..6) OUT.csv\n");
    return 2;
  }
  const int exponent = std::stoi(argv[1]);
  const int tiles[][2] = {{1, 1}, {5, 2}, {10, 10}};
  if (exponent < 4 || exponent > 6) throw std::invalid_argument("EXPONENT must be 4, 5 or 6");
  const int tx = tiles[exponent - 4][0], ty = tiles[exponent - 4][1];
  const ParticleStore bed = tile(settled_seed_bed(), tx, ty);
  std::FILE* out = std::fopen(argv[2], "w");
  if (!out) throw std::runtime_error(std::string("cannot write ") + argv[2]);
  std::fprintf(out, "x,y,z,r,vx,vy,vz\n");
  for (std::size_t i = 0; i < bed.size(); ++i) {
    const Real4 p = bed.position_radius[i], v = bed.velocity_inv_mass[i];
    std::fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", p.x, p.y, p.z, p.w, v.x, v.y,
                 v.z);
  }
  std::fclose(out);
  std::printf("%.17g %.17g\n", kSide * tx, kSide * ty);
  return 0;
}
