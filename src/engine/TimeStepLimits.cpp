#include "engine/TimeStepLimits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/contact/ContactSlots.hpp"
#include "core/contact/ParallelBond.hpp"
#include "engine/SceneSetup.hpp"

namespace gpudem {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// G of a material [Pa].
double shear_modulus(const Material& m) { return gpudem::shear_modulus(m.young, m.poisson); }

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

/// ω² of a bond of table `b` between the particles i and j of `particles`.
double bond_omega2(const BondSettings& b, const ParticleStore& particles, std::size_t i,
                   std::size_t j) {
  const BondParams p{b.young,          gpudem::shear_modulus(b.young, b.poisson),
                     b.radius_factor,  b.tensile_strength,
                     b.shear_strength, b.damping_ratio};
  return bond_frequency_squared(
      p, particles.position_radius[i].w, 1 / particles.velocity_inv_mass[i].w,
      particles.position_radius[j].w, 1 / particles.velocity_inv_mass[j].w);
}

/// ω² of the stiffest bond the [[bond]] tables can make between the particles present, each
/// material by its smallest particle (a table of listed pairs: any two materials); 0 without
/// bonds.
double stiffest_bond(const Scene& scene, const ParticleStore& particles) {
  const std::vector<std::size_t> smallest = smallest_particle_per_material(scene, particles);
  const std::size_t none = particles.size();
  double omega2 = 0;
  for (const BondSettings& b : scene.bonds)
    for (std::size_t m = 0; m < smallest.size(); ++m)
      for (std::size_t n = m; n < smallest.size(); ++n) {
        const bool bonded = !b.pairs.empty() || (m == b.a && n == b.b) || (m == b.b && n == b.a);
        if (bonded && smallest[m] != none && smallest[n] != none)
          omega2 = std::max(omega2, bond_omega2(b, particles, smallest[m], smallest[n]));
      }
  return omega2;
}

/// The materials of the plane walls and the mesh walls, each as often as it is used.
std::vector<MaterialId> wall_materials(const Scene& scene) {
  std::vector<MaterialId> ids;
  for (const WallSettings& w : scene.walls) ids.push_back(w.material);
  for (const MeshSettings& m : scene.meshes) ids.push_back(m.material);
  return ids;
}

/// γ of materials a and b when the law adheres by JKR, else 0 [J/m²].
double adhesion(const Scene& scene, std::size_t a, std::size_t b) {
  if (scene.contact.model.cohesion != CohesionLaw::Jkr) return 0;
  return pair_params(scene, static_cast<MaterialId>(a), static_cast<MaterialId>(b)).surface_energy;
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
      pairs.push_back({ra * rb / (ra + rb), ma * mb / (ma + mb), pair_young_modulus(mat_a, mat_b),
                       pair_shear_modulus(mat_a, mat_b), scene.contact.stiffness, v,
                       adhesion(scene, a, b)});
    }
    for (const MaterialId id : wall_materials(scene)) {
      const Material& wall = scene.materials[id];
      pairs.push_back({ra, ma, pair_young_modulus(mat_a, wall), pair_shear_modulus(mat_a, wall),
                       scene.contact.stiffness, v, adhesion(scene, a, id)});
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

/// √(2 |g| H), H the extent of the domain along g: a free fall across the domain [m/s].
double fall_speed(const Scene& scene) {
  const Vec3 g = scene.simulation.gravity;
  const double g_norm = norm(g);
  const double height =
      g_norm > 0 ? extent_along(scene.domain.min, scene.domain.max, (1 / g_norm) * g) : 0.0;
  return std::sqrt(2 * g_norm * height);
}

/// The largest particle speed [m/s].
double fastest_particle(const ParticleStore& particles) {
  double fastest = 0;
  for (const Real4& v : particles.velocity_inv_mass) fastest = std::max(fastest, norm(xyz(v)));
  return fastest;
}

/// |v| + |ω| ρ at the mesh's fastest keyframe, ρ its farthest vertex from the rotation centre
/// at t = 0 (a rigid motion keeps that distance; velocities are linear between keyframes) [m/s].
double fastest_mesh_point(const TriangleMesh& mesh, const MeshSettings& settings) {
  double reach = 0;
  for (const Vec3& v : mesh.vertices) reach = std::max(reach, norm(v - settings.centre));
  double fastest = 0;
  for (const MotionKeyframe& k : settings.keyframes)
    fastest = std::max(fastest, norm(k.velocity) + norm(k.angular_velocity) * reach);
  return fastest;
}

/// √(2 a L) of the fastest piston: a = |P + M g·n| / M its acceleration under its drive alone,
/// L the domain's extent along its normal (from rest across the whole box) [m/s].
double fastest_piston(const Scene& scene) {
  double fastest = 0;
  for (const WallSettings& w : scene.walls) {
    if (!w.loaded()) continue;
    const double drive = std::fabs(w.load + w.mass * dot(scene.simulation.gravity, w.normal));
    const double run = extent_along(scene.domain.min, scene.domain.max, w.normal);
    fastest = std::max(fastest, std::sqrt(2 * drive / w.mass * run));
  }
  return fastest;
}

/// The fastest prescribed velocity of a fixed material (Material::velocity), 0 without one.
double fastest_grip(const Scene& scene) {
  double fastest = 0;
  for (const Material& m : scene.materials)
    if (m.fixed) fastest = std::max(fastest, norm(m.velocity));
  return fastest;
}

/// The contact of particles i and j (j = i allowed: two such particles) at impact speed v.
ImpactPair particle_pair(const Scene& scene, const ParticleStore& particles, std::size_t i,
                         std::size_t j, double v) {
  const double ri = particles.position_radius[i].w, rj = particles.position_radius[j].w;
  const double mi = 1 / particles.velocity_inv_mass[i].w, mj = 1 / particles.velocity_inv_mass[j].w;
  const Material& a = scene.materials[particles.material[i]];
  const Material& b = scene.materials[particles.material[j]];
  return {ri * rj / (ri + rj),      mi * mj / (mi + mj),     pair_young_modulus(a, b),
          pair_shear_modulus(a, b), scene.contact.stiffness, v};
}

/// The contact of particle i with a wall of material `wall` at impact speed v (R* = r, m* = m).
ImpactPair wall_pair(const Scene& scene, const ParticleStore& particles, std::size_t i,
                     MaterialId wall, double v) {
  const Material& a = scene.materials[particles.material[i]];
  const Material& w = scene.materials[wall];
  return {particles.position_radius[i].w, 1 / particles.velocity_inv_mass[i].w,
          pair_young_modulus(a, w),       pair_shear_modulus(a, w),
          scene.contact.stiffness,        v};
}

/// The impact speed at which Normal's peak overlap of `pair` reaches `ratio` × r, by bisection
/// on log v (δ_max grows with v) [m/s].
template <class Normal>
double speed_at_overlap(ImpactPair pair, double r, double ratio) {
  double lo = 1e-9, hi = 1e9;
  for (int k = 0; k < 200; ++k) {
    pair.speed = std::sqrt(lo * hi);
    (Normal::peak_overlap(pair) < ratio * r ? lo : hi) = pair.speed;
  }
  return std::sqrt(lo * hi);
}

/// Keeps the contact in `deepest` when it overlaps deeper, relative to its smaller radius r.
template <class Normal>
void keep_deeper(PeakOverlap& deepest, const ImpactPair& pair, double r, MaterialId material,
                 MaterialId other, bool wall) {
  const double ratio = Normal::peak_overlap(pair) / r;
  if (!(ratio > deepest.ratio)) return;
  deepest = PeakOverlap{ratio,
                        pair.speed,
                        r,
                        material,
                        other,
                        wall,
                        speed_at_overlap<Normal>(pair, r, kUnstableOverlapRatio)};
}

/// PeakOverlap of normal law Normal at impact speed v.
template <class Normal>
PeakOverlap deepest_contact(const Scene& scene, const ParticleStore& particles, double v) {
  PeakOverlap deepest;
  deepest.speed = v;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double ri = particles.position_radius[i].w;
    for (std::size_t j = i; j < particles.size(); ++j) {
      const double rj = particles.position_radius[j].w;
      const bool i_smaller = ri <= rj;
      keep_deeper<Normal>(deepest, particle_pair(scene, particles, i, j, v), std::min(ri, rj),
                          particles.material[i_smaller ? i : j],
                          particles.material[i_smaller ? j : i], false);
    }
    for (const MaterialId wall : wall_materials(scene))
      keep_deeper<Normal>(deepest, wall_pair(scene, particles, i, wall, v), ri,
                          particles.material[i], wall, true);
  }
  return deepest;
}

}  // namespace

