// Normal impacts against closed forms: the elastic Hertz impact (Johnson 1985), the restitution
// of the damped Hertz and Hooke laws, and the viscoelastic law of Brilliantov et al. (1996).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDensity = 2500;  // [kg/m³]

/// A sphere or wall material of density 2500 kg/m³.
Material elastic_material(double young, double poisson, double restitution) {
  Material m;
  m.name = "m" + std::to_string(young);
  m.density = kDensity;
  m.young = young;
  m.poisson = poisson;
  m.restitution = restitution;
  return m;
}

/// 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
double effective_young(const Material& a, const Material& b) {
  return 1 / ((1 - a.poisson * a.poisson) / a.young + (1 - b.poisson * b.poisson) / b.young);
}

/// Records `name` (measured), `name_expected` and `name_relative_error` for the validation table.
void record(const std::string& name, double measured, double expected) {
  ::testing::Test::RecordProperty(name, significant(measured));
  ::testing::Test::RecordProperty(name + "_expected", significant(expected));
  ::testing::Test::RecordProperty(name + "_relative_error", significant(measured / expected - 1));
}

double reduced(double a, double b) { return a * b / (a + b); }

/// Elastic Hertz impact at approach speed v (Johnson, Contact Mechanics, 1985, §11.4):
/// δ_max = (15 m* v² / (16 E* √R*))^{2/5}, F_max = 4/3 E* √R* δ_max^{3/2} and
/// t_c = 2 (δ_max / v) ∫₀¹ (1 − x^{5/2})^{−1/2} dx = 2 (δ_max / v) (2/5) B(2/5, 1/2),
/// i.e. t_c = 2.868 (m*² / (R* E*² v))^{1/5}.
struct HertzImpact {
  double overlap, force, duration;
};

HertzImpact hertz_impact(double e_star, double r_star, double m_star, double v) {
  HertzImpact h;
  h.overlap = std::pow(15 * m_star * v * v / (16 * e_star * std::sqrt(r_star)), 0.4);
  h.force = 4.0 / 3.0 * e_star * std::sqrt(r_star) * std::pow(h.overlap, 1.5);
  const double beta_integral = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  h.duration = 2 * h.overlap / v * 0.4 * beta_integral;
  return h;
}

/// Contact duration of the undamped Hooke oscillator, t_c = π √(m* / k_n).
double hooke_duration(double stiffness, double m_star) {
  return kPi * std::sqrt(m_star / stiffness);
}

/// A scene without gravity in a 0.2 m box around the origin; the contact law `model`, the
/// given materials and an explicit time step.
Scene impact_scene(const ContactModel& model, const std::vector<Material>& materials, double dt) {
  Scene scene = basic_scene({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}, 0, 1, 0);
  scene.materials = materials;
  scene.contact.model = model;
  scene.simulation.gravity = {0, 0, 0};
  scene.simulation.dt_auto = false;
  scene.simulation.dt = dt;
  return scene;
}

/// One contact seen after a step: overlap δ, its rate δ̇ (positive approaching) and the normal
/// force F_n (positive repulsive).
struct ContactState {
  double overlap = 0, overlap_rate = 0, normal_force = 0;
};

std::size_t index_of(const ParticleStore& p, ParticleId id) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] == id) return i;
  return p.size();
}

/// Particles 0 and 1: n from 0 to 1, δ = r₀ + r₁ − |x₁ − x₀|, δ̇ = (v₀ − v₁)·n, F_n = −F₀·n.
ContactState pair_state(const ParticleStore& p) {
  const std::size_t a = index_of(p, 0), b = index_of(p, 1);
  const Vec3 d = xyz(p.position_radius[b]) - xyz(p.position_radius[a]);
  const Vec3 n = (1 / norm(d)) * d;
  ContactState s;
  s.overlap = p.position_radius[a].w + p.position_radius[b].w - norm(d);
  s.overlap_rate = dot(xyz(p.velocity_inv_mass[a]) - xyz(p.velocity_inv_mass[b]), n);
  s.normal_force = -dot(p.force[a], n);
  return s;
}

/// Particle 0 on the floor z = 0: δ = r − z, δ̇ = −v_z, F_n = −(force on the wall)_z, read
/// from the engine's diagnostics while in contact (0 before).
ContactState wall_state(const ParticleStore& p, const StepEngine& engine) {
  ContactState s;
  s.overlap = p.position_radius[0].w - p.position_radius[0].z;
  s.overlap_rate = -p.velocity_inv_mass[0].z;
  s.normal_force = s.overlap > 0 ? -engine.diagnostics().wall_force[0].z : 0.0;
  return s;
}

/// What one normal impact measured, sampled after every step.
struct ImpactRecord {
  double approach_speed = 0;             ///< normal relative speed before contact [m/s]
  double rebound_speed = 0;              ///< normal relative speed after separation [m/s]
  double peak_overlap = 0;               ///< [m]
  double peak_force = 0;                 ///< [N]
  double duration = 0;                   ///< time with δ > 0, crossings interpolated [s]
  double largest_pull = 0;               ///< largest attractive normal force, ≥ 0 [N]
  std::vector<ContactState> in_contact;  ///< the samples with δ > 0
  double restitution() const { return rebound_speed / approach_speed; }
};

