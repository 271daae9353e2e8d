// Host-backend throughput on settled beds: settles a periodic bed of 10^4 spheres, tiles it
// in x and y to 10^4, 10^5 and 10^6 particles, and times the step loop at 1 and 2 OpenMP
// threads in double and in mixed precision. Prints a Markdown table (particle-steps/s, bytes
// per particle, and for mixed the largest force error against double over the largest force),
// then the largest bed's bytes per particle by array in each precision.
// With a second argument, also writes the 10^5 bed for LAMMPS (scripts/bench_vs_lammps.sh).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "SettledBed.hpp"

namespace gpudem {
namespace {

const char* precision_name(Precision precision) {
  switch (precision) {
    case Precision::Double:
      return "double";
    case Precision::Mixed:
      return "mixed";
    case Precision::Float:
      return "float";
  }
  return "?";
}

/// Times one bed at one thread count and precision, prints its row and returns the engine's
/// memory by array after the timed steps.
std::vector<MemoryUse> measure(const ParticleStore& bed, int tx, int ty, int threads,
                               Precision precision) {
  set_threads(threads);
  const Scene scene = bed_scene(kSide * tx, kSide * ty);
  EngineSetup setup = make_engine_setup(scene, bed);
  setup.precision = precision;
  auto engine = make_host_engine(setup);
  engine->set_particles(bed);
  std::string error = "–";
  if (precision != Precision::Double) {
    setup.precision = Precision::Double;
    auto exact = make_host_engine(setup);
    exact->set_particles(bed);
    char text[32];
    std::snprintf(text, sizeof text, "%.2g", force_error(*engine, *exact));
    error = text;
  }
  const int steps = std::max(20, static_cast<int>(3e7 / bed.size()));
  for (int n = 0; n < 5; ++n) engine->step();
  const std::uint64_t rebuilds0 = engine->rebuild_count();
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < steps; ++n) engine->step();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto t1 = std::chrono::steady_clock::now();
  engine->rebuild_neighbors();  // sort by cell, list, history carry-over, forces
  const double rebuild =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  std::printf("| %zu | %s | %d | %d | %.3g | %.1f | %llu | %.3g | %s |\n", bed.size(),
              precision_name(precision), threads, steps, steps * double(bed.size()) / seconds,
              double(engine->memory_bytes()) / bed.size(),
              static_cast<unsigned long long>(engine->rebuild_count() - rebuilds0), rebuild,
              error.c_str());
  std::fflush(stdout);
  return engine->memory_use();
}

/// Markdown table of the bytes per particle of each array, double and mixed side by side.
void print_memory_by_array(const std::vector<MemoryUse> (&by_policy)[3], std::size_t particles) {
  std::printf("\nmemory by array of the %zu-particle bed after the timed steps:\n\n", particles);
  std::printf(
      "| array | double [bytes/particle] | mixed [bytes/particle] | float [bytes/particle] |\n"
      "|---|---|---|---|\n");
  double totals[3] = {0, 0, 0};
  for (std::size_t k = 0; k < by_policy[0].size(); ++k) {
    std::printf("| %s", by_policy[0][k].name);
    for (int p = 0; p < 3; ++p) {
      const double bytes = k < by_policy[p].size() ? double(by_policy[p][k].bytes) / particles : 0;
      std::printf(" | %.1f", bytes);
      totals[p] += bytes;
    }
    std::printf(" |\n");
  }
  std::printf("| total | %.1f | %.1f | %.1f |\n", totals[0], totals[1], totals[2]);
}

/// Writes `bed` as a LAMMPS data file (atom_style sphere) plus `<path>.params`, a LAMMPS
/// include with the same time step, stiffness and damping, for a side-by-side run with
/// pair gran/hooke/history. LAMMPS' dashpots are per unit reduced mass, so they use the
/// reduced mass of two mean-size particles.
void write_lammps_bed(const ParticleStore& bed, int tx, int ty, const std::string& path) {
  const Scene scene = bed_scene(kSide * tx, kSide * ty);
  std::FILE* data = std::fopen(path.c_str(), "w");
  if (!data) throw std::runtime_error("cannot write " + path);
  std::fprintf(data, "settled bed\n\n%zu atoms\n1 atom types\n\n", bed.size());
  std::fprintf(data, "0 %.9g xlo xhi\n0 %.9g ylo yhi\n0 %.9g zlo zhi\n\nAtoms # sphere\n\n",
               scene.domain.max.x, scene.domain.max.y, scene.domain.max.z);
  double mean_mass = 0;
  for (std::size_t i = 0; i < bed.size(); ++i) {
    const Real4 p = bed.position_radius[i];
    std::fprintf(data, "%zu 1 %.12g %.9g %.12g %.12g %.12g\n", i + 1, 2 * p.w,
                 scene.materials[0].density, p.x, p.y, p.z);
    mean_mass += 1 / bed.velocity_inv_mass[i].w / bed.size();
  }
  std::fclose(data);
  const EngineSetup setup = make_engine_setup(scene, bed);
  const ContactPairParams& pair = setup.pair_params[0];
  const double reduced_mass = mean_mass / 2;
  std::FILE* params = std::fopen((path + ".params").c_str(), "w");
  if (!params) throw std::runtime_error("cannot write " + path + ".params");
  std::fprintf(
      params,
      "variable dt equal %.9g\nvariable kn equal %.9g\nvariable kt equal %.9g\n"
      "variable gn equal %.9g\nvariable gt equal %.9g\nvariable mu equal %.9g\n"
      "variable skin equal %.9g\n",
      setup.dt, pair.hooke_stiffness, pair.hooke_tangential_stiffness,
      2 * pair.restitution_beta * std::sqrt(pair.hooke_stiffness / reduced_mass),
      2 * pair.restitution_beta * std::sqrt(pair.hooke_tangential_stiffness / reduced_mass),
      pair.friction_static, setup.skin);
  std::fclose(params);
}

}  // namespace
}  // namespace gpudem

int main(int argc, char** argv) {
  using namespace gpudem;
  const int max_exponent = argc > 1 ? std::stoi(argv[1]) : 6;
  const std::string lammps_data = argc > 2 ? argv[2] : "";
  std::printf("settling the 10^4 seed bed...\n");
  std::fflush(stdout);
  const ParticleStore seed = settled_seed_bed();
  std::printf(
      "| particles | precision | threads | steps | particle-steps/s | bytes/particle | rebuilds "
      "in timed steps | one rebuild [s] | force error vs double |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  const int tiles[][2] = {{1, 1}, {5, 2}, {10, 10}};
  std::vector<MemoryUse> by_policy[3];  // the largest bed's, by Precision
  std::size_t largest = 0;
  for (int e = 4; e <= max_exponent && e <= 6; ++e) {
    const ParticleStore bed = tile(seed, tiles[e - 4][0], tiles[e - 4][1]);
    if (e == 5 && !lammps_data.empty()) write_lammps_bed(bed, 5, 2, lammps_data);
    largest = bed.size();
    for (Precision precision : {Precision::Double, Precision::Mixed, Precision::Float})
      for (int threads : {1, 2})
        by_policy[static_cast<int>(precision)] =
            measure(bed, tiles[e - 4][0], tiles[e - 4][1], threads, precision);
  }
  if (largest > 0) print_memory_by_array(by_policy, largest);
  return 0;
}
