// JKR adhesion through the whole engine: two spheres, and a sphere and a wall, meet without
// damping. Before touch there is no force; the contact forms at touch, pulls with at most the
// pull-off force 3/2 π γ R* and holds until the overlap reaches δ_c, where it parts, taking the
// work of adhesion W = −∫_{δ_c}^0 F dδ with it: the rebound speed is v √(1 − W/K), K = ½ m* v²
// (Johnson, Kendall & Roberts 1971; W here integrated from the JKR relation's parametric form).
// Below K = W the pair is captured and never parts.
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
constexpr double kDensity = 2500, kRadius = 1e-3, kGamma = 0.5;  // [kg/m³], [m], [J/m²]
constexpr ContactModel kElasticJkr{NormalLaw::Hertz, DampingLaw::None, TangentialLaw::None,
                                   RollingLaw::None, CohesionLaw::Jkr};

Material sticky_material() {
  Material m;
  m.name = "sticky";
  m.density = kDensity;
  m.young = 1e7;
  m.poisson = 0.3;
  m.restitution = 1;
  m.surface_energy = kGamma;
  return m;
}

/// The JKR pair of two sticky_material surfaces with effective radius R*.
struct JkrPair {
  double young, radius, mass;
  /// a_c = (π γ R*²/(8E*))^{1/3}.
  double parting_radius() const { return std::cbrt(kPi * kGamma * radius * radius / (8 * young)); }
  double parting_overlap() const {
    return -0.75 * std::cbrt(kPi * kPi * kGamma * kGamma * radius / (young * young));
  }
  double pull_off() const { return 1.5 * kPi * kGamma * radius; }
  /// F(a) = 4E* a³/(3R*) − √(8π γ E* a³) and δ(a) = a²/R* − √(2π γ a/E*).
  double force(double a) const {
    return 4 * young * a * a * a / (3 * radius) - std::sqrt(8 * kPi * kGamma * young * a * a * a);
  }
  double overlap(double a) const {
    return a * a / radius - std::sqrt(2 * kPi * kGamma * a / young);
  }
  /// W = −∫_{δ_c}^0 F dδ along a from a_c to the touch radius a₀ (δ(a₀) = 0), midpoint rule.
  double work_of_adhesion() const {
    const double a_c = parting_radius(), a_0 = std::cbrt(16.0) * a_c;
    const int n = 100000;
    double work = 0;
    for (int k = 0; k < n; ++k) {
      const double a0 = a_c + (a_0 - a_c) * k / n, a1 = a_c + (a_0 - a_c) * (k + 1) / n;
      work -= force(0.5 * (a0 + a1)) * (overlap(a1) - overlap(a0));
    }
    return work;
  }
};

double effective_young(const Material& m) {
  return 1 / (2 * (1 - m.poisson * m.poisson) / m.young);
}

/// What one sticky impact showed, sampled after every step.
struct StickyImpact {
  double force_before_touch = 0;  ///< largest |F_n| before the first touch [N]
  double largest_pull = 0;        ///< [N]
  double last_held_overlap = 0;   ///< the smallest δ at which the contact still pulled [m]
  bool parted = false;
  double rebound_speed = 0;  ///< [m/s]
};

class JkrImpact : public BackendTest {
 public:
  /// Runs particle 0 into particle 1 (or the floor) for at most `steps` steps.
  StickyImpact collide(const Scene& scene, ParticleStore particles, long steps) {
    return collide(scene, make_engine_setup(scene, particles), particles, steps);
  }
  /// The same on a given engine setup (a floor that is a mesh).
  StickyImpact collide(const Scene& scene, const EngineSetup& setup, ParticleStore particles,
                       long steps) {
    const bool on_wall = !scene.walls.empty() || !setup.meshes.empty();
    auto engine = make_engine(setup);
    engine->set_particles(particles);
    StickyImpact impact;
    bool touched = false;
    for (long n = 0; n < steps; ++n) {
      engine->step();
      engine->get_particles(particles);
      const Sample s = sample(particles, on_wall);
      if (!touched && s.overlap <= 0) {
        impact.force_before_touch = std::max(impact.force_before_touch, std::abs(s.force));
        continue;
      }
      touched = true;
      if (s.force != 0) {
        impact.largest_pull = std::max(impact.largest_pull, -s.force);
        impact.last_held_overlap = std::min(impact.last_held_overlap, s.overlap);
      } else {
        impact.parted = true;
        impact.rebound_speed = -s.overlap_rate;
        return impact;
      }
    }
    return impact;
  }

