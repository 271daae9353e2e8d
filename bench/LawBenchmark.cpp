// Cost of each contact-law slot: the same settled bed of 10^5 spheres (the 10^4 seed bed of
// SettledBed.hpp tiled 5 × 2) timed with one law after another at the same time step, on one
// and two threads. Prints a Markdown table: law, particle-steps/s, history values and extra
// bytes read per contact, bytes per particle held by the engine.
#include <chrono>
#include <cstdio>
#include <vector>

#include "SettledBed.hpp"

namespace gpudem {
namespace {

/// Laws that switch on one slot after another, Hooke family then Hertz family.
std::vector<ContactModel> laws_to_time() {
  using N = NormalLaw;
  using D = DampingLaw;
  using T = TangentialLaw;
  using R = RollingLaw;
  using C = CohesionLaw;
  return {
      {N::Hooke, D::None, T::None, R::None, C::None},
      {N::Hooke, D::Restitution, T::None, R::None, C::None},
      {N::Hooke, D::Restitution, T::LinearHistory, R::None, C::None},
      {N::Hooke, D::Restitution, T::LinearHistory, R::ConstantTorque, C::None},
      {N::Hooke, D::Restitution, T::LinearHistory, R::Epsd, C::None},
      {N::Hooke, D::Restitution, T::LinearHistory, R::None, C::Sjkr},
      {N::Hertz, D::None, T::None, R::None, C::None},
      {N::Hertz, D::Restitution, T::None, R::None, C::None},
      {N::Hertz, D::Viscoelastic, T::None, R::None, C::None},
      {N::Hertz, D::Restitution, T::Mindlin, R::None, C::None},
      {N::Hertz, D::Restitution, T::Mindlin, R::ConstantTorque, C::None},
      {N::Hertz, D::Restitution, T::Mindlin, R::Epsd, C::None},
      {N::Hertz, D::Restitution, T::Mindlin, R::Epsd, C::Sjkr},
      {N::Hertz, D::Restitution, T::Mindlin, R::None, C::Jkr},
      {N::Hertz, D::Restitution, T::Mindlin, R::Epsd, C::Jkr},
  };
}

/// Particle-steps per second of `steps` steps after a few warm-up steps.
double throughput(StepEngine& engine, std::size_t n, int steps) {
  for (int k = 0; k < 5; ++k) engine.step();
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) engine.step();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return steps * double(n) / seconds;
}

void time_law(const ParticleStore& bed, const ContactModel& model, double dt) {
  Scene scene = bed_scene(kSide * 5, kSide * 2);
  scene.contact.model = model;
  if (model.normal == NormalLaw::Hertz) scene.contact.stiffness = 0;
  scene.materials[0].viscoelastic_time = 1e-4;
  scene.materials[0].rolling_friction = 0.1;
  scene.materials[0].cohesion_energy_density = 1e3;
  scene.materials[0].surface_energy = 0.01;
  scene.simulation.dt_auto = false;
  scene.simulation.dt = dt;
  scene.simulation.allow_unstable_dt = true;  // the same dt for every law, for a fair cost
  const EngineSetup setup = make_engine_setup(scene, bed);
  std::vector<double> rate;
  std::size_t bytes = 0;
  for (int threads : {1, 2}) {
    set_threads(threads);
    auto engine = make_host_engine(setup);
    engine->set_particles(bed);
    rate.push_back(throughput(*engine, bed.size(), 200));
    bytes = engine->memory_bytes();
  }
  std::printf("| %s | %.3g | %.3g | %d | %.1f |\n", contact_model_name(model).c_str(), rate[0],
              rate[1], static_cast<int>(contact_history_width(model)), double(bytes) / bed.size());
  std::fflush(stdout);
}

}  // namespace
}  // namespace gpudem

int main() {
  using namespace gpudem;
  std::printf("settling the 10^4 seed bed...\n");
  std::fflush(stdout);
  const ParticleStore bed = tile(settled_seed_bed(), 5, 2);
  Scene hooke = bed_scene(kSide * 5, kSide * 2);
  const double dt = make_engine_setup(hooke, bed).dt;
  std::printf("10^5 particles, dt = %.3g s for every law\n\n", dt);
  std::printf(
      "| law (normal/damping/tangential/rolling/cohesion) | particle-steps/s, 1 thread | "
      "2 threads | history values per contact | bytes/particle |\n|---|---|---|---|---|\n");
  for (const ContactModel& model : laws_to_time()) time_law(bed, model, dt);
  return 0;
}
