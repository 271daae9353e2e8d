// Box insertion at start-up, as a run does it (comm/StartParts.hpp): `count` spheres of radius
// 1 ± 0.5 mm at a solid fraction in a box `aspect` times as long along x as across, cut into
// `layers` stacked sources, placed sequentially (all on every rank, then each keeps its share)
// or by tiles (each rank places its part), on however many ranks this runs, with the OpenMP
// threads OMP_NUM_THREADS gives. Prints one Markdown row: placement, layers, ranks, threads,
// the largest share, the slowest rank's seconds,
// spheres/s over all ranks and the largest peak resident memory of a rank; or why the box
// could not hold the spheres (exit 1).
#include <mpi.h>
#include <sys/resource.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#if defined(GPUDEM_HAVE_OPENMP)
#include <omp.h>
#endif

#include "comm/StartParts.hpp"
#include "core/InputError.hpp"

namespace gpudem {
namespace {

/// Mean volume of a sphere of radius uniform on [0.5, 1.5] mm: (4/3)π E[r³] [m³].
constexpr double kMeanSphereVolume = 5.2360e-9;

/// The box cut into `layers` stacked sources along z (alternately of two materials), each of
/// count / layers spheres.
Scene box_scene(double count, double fraction, double aspect, Placement placement, int layers) {
  const double side = std::cbrt(count * kMeanSphereVolume / fraction / aspect);
  Scene scene;
  scene.file = "<bench>";
  scene.domain.max = {aspect * side, side, side};
  scene.materials.push_back({"subsoil", 2500.0});
  scene.materials.push_back({"topsoil", 1800.0});
  for (int k = 0; k < layers; ++k) {
    ParticleSource source;
    source.region_min = {0, 0, side * k / layers};
    source.region_max = {aspect * side, side, side * (k + 1) / layers};
    source.count = static_cast<std::uint64_t>(count / layers);
    source.radius.mean = 1e-3;
    source.radius.spread = 0.5e-3;
    source.material = static_cast<MaterialId>(k % 2);
    source.placement = placement;
    scene.sources.push_back(source);
  }
  return scene;
}

double peak_resident_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

double max_over_ranks(double x) {
  double all = 0;
  MPI_Allreduce(&x, &all, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return all;
}

}  // namespace
}  // namespace gpudem

int main(int argc, char** argv) {
  using namespace gpudem;
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  double count = 1e6, fraction = 0.3, aspect = 1;
  std::string placement = "tiled";
  int layers = 1;
  bool header = false;
  CLI::App app{"Box insertion at start-up, sequential or tiled, on the ranks this runs on"};
  app.add_option("--count", count, "spheres to insert")->check(CLI::Range(1.0, 4e9));
  app.add_option("--fraction", fraction, "solid fraction of the box")->check(CLI::Range(0.01, 0.4));
  app.add_option("--aspect", aspect, "length along x over the other edges")
      ->check(CLI::Range(1.0, 1e3));
  app.add_option("--placement", placement, "sequential or tiled")
      ->check(CLI::IsMember({"sequential", "tiled"}));
  app.add_option("--layers", layers, "stacked sources the box is cut into along z")
      ->check(CLI::Range(1, 64));
  app.add_flag("--header", header, "print the table's header first");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = rank == 0 ? app.exit(e) : 1;
    MPI_Finalize();
    return code;
  }
  const Scene scene =
      box_scene(count, fraction, aspect,
                placement == "tiled" ? Placement::Tiled : Placement::Sequential, layers);
  int threads = 1;
#if defined(GPUDEM_HAVE_OPENMP)
  threads = omp_get_max_threads();
#endif
  MPI_Barrier(MPI_COMM_WORLD);
  const auto t0 = std::chrono::steady_clock::now();
  ParticleStore share;
  try {
    share = create_start_part(MpiRankGroup(MPI_COMM_WORLD), scene, {});
  } catch (const InputError& e) {  // a region too full (on every rank alike)
    if (rank == 0)
      std::printf("| %s | %d | %d | %d | failed: %s |\n", placement.c_str(), layers, ranks, threads,
                  e.what());
    MPI_Finalize();
    return 1;
  }
  const double seconds =
      max_over_ranks(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const double largest_share = max_over_ranks(static_cast<double>(share.size()));
  const double resident = max_over_ranks(peak_resident_mib());
  if (rank == 0) {
    if (header)
      std::printf(
          "| placement | layers | ranks | threads | largest share | seconds | spheres/s | peak "
          "memory per rank [MiB] |\n|---|---|---|---|---|---|---|---|\n");
    std::printf("| %s | %d | %d | %d | %.0f | %.3f | %.3g | %.0f |\n", placement.c_str(), layers,
                ranks, threads, largest_share, seconds, count / seconds, resident);
  }
  MPI_Finalize();
  return 0;
}
