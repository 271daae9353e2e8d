// The JKR cohesion slot against the JKR relations written independently (Johnson, Kendall &
// Roberts 1971): the force–overlap curve through the force-side root for a, the pull-off force
// 3/2 π γ R*, the parting overlap δ_c = −(3/4)(π²γ²R*/E*²)^{1/3}, the energy as the integral
// of the force, the Hertz limit γ = 0 and the friction load of Thornton & Yin.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/contact/ContactLaw.hpp"
#include "support/Format.hpp"

namespace gpudem::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

using ElasticJkr = ContactLawOf<NormalLaw::Hertz, DampingLaw::None, TangentialLaw::None,
                                RollingLaw::None, CohesionLaw::Jkr>;
using ElasticHertz = ContactLawOf<NormalLaw::Hertz, DampingLaw::None, TangentialLaw::None,
                                  RollingLaw::None, CohesionLaw::None>;
using JkrMindlin = ContactLawOf<NormalLaw::Hertz, DampingLaw::None, TangentialLaw::Mindlin,
                                RollingLaw::None, CohesionLaw::Jkr>;

constexpr double kYoung = 5e6, kRadius = 5e-4, kGamma = 0.2;  // E* [Pa], R* [m], γ [J/m²]

ContactPairParams jkr_params(double gamma) {
  ContactPairParams p;
  p.effective_young = kYoung;
  p.effective_shear = 2e6;
  p.friction_static = 0.5;
  p.friction_dynamic = 0.4;
  p.surface_energy = gamma;
  return p;
}

/// A contact at overlap δ (negative: a gap), at rest, normal along +x.
ContactPoint point_at(double overlap) {
  ContactPoint c;
  c.normal = {1, 0, 0};
  c.overlap = overlap;
  c.reduced_mass = 1e-5;
  c.effective_radius = kRadius;
  return c;
}

/// F_n, positive repulsive, of law L at overlap δ (the force on i is −F_n n).
template <class Law>
double normal_force(const ContactPairParams& p, double overlap) {
  typename Law::State state{};
  return -Law::evaluate(p, point_at(overlap), state.value, 0).force.x;
}

/// δ_c of the JKR paper's form, written apart from the code's 3 a_c²/R*.
double parting_overlap(double gamma) {
  return -0.75 * std::cbrt(kPi * kPi * gamma * gamma * kRadius / (kYoung * kYoung));
}

/// δ of force F on the branch `stable` (a above the pull-off radius) from the force-side
/// relation a³ = (3R*/4E*)(F + 3πγR* ± √(6πγR*F + (3πγR*)²)), δ = a²/R* − √(2πγa/E*).
double overlap_of_force(double force, bool stable) {
  const double g = 3 * kPi * kGamma * kRadius;
  const double root = std::sqrt(std::max(0.0, 2 * g * force + g * g));
  const double a = std::cbrt(3 * kRadius / (4 * kYoung) * (force + g + (stable ? root : -root)));
  return a * a / kRadius - std::sqrt(2 * kPi * kGamma * a / kYoung);
}

/// Overlaps from 4 |δ_c| down to δ_c (exclusive), n of them.
std::vector<double> unloading_path(int n) {
  const double dc = parting_overlap(kGamma);
  std::vector<double> path;
  for (int k = 0; k < n; ++k) path.push_back(-4 * dc + (5 * -dc) * -(k + 0.5) / n);
  return path;
}

/// With k = 1 (a_c = R*) the relative radius solves â² − 4√â = δ̂ in the JKR paper's scaling;
/// with the k of a soil grain it does the same in lengths of a_c.
TEST(JkrRelation, RelativeRadiusSolvesTheQuarticFromPartingToDeepOverlap) {
  for (const double k : {1.0, 1e-9}) {
    const double scale = std::cbrt(k);  // a_c / R*
    for (const double d :
         {-3.0, -2.9999, -2.5, -1.443, -0.5, 0.0, 0.3, 1.0, 7.0, 1e3, 1e5, 2e6, 1e9}) {
      const double a = jkr_relative_radius(k, d * scale * scale) / scale;  // â
      EXPECT_GE(a, 1.0 - 1e-12) << d;
      EXPECT_NEAR(a * a - 4 * std::sqrt(a), d, 1e-11 * std::max(1.0, std::abs(d))) << d;
      // In float: a small backward error everywhere; near the fold δ̂ = −3, where â − 1 grows
      // as √(δ̂ + 3), the forward error is that backward error over dδ̂/dâ → 0.
      const float kf = static_cast<float>(k), df = static_cast<float>(d * scale * scale);
      const double af = jkr_relative_radius(kf, df) / scale;
      EXPECT_NEAR(af * af - 4 * std::sqrt(af), d, 32 * 1.2e-7 * std::max(1.0, std::abs(d))) << d;
      if (d >= -2.5) {
        EXPECT_NEAR(af, a, 2e-6 * a) << "float at " << d;
      }
    }
  }
  EXPECT_NEAR(jkr_relative_radius(1.0, 0.0), std::cbrt(16.0), 1e-14);  // â₀ at touch
}

