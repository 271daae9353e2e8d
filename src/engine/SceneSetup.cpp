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
#include "engine/BondClods.hpp"
#include "engine/MeshReach.hpp"

namespace gpudem {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

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
  p.effective_young = pair_young_modulus(a, b);
  p.effective_shear = pair_shear_modulus(a, b);
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
  p.surface_energy = value(given.surface_energy, a.surface_energy, b.surface_energy);
}

std::vector<ContactPairParams> pair_table(const Scene& scene) {
  const std::size_t m = scene.materials.size();
  std::vector<ContactPairParams> table(m * m);
  for (MaterialId a = 0; a < m; ++a)
    for (MaterialId b = 0; b < m; ++b) table[a * m + b] = pair_params(scene, a, b);
  return table;
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

/// The largest gap at which JKR adhesion still holds a contact: |δ_c| over every material pair
/// at R* = r_max (a wall's; δ_c grows as R*^{1/3}) [m]; 0 for other cohesion laws.
double largest_pull_off_gap(const Scene& scene, const std::vector<ContactPairParams>& table,
                            double r_max) {
  if (scene.contact.model.cohesion != CohesionLaw::Jkr || !(r_max > 0)) return 0;
  double gap = 0;
  for (const ContactPairParams& p : table) gap = std::max(gap, JkrCohesion::pull_off_gap(p, r_max));
  return gap;
}

/// Refuses a skin that JKR's held contacts outgrow: a contact parts at δ_c, and the neighbour
/// list keeps a pair only while its gap stays under the skin at each build.
void require_skin_covers_pull_off(const Scene& scene, double skin, double gap) {
  if (!(gap > 0) || skin > gap) return;
  throw InputError(scene.file, 0, "neighbor.skin",
                   (scene.neighbor.skin > 0 ? "skin "
                                            : "the automatic skin (half the smallest "
                                              "radius) ") +
                       short_number(skin) + " m does not cover the JKR pull-off gap " +
                       short_number(gap) + " m at which adhesion parts a contact: set a skin > " +
                       short_number(gap) + " m");
}

/// Refuses a [[bond]] gap that the skin does not hold twice over: bonds form along the neighbour
/// list, and a bond is kept only while its surface gap stays under 0.9 skin (check_bond_reach).
void require_skin_covers_bond_gaps(const Scene& scene, double skin) {
  for (std::size_t k = 0; k < scene.bonds.size(); ++k) {
    const double gap = scene.bonds[k].gap;
    if (gap <= 0.5 * skin) continue;
    throw InputError(scene.file, 0, "bond[" + std::to_string(k) + "].gap",
                     "gap " + short_number(gap) + " m is more than half the neighbour skin " +
                         short_number(skin) +
                         " m, within which bonds form and hold: set neighbor.skin >= " +
                         short_number(2 * gap) + " m or a smaller gap");
  }
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

/// The area of the domain box's cross-section by a plane of unit normal n, at most: for each
/// axis k with n_k ≠ 0, the box's face across k over |n_k| (the section's projection on that
/// face is within the face) [m²].
double largest_section(const Scene& scene, Vec3 n) {
  const Vec3 L = scene.domain.max - scene.domain.min;
  double area = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
    if (axis(n, k) != 0)
      area = std::min(area, axis(L, (k + 1) % 3) * axis(L, (k + 2) % 3) / std::fabs(axis(n, k)));
  return area;
}

/// Refuses a piston lighter than a close-packed layer of the heaviest particles against it:
/// N = A / (2√3 r²) spheres of radius r (the largest) on its section A, each of the heaviest
/// mass m. A piston of mass M pressed by N contacts of stiffness k oscillates at
/// ω² ≈ k/m + N k/M; with M ≥ N m that stays within √2 of a particle's own contact frequency,
/// which the time step resolves, and the contact law may treat the piston as a fixed wall.
void require_pistons_outweigh_a_layer(const Scene& scene, const ParticleStore& particles) {
  const double r_max = largest_radius(particles);
  double m_max = 0;
  for (const Real4& v : particles.velocity_inv_mass) m_max = std::max(m_max, 1 / v.w);
  for (std::size_t k = 0; k < scene.walls.size(); ++k) {
    const WallSettings& w = scene.walls[k];
    if (!w.loaded() || r_max == 0) continue;
    const double layer = largest_section(scene, w.normal) / (2 * std::sqrt(3.0) * r_max * r_max);
    const double least = layer * m_max;
    if (w.mass >= least) continue;
    throw InputError(scene.file, w.mass_line, "wall[" + std::to_string(k) + "].mass",
                     "piston '" + w.name + "' of " + short_number(w.mass) +
                         " kg is lighter than a close-packed layer of the heaviest particles "
                         "against it (" +
                         short_number(layer) + " particles of " + short_number(m_max) + " kg, " +
                         short_number(least) +
                         " kg), which the time step would not resolve; give it at least that "
                         "mass");
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
          " s and 2/omega of the stiffest contact or bond; contact duration t_c = " +
          short_number(limits.contact_duration) +
          " s); use a smaller dt or dt = \"auto\", or set simulation.allow_unstable_dt = true "
          "to run anyway");
}

/// What the deepest impact of `p` would do, and how fast this law holds it.
std::string impact_text(const Scene& scene, const PeakOverlap& p) {
  const std::string against = p.wall ? "a wall of '" + scene.materials[p.other].name + "'"
                                     : "a '" + scene.materials[p.other].name + "' particle";
  return "an impact at v = " + short_number(p.speed) + " m/s of a '" +
         scene.materials[p.material].name + "' particle of radius " + short_number(p.radius) +
         " m against " + against + " would overlap by " + short_number(100 * p.ratio) +
         " % of its radius at the peak (" + contact_model_name(scene.contact.model) +
         ", undamped), past the " + short_number(100 * kUnstableOverlapRatio) +
         " % at which a run stops as unstable; this contact holds impacts up to " +
         short_number(p.unstable_speed) + " m/s";
}

/// The key that stiffens the deepest contact: contact.stiffness for a law of one stiffness,
/// else the Young's modulus of the softer material of the contact.
std::string stiffness_key(const Scene& scene, const PeakOverlap& p) {
  if (scene.contact.model.normal == NormalLaw::Hooke) return "contact.stiffness";
  const bool other_softer = scene.materials[p.other].young < scene.materials[p.material].young;
  return "material[" + std::to_string(other_softer ? p.other : p.material) + "].young";
}

/// Refuses impacts whose peak overlap would pass kUnstableOverlapRatio unless the scene allows
/// it, naming the key that stiffens the contact.
void require_holdable_impacts(const Scene& scene, const PeakOverlap& p) {
  if (!(p.ratio > kUnstableOverlapRatio) || scene.simulation.allow_unstable_dt) return;
  const std::string key = stiffness_key(scene, p);
  throw InputError(scene.file, 0, key,
                   impact_text(scene, p) + ": stiffen the contact (" + key +
                       ") or lower the speed, or set simulation.allow_unstable_dt = true to run "
                       "anyway");
}

}  // namespace

ContactPairParams pair_params(const Scene& scene, MaterialId a, MaterialId b) {
  ContactPairParams p;
  const Material& ma = scene.materials[a];
  const Material& mb = scene.materials[b];
  set_elastic_constants(p, scene.contact, ma, mb);
  set_mixed_values(p, scene.contact.mixing, ma, mb, pair_override(scene.contact, a, b));
  return p;
}

std::vector<std::string> time_step_warnings(const Scene& scene, const ParticleStore& particles,
                                            const EngineSetup& setup) {
  std::vector<std::string> warnings;
  const PeakOverlap launched =
      peak_overlap(scene, particles, launch_speed(scene, particles, setup.meshes));
  const PeakOverlap fallen = peak_overlap(scene, particles, impact_speed(scene, particles));
  if (launched.ratio > kUnstableOverlapRatio)
    warnings.push_back(impact_text(scene, launched) +
                       " (run anyway: simulation.allow_unstable_dt)");
  else if (fallen.ratio > kUnstableOverlapRatio)
    warnings.push_back(impact_text(scene, fallen) +
                       "; that speed is a free fall across the whole domain, an upper bound: "
                       "particles falling that far at once would stop the run");
  const TimeStepLimits limits = time_step_limits(scene, particles, setup.meshes);
  const double r_min = smallest_radius(particles);
  const double moved = limits.max_speed * setup.dt / r_min;
  if (!scene.simulation.dt_auto && moved > scene.simulation.displacement_fraction)
    warnings.push_back("dt = " + short_number(setup.dt) + " s lets a particle at v_max = " +
                       short_number(limits.max_speed) + " m/s move " + short_number(moved) +
                       " of the smallest radius in one step, more than "
                       "simulation.displacement_fraction = " +
                       short_number(scene.simulation.displacement_fraction) +
                       ", so contacts may start that deep; dt = \"auto\" keeps within it");
  return warnings;
}

ExactUnits exact_units(const Scene& scene, const ParticleStore& particles) {
  constexpr double standard_gravity = 9.80665;  // m/s² (CGPM 1901)
  double lightest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Real4& x = particles.position_radius[i];
    const double inv_mass = particles.velocity_inv_mass[i].w;
    const double mass = inv_mass > 0 ? 1 / inv_mass
                                     : scene.materials[particles.material[i]].density * 4.0 / 3.0 *
                                           kPi * x.w * x.w * x.w;
    lightest = std::min(lightest, mass);
  }
  const double r_min = smallest_radius(particles);
  if (!(std::isfinite(lightest) && lightest > 0 && std::isfinite(r_min) && r_min > 0))
    return exact_units_for_grains(1.0, 1.0);  // nothing to sum
  return exact_units_for_grains(lightest * standard_gravity, r_min);
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
  for (std::uint32_t k = 0; k < scene.walls.size(); ++k) {
    const WallSettings& w = scene.walls[k];
    s.walls.push_back(PlaneWall{w.point, w.normal, w.material, Vec3{}});
    if (w.loaded()) s.pistons.push_back(PistonSetup{k, w.mass, w.load});
  }
  require_pistons_outweigh_a_layer(scene, particles);
  s.meshes = mesh_walls(scene);
  s.exact_units = exact_units(scene, particles);
  const double r_min = smallest_radius(particles);
  s.skin =
      scene.neighbor.skin > 0 ? scene.neighbor.skin : (std::isfinite(r_min) ? 0.5 * r_min : 0.0);
  require_meshes_fit_periodic_axes(scene, s.meshes, largest_radius(particles), s.skin);
  require_skin_covers_pull_off(
      scene, s.skin, largest_pull_off_gap(scene, s.pair_params, largest_radius(particles)));
  require_skin_covers_bond_gaps(scene, s.skin);
  s.bonds = scene.bonds;
  s.clods = draw_clods(scene);
  for (const BondSettings& b : scene.bonds)
    s.bond_pairs.push_back(b.pairs.empty() ? std::vector<ListedBond>{} : read_bond_pairs(b.pairs));
  for (const Material& m : scene.materials)
    if (m.fixed || m.drag > 0) s.material_motion.resize(scene.materials.size());
  for (std::size_t k = 0; k < s.material_motion.size(); ++k)
    s.material_motion[k] = {scene.materials[k].fixed ? 1u : 0u, scene.materials[k].drag,
                            scene.materials[k].velocity};
  require_meshes_meet_the_domain(scene, s.meshes, std::isfinite(r_min) ? 2 * r_min : 0.0);
  const TimeStepLimits limits = time_step_limits(scene, particles, s.meshes);
  require_stable_dt(scene, limits);
  require_holdable_impacts(
      scene, peak_overlap(scene, particles, launch_speed(scene, particles, s.meshes)));
  if (scene.simulation.dt_auto) {
    const double fraction = scene.simulation.dt_fraction;
    const double step =
        scene.simulation.dt_adaptive ? fraction * limits.critical() : limits.automatic(fraction);
    s.dt = std::isfinite(step) ? step : scene.simulation.end_time;
  } else {
    s.dt = scene.simulation.dt;
  }
  return s;
}

ParticleStore setup_deciding_particles(const Scene& scene, const ParticleStore& particles) {
  const std::size_t n = particles.size();
  std::vector<std::size_t> chosen = smallest_particle_per_material(scene, particles);
  std::size_t largest = n, lightest = n, heaviest = n, fastest = n;
  const auto radius = [&](std::size_t i) { return particles.position_radius[i].w; };
  const auto inv_mass = [&](std::size_t i) { return particles.velocity_inv_mass[i].w; };
  const auto speed2 = [&](std::size_t i) { return norm2(xyz(particles.velocity_inv_mass[i])); };
  for (std::size_t i = 0; i < n; ++i) {
    if (largest == n || radius(i) > radius(largest)) largest = i;
    if (lightest == n || inv_mass(i) > inv_mass(lightest)) lightest = i;
    if (heaviest == n || inv_mass(i) < inv_mass(heaviest)) heaviest = i;
    if (fastest == n || speed2(i) > speed2(fastest)) fastest = i;
  }
  chosen.insert(chosen.end(), {largest, lightest, heaviest, fastest});
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  ParticleStore out;
  for (const std::size_t i : chosen)
    if (i != n) out.append_row(particles, i);  // n: an absent material, or no particles
  return out;
}

}  // namespace gpudem
