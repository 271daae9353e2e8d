// Parallel bonds through the whole engine. A cantilever of twenty spheres joined by bonds,
// clamped by a fixed sphere at x = 0, released from rest under its own weight: its tip swings
// about the static deflection of a beam of the bond's section EI under the spheres' weights as
// point loads, Σ P a²(3L − a)/(6EI) (Euler–Bernoulli), plus Σ P a/(κGA) (Timoshenko,
// κ = 6(1 + ν)/(7 + 6ν) for a circle), at the first natural frequency of that beam with the
// spheres as lumped masses. Pulled along its axis, it stretches by Σ P a/(EA) and rings at the
// quarter-wave frequency c/(4L) of a bar whose wave speed is c = √(E/ρ), ρ the spheres' mass
// per volume of bond. Two spheres pulled apart break their bond when its tensile stress reaches
// the strength, and the bond's elastic energy leaves with it. Loaded to a large deflection and
// brought to rest by drag, the cantilever's tip lies where the elastica puts it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kNodes = 20;  // free spheres of the beam
constexpr double kRadius = 1e-3, kDensity = 1000, kYoung = 1e7, kPoisson = 0.25;
constexpr ContactModel kElasticHertz{NormalLaw::Hertz, DampingLaw::None, TangentialLaw::None,
                                     RollingLaw::None, CohesionLaw::None};

double spacing() { return 2 * kRadius; }
double node_mass() { return sphere_mass(kDensity, kRadius); }
double area() { return kPi * kRadius * kRadius; }
double second_moment() { return 0.25 * kPi * std::pow(kRadius, 4); }

BondSettings bond_between(MaterialId a, MaterialId b) {
  BondSettings bond;
  bond.a = a;
  bond.b = b;
  bond.gap = 1e-5;
  bond.young = kYoung;
  bond.poisson = kPoisson;
  return bond;
}

/// Material 0 the beam's spheres, material 1 the fixed clamp; bonds between touching spheres.
Scene beam_scene(Vec3 gravity, double dt, double drag = 0) {
  Scene s = basic_scene({-0.01, -0.05, -0.05}, {0.06, 0.05, 0.05}, 0, 1, 0);
  s.materials[0].density = kDensity;
  s.materials[0].young = kYoung;
  s.materials[0].drag = drag;
  Material clamp = s.materials[0];
  clamp.name = "clamp";
  clamp.fixed = true;
  s.materials.push_back(clamp);
  s.contact.model = kElasticHertz;
  s.bonds = {bond_between(0, 0), bond_between(1, 0)};
  s.neighbor.skin = 5e-4;
  s.simulation.gravity = gravity;
  s.simulation.dt_auto = false;
  s.simulation.dt = dt;
  return s;
}

/// The clamp (id 0) at the origin and the beam's spheres (ids 1..kNodes) along +x, touching.
ParticleStore beam_particles() {
  ParticleStore p;
  const double inv_mass = 1 / node_mass();
  p.add(0, {0, 0, 0}, kRadius, 1, {0, 0, 0}, inv_mass);
  for (int k = 1; k <= kNodes; ++k)
    p.add(k, {k * spacing(), 0, 0}, kRadius, 0, {0, 0, 0}, inv_mass);
  return p;
}

/// The tip's displacement along one axis, sampled every few steps.
struct TipRecord {
  double interval = 0;  ///< [s] between samples
  std::vector<double> displacement;
};

/// The mean of a swinging record over its whole periods, and the period.
struct Swing {
  double mean = 0, period = 0;
};

/// Upward crossings of the record's mean, then the mean between the first and the last of them
/// (whole periods of the first mode) and the period between them.
Swing whole_periods(const TipRecord& r) {
  const std::vector<double>& w = r.displacement;
  double mean = 0;
  for (const double x : w) mean += x / w.size();
  std::vector<double> crossings;
  std::size_t first = 0, last = 0;
  for (std::size_t k = 1; k < w.size(); ++k)
    if (w[k - 1] < mean && w[k] >= mean) {
      crossings.push_back((k - 1 + (mean - w[k - 1]) / (w[k] - w[k - 1])) * r.interval);
      (crossings.size() == 1 ? first : last) = k;
    }
  Swing s;
  if (crossings.size() < 3) return s;
  for (std::size_t k = first; k < last; ++k) s.mean += w[k] / (last - first);
  s.period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  return s;
}