/// E* of two materials (HertzNormal).
double pair_young_modulus(const Material& a, const Material& b) {
  return HertzNormal::effective_modulus(a.young, a.poisson, b.young, b.poisson);
}

/// G* of two materials (MindlinTangential).
double pair_shear_modulus(const Material& a, const Material& b) {
  return MindlinTangential::effective_shear_modulus(a.young, a.poisson, b.young, b.poisson);
}

/// The smallest radius in the store, or +inf.
double smallest_radius(const ParticleStore& particles) {
  double r = kInfinity;
  for (const Real4& p : particles.position_radius) r = std::min(r, p.w);
  return r;
}

double fastest_tool(const Scene& scene, const std::vector<MeshWallSetup>& meshes) {
  double fastest = 0;
  for (std::size_t i = 0; i < meshes.size() && i < scene.meshes.size(); ++i)
    fastest = std::max(fastest, fastest_mesh_point(meshes[i].mesh, scene.meshes[i]));
  return fastest;
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

double impact_speed(const Scene& scene, const ParticleStore& particles) {
  if (scene.simulation.impact_speed > 0) return scene.simulation.impact_speed;
  const double v = fall_speed(scene) + fastest_particle(particles);
  return v > 0 ? v : 1.0;
}

double max_speed(const Scene& scene, const ParticleStore& particles,
                 const std::vector<MeshWallSetup>& meshes) {
  return fall_speed(scene) + fastest_particle(particles) + fastest_tool(scene, meshes) +
         fastest_piston(scene) + fastest_grip(scene);
}

double launch_speed(const Scene& scene, const ParticleStore& particles,
                    const std::vector<MeshWallSetup>& meshes) {
  if (scene.simulation.impact_speed > 0) return scene.simulation.impact_speed;
  return fastest_particle(particles) + fastest_tool(scene, meshes);
}

PeakOverlap peak_overlap(const Scene& scene, const ParticleStore& particles, double v) {
  PeakOverlap deepest;
  const ContactModel& model = scene.contact.model;
  visit_slot(NormalSlots{}, static_cast<std::size_t>(model.normal), [&](auto normal) {
    deepest = deepest_contact<decltype(normal)>(scene, particles, v);
  });
  return deepest;
}

TimeStepLimits time_step_limits(const Scene& scene, const ParticleStore& particles,
                                const std::vector<MeshWallSetup>& meshes) {
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
  limits.bond = kInfinity;
  const double bond_omega2 = stiffest_bond(scene, particles);
  if (bond_omega2 > 0) {
    limits.bond = kPi / std::sqrt(bond_omega2);
    limits.stable = std::min(limits.stable, 2 / std::sqrt(bond_omega2));
  }
  limits.max_speed = max_speed(scene, particles, meshes);
  limits.displacement = limits.max_speed > 0 ? scene.simulation.displacement_fraction *
                                                   smallest_radius(particles) / limits.max_speed
                                             : kInfinity;
  return limits;
}

}  // namespace gpudem
