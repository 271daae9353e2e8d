// The parallel bond (Potyondy & Cundall 2004) against its defining relations, written here
// from the beam of the bond's section: axial force k̄_n A (L − L₀), shear force k̄_s A u_s,
// twisting moment k̄_s J θ_n and bending moment k̄_n I θ_s for the relative displacement and
// rotation built up over steps, with k̄_n = E/L₀, k̄_s = G/L₀, A = π r_b², I = π r_b⁴/4,
// J = 2I; momentum and angular momentum conserved by every evaluation; the stored loads rotated
// with the bond; breaking at the tensile and shear strengths; the stored energy as the work
// done on the bond.
#include <gtest/gtest.h>

#include <cmath>

#include "core/contact/ParallelBond.hpp"

namespace gpudem::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kYoung = 2e7, kPoisson = 0.25, kRadius = 1e-3, kRest = 2e-3;

BondParams params(double tensile = INFINITY, double shear = INFINITY) {
  return BondParams{kYoung, kYoung / (2 * (1 + kPoisson)), 0.8, tensile, shear, 0};
}

double section_radius() { return 0.8 * kRadius; }
double area() { return kPi * std::pow(section_radius(), 2); }
double second_moment() { return 0.25 * kPi * std::pow(section_radius(), 4); }

/// Two equal spheres along +x at distance L₀ + stretch, at rest.
BondGeometry<double> along_x(double stretch = 0) {
  BondGeometry<double> g;
  g.normal = {1, 0, 0};
  g.stretch = stretch;
  g.arm_a = g.arm_b = 0.5 * (kRest + stretch);
  g.min_radius = kRadius;
  g.reduced_mass = 1e-6;
  g.reduced_inertia = 1e-13;
  return g;
}

/// A fresh bond record of rest length L₀.
struct Record {
  double value[bond_value::width] = {kRest};
};

TEST(ParallelBond, AxialForceIsTheSectionsStiffnessTimesTheStretch) {
  Record r;
  const double stretch = 1e-6;
  const BondLoad<double> load = evaluate_bond(params(), along_x(stretch), r.value, 1e-6);
  const double expected = kYoung / kRest * area() * stretch;
  EXPECT_NEAR(load.force.x, expected, 1e-12 * expected);  // pulls a towards b
  EXPECT_EQ(load.force.y, 0.0);
  EXPECT_EQ(load.torque_a.z, 0.0);
  const BondLoad<double> pushed = evaluate_bond(params(), along_x(-stretch), r.value, 1e-6);
  EXPECT_NEAR(pushed.force.x, -expected, 1e-12 * expected);
}

TEST(ParallelBond, ShearBuildsUpFromTheRelativeSlipAtTheContactPoint) {
  Record r;
  BondGeometry<double> g = along_x();
  g.velocity = {0, 0.01, 0};  // b slides along +y relative to a
  const double dt = 1e-5;
  BondLoad<double> load;
  for (int k = 0; k < 10; ++k) load = evaluate_bond(params(), g, r.value, dt);
  const double ks = kYoung / (2 * (1 + kPoisson)) / kRest * area();
  const double expected = ks * 0.01 * 10 * dt;
  EXPECT_NEAR(load.force.y, expected, 1e-12 * expected);
  // Its moment about each centre: the arm L/2 along x times F_y gives +z on both ends.
  EXPECT_NEAR(load.torque_a.z, 0.5 * kRest * expected, 1e-12 * expected * kRest);
  EXPECT_NEAR(load.torque_b.z, 0.5 * kRest * expected, 1e-12 * expected * kRest);
}

TEST(ParallelBond, BendingAndTwistFollowTheRelativeRotation) {
  Record r;
  BondGeometry<double> g = along_x();
  g.spin = {3, 2, 0};  // b turns about x (twist) and y (bending) relative to a
  const double dt = 1e-5;
  BondLoad<double> load;
  for (int k = 0; k < 4; ++k) load = evaluate_bond(params(), g, r.value, dt);
  const double bending = kYoung / kRest * second_moment() * 2 * 4 * dt;
  const double twist = kYoung / (2 * (1 + kPoisson)) / kRest * 2 * second_moment() * 3 * 4 * dt;
  EXPECT_NEAR(load.torque_a.y, bending, 1e-12 * bending);
  EXPECT_NEAR(load.torque_b.y, -bending, 1e-12 * bending);
  EXPECT_NEAR(load.torque_a.x, twist, 1e-12 * twist);
  EXPECT_NEAR(load.torque_b.x, -twist, 1e-12 * twist);
}

TEST(ParallelBond, EveryEvaluationConservesMomentumAndAngularMomentum) {
  Record r;
  BondGeometry<double> g;
  const Vec3 d{1.7e-3, 0.6e-3, -0.9e-3};
  g.normal = (1 / norm(d)) * d;
  g.stretch = norm(d) - kRest;
  g.arm_a = 0.4 * norm(d);
  g.arm_b = 0.6 * norm(d);
  g.min_radius = kRadius;
  g.reduced_mass = 1e-6;
  g.reduced_inertia = 1e-13;
  g.velocity = {0.02, -0.03, 0.01};
  g.spin = {5, -7, 2};
  BondParams p = params();
  p.damping_ratio = 0.2;
  const Vec3 xa{0.01, -0.02, 0.03}, xb = xa + d;
  for (int k = 0; k < 5; ++k) {
    const BondLoad<double> load = evaluate_bond(p, g, r.value, 1e-5);
    // a gets F, b gets −F; their moments about the origin cancel with the torques.
    const Vec3 total =
        cross(xa, load.force) + load.torque_a + cross(xb, -load.force) + load.torque_b;
    const double scale = norm(load.force) * norm(d) + norm(load.torque_a);
    EXPECT_LT(norm(total), 1e-12 * scale) << "step " << k;
  }
}