TEST(JkrLaw, ForceOverlapCurveFollowsTheForceSideRelationOnBothBranches) {
  const ContactPairParams p = jkr_params(kGamma);
  const double pull_off = 1.5 * kPi * kGamma * kRadius;
  const double scale = -parting_overlap(kGamma);
  int unstable = 0;
  for (const double overlap : unloading_path(400)) {
    const double force = normal_force<ElasticJkr>(p, overlap);
    const double a = jkr_contact_radius(kGamma, kYoung, kRadius, overlap);
    const bool stable = a * a * a >= 9 * kPi * kGamma * kRadius * kRadius / (8 * kYoung);
    unstable += stable ? 0 : 1;
    EXPECT_NEAR(overlap_of_force(force, stable), overlap, 1e-9 * scale)
        << "F = " << force / pull_off << " F_c";
  }
  EXPECT_GT(unstable, 10) << "the path never passed the pull-off point";
}

TEST(JkrLaw, PullOffIsThreeHalvesPiGammaRAndTheContactPartsAtDeltaC) {
  const ContactPairParams p = jkr_params(kGamma);
  double largest_pull = 0;
  for (const double overlap : unloading_path(20000))
    largest_pull = std::max(largest_pull, -normal_force<ElasticJkr>(p, overlap));
  const double pull_off = 1.5 * kPi * kGamma * kRadius;
  RecordProperty("pull_off_relative_error", significant(largest_pull / pull_off - 1));
  EXPECT_NEAR(largest_pull, pull_off, 1e-4 * pull_off);
  const double dc = parting_overlap(kGamma);
  EXPECT_NEAR(JkrCohesion::pull_off_gap(p, kRadius), -dc, 1e-12 * -dc);
  // At δ_c the pull is 5/6 π γ R*; on touch, 4/3 π γ R*.
  EXPECT_NEAR(-normal_force<ElasticJkr>(p, dc), 5.0 / 6 * kPi * kGamma * kRadius, 1e-6 * pull_off);
  EXPECT_NEAR(-normal_force<ElasticJkr>(p, 0), 4.0 / 3 * kPi * kGamma * kRadius, 1e-9 * pull_off);
}

TEST(JkrLaw, EnergyIsTheIntegralOfTheForceFromTouch) {
  const ContactPairParams p = jkr_params(kGamma);
  const double dc = parting_overlap(kGamma);
  const int n = 20000;
  double work = 0;  // ∫₀^δ F dδ' by the trapezoid rule, δ running down to δ_c, then up again
  for (const double end : {0.999 * dc, 6 * -dc}) {
    work = 0;
    double previous = normal_force<ElasticJkr>(p, 0);
    for (int k = 1; k <= n; ++k) {
      const double here = normal_force<ElasticJkr>(p, end * k / n);
      work += 0.5 * (previous + here) * end / n;
      previous = here;
    }
    typename ElasticJkr::State state{};
    const double energy = ElasticJkr::energy(p, point_at(end), state.value);
    EXPECT_NEAR(energy, work, 1e-6 * std::abs(work)) << "δ = " << end;
  }
}

TEST(JkrLaw, WithoutAdhesionItIsHertz) {
  const ContactPairParams p = jkr_params(0);
  for (const double overlap : {1e-7, 1e-5, 1e-4}) {
    const double hertz = normal_force<ElasticHertz>(p, overlap);
    EXPECT_NEAR(normal_force<ElasticJkr>(p, overlap), hertz, 1e-12 * hertz);
  }
  EXPECT_EQ(JkrCohesion::pull_off_gap(p, kRadius), 0.0);
}

TEST(JkrLaw, DeepContactsApproachHertz) {
  const ContactPairParams with = jkr_params(kGamma), without = jkr_params(0);
  const double deep = 1e4 * -parting_overlap(kGamma);
  const double hertz = normal_force<ElasticHertz>(without, deep);
  const double jkr = normal_force<ElasticJkr>(with, deep);
  EXPECT_LT(jkr, hertz);
  EXPECT_NEAR(jkr, hertz, 0.02 * hertz);
}

/// A sliding contact in tension: |F_t| = μ_d (F_JKR + 3π γ R*), the friction load of Thornton
/// & Yin, positive although the contact pulls.
TEST(JkrLaw, FrictionInTensionScalesWithTheJkrForcePlusTwicePullOff) {
  const ContactPairParams p = jkr_params(kGamma);
  const double overlap = 0.5 * parting_overlap(kGamma);
  ContactPoint c = point_at(overlap);
  c.velocity = {0, 1, 0};  // sliding along y
  typename JkrMindlin::State state{};
  state.value[1] = 1.0;  // a stretched spring: far past the Coulomb limit
  const auto f = JkrMindlin::evaluate(p, c, state.value, 1e-6);
  const double jkr = normal_force<ElasticJkr>(p, overlap);
  ASSERT_LT(jkr, 0);
  const double limit = 0.4 * (jkr + 3 * kPi * kGamma * kRadius);
  EXPECT_NEAR(norm(f.tangential), limit, 1e-9 * limit);
  EXPECT_EQ(state.value[JkrMindlin::formed_offset], 1.0);
  EXPECT_TRUE(JkrMindlin::has_formed(state.value));
}

}  // namespace
}  // namespace gpudem::test