 private:
  struct Sample {
    double overlap, overlap_rate, force;
  };
  /// δ, δ̇ (positive approaching) and F_n (positive repulsive) of particle 0 with 1 or the floor.
  static Sample sample(const ParticleStore& p, bool on_wall) {
    if (on_wall) {
      const double force = p.force[0].z;
      return {p.position_radius[0].w - p.position_radius[0].z, -p.velocity_inv_mass[0].z, force};
    }
    const std::size_t a = p.id[0] == 0 ? 0 : 1, b = 1 - a;
    const Vec3 d = xyz(p.position_radius[b]) - xyz(p.position_radius[a]);
    const Vec3 n = (1 / norm(d)) * d;
    return {p.position_radius[a].w + p.position_radius[b].w - norm(d),
            dot(xyz(p.velocity_inv_mass[a]) - xyz(p.velocity_inv_mass[b]), n), -dot(p.force[a], n)};
  }
};

/// A scene without gravity around the origin, explicit dt, the elastic JKR law.
Scene sticky_scene(bool on_wall, double dt) {
  Scene scene = basic_scene({-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}, 0, 1, 0);
  scene.materials = {sticky_material()};
  scene.contact.model = kElasticJkr;
  scene.simulation.gravity = {0, 0, 0};
  scene.simulation.dt_auto = false;
  scene.simulation.dt = dt;
  if (on_wall) add_floor(scene, 0);
  return scene;
}

/// Particle 0 at speed v towards particle 1 along x, or towards the floor, from a gap of
/// a hundredth of the radius.
ParticleStore approaching(bool on_wall, double v) {
  const double inv_mass = 1 / sphere_mass(kDensity, kRadius), gap = 0.01 * kRadius;
  ParticleStore p;
  if (on_wall) {
    p.add(0, {0, 0, kRadius + gap}, kRadius, 0, {0, 0, -v}, inv_mass);
  } else {
    p.add(0, {-kRadius - gap, 0, 0}, kRadius, 0, {v, 0, 0}, inv_mass);
    p.add(1, {kRadius, 0, 0}, kRadius, 0, {0, 0, 0}, inv_mass);
  }
  return p;
}

JkrPair pair_of(bool on_wall) {
  const double e = effective_young(sticky_material()), m = sphere_mass(kDensity, kRadius);
  return on_wall ? JkrPair{e, kRadius, m} : JkrPair{e, 0.5 * kRadius, 0.5 * m};
}