class BondedBeam : public BackendTest {
 public:
  std::unique_ptr<StepEngine> make_engine_for(const EngineSetup& setup) const {
    return make_engine(setup);
  }

  /// Runs the beam under `gravity` for `steps` steps, sampling the tip's displacement along
  /// `axis` every `every` steps.
  TipRecord swing(Vec3 gravity, double dt, long steps, int every, int axis_index, double drag = 0) {
    const Scene scene = beam_scene(gravity, dt, drag);
    ParticleStore p = beam_particles();
    auto engine = make_engine(make_engine_setup(scene, p));
    engine->set_particles(p);
    engine->create_bonds();
    EXPECT_EQ(engine->diagnostics().bond_count, std::uint64_t(kNodes));
    TipRecord record{every * dt, {}};
    const double start = axis(Vec3{kNodes * spacing(), 0, 0}, axis_index);
    for (long n = 0; n < steps; ++n) {
      engine->step();
      if (n % every != every - 1) continue;
      engine->get_particles(p);
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p.id[i] == ParticleId(kNodes))
          record.displacement.push_back(axis(xyz(p.position_radius[i]), axis_index) - start);
    }
    EXPECT_EQ(engine->diagnostics().broken_bond_count, 0u);
    return record;
  }
};

/// Σ P a²(3L − a)/(6EI): the tip deflection of an Euler–Bernoulli cantilever of length L under
/// the spheres' weights P at a = k d.
double euler_bernoulli_tip(double weight) {
  const double length = kNodes * spacing();
  double tip = 0;
  for (int k = 1; k <= kNodes; ++k) {
    const double a = k * spacing();
    tip += weight * a * a * (3 * length - a) / (6 * kYoung * second_moment());
  }
  return tip;
}

/// The shear deflection Σ P a/(κGA) that Timoshenko's beam adds.
double timoshenko_shear_tip(double weight) {
  const double kappa = 6 * (1 + kPoisson) / (7 + 6 * kPoisson);
  const double shear = kYoung / (2 * (1 + kPoisson));
  double tip = 0;
  for (int k = 1; k <= kNodes; ++k) tip += weight * k * spacing() / (kappa * shear * area());
  return tip;
}

/// The first bending frequency of the Euler–Bernoulli cantilever with the spheres as point
/// masses m at a = k d [Hz]: ω² = 1/λ, λ the largest eigenvalue of m F, F the beam's flexibility
/// between the masses (power iteration).
double lumped_first_frequency() {
  const double ei = kYoung * second_moment();
  std::vector<double> v(kNodes, 1.0), next(kNodes);
  double lambda = 0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    for (int i = 0; i < kNodes; ++i) {
      next[i] = 0;
      for (int j = 0; j < kNodes; ++j) {
        const double a = std::min(i + 1, j + 1) * spacing(), b = std::max(i + 1, j + 1) * spacing();
        next[i] += node_mass() * a * a * (3 * b - a) / (6 * ei) * v[j];
      }
    }
    lambda = next[kNodes - 1] / v[kNodes - 1];
    for (int i = 0; i < kNodes; ++i) v[i] = next[i] / next[kNodes - 1];
  }
  return 1 / (2 * kPi * std::sqrt(lambda));
}