TEST(ParallelBond, StoredLoadsTurnWithTheBondAndKeepTheirLength) {
  Record r;
  BondGeometry<double> g = along_x();
  g.velocity = {0, 0.01, 0};
  g.spin = {0, 4, 3};
  evaluate_bond(params(), g, r.value, 1e-5);
  const double shear = norm(load_vec(r.value + bond_value::shear));
  const double bending = norm(load_vec(r.value + bond_value::bending));
  g = along_x();
  const double turn = kPi / 6;  // the bond turned by 30° about z
  g.normal = {std::cos(turn), std::sin(turn), 0};
  evaluate_bond(params(), g, r.value, 1e-5);
  const Vec3 shear_now = load_vec(r.value + bond_value::shear);
  const Vec3 bending_now = load_vec(r.value + bond_value::bending);
  EXPECT_NEAR(norm(shear_now), shear, 1e-12 * shear);
  EXPECT_NEAR(norm(bending_now), bending, 1e-12 * bending);
  EXPECT_NEAR(dot(shear_now, g.normal), 0.0, 1e-12 * shear);
  EXPECT_NEAR(dot(bending_now, g.normal), 0.0, 1e-12 * bending);
  EXPECT_LT(shear_now.x, -0.4 * shear);  // it turned with the bond, towards −x
}

TEST(ParallelBond, BreaksWhenTheTensileStressReachesTheStrength) {
  const double strength = 1e5;  // σ = k̄_n (L − L₀) reaches it at L − L₀ = σ L₀ / E
  const double at = strength * kRest / kYoung;
  Record below, above;
  EXPECT_FALSE(evaluate_bond(params(strength), along_x(0.999 * at), below.value, 1e-6).broken);
  EXPECT_TRUE(evaluate_bond(params(strength), along_x(1.001 * at), above.value, 1e-6).broken);
  // In compression the tensile strength is never reached.
  EXPECT_FALSE(evaluate_bond(params(strength), along_x(-10 * at), below.value, 1e-6).broken);
}

TEST(ParallelBond, BendingAddsItsEdgeStressToTheTension) {
  // σ = F_n/A + |M_b| r_b/I: a bending moment alone breaks the bond at M_b = σ_c I / r_b.
  const double strength = 1e5, dt = 1e-5, spin = 1.3;
  const double moment_per_step = kYoung / kRest * second_moment() * spin * dt;
  const int steps_to_break =
      static_cast<int>(std::ceil(strength * second_moment() / section_radius() / moment_per_step));
  Record r;
  BondGeometry<double> g = along_x();
  g.spin = {0, spin, 0};
  for (int k = 1; k < steps_to_break; ++k)
    ASSERT_FALSE(evaluate_bond(params(strength), g, r.value, dt).broken) << "step " << k;
  EXPECT_TRUE(evaluate_bond(params(strength), g, r.value, dt).broken);
}

TEST(ParallelBond, BreaksWhenTheShearStressReachesTheShearStrength) {
  const double strength = 5e4, dt = 1e-5, slip_rate = 0.01;
  const double ks = kYoung / (2 * (1 + kPoisson)) / kRest * area();
  const double force_per_step = ks * slip_rate * dt;
  const int steps_to_break = static_cast<int>(std::ceil(strength * area() / force_per_step));
  Record r;
  BondGeometry<double> g = along_x();
  g.velocity = {0, slip_rate, 0};
  for (int k = 1; k < steps_to_break; ++k)
    ASSERT_FALSE(evaluate_bond(params(INFINITY, strength), g, r.value, dt).broken);
  EXPECT_TRUE(evaluate_bond(params(INFINITY, strength), g, r.value, dt).broken);
}

TEST(ParallelBond, StoredEnergyIsTheWorkDoneOnTheBond) {
  // Bend, shear, twist and stretch the bond along a path, summing the work F·Δu + M·Δθ that the
  // loads on a do against the relative motion; the energy the bond reports equals it.
  Record r;
  BondGeometry<double> g = along_x();
  const double dt = 1e-6;
  double work = 0;
  for (int k = 0; k < 2000; ++k) {
    g.velocity = {1e-3 * std::cos(1e-3 * k), 2e-3, -1e-3};
    g.spin = {0.5, -0.3, 0.2 * std::sin(2e-3 * k)};
    const BondLoad<double> before = evaluate_bond(params(), g, r.value, 0.0);
    g.stretch += dt * g.velocity.x;
    const BondLoad<double> after = evaluate_bond(params(), g, r.value, dt);
    const Vec3 force = 0.5 * (before.force + after.force);
    const Vec3 moment = 0.5 * (before.torque_a + after.torque_a) -
                        cross(g.arm_a * g.normal, 0.5 * (before.force + after.force));
    // b moves by v dt relative to a, against the force −F on b; the moment likewise.
    work += dot(force, dt * g.velocity) + dot(moment, dt * g.spin);
  }
  const double energy = bond_energy(params(), g, r.value);
  EXPECT_NEAR(energy, work, 1e-6 * work);
}

}  // namespace
}  // namespace gpudem::test