class NormalImpact : public BackendTest {
 protected:
  /// Runs `particles` (0 and 1 approaching along x, or 0 falling on the floor when the scene
  /// has a wall) until the contact has opened again.
  ImpactRecord collide(const Scene& scene, ParticleStore particles) {
    const bool on_wall = !scene.walls.empty();
    auto engine = make_engine(make_engine_setup(scene, particles));
    engine->set_particles(particles);
    ImpactRecord impact;
    ContactState previous = sample(*engine, on_wall);
    impact.approach_speed = previous.overlap_rate;
    const double dt = scene.simulation.dt;
    // Time within the last step at which δ crossed zero, by linear interpolation.
    auto crossing = [&](const ContactState& s) {
      return dt * previous.overlap / (previous.overlap - s.overlap);
    };
    bool touched = false;
    for (long n = 0; n < 1000000; ++n) {
      engine->step();
      const ContactState s = sample(*engine, on_wall);
      if (s.overlap > 0) {
        impact.duration += touched ? dt : dt - crossing(s);
        touched = true;
        impact.in_contact.push_back(s);
        impact.peak_overlap = std::max(impact.peak_overlap, s.overlap);
        impact.peak_force = std::max(impact.peak_force, s.normal_force);
        impact.largest_pull = std::max(impact.largest_pull, -s.normal_force);
      } else if (touched) {
        impact.duration += crossing(s);
        impact.rebound_speed = -s.overlap_rate;
        return impact;
      }
      previous = s;
    }
    ADD_FAILURE() << "the contact did not open again";
    return impact;
  }

 private:
  ContactState sample(StepEngine& engine, bool on_wall) {
    engine.get_particles(current_);
    return on_wall ? wall_state(current_, engine) : pair_state(current_);
  }
  ParticleStore current_;
};

/// Particle 0 (material 0, radius r0) moving at +v along x towards particle 1 (material 1,
/// radius r1) at rest, the gap being a tenth of r1.
ParticleStore approaching_pair(const Scene& scene, double r0, double r1, double v) {
  ParticleStore p;
  const double gap = 0.1 * r1;
  p.add(0, {-r0 - gap, 0, 0}, r0, 0, {v, 0, 0}, 1 / sphere_mass(scene.materials[0].density, r0));
  p.add(1, {r1, 0, 0}, r1, 1, {0, 0, 0}, 1 / sphere_mass(scene.materials[1].density, r1));
  return p;
}

/// Particle 0 (material 0) falling at speed v on the floor z = 0 from a tenth of r above it.
ParticleStore falling_sphere(const Scene& scene, double r, double v) {
  ParticleStore p;
  p.add(0, {0, 0, 1.1 * r}, r, 0, {0, 0, -v}, 1 / sphere_mass(scene.materials[0].density, r));
  return p;
}

void add_wall_of_material(Scene& scene, MaterialId material) {
  add_floor(scene, 0);
  scene.walls.back().material = material;
}

constexpr ContactModel kElasticHertz{NormalLaw::Hertz, DampingLaw::None, TangentialLaw::None,
                                     RollingLaw::None, CohesionLaw::None};

/// Records measured vs closed-form values and checks them within 1 %.
void expect_hertz_impact(const ImpactRecord& r, const HertzImpact& h) {
  record("duration", r.duration, h.duration);
  record("peak_overlap", r.peak_overlap, h.overlap);
  record("peak_force", r.peak_force, h.force);
  EXPECT_NEAR(r.duration, h.duration, 0.01 * h.duration);
  EXPECT_NEAR(r.peak_overlap, h.overlap, 0.01 * h.overlap);
  EXPECT_NEAR(r.peak_force, h.force, 0.01 * h.force);
  EXPECT_NEAR(r.restitution(), 1.0, 0.01);
}

/// Two spheres of different materials and radii, 1 m/s: t_c, δ_max and F_max of Hertz.
TEST_P(NormalImpact, ElasticHertzPairMatchesClosedForm) {
  const std::vector<Material> materials{elastic_material(1e8, 0.3, 1),
                                        elastic_material(2e8, 0.25, 1)};
  const double r0 = 0.01, r1 = 0.006, v = 1;
  const double m_star = reduced(sphere_mass(kDensity, r0), sphere_mass(kDensity, r1));
  const HertzImpact h =
      hertz_impact(effective_young(materials[0], materials[1]), reduced(r0, r1), m_star, v);
  const Scene scene = impact_scene(kElasticHertz, materials, h.duration / 1000);
  expect_hertz_impact(collide(scene, approaching_pair(scene, r0, r1, v)), h);
}