TEST_P(BondedBeam, CantileverSwingsAboutTheBeamsDeflectionAtItsFirstFrequency) {
  const double g = 9.81, dt = 2e-6;
  const TipRecord record = swing({0, 0, -g}, dt, 150000, 10, 2);
  const Swing s = whole_periods(record);
  ASSERT_GT(s.period, 0) << "the tip did not swing";
  const double weight = node_mass() * g, deflection = -s.mean;
  const double eb = euler_bernoulli_tip(weight), timoshenko = eb + timoshenko_shear_tip(weight);
  const double f = 1 / s.period, f_lumped = lumped_first_frequency();
  RecordProperty("tip_deflection", significant(deflection));
  RecordProperty("euler_bernoulli", significant(eb));
  RecordProperty("timoshenko", significant(timoshenko));
  RecordProperty("deflection_error_eb", significant(deflection / eb - 1));
  RecordProperty("deflection_error_timoshenko", significant(deflection / timoshenko - 1));
  RecordProperty("frequency", significant(f));
  RecordProperty("frequency_lumped_beam", significant(f_lumped));
  RecordProperty("frequency_error", significant(f / f_lumped - 1));
  EXPECT_NEAR(deflection, eb, 0.02 * eb);
  EXPECT_NEAR(deflection, timoshenko, 0.02 * timoshenko);
  EXPECT_NEAR(f, f_lumped, 0.02 * f_lumped);
}

TEST_P(BondedBeam, AxialPullStretchesAndRingsAtTheBarsWaveSpeed) {
  const double g = 9.81, dt = 2e-6;
  const TipRecord record = swing({g, 0, 0}, dt, 5000, 1, 0);
  const Swing s = whole_periods(record);
  ASSERT_GT(s.period, 0) << "the tip did not ring";
  double stretch = 0;  // Σ P a/(EA)
  for (int k = 1; k <= kNodes; ++k) stretch += node_mass() * g * k * spacing() / (kYoung * area());
  const double bar_length = kNodes * spacing() + kRadius;  // clamp centre to the tip's far side
  const double density = node_mass() / (area() * spacing());
  const double speed = 4 * bar_length / s.period, expected = std::sqrt(kYoung / density);
  RecordProperty("stretch", significant(s.mean));
  RecordProperty("stretch_expected", significant(stretch));
  RecordProperty("wave_speed", significant(speed));
  RecordProperty("wave_speed_expected", significant(expected));
  EXPECT_NEAR(s.mean, stretch, 0.02 * stretch);
  EXPECT_NEAR(speed, expected, 0.01 * expected);
}

/// The beam's last sphere made a grip (a fixed material moving at v along x): the grip moves
/// exactly v t, and the bar's kNodes bonds in series, each of k̄_n A = EA/d, pull the clamp
/// and the grip with EA/(kNodes d) · v t (drag keeps the pull quasi-static).
TEST_P(BondedBeam, AGripPullsTheBarAtItsVelocity) {
  const double dt = 2e-6, v = 1e-3;
  const long steps = 20000;
  Scene scene = beam_scene({0, 0, 0}, dt, 200);
  Material grip = scene.materials[1];
  grip.name = "grip";
  grip.velocity = {v, 0, 0};
  scene.materials.push_back(grip);
  scene.bonds.push_back(bond_between(2, 0));
  ParticleStore p = beam_particles();
  p.material.back() = 2;
  auto engine = make_engine(make_engine_setup(scene, p));
  engine->set_particles(p);
  engine->create_bonds();
  EXPECT_EQ(engine->diagnostics().bond_count, std::uint64_t(kNodes));
  for (long n = 0; n < steps; ++n) engine->step();
  engine->get_particles(p);
  const double pulled = v * dt * steps, tension = kYoung * area() / spacing() / kNodes * pulled;
  int found = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.id[i] == ParticleId(kNodes)) {
      ++found;
      EXPECT_NEAR(p.position_radius[i].x, kNodes * spacing() + pulled, 1e-12);
      EXPECT_EQ(p.velocity_inv_mass[i].x, v);
      EXPECT_EQ(norm(p.angular_velocity[i]), 0.0);
      EXPECT_NEAR(p.force[i].x, -tension, 0.01 * tension);
    }
    if (p.id[i] == 0) {
      ++found;
      EXPECT_NEAR(p.force[i].x, tension, 0.01 * tension);
    }
  }
  EXPECT_EQ(found, 2) << "the clamp and the grip";
  EXPECT_EQ(engine->diagnostics().broken_bond_count, 0u);
}

