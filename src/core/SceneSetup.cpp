#include "core/SceneSetup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gpudem {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Pair value of a material property: the arithmetic mean of the two materials.
double pair_mean(double a, double b) { return 0.5 * (a + b); }

std::vector<LinearPairParams> pair_table(const Scene& scene) {
  const std::size_t m = scene.materials.size();
  std::vector<LinearPairParams> table(m * m);
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = 0; b < m; ++b) {
      const Material& ma = scene.materials[a];
      const Material& mb = scene.materials[b];
      LinearPairParams& p = table[a * m + b];
      p.stiffness = scene.contact.stiffness;
      p.damping_beta = scene.contact.damping == "restitution"
                           ? restitution_beta(pair_mean(ma.restitution, mb.restitution))
                           : 0.0;
      const bool tangential = scene.contact.tangential == "linear_history";
      p.tangential_stiffness = tangential ? kTangentialStiffnessRatio * p.stiffness : 0.0;
      p.friction = tangential ? pair_mean(ma.friction, mb.friction) : 0.0;
      p.rolling_friction = scene.contact.rolling == "constant_torque"
                               ? pair_mean(ma.rolling_friction, mb.rolling_friction)
                               : 0.0;
    }
  return table;
}

/// The smallest radius in the store, or +inf.
double smallest_radius(const ParticleStore& particles) {
  double r = std::numeric_limits<double>::infinity();
  for (const Real4& p : particles.position_radius) r = std::min(r, p.w);
  return r;
}

}  // namespace

TimeStepLimits time_step_limits(const Scene& scene, const ParticleStore& particles) {
  TimeStepLimits limits;
  limits.contact_duration = std::numeric_limits<double>::infinity();
  limits.rayleigh = std::numeric_limits<double>::infinity();
  double max_inv_mass = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    max_inv_mass = std::max(max_inv_mass, particles.velocity_inv_mass[i].w);
    const Material& mat = scene.materials[particles.material[i]];
    const double shear = mat.young / (2 * (1 + mat.poisson));
    const double t_r = kPi * particles.position_radius[i].w * std::sqrt(mat.density / shear) /
                       (0.1631 * mat.poisson + 0.8766);
    limits.rayleigh = std::min(limits.rayleigh, t_r);
  }
  if (max_inv_mass > 0) {
    const double lightest_pair_mass = 0.5 / max_inv_mass;  // m* of two lightest particles
    limits.contact_duration = kPi * std::sqrt(lightest_pair_mass / scene.contact.stiffness);
  }
  return limits;
}

EngineSetup make_engine_setup(const Scene& scene, const ParticleStore& particles) {
  EngineSetup s;
  s.box.lo = scene.domain.min;
  s.box.length = scene.domain.max - scene.domain.min;
  for (int k = 0; k < 3; ++k) s.box.periodic[k] = scene.domain.periodic[k];
  s.gravity = scene.simulation.gravity;
  s.integrator = scene.simulation.integrator;
  s.material_count = static_cast<std::uint32_t>(scene.materials.size());
  s.pair_params = pair_table(scene);
  for (const WallSettings& w : scene.walls)
    s.walls.push_back(PlaneWall{w.point, w.normal, w.material});
  const double r_min = smallest_radius(particles);
  s.skin =
      scene.neighbor.skin > 0 ? scene.neighbor.skin : (std::isfinite(r_min) ? 0.5 * r_min : 0.0);
  if (scene.simulation.dt_auto) {
    const double critical = time_step_limits(scene, particles).critical();
    s.dt = std::isfinite(critical) ? scene.simulation.dt_fraction * critical
                                   : scene.simulation.end_time;
  } else {
    s.dt = scene.simulation.dt;
  }
  return s;
}

}  // namespace gpudem
