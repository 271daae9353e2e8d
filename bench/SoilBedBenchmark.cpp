// Throughput of one backend on settled soil beds (Hertz–Mindlin with restitution damping and
// constant-torque rolling resistance): settles a periodic bed of 10^4 spheres on that backend,
// tiles it in x and y to each requested size, and times the step loop in each precision.
// Prints a Markdown table: particle-steps/s, bytes per particle, the effective memory
// bandwidth (the fewest bytes a step must move over its time: step_traffic_bytes), the time
// split of a second run that waits for the device at the end of each part
// (EngineSetup::exact_phase_times), and the largest force error against double.
//   gpudem-bench-soil --backend cuda --sizes 1e5,1e6,1e7 --largest
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "SettledBed.hpp"
#include "engine/CudaMemory.hpp"

namespace gpudem {
namespace {

constexpr std::size_t kSeedCount = 10000;

/// The soil bed's scene over a periodic box of side_x × side_y: spheres of R = 2.5 ± 0.5 mm,
/// ρ = 2650 kg/m³, E = 10 MPa, ν = 0.3, e = 0.3, μ = 0.5, μ_r = 0.1, on a floor.
Scene soil_scene(double side_x, double side_y) {
  Scene s = test::basic_scene({0, 0, 0}, {side_x, side_y, 0.3}, 0, 0.3, 0.5);
  s.materials[0].density = 2650;
  s.materials[0].young = 1e7;
  s.materials[0].rolling_friction = 0.1;
  s.contact.model = {NormalLaw::Hertz, DampingLaw::Restitution, TangentialLaw::Mindlin,
                     RollingLaw::ConstantTorque, CohesionLaw::None};
  s.domain.periodic = {true, true, false};
  test::add_floor(s);
  return s;
}

struct Options {
  std::string backend = "cuda";
  std::vector<double> sizes{1e5, 1e6, 1e7};
  std::vector<std::string> precisions{"mixed", "double", "float"};
  bool largest = false;            ///< also the largest bed the device memory holds
  double particle_steps = 2e9;     ///< timed particle-steps per run (steps = this / size)
  double memory_share = 0.85;      ///< of the free device memory the largest bed may take
  std::size_t error_limit = 20e6;  ///< largest bed whose force error against double is taken
};

bool on_cuda(const Options& o) { return o.backend == "cuda"; }

/// Waits for the device's queued work, so that a host clock read after it covers that work.
void wait_for(const Options& o) {
  if (on_cuda(o)) cuda::synchronize_device();
}

Precision precision_of(const std::string& name) {
  static const std::map<std::string, Precision> names{
      {"double", Precision::Double}, {"mixed", Precision::Mixed}, {"float", Precision::Float}};
  const auto it = names.find(name);
  if (it == names.end()) throw std::invalid_argument("unknown precision '" + name + "'");
  return it->second;
}

/// Tiles tx × ty of the seed bed for about `count` tiles: count itself when it factors with
/// tx / ty <= 4, else the near-square tiling with ty = ⌊√count⌋ and tx = ⌊count / ty⌋.
std::pair<int, int> tiling(std::size_t count) {
  const int root = static_cast<int>(std::sqrt(double(count)));
  int ty = root;
  while (count % ty != 0) --ty;
  if (count / ty <= 4 * std::size_t(ty)) return {static_cast<int>(count / ty), ty};
  return {static_cast<int>(count / root), root};
}

/// Bytes one step must read or write at least once, from the engine's arrays: the state it
/// reads and writes (position, velocity, spin), the loads it writes and the next kick reads,
/// the materials and overlap ratios, the positions at the last list build (the rebuild test),
/// the neighbour list it reads and the contact history it reads and writes. Ghosts, cell
/// lists and rebuild scratch are not touched on a step without a rebuild.
double step_traffic_bytes(const std::vector<MemoryUse>& memory) {
  static const std::map<std::string, double> passes{
      {"position, radius", 2},       {"velocity, inverse mass", 2},
      {"angular velocity", 2},       {"id, material", 1},
      {"force, torque", 2},          {"overlap ratio", 1},
      {"position at list build", 1}, {"neighbour list", 1},
      {"pair history", 2},           {"wall history", 2}};
  double bytes = 0;
  std::size_t found = 0;
  for (const MemoryUse& use : memory) {
    const auto it = passes.find(use.name);
    if (it == passes.end()) continue;
    bytes += it->second * double(use.bytes);
    ++found;
  }
  if (found != passes.size()) throw std::logic_error("the engine's memory report lacks an array");
  return bytes;
}

class Bench {
 public:
  explicit Bench(const Options& options)
      : options_(options), make_(on_cuda(options) ? make_cuda_engine : make_host_engine) {}

  void run() {
    Scene seed_scene = soil_scene(kSide, kSide);
    test::add_box_source(seed_scene, {0, 0, 0}, {kSide, kSide, 0.3}, kSeedCount, 2.5e-3, 0.5e-3);
    seed_ = settle(seed_scene, make_);
    std::printf(
        "\n| particles | precision | steps | particle-steps/s | bytes/particle | effective "
        "bandwidth [GB/s] | integrate / forces / neighbours [%% of step] | rebuilds | force "
        "error vs double |\n|---|---|---|---|---|---|---|---|---|\n");
    double bytes_per_particle = 0;
    for (const double size : options_.sizes) bytes_per_particle = measure_size(size);
    if (options_.largest && on_cuda(options_) && bytes_per_particle > 0) {
      const double fits =
          options_.memory_share * double(cuda::free_device_memory()) / bytes_per_particle;
      measure_size(std::floor(fits / kSeedCount) * kSeedCount, {options_.precisions.front()});
    }
  }