/// Two free spheres bonded along x, flying apart at relative speed v, the bond breaking at
/// stretch `breaking_stretch` (tensile strength k̄_n · stretch).
TEST_P(BondedBeam, BondBreaksAtItsTensileStrengthAndTakesItsEnergy) {
  Scene scene = beam_scene({0, 0, 0}, 1e-7);
  const double kn = kYoung / spacing() * area(), reduced_mass = 0.5 * node_mass(), v = 0.05;
  const double most_stretch = v * std::sqrt(reduced_mass / kn);
  const double breaking_stretch = 0.5 * most_stretch;
  scene.bonds[0].tensile_strength = kYoung / spacing() * breaking_stretch;
  ParticleStore p;
  p.add(1, {0, 0, 0}, kRadius, 0, {-0.5 * v, 0, 0}, 1 / node_mass());
  p.add(2, {spacing(), 0, 0}, kRadius, 0, {0.5 * v, 0, 0}, 1 / node_mass());
  auto engine = make_engine(make_engine_setup(scene, p));
  engine->set_particles(p);
  engine->create_bonds();
  const double start_energy = engine->diagnostics().kinetic_translational;
  double last_intact_stretch = 0, worst_drift = 0;
  for (int n = 0; n < 200000 && engine->diagnostics().bond_count == 1; ++n) {
    const Diagnostics d = engine->diagnostics();
    worst_drift = std::max(worst_drift,
                           std::abs(d.kinetic_translational + d.potential_elastic - start_energy));
    engine->get_particles(p);
    last_intact_stretch = std::abs(p.position_radius[1].x - p.position_radius[0].x) - spacing();
    engine->step();
  }
  const Diagnostics after = engine->diagnostics();
  ASSERT_EQ(after.bond_count, 0u);
  EXPECT_EQ(after.broken_bond_count, 1u);
  EXPECT_EQ(after.potential_elastic, 0.0);
  const double step_stretch = v * 1e-7;
  RecordProperty("last_intact_stretch", significant(last_intact_stretch));
  RecordProperty("breaking_stretch", significant(breaking_stretch));
  EXPECT_LT(last_intact_stretch, breaking_stretch);
  EXPECT_GT(last_intact_stretch, breaking_stretch - 2 * step_stretch);
  EXPECT_LT(worst_drift, 1e-3 * start_energy);
  // The bond held ½ k δ_b² = ¼ of the kinetic energy when it broke; that energy is gone.
  const double kept = after.kinetic_translational / start_energy;
  RecordProperty("kinetic_energy_kept", significant(kept));
  EXPECT_NEAR(kept, 0.75, 0.01);
}

/// A 6×6×6 lattice of touching spheres with two clods: bonds join only touching pairs whose
/// two centres lie in the same clod sphere, counted here pair by pair.
TEST_P(BondedBeam, ClodsBondOnlyTheSpheresTheyHold) {
  Scene scene = beam_scene({0, 0, 0}, 1e-6);
  scene.bonds.pop_back();  // one table, soil with soil
  ParticleStore p;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k)
        p.add(p.size(), {i * spacing(), j * spacing() - 0.005, k * spacing() - 0.005}, kRadius, 0,
              {0, 0, 0}, 1 / node_mass());
  EngineSetup setup = make_engine_setup(scene, p);
  const std::vector<Real4> clods = {{0.002, -0.003, -0.003, 0.0035}, {0.008, 0.004, 0.004, 0.005}};
  setup.clods = {clods};
  std::uint64_t expected = 0;
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = a + 1; b < p.size(); ++b) {
      const Vec3 xa = xyz(p.position_radius[a]), xb = xyz(p.position_radius[b]);
      if (norm(xb - xa) - 2 * kRadius > 1e-5) continue;
      bool held = false;
      for (const Real4& c : clods)
        held = held || (norm(xa - xyz(c)) <= c.w && norm(xb - xyz(c)) <= c.w);
      expected += held ? 1 : 0;
    }
  auto engine = make_engine(setup);
  engine->set_particles(p);
  engine->create_bonds();
  RecordProperty("bonds", static_cast<int>(expected));
  EXPECT_GT(expected, 10u);
  EXPECT_EQ(engine->diagnostics().bond_count, expected);
}