/// A sphere on a wall of another material, 1 m/s: R* = r, m* = m.
TEST_P(NormalImpact, ElasticHertzWallMatchesClosedForm) {
  const std::vector<Material> materials{elastic_material(1e8, 0.3, 1),
                                        elastic_material(2e8, 0.25, 1)};
  const double r = 0.01, v = 1;
  const HertzImpact h =
      hertz_impact(effective_young(materials[0], materials[1]), r, sphere_mass(kDensity, r), v);
  Scene scene = impact_scene(kElasticHertz, materials, h.duration / 1000);
  add_wall_of_material(scene, 1);
  expect_hertz_impact(collide(scene, falling_sphere(scene, r, v)), h);
}

/// The restitution damping gives the input e for e ∈ {0.05, …, 1} (EDEM / DEM-Engine form for
/// Hertz, Tsuji et al. 1992 for Hooke): measured e within 1 %. dt = t_c / 1000.
class Restitution : public NormalImpact {
 protected:
  void check(NormalLaw law, bool on_wall) {
    const double r0 = 0.01, r1 = 0.006, v = 0.5, stiffness = 1e4;
    const ContactModel model{law, DampingLaw::Restitution, TangentialLaw::None, RollingLaw::None,
                             CohesionLaw::None};
    for (const double e : {0.05, 0.2, 0.5, 0.8, 0.95, 1.0}) {
      const Material material = elastic_material(1e8, 0.3, e);
      const double m0 = sphere_mass(kDensity, r0);
      const double m_star = on_wall ? m0 : reduced(m0, sphere_mass(kDensity, r1));
      const double r_star = on_wall ? r0 : reduced(r0, r1);
      const double t_c =
          law == NormalLaw::Hertz
              ? hertz_impact(effective_young(material, material), r_star, m_star, v).duration
              : hooke_duration(stiffness, m_star);
      Scene scene = impact_scene(model, {material, material}, t_c / 1000);
      scene.contact.stiffness = stiffness;
      if (on_wall) add_wall_of_material(scene, 1);
      const ImpactRecord impact = collide(
          scene, on_wall ? falling_sphere(scene, r0, v) : approaching_pair(scene, r0, r1, v));
      RecordProperty("e_" + significant(e), significant(impact.restitution()));
      EXPECT_NEAR(impact.restitution(), e, 0.01 * e) << "input e = " << e;
    }
  }
};

TEST_P(Restitution, HertzPair) { check(NormalLaw::Hertz, false); }
TEST_P(Restitution, HertzWall) { check(NormalLaw::Hertz, true); }
TEST_P(Restitution, HookePair) { check(NormalLaw::Hooke, false); }
TEST_P(Restitution, HookeWall) { check(NormalLaw::Hooke, true); }

/// Viscoelastic law F_n = max(0, 4/3 E* √R* (δ^{3/2} + A √δ δ̇)) (Brilliantov et al., Phys.
/// Rev. E 53 (1996) 5382): never attractive, e < 1 falling with the impact speed, and for
/// small A, 1 − e = C₁ A (4/3 E*√R*/m*)^{2/5} v^{1/5} + O(A²) (Ramírez et al., Phys. Rev. E 60
/// (1999) 4465), so (1 − e(v₂)) / (1 − e(v₁)) = (v₂/v₁)^{1/5}.
TEST_P(NormalImpact, ViscoelasticNeverPullsAndFollowsFifthRootLaw) {
  const double r = 0.01, a = 1e-5;
  Material material = elastic_material(1e8, 0.3, 1);
  material.viscoelastic_time = a;
  const double e_star = effective_young(material, material);
  const ContactModel model{NormalLaw::Hertz, DampingLaw::Viscoelastic, TangentialLaw::None,
                           RollingLaw::None, CohesionLaw::None};
  const std::vector<double> speeds{0.5, 1, 2};
  std::vector<double> restitution;
  for (const double v : speeds) {
    const double t_c = hertz_impact(e_star, r, sphere_mass(kDensity, r), v).duration;
    Scene scene = impact_scene(model, {material}, t_c / 1000);
    add_wall_of_material(scene, 0);
    const ImpactRecord impact = collide(scene, falling_sphere(scene, r, v));
    // Steps where the unclamped law would pull: the end of the contact, δ < A |δ̇|.
    int would_pull = 0;
    for (const ContactState& s : impact.in_contact)
      if (s.overlap * std::sqrt(s.overlap) + a * std::sqrt(s.overlap) * s.overlap_rate < 0)
        ++would_pull;
    RecordProperty("e_at_" + significant(v), significant(impact.restitution()));
    EXPECT_EQ(impact.largest_pull, 0.0) << "v = " << v;
    EXPECT_GT(would_pull, 0) << "v = " << v << ": the no-attraction clamp was never needed";
    EXPECT_LT(impact.restitution(), 1.0);
    restitution.push_back(impact.restitution());
  }
  EXPECT_GT(restitution[0], restitution[1]);
  EXPECT_GT(restitution[1], restitution[2]);
  const double ratio = (1 - restitution[2]) / (1 - restitution[0]);
  const double expected = std::pow(speeds[2] / speeds[0], 0.2);
  record("dissipation_ratio", ratio, expected);
  EXPECT_NEAR(ratio, expected, 0.03 * expected);
}

GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(NormalImpact);
GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Restitution);

}  // namespace
}  // namespace gpudem::test