/// The impact at K = 2W: no force before touch, the pull-off force, parting at δ_c and the
/// rebound speed v √(1 − W/K) = v/√2, each within 1 %.
void check_parting(JkrImpact& test, bool on_wall) {
  const JkrPair pair = pair_of(on_wall);
  const double work = pair.work_of_adhesion();
  const double v = std::sqrt(4 * work / pair.mass);  // ½ m* v² = 2W
  const Scene scene = sticky_scene(on_wall, 5e-8);
  const StickyImpact impact = test.collide(scene, approaching(on_wall, v), 2000000);
  ASSERT_TRUE(impact.parted);
  EXPECT_EQ(impact.force_before_touch, 0.0);
  const std::string where = on_wall ? "wall_" : "pair_";
  ::testing::Test::RecordProperty(where + "pull_off", significant(impact.largest_pull));
  ::testing::Test::RecordProperty(where + "pull_off_expected", significant(pair.pull_off()));
  ::testing::Test::RecordProperty(where + "pull_off_relative_error",
                                  significant(impact.largest_pull / pair.pull_off() - 1));
  EXPECT_NEAR(impact.largest_pull, pair.pull_off(), 0.01 * pair.pull_off());
  const double dc = pair.parting_overlap();
  ::testing::Test::RecordProperty(where + "last_held_overlap",
                                  significant(impact.last_held_overlap));
  ::testing::Test::RecordProperty(where + "parting_overlap", significant(dc));
  EXPECT_LE(impact.last_held_overlap, 0.99 * dc);
  EXPECT_GE(impact.last_held_overlap, dc);
  const double e = impact.rebound_speed / v;
  ::testing::Test::RecordProperty(where + "restitution", significant(e));
  ::testing::Test::RecordProperty(where + "restitution_relative_error",
                                  significant(e / std::sqrt(0.5) - 1));
  EXPECT_NEAR(e, std::sqrt(0.5), 0.01 * std::sqrt(0.5));
}

TEST_P(JkrImpact, PairPartsAtDeltaCAndKeepsTheWorkOfAdhesion) { check_parting(*this, false); }
TEST_P(JkrImpact, WallPartsAtDeltaCAndKeepsTheWorkOfAdhesion) { check_parting(*this, true); }

/// At K = 0.8 W the sphere stays on the wall: over forty contact times it never parts.
TEST_P(JkrImpact, BelowTheWorkOfAdhesionTheSphereIsCaptured) {
  const JkrPair pair = pair_of(true);
  const double v = std::sqrt(1.6 * pair.work_of_adhesion() / pair.mass);
  const StickyImpact impact = collide(sticky_scene(true, 5e-8), approaching(true, v), 400000);
  EXPECT_FALSE(impact.parted);
  EXPECT_GT(impact.largest_pull, 0.5 * pair.pull_off());
  EXPECT_GT(impact.last_held_overlap, pair.parting_overlap());
}

/// The floor as a mesh of two triangles, the sphere coming down on their shared diagonal: the
/// same pull-off, parting overlap and rebound as on the plane wall.
TEST_P(JkrImpact, MeshFloorHoldsAndPartsAsThePlaneWall) {
  const JkrPair pair = pair_of(true);
  const double v = std::sqrt(4 * pair.work_of_adhesion() / pair.mass);
  const StickyImpact plane = collide(sticky_scene(true, 5e-8), approaching(true, v), 2000000);
  const Scene scene = sticky_scene(false, 5e-8);
  const ParticleStore sphere = approaching(true, v);
  EngineSetup setup = make_engine_setup(scene, sphere);
  MeshWallSetup floor;
  const Vec3 a{-0.005, -0.005, 0}, b{0.005, -0.005, 0}, c{0.005, 0.005, 0}, d{-0.005, 0.005, 0};
  floor.mesh = build_mesh({{a, b, c}, {a, c, d}});
  setup.meshes.push_back(floor);
  const StickyImpact mesh = collide(scene, setup, sphere, 2000000);
  ASSERT_TRUE(plane.parted);
  ASSERT_TRUE(mesh.parted);
  EXPECT_EQ(mesh.force_before_touch, 0.0);
  RecordProperty("mesh_restitution", significant(mesh.rebound_speed / v));
  RecordProperty("mesh_last_held_overlap", significant(mesh.last_held_overlap));
  EXPECT_NEAR(mesh.largest_pull, plane.largest_pull, 1e-9 * plane.largest_pull);
  EXPECT_NEAR(mesh.last_held_overlap, plane.last_held_overlap, 1e-3 * -pair.parting_overlap());
  EXPECT_NEAR(mesh.rebound_speed, plane.rebound_speed, 1e-6 * v);
}

GPUDEM_INSTANTIATE_BACKENDS(JkrImpact);

}  // namespace
}  // namespace gpudem::test