/// The beam's spheres with a table of listed pairs: exactly the listed pairs are bonded, whatever
/// their materials; a pair too far apart to be bonded is refused, naming the file and line.
TEST_P(BondedBeam, ListedPairsAreBondedAndNoOthers) {
  Scene scene = beam_scene({0, 0, 0}, 1e-6);
  scene.bonds.resize(1);
  ParticleStore p = beam_particles();
  EngineSetup setup = make_engine_setup(scene, p);
  setup.bonds[0].pairs = "pairs.csv";  // the file's name, for messages; its pairs below
  setup.bond_pairs = {{{0, 1, 2}, {3, 4, 3}, {4, 5, 4}, {9, 10, 5}}};  // the clamp's too
  auto engine = make_engine(setup);
  engine->set_particles(p);
  engine->create_bonds();
  EXPECT_EQ(engine->diagnostics().bond_count, 4u);
  const auto refused = [&](const ParticleStore& particles, const std::string& phrase) {
    auto refusing = make_engine(setup);
    refusing->set_particles(particles);
    try {
      refusing->create_bonds();
      ADD_FAILURE() << "accepted; expected: " << phrase;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
    }
  };
  setup.bond_pairs = {{{3, 4, 2}, {5, 7, 3}}};  // 5 and 7 are a sphere apart
  refused(p, "pairs.csv:3: the pair 5, 7 was not bonded");
  ParticleStore apart = p;  // sphere 10 moved 0.3 mm (0.6 skin) beyond sphere 9
  for (std::size_t i = 0; i < apart.size(); ++i)
    if (apart.id[i] >= 10) apart.position_radius[i].x += 3e-4;
  setup.bond_pairs = {{{9, 10, 2}}};
  refused(apart, "more than half the neighbour skin");
}

/// The tip of the elastica under point loads P at a_k = k d: θ'' = −V(s) cos θ / EI with V(s)
/// the loads beyond s, θ(0) = 0 (clamped) and θ'(L) = 0 (no moment at the free end), by shooting
/// on θ'(0) (bisection between 0 and the straight beam's Σ P a_k / EI) with RK4 steps of d/100.
struct TipPosition {
  double shortening = 0, deflection = 0;  ///< along x towards the clamp, and down [m]
};

TipPosition elastica_tip(double weight) {
  const double ei = kYoung * second_moment(), length = kNodes * spacing(), h = spacing() / 100;
  const auto shoot = [&](double root_curvature, TipPosition& tip) {
    double y[4] = {0, root_curvature, 0, 0};  // θ, θ', x, z (down)
    for (int e = 0; e < kNodes; ++e) {
      const double shear = weight * (kNodes - e);
      const auto rate = [&](const double* u, double* du) {
        du[0] = u[1];
        du[1] = -shear * std::cos(u[0]) / ei;
        du[2] = std::cos(u[0]);
        du[3] = std::sin(u[0]);
      };
      for (int step = 0; step < 100; ++step) {
        double k1[4], k2[4], k3[4], k4[4], u[4];
        rate(y, k1);
        for (int c = 0; c < 4; ++c) u[c] = y[c] + 0.5 * h * k1[c];
        rate(u, k2);
        for (int c = 0; c < 4; ++c) u[c] = y[c] + 0.5 * h * k2[c];
        rate(u, k3);
        for (int c = 0; c < 4; ++c) u[c] = y[c] + h * k3[c];
        rate(u, k4);
        for (int c = 0; c < 4; ++c) y[c] += h / 6 * (k1[c] + 2 * k2[c] + 2 * k3[c] + k4[c]);
      }
    }
    tip = {length - y[2], y[3]};
    return y[1];  // θ'(L)
  };
  double low = 0, high = 0;
  for (int k = 1; k <= kNodes; ++k) high += weight * k * spacing() / ei;
  TipPosition tip;
  for (int iteration = 0; iteration < 80; ++iteration) {
    const double mid = 0.5 * (low + high);
    (shoot(mid, tip) < 0 ? low : high) = mid;
  }
  shoot(0.5 * (low + high), tip);
  return tip;
}