 private:
  /// Times each precision on the bed of `size` particles (rounded to whole seed beds);
  /// returns the first precision's bytes per particle.
  double measure_size(double size) { return measure_size(size, options_.precisions); }

  double measure_size(double size, const std::vector<std::string>& precisions) {
    const std::size_t tiles = std::max<std::size_t>(1, std::llround(size / kSeedCount));
    const auto [tx, ty] = tiling(tiles);
    const ParticleStore bed = tile(seed_, tx, ty);
    const Scene scene = soil_scene(kSide * tx, kSide * ty);
    double first = 0;
    for (const std::string& name : precisions) {
      const double bytes = measure(scene, bed, precision_of(name), name);
      if (first == 0) first = bytes;
    }
    return first;
  }

  /// One row: the throughput run, then the split run; returns the bytes per particle.
  double measure(const Scene& scene, const ParticleStore& bed, Precision precision,
                 const std::string& name) {
    EngineSetup setup = make_engine_setup(scene, bed);
    setup.precision = precision;
    const int steps = std::clamp(static_cast<int>(options_.particle_steps / bed.size()), 20, 20000);
    std::string error = "–";
    if (precision != Precision::Double && bed.size() <= options_.error_limit) {
      char text[32];
      std::snprintf(text, sizeof text, "%.2g", error_against_double(setup, bed));
      error = text;
    }
    double rate = 0, bytes = 0, traffic = 0;
    std::uint64_t rebuilds = 0;
    {
      auto engine = make_(setup);
      engine->set_particles(bed);
      engine->tune_launches();
      for (int n = 0; n < 5; ++n) engine->step();
      wait_for(options_);
      const std::uint64_t rebuilds0 = engine->rebuild_count();
      const auto t0 = std::chrono::steady_clock::now();
      for (int n = 0; n < steps; ++n) engine->step();
      wait_for(options_);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      rate = steps * double(bed.size()) / seconds;
      rebuilds = engine->rebuild_count() - rebuilds0;
      bytes = double(engine->memory_bytes()) / bed.size();
      traffic = step_traffic_bytes(engine->memory_use()) * steps / seconds;
    }
    const std::string split = time_split(setup, bed, std::max(10, steps / 4));
    std::printf("| %zu | %s | %d | %.3g | %.1f | %.3g | %s | %llu | %s |\n", bed.size(),
                name.c_str(), steps, rate, bytes, traffic / 1e9, split.c_str(),
                static_cast<unsigned long long>(rebuilds), error.c_str());
    std::fflush(stdout);
    return bytes;
  }

  /// Shares of the step in integration, forces and neighbour lists (with the periodic wrap
  /// and ghost plan of a rebuild) over `steps` steps of an engine that waits for the device at
  /// the end of each part.
  std::string time_split(EngineSetup setup, const ParticleStore& bed, int steps) {
    setup.exact_phase_times = true;
    auto engine = make_(setup);
    engine->set_particles(bed);
    engine->tune_launches();
    for (int n = 0; n < 5; ++n) engine->step();
    const StepTimes before = engine->step_times();
    for (int n = 0; n < steps; ++n) engine->step();
    const StepTimes after = engine->step_times();
    const double integrate = after.integrate - before.integrate;
    const double forces = after.forces - before.forces;
    const double neighbors = after.neighbors - before.neighbors + after.ghosts - before.ghosts +
                             after.migration - before.migration;  // a rebuild's other parts
    const double total = integrate + forces + neighbors;
    char text[64];
    std::snprintf(text, sizeof text, "%.1f / %.1f / %.1f", 100 * integrate / total,
                  100 * forces / total, 100 * neighbors / total);
    return text;
  }

  double error_against_double(EngineSetup setup, const ParticleStore& bed) {
    auto engine = make_(setup);
    engine->set_particles(bed);
    setup.precision = Precision::Double;
    auto exact = make_(setup);
    exact->set_particles(bed);
    return force_error(*engine, *exact);
  }

  Options options_;
  EngineMaker make_;
  ParticleStore seed_;
};

}  // namespace
}  // namespace gpudem

int main(int argc, char** argv) {
  using namespace gpudem;
  Options options;
  CLI::App app{"gpudem-bench-soil: step throughput on settled soil beds (Hertz–Mindlin, rolling)"};
  app.add_option("--backend", options.backend, "host or cuda")
      ->check(CLI::IsMember({"host", "cuda"}));
  app.add_option("--sizes", options.sizes, "bed sizes [particles], rounded to 10^4")
      ->delimiter(',');
  app.add_option("--precisions", options.precisions, "double, mixed and/or float")
      ->delimiter(',')
      ->check(CLI::IsMember({"double", "mixed", "float"}));
  app.add_flag("--largest", options.largest,
               "also the largest bed that fits the free device memory (first precision)");
  app.add_option("--particle-steps", options.particle_steps,
                 "particle-steps per timed run (at least 20 steps)");
  CLI11_PARSE(app, argc, argv);
  if (on_cuda(options) && cuda::device_count() == 0) {
    std::fprintf(stderr, "gpudem-bench-soil: no CUDA device (built with CUDA: %s)\n",
                 cuda::compiled_in() ? "yes" : "no");
    return 1;
  }
  if (on_cuda(options)) std::printf("device: %s\n", cuda::device_description().c_str());
  Bench(options).run();
  return 0;
}
