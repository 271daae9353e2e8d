// Writes the benchmarks' settled bed (SettledBed.hpp) of 10^4, 10^5 or 10^6 spheres as a
// particle CSV (x, y, z, r, vx, vy, vz) for scenes run through gpudem-mpi, and prints the
// periodic extents of the tiled bed: "lx ly". With TX and TY instead of an exponent, the
// 10^4 seed bed tiled TX times along x and TY along y (weak-scaling beds).
//   gpudem-bench-write-bed EXPONENT OUT.csv
//   gpudem-bench-write-bed TX TY OUT.csv
#include <cstdio>
#include <stdexcept>
#include <string>

#include "SettledBed.hpp"

int main(int argc, char** argv) {
  using namespace gpudem;
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr,
                 "usage: gpudem-bench-write-bed EXPONENT(4..6) OUT.csv\n"
                 "       gpudem-bench-write-bed TX TY OUT.csv\n");
    return 2;
  }
  int tx = 0, ty = 0;
  if (argc == 4) {
    tx = std::stoi(argv[1]);
    ty = std::stoi(argv[2]);
    if (tx < 1 || ty < 1) throw std::invalid_argument("TX and TY must be positive");
  } else {
    const int exponent = std::stoi(argv[1]);
    const int tiles[][2] = {{1, 1}, {5, 2}, {10, 10}};
    if (exponent < 4 || exponent > 6) throw std::invalid_argument("EXPONENT must be 4, 5 or 6");
    tx = tiles[exponent - 4][0];
    ty = tiles[exponent - 4][1];
  }
  const char* path = argv[argc - 1];
  const ParticleStore bed = tile(settled_seed_bed(), tx, ty);
  std::FILE* out = std::fopen(path, "w");
  if (!out) throw std::runtime_error(std::string("cannot write ") + path);
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
