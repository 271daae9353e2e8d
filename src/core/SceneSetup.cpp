#include "core/SceneSetup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/InputError.hpp"
#include "core/StlReader.hpp"

namespace gpudem {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// k_t / k_n of the linear history law: equal normal and tangential oscillation periods of a
/// solid sphere.
constexpr double kTangentialStiffnessRatio = 2.0 / 7.0;

/// |β| = |ln e| / √(ln² e + π²): the damping ratio of a linear spring–dashpot whose
/// coefficient of restitution is e (Tsuji et al. 1992); 0 for e = 1.
double restitution_damping_ratio(double e) {
  const double log_e = std::log(e);
  return std::abs(log_e) / std::sqrt(log_e * log_e + kPi * kPi);
}

/// G = E / (2(1 + ν)) [Pa].
double shear_modulus(const Material& m) { return m.young / (2 * (1 + m.poisson)); }

/// E* of two bodies in Hertz contact: 1/E* = (1 − ν_a²)/E_a + (1 − ν_b²)/E_b [Pa]
/// (Johnson 1985).
double effective_young(const Material& a, const Material& b) {
  return 1 / ((1 - a.poisson * a.poisson) / a.young + (1 - b.poisson * b.poisson) / b.young);
}

/// G* of the Mindlin tangential stiffness: 1/G* = (2 − ν_a)/G_a + (2 − ν_b)/G_b [Pa]
/// (Mindlin 1949, as in the Hertz–Mindlin model of Di Renzo & Di Maio 2004).
double effective_shear(const Material& a, const Material& b) {
  return 1 / ((2 - a.poisson) / shear_modulus(a) + (2 - b.poisson) / shear_modulus(b));
}

/// μ_d of a material: friction_dynamic, or the static friction when it is not given (< 0).
double dynamic_friction(const Material& m) {
  return m.friction_dynamic < 0 ? m.friction : m.friction_dynamic;
}

/// The [[pair]] entry of materials a and b in either order; all values "not given" when none.
PairOverride pair_override(const ContactSettings& contact, MaterialId a, MaterialId b) {
  for (const PairOverride& p : contact.pairs) {
    if ((p.a == a && p.b == b) || (p.a == b && p.b == a)) return p;
  }
  return PairOverride{a, b};
}

/// Hooke stiffnesses and the elastic constants of the pair (Hertz, Mindlin).
void set_elastic_constants(ContactPairParams& p, const ContactSettings& contact, const Material& a,
                           const Material& b) {
  p.hooke_stiffness = contact.stiffness;
  p.hooke_tangential_stiffness = contact.model.tangential == TangentialLaw::LinearHistory
                                     ? kTangentialStiffnessRatio * contact.stiffness
                                     : 0.0;
  p.effective_young = effective_young(a, b);
  p.effective_shear = effective_shear(a, b);
}

/// Restitution, friction, rolling and cohesion values: the [[pair]] entry's where it gives
/// one (>= 0), else the mixing rule applied to the two materials' values.
void set_mixed_values(ContactPairParams& p, MixingRule rule, const Material& a, const Material& b,
                      const PairOverride& given) {
  const auto value = [rule](double given_value, double value_a, double value_b) {
    return given_value >= 0 ? given_value : mix(rule, value_a, value_b);
  };
  p.restitution_beta =
      restitution_damping_ratio(value(given.restitution, a.restitution, b.restitution));
  p.friction_static = value(given.friction, a.friction, b.friction);
  p.friction_dynamic = value(given.friction_dynamic, dynamic_friction(a), dynamic_friction(b));
  p.rolling_friction = value(given.rolling_friction, a.rolling_friction, b.rolling_friction);
  p.rolling_damping = mix(rule, a.rolling_damping, b.rolling_damping);
  p.viscoelastic_time = mix(rule, a.viscoelastic_time, b.viscoelastic_time);
  p.cohesion_energy_density =
      value(given.cohesion_energy_density, a.cohesion_energy_density, b.cohesion_energy_density);
}

std::vector<ContactPairParams> pair_table(const Scene& scene) {
  const std::size_t m = scene.materials.size();
  std::vector<ContactPairParams> table(m * m);
  for (MaterialId a = 0; a < m; ++a)
    for (MaterialId b = 0; b < m; ++b) {
      const Material& ma = scene.materials[a];
      const Material& mb = scene.materials[b];
      set_elastic_constants(table[a * m + b], scene.contact, ma, mb);
      set_mixed_values(table[a * m + b], scene.contact.mixing, ma, mb,
                       pair_override(scene.contact, a, b));
    }
  return table;
}

/// The smallest radius in the store, or +inf.
double smallest_radius(const ParticleStore& particles) {
  double r = kInfinity;
  for (const Real4& p : particles.position_radius) r = std::min(r, p.w);
  return r;
}

/// T_R = π r √(ρ/G) / (0.1631 ν + 0.8766) of a sphere of radius r (Rayleigh wave crossing).
double rayleigh_time(const Material& m, double radius) {
  return kPi * radius * std::sqrt(m.density / shear_modulus(m)) / (0.1631 * m.poisson + 0.8766);
}

double smallest_rayleigh_time(const Scene& scene, const ParticleStore& particles) {
  double t = kInfinity;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    t = std::min(
        t, rayleigh_time(scene.materials[particles.material[i]], particles.position_radius[i].w));
  }
  return t;
}

