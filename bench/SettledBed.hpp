#pragma once
// The settled bed the host benchmarks time: a periodic bed of 10^4 spheres poured onto a
// floor and stepped until nearly at rest, tiled in x and y to larger beds.
#include <algorithm>
#include <cstdio>

#if defined(GPUDEM_HAVE_OPENMP)
#include <omp.h>
#endif

#include "core/ParticleSources.hpp"
#include "engine/SceneSetup.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem {

inline constexpr double kSide = 0.12;  // periodic cell of the seed bed [m]

inline Scene bed_scene(double side_x, double side_y) {
  Scene s = test::basic_scene({0, 0, 0}, {side_x, side_y, 0.3}, 2000, 0.2, 0.5);
  s.materials[0].density = 1850;
  s.materials[0].young = 1e6;
  s.domain.periodic = {true, true, false};
  test::add_floor(s);
  return s;
}

/// Makes an engine of one backend for a setup (make_host_engine, make_cuda_engine).
using EngineMaker = std::unique_ptr<StepEngine> (*)(const EngineSetup&);

/// The particles of `scene`'s sources, poured and stepped on `make`'s engine until their
/// kinetic energy is below 1e-6 of the initial potential energy (at most 80,000 steps).
inline ParticleStore settle(const Scene& scene, EngineMaker make) {
  ParticleStore particles;
  create_particles(scene, particles);
  auto engine = make(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  const double potential = engine->diagnostics().potential_gravity;
  for (int block = 0; block < 400; ++block) {
    for (int n = 0; n < 200; ++n) engine->step();
    const Diagnostics d = engine->diagnostics();
    if (block > 20 && d.kinetic_translational + d.kinetic_rotational < 1e-6 * potential) break;
  }
  const Diagnostics d = engine->diagnostics();
  std::printf("seed bed: kinetic / initial potential energy %.2e, max overlap %.3f of a radius\n",
              (d.kinetic_translational + d.kinetic_rotational) / potential, d.max_overlap_ratio);
  engine->get_particles(particles);
  return particles;
}

/// A settled periodic bed of 10^4 particles (Hooke, linear history; bed_scene), settled on the
/// host backend.
inline ParticleStore settled_seed_bed() {
  Scene scene = bed_scene(kSide, kSide);
  test::add_box_source(scene, {0, 0, 0}, {kSide, kSide, 0.3}, 10000, 2.5e-3, 0.5e-3);
  return settle(scene, make_host_engine);
}

/// The seed bed repeated tx × ty times in x and y.
inline ParticleStore tile(const ParticleStore& seed, int tx, int ty) {
  ParticleStore out;
  ParticleId next = 0;
  for (int a = 0; a < tx; ++a)
    for (int b = 0; b < ty; ++b)
      for (std::size_t i = 0; i < seed.size(); ++i) {
        const Real4 p = seed.position_radius[i];
        const Real4 v = seed.velocity_inv_mass[i];
        out.add(next++, {p.x + a * kSide, p.y + b * kSide, p.z}, p.w, seed.material[i],
                {v.x, v.y, v.z}, v.w);
      }
  return out;
}

/// Largest |F_a − F_b| over the largest |F_b| of two engines holding the same particles in the
/// same order (b the reference, e.g. the double-precision engine).
inline double force_error(const StepEngine& a, const StepEngine& b) {
  ParticleStore pa, pb;
  a.get_particles(pa);
  b.get_particles(pb);
  double largest = 0, worst = 0;
  for (std::size_t i = 0; i < pb.size(); ++i) {
    largest = std::max(largest, norm(pb.force[i]));
    worst = std::max(worst, norm(pa.force[i] - pb.force[i]));
  }
  return worst / largest;
}

inline void set_threads(int n) {
#if defined(GPUDEM_HAVE_OPENMP)
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

}  // namespace gpudem