TEST_P(BondedBeam, LargeDeflectionRestsOnTheElastica) {
  // Loads of 8 EI/L² in all: the linear beam would put the tip below the length of the beam.
  const double length = kNodes * spacing();
  const double g = 8 * kYoung * second_moment() / (length * length) / (kNodes * node_mass());
  const double dt = 2e-6, drag = 200;  // about 0.8 of the first mode's critical damping
  const TipRecord down = swing({0, 0, -g}, dt, 100000, 100000, 2, drag);
  const TipRecord along = swing({0, 0, -g}, dt, 100000, 100000, 0, drag);
  ASSERT_EQ(down.displacement.size(), 1u);
  const TipPosition expected = elastica_tip(node_mass() * g);
  const double deflection = -down.displacement[0], shortening = -along.displacement[0];
  const double linear = euler_bernoulli_tip(node_mass() * g);
  RecordProperty("tip_deflection", significant(deflection));
  RecordProperty("elastica_deflection", significant(expected.deflection));
  RecordProperty("linear_deflection", significant(linear));
  RecordProperty("tip_shortening", significant(shortening));
  RecordProperty("elastica_shortening", significant(expected.shortening));
  EXPECT_GT(linear, 1.5 * expected.deflection);  // the case is far from linear
  EXPECT_NEAR(deflection, expected.deflection, 0.02 * expected.deflection);
  EXPECT_NEAR(shortening, expected.shortening, 0.02 * expected.shortening);
}

/// The beam standing on its clamp under gravity along −x, a column loaded by its own weight,
/// started with a lateral tilt of speed 1 mm/s at the top and brought to rest by drag: the tip's
/// lateral displacement at the end [m].
double standing_column_sway(BondedBeam& test, double g) {
  Scene scene = beam_scene({-g, 0, 0}, 2e-6, 100);
  ParticleStore p = beam_particles();
  for (std::size_t i = 1; i < p.size(); ++i)
    p.velocity_inv_mass[i].z = 1e-3 * p.position_radius[i].x / (kNodes * spacing());
  auto engine = test.make_engine_for(make_engine_setup(scene, p));
  engine->set_particles(p);
  engine->create_bonds();
  for (long n = 0; n < 150000; ++n) engine->step();
  engine->get_particles(p);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] == ParticleId(kNodes)) return std::abs(p.position_radius[i].z);
  return NAN;
}

/// Greenhill (1881): a column clamped at its foot buckles under its own weight q per length once
/// q L³ / EI reaches 7.837. At 0.8 of that load the tilted column straightens; at 1.2 it bends
/// over to a large deflection (spheres as point weights shift the threshold by a few per cent).
TEST_P(BondedBeam, ColumnBucklesUnderItsOwnWeightAtGreenhillsLoad) {
  const double length = kNodes * spacing();
  const double critical_q = 7.837 * kYoung * second_moment() / std::pow(length, 3);
  const double critical_g = critical_q * spacing() / node_mass();
  const double below = standing_column_sway(*this, 0.8 * critical_g);
  const double above = standing_column_sway(*this, 1.2 * critical_g);
  RecordProperty("sway_below", significant(below / length));
  RecordProperty("sway_above", significant(above / length));
  EXPECT_LT(below, 1e-4 * length);
  EXPECT_GT(above, 0.2 * length);
}

GPUDEM_INSTANTIATE_BACKENDS(BondedBeam);

}  // namespace
}  // namespace gpudem::test
