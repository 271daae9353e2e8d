// Box insertion speed: random sequential insertion of `count` spheres of radius 1 ± 0.5 mm in a
// cube at a solid fraction, placed sequentially and by tiles at each thread count, and the tiled
// part of one rank of P (its own share of the tiles and the margin it recomputes). Prints a
// Markdown table: seconds, spheres/s and the spheres held.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#if defined(GPUDEM_HAVE_OPENMP)
#include <omp.h>
#endif

#include "core/ParticleSources.hpp"

namespace gpudem {
namespace {

/// Mean volume of a sphere of radius uniform on [0.5, 1.5] mm: (4/3)π E[r³] [m³].
constexpr double kMeanSphereVolume = 5.2360e-9;

Scene cube_scene(double count, double fraction, Placement placement) {
  const double side = std::cbrt(count * kMeanSphereVolume / fraction);
  Scene scene;
  scene.file = "<bench>";
  scene.domain.max = {side, side, side};
  scene.materials.push_back({"grain", 2500.0});
  ParticleSource source;
  source.region_max = scene.domain.max;
  source.count = static_cast<std::uint64_t>(count);
  source.radius.mean = 1e-3;
  source.radius.spread = 0.5e-3;
  source.placement = placement;
  scene.sources.push_back(source);
  return scene;
}

void set_threads(int threads) {
#if defined(GPUDEM_HAVE_OPENMP)
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
}

template <class Create>
void time_row(const char* what, int threads, const Create& create) {
  set_threads(threads);
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t spheres = create();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("| %s | %d | %zu | %.3f | %.3g |\n", what, threads, spheres, s, spheres / s);
  std::fflush(stdout);
}

}  // namespace
}  // namespace gpudem

int main(int argc, char** argv) {
  using namespace gpudem;
  double count = 1e6, fraction = 0.3;
  std::vector<int> threads{1, 2}, parts{4, 16};
  bool sequential = true;
  CLI::App app{"Box insertion speed, sequential and tiled"};
  app.add_option("--count", count, "spheres to insert")->check(CLI::Range(1.0, 4e9));
  app.add_option("--fraction", fraction, "solid fraction of the cube")->check(CLI::Range(0.01, 0.4));
  app.add_option("--threads", threads, "OpenMP thread counts");
  app.add_option("--parts", parts, "rank counts whose middle part is timed (tiled)");
  app.add_flag("!--no-sequential", sequential, "skip the sequential placement");
  CLI11_PARSE(app, argc, argv);
  std::printf("%.3g spheres of radius 1 ± 0.5 mm in a cube at a solid fraction of %.2f\n\n", count,
              fraction);
  std::printf("| placement | threads | spheres held | seconds | spheres/s |\n|---|---|---|---|---|\n");
  for (const int t : threads) {
    if (sequential)
      time_row("sequential", t, [&] {
        ParticleStore store;
        create_particles(cube_scene(count, fraction, Placement::Sequential), store);
        return store.size();
      });
    time_row("tiled", t, [&] {
      ParticleStore store;
      create_particles(cube_scene(count, fraction, Placement::Tiled), store);
      return store.size();
    });
    for (const int p : parts) {
      char what[48];
      std::snprintf(what, sizeof what, "tiled, part %d of %d", p / 2, p);
      time_row(what, t, [&] {
        return create_particle_part(cube_scene(count, fraction, Placement::Tiled),
                                    FilePart{p / 2, p})
            .size();
      });
    }
  }
  return 0;
}
