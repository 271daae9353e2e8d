#include "engine/SceneSetup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/InputError.hpp"
#include "core/StlReader.hpp"
#include "core/contact/ContactSlots.hpp"
#include "engine/MeshReach.hpp"

namespace gpudem {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// G of a material [Pa].
double shear_modulus(const Material& m) { return gpudem::shear_modulus(m.young, m.poisson); }

/// E* of two materials (HertzNormal).
double effective_young(const Material& a, const Material& b) {
  return HertzNormal::effective_modulus(a.young, a.poisson, b.young, b.poisson);
}

/// G* of two materials (MindlinTangential).
double effective_shear(const Material& a, const Material& b) {
  return MindlinTangential::effective_shear_modulus(a.young, a.poisson, b.young, b.poisson);
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
                                     ? LinearHistoryTangential::stiffness_ratio * contact.stiffness
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
      RestitutionDamping::damping_ratio(value(given.restitution, a.restitution, b.restitution));
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

/// The contacts that bound the step of a law whose stiffness depends on the contact's size
/// (Normal::needs_effective_radius): the smallest particles of every two materials present (a
/// material with itself included), and of every material present with each wall, at impact
/// speed v.
std::vector<ImpactPair> extreme_pairs(const Scene& scene, const ParticleStore& particles,
                                      double v) {
  const std::vector<std::size_t> smallest = smallest_particle_per_material(scene, particles);
  std::vector<ImpactPair> pairs;
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
                       effective_shear(mat_a, mat_b), scene.contact.stiffness, v});
    }
    for (const MaterialId id : wall_materials(scene)) {
      const Material& wall = scene.materials[id];
      pairs.push_back({ra, ma, effective_young(mat_a, wall), effective_shear(mat_a, wall),
                       scene.contact.stiffness, v});
    }
  }
  return pairs;
}

/// The contact that bounds the step of a law whose stiffness does not depend on size: the two
/// lightest particles (m* = 1 / (2 max 1/m)); none without particles.
std::vector<ImpactPair> lightest_pair(const Scene& scene, const ParticleStore& particles) {
  double max_inv_mass = 0;
  for (const Real4& v : particles.velocity_inv_mass) max_inv_mass = std::max(max_inv_mass, v.w);
  if (!(max_inv_mass > 0)) return {};
  ImpactPair pair;
  pair.mass = 0.5 / max_inv_mass;
  pair.stiffness = scene.contact.stiffness;
  return {pair};
}

/// The smallest t_c and stable step of normal law Normal with tangential law Tangential over
/// the pairs that bound them.
template <class Normal, class Tangential>
void set_contact_limits(TimeStepLimits& limits, const Scene& scene,
                        const ParticleStore& particles) {
  const std::vector<ImpactPair> pairs =
      Normal::needs_effective_radius
          ? extreme_pairs(scene, particles, impact_speed(scene, particles))
          : lightest_pair(scene, particles);
  for (const ImpactPair& p : pairs) {
    limits.contact_duration = std::min(limits.contact_duration, Normal::contact_duration(p));
    limits.stable = std::min(limits.stable, Normal::template stable_step<Tangential>(p));
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
  const ContactModel& model = scene.contact.model;
  visit_slot(NormalSlots{}, static_cast<std::size_t>(model.normal), [&](auto normal) {
    visit_slot(TangentialSlots{}, static_cast<std::size_t>(model.tangential), [&](auto tangential) {
      set_contact_limits<decltype(normal), decltype(tangential)>(limits, scene, particles);
    });
  });
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
  require_meshes_meet_the_domain(scene, s.meshes, std::isfinite(r_min) ? 2 * r_min : 0.0);
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
  for (const std::size_t i : chosen)
    if (i != n) out.append_row(particles, i);  // n: an absent material, or no particles
  return out;
}

}  // namespace gpudem