/// m* of the two lightest particles [kg]; +inf without particles.
double lightest_pair_mass(const ParticleStore& particles) {
  double max_inv_mass = 0;
  for (const Real4& v : particles.velocity_inv_mass) max_inv_mass = std::max(max_inv_mass, v.w);
  return max_inv_mass > 0 ? 0.5 / max_inv_mass : kInfinity;
}

/// Hooke: t_c = π √(m*/k_n) and the stable limit 2/ω = 2 √(m*/k_n) for the lightest pair.
void set_hooke_limits(TimeStepLimits& limits, const Scene& scene, const ParticleStore& particles) {
  const double m_star = lightest_pair_mass(particles);
  if (!std::isfinite(m_star)) return;
  const double k = scene.contact.stiffness;
  limits.contact_duration = kPi * std::sqrt(m_star / k);
  limits.stable = std::min(limits.stable, 2 * std::sqrt(m_star / k));
}

/// Reduced radius, reduced mass and effective moduli of one Hertz contact.
struct HertzPair {
  double radius;  ///< R* [m]
  double mass;    ///< m* [kg]
  double young;   ///< E* [Pa]
  double shear;   ///< G* [Pa]
};

/// t_c = 2.87 (m*² / (R* E*² v))^{1/5} (Johnson 1985).
double hertz_contact_duration(const HertzPair& p, double v) {
  return 2.87 * std::pow(p.mass * p.mass / (p.radius * p.young * p.young * v), 0.2);
}

/// 2/ω of the stiffest moment of an impact at v, δ_max = (15 m* v² / (16 E* √R*))^{2/5}
/// (Johnson 1985): normal mode ω² = S_n/m*, S_n = 2 E* √(R* δ_max); with the Mindlin spring
/// also the tangential mode ω² = S_t / (2/7 m*), S_t = 8 G* √(R* δ_max), whose effective mass
/// is 2/7 m* because the contact point of a free sphere also moves by rotation.
double hertz_stable_step(const HertzPair& p, double v, bool mindlin) {
  const double peak_overlap =
      std::pow(15 * p.mass * v * v / (16 * p.young * std::sqrt(p.radius)), 0.4);
  const double root = std::sqrt(p.radius * peak_overlap);
  double omega2 = 2 * p.young * root / p.mass;
  if (mindlin) omega2 = std::max(omega2, 8 * p.shear * root / (2.0 / 7.0 * p.mass));
  return 2 / std::sqrt(omega2);
}

/// The materials of the plane walls and the mesh walls, each as often as it is used.
std::vector<MaterialId> wall_materials(const Scene& scene) {
  std::vector<MaterialId> ids;
  for (const WallSettings& w : scene.walls) ids.push_back(w.material);
  for (const MeshSettings& m : scene.meshes) ids.push_back(m.material);
  return ids;
}

/// The mesh walls of the scene, read, placed and welded. An STL error becomes an error of the
/// scene's `mesh[i].file` key, its message naming the STL file.
std::vector<MeshWallSetup> mesh_walls(const Scene& scene) {
  std::vector<MeshWallSetup> walls;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshSettings& m = scene.meshes[i];
    MeshWallSetup wall;
    try {
      wall.mesh = load_mesh(m.file, m.placement);
    } catch (const InputError& e) {
      throw InputError(scene.file, m.line, "mesh[" + std::to_string(i) + "].file", e.what());
    }
    wall.material = m.material;
    wall.motion = PrescribedMotion(m.centre, m.keyframes);
    walls.push_back(std::move(wall));
  }
  return walls;
}

/// Index of the smallest particle of each material; particles.size() for an absent material.
std::vector<std::size_t> smallest_particle_per_material(const Scene& scene,
                                                        const ParticleStore& particles) {
  const std::size_t none = particles.size();
  std::vector<std::size_t> smallest(scene.materials.size(), none);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    std::size_t& s = smallest[particles.material[i]];
    if (s == none || particles.position_radius[i].w < particles.position_radius[s].w) s = i;
  }
  return smallest;
}

/// The Hertz contacts that bound the step: the smallest particles of every two materials
/// present (a material with itself included), and of every material present with each wall.
std::vector<HertzPair> hertz_extreme_pairs(const Scene& scene, const ParticleStore& particles) {
  const std::vector<std::size_t> smallest = smallest_particle_per_material(scene, particles);
  std::vector<HertzPair> pairs;
  for (std::size_t a = 0; a < smallest.size(); ++a) {
    if (smallest[a] == particles.size()) continue;
    const double ra = particles.position_radius[smallest[a]].w;
    const double ma = 1 / particles.velocity_inv_mass[smallest[a]].w;
    const Material& mat_a = scene.materials[a];
    for (std::size_t b = a; b < smallest.size(); ++b) {
      if (smallest[b] == particles.size()) continue;
      const double rb = particles.position_radius[smallest[b]].w;
      const double mb = 1 / particles.velocity_inv_mass[smallest[b]].w;
      const Material& mat_b = scene.materials[b];
      pairs.push_back({ra * rb / (ra + rb), ma * mb / (ma + mb), effective_young(mat_a, mat_b),
                       effective_shear(mat_a, mat_b)});
    }
    for (const MaterialId id : wall_materials(scene)) {
      const Material& wall = scene.materials[id];
      pairs.push_back({ra, ma, effective_young(mat_a, wall), effective_shear(mat_a, wall)});
    }
  }
  return pairs;
}

/// Hertz: the smallest t_c and 2/ω over hertz_extreme_pairs at the impact speed.
void set_hertz_limits(TimeStepLimits& limits, const Scene& scene, const ParticleStore& particles) {
  const double v = impact_speed(scene, particles);
  for (const HertzPair& p : hertz_extreme_pairs(scene, particles)) {
    limits.contact_duration = std::min(limits.contact_duration, hertz_contact_duration(p, v));
    limits.stable =
        std::min(limits.stable,
                 hertz_stable_step(p, v, scene.contact.model.tangential == TangentialLaw::Mindlin));
  }
}

/// Extent of the box [lo, hi] along the unit vector u: Σ_k |(hi − lo)_k u_k| [m].
double extent_along(Vec3 lo, Vec3 hi, Vec3 u) {
  const Vec3 l = hi - lo;
  return std::abs(l.x * u.x) + std::abs(l.y * u.y) + std::abs(l.z * u.z);
}

/// "1.234e-05": numbers in messages, four significant digits.
std::string short_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

/// The largest radius in the store, or 0.
double largest_radius(const ParticleStore& particles) {
  double r = 0;
  for (const Real4& p : particles.position_radius) r = std::max(r, p.w);
  return r;
}

/// True when some keyframe of the mesh's motion has a non-zero angular velocity.
bool ever_rotates(const MeshSettings& mesh) {
  for (const MotionKeyframe& k : mesh.keyframes)
    if (norm2(k.angular_velocity) > 0) return true;
  return false;
}

/// h_k, how far along axis k the mesh reaches from the centre b₀ of its bounding box: half its
/// extent along k, or, for a mesh that ever rotates, the largest distance from b₀ to a vertex
/// (a bound along every axis in every pose) [m].
double half_span(const TriangleMesh& mesh, bool rotates, int k) {
  Vec3 lo = mesh.vertices.front(), hi = mesh.vertices.front();
  for (const Vec3& v : mesh.vertices)
    for (int a = 0; a < 3; ++a) {
      axis(lo, a) = std::min(axis(lo, a), axis(v, a));
      axis(hi, a) = std::max(axis(hi, a), axis(v, a));
    }
  if (!rotates) return 0.5 * (axis(hi, k) - axis(lo, k));
  const Vec3 centre = 0.5 * (lo + hi);
  double reach = 0;
  for (const Vec3& v : mesh.vertices) reach = std::max(reach, norm(v - centre));
  return reach;
}

/// Refuses a mesh too wide for a periodic axis: a particle meets each mesh as its periodic image
/// nearest the mesh's image centre, which is the image within reach of the mesh while
/// h_k + r_max + 2 skin < L_k / 2 (within reach r + skin of the mesh at a list build, then both
/// move at most skin / 2 until the next).
void require_meshes_fit_periodic_axes(const Scene& scene, const std::vector<MeshWallSetup>& meshes,
                                      double r_max, double skin) {
  static const char* const kAxisName[3] = {"x", "y", "z"};
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const MeshSettings& settings = scene.meshes[i];
    for (int k = 0; k < 3; ++k) {
      if (!scene.domain.periodic[k] || meshes[i].mesh.vertices.empty()) continue;
      const double L = axis(scene.domain.max, k) - axis(scene.domain.min, k);
      const double span = 2 * half_span(meshes[i].mesh, ever_rotates(settings), k);
      const double room = L - 2 * (r_max + 2 * skin);
      if (span < room) continue;
      throw InputError(scene.file, settings.line, "mesh[" + std::to_string(i) + "].file",
                       "mesh '" + settings.name + "' spans " + short_number(span) +
                           " m along periodic axis " + kAxisName[k] + " (L = " + short_number(L) +
                           " m); a mesh must fit within L - 2 (r_max + 2 skin) = " +
                           short_number(room) + " m to meet each particle as one periodic image");
    }
  }
}

/// Refuses an explicit dt above the stable limit unless the scene allows it.
void require_stable_dt(const Scene& scene, const TimeStepLimits& limits) {
  const SimulationSettings& sim = scene.simulation;
  if (sim.dt_auto || sim.allow_unstable_dt || !(sim.dt > limits.stable)) return;
  throw InputError(
      scene.file, sim.dt_line, "simulation.dt",
      "dt = " + short_number(sim.dt) + " s exceeds the stable limit " +
          short_number(limits.stable) +
          " s (the smaller of the Rayleigh time T_R = " + short_number(limits.rayleigh) +
          " s and 2/omega of the stiffest contact; contact duration t_c = " +
          short_number(limits.contact_duration) +
          " s); use a smaller dt or dt = \"auto\", or set simulation.allow_unstable_dt = true "
          "to run anyway");
}

}  // namespace

double impact_speed(const Scene& scene, const ParticleStore& particles) {
  if (scene.simulation.impact_speed > 0) return scene.simulation.impact_speed;
  const Vec3 g = scene.simulation.gravity;
  const double g_norm = norm(g);
  const double height =
      g_norm > 0 ? extent_along(scene.domain.min, scene.domain.max, (1 / g_norm) * g) : 0.0;
  double fastest = 0;
  for (const Real4& v : particles.velocity_inv_mass) fastest = std::max(fastest, norm(xyz(v)));
  const double v = std::sqrt(2 * g_norm * height) + fastest;
  return v > 0 ? v : 1.0;
}

TimeStepLimits time_step_limits(const Scene& scene, const ParticleStore& particles) {
  TimeStepLimits limits;
  limits.rayleigh = smallest_rayleigh_time(scene, particles);
  limits.contact_duration = kInfinity;
  limits.stable = limits.rayleigh;
  if (scene.contact.model.normal == NormalLaw::Hooke) {
    set_hooke_limits(limits, scene, particles);
  } else {
    set_hertz_limits(limits, scene, particles);
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
  s.precision = scene.simulation.precision;
  s.contact_model = scene.contact.model;
  s.material_count = static_cast<std::uint32_t>(scene.materials.size());
  s.pair_params = pair_table(scene);
  for (const WallSettings& w : scene.walls)
    s.walls.push_back(PlaneWall{w.point, w.normal, w.material});
  s.meshes = mesh_walls(scene);
  const double r_min = smallest_radius(particles);
  s.skin =
      scene.neighbor.skin > 0 ? scene.neighbor.skin : (std::isfinite(r_min) ? 0.5 * r_min : 0.0);
  require_meshes_fit_periodic_axes(scene, s.meshes, largest_radius(particles), s.skin);
  const TimeStepLimits limits = time_step_limits(scene, particles);
  require_stable_dt(scene, limits);
  if (scene.simulation.dt_auto) {
    const double critical = limits.critical();
    s.dt = std::isfinite(critical) ? scene.simulation.dt_fraction * critical
                                   : scene.simulation.end_time;
  } else {
    s.dt = scene.simulation.dt;
  }
  return s;
}

ParticleStore setup_deciding_particles(const Scene& scene, const ParticleStore& particles) {
  const std::size_t n = particles.size();
  std::vector<std::size_t> chosen = smallest_particle_per_material(scene, particles);
  std::size_t largest = n, lightest = n, fastest = n;
  const auto radius = [&](std::size_t i) { return particles.position_radius[i].w; };
  const auto inv_mass = [&](std::size_t i) { return particles.velocity_inv_mass[i].w; };
  const auto speed2 = [&](std::size_t i) { return norm2(xyz(particles.velocity_inv_mass[i])); };
  for (std::size_t i = 0; i < n; ++i) {
    if (largest == n || radius(i) > radius(largest)) largest = i;
    if (lightest == n || inv_mass(i) > inv_mass(lightest)) lightest = i;
    if (fastest == n || speed2(i) > speed2(fastest)) fastest = i;
  }
  chosen.insert(chosen.end(), {largest, lightest, fastest});
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  ParticleStore out;
  for (const std::size_t i : chosen) {
    if (i == n) continue;  // an absent material, or no particles
    out.position_radius.push_back(particles.position_radius[i]);
    out.velocity_inv_mass.push_back(particles.velocity_inv_mass[i]);
    out.angular_velocity.push_back(particles.angular_velocity[i]);
    out.id.push_back(particles.id[i]);
    out.material.push_back(particles.material[i]);
  }
  out.force.resize(out.size());
  out.torque.resize(out.size());
  return out;
}

}  // namespace gpudem
