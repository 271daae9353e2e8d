// The contact laws evaluated in lanes (core/Lanes.hpp), as the host's pair sweep evaluates
// them: every lane's contact point (from the two particles' states) and its force, tangential
// force, rolling torque and new history are the same bits as the scalar law's on that lane's
// contact, sliding or sticking, rolling at the limit or not, advancing the history or reading it
// (dt = 0); and the exact sums' terms of a vector in lanes are the scalar terms, in one word or
// spilled, also beyond the limit and for NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/Lanes.hpp"
#include "core/contact/ContactLaw.hpp"
#include "engine/ContactVisitor.hpp"
#include "engine/ExactSum.hpp"

namespace gpudem::test {
namespace {

constexpr int kLanes = 8;

template <class S>
bool same_bits(S a, S b) {
  return std::memcmp(&a, &b, sizeof(S)) == 0;
}

/// Two particles in contact, their pair's constants and the contact's stored history, in Real.
template <class Law>
struct Contact {
  ContactPairParams params;
  Real4 xi, vi, xj, vj;  ///< centres and radii, velocities and inverse masses
  Vec3 wi, wj;
  double history[Law::history_size > 0 ? Law::history_size : 1] = {};
};

/// Contacts whose springs span from well inside to well beyond their friction limits, some
/// blank, some marked sliding, some without relative spin.
template <class Law>
Contact<Law> random_contact(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, u(rng)); };
  const auto vector = [&](double scale) {
    return Vec3{scale * (2 * u(rng) - 1), scale * (2 * u(rng) - 1), scale * (2 * u(rng) - 1)};
  };
  Contact<Law> c;
  ContactPairParams& p = c.params;
  p.effective_young = log_uniform(1e6, 1e8);
  p.effective_shear = p.effective_young / 2.6;
  p.hooke_stiffness = log_uniform(1e3, 1e5);
  p.hooke_tangential_stiffness = 2.0 / 7.0 * p.hooke_stiffness;
  p.restitution_beta = 0.1 + 0.3 * u(rng);
  p.viscoelastic_time = log_uniform(1e-6, 1e-4);
  p.friction_static = 0.2 + 0.6 * u(rng);
  p.friction_dynamic = p.friction_static * (0.7 + 0.3 * u(rng));
  p.rolling_friction = u(rng) < 0.2 ? 0 : 0.1 * u(rng);
  p.rolling_damping = 0.5 * u(rng);
  p.cohesion_energy_density = 1e4 * u(rng);
  const double ri = log_uniform(1e-3, 1e-2), rj = log_uniform(1e-3, 1e-2);
  const Vec3 n = vector(1);
  const Vec3 d = ((ri + rj) * (1 - log_uniform(1e-5, 1e-1)) / norm(n)) * n;
  c.xi = {u(rng), u(rng), u(rng), ri};
  c.xj = {c.xi.x + d.x, c.xi.y + d.y, c.xi.z + d.z, rj};
  const Vec3 vi = vector(0.1), vj = vector(0.1);
  c.vi = {vi.x, vi.y, vi.z, 1 / log_uniform(1e-3, 1e-1)};
  c.vj = {vj.x, vj.y, vj.z, 1 / log_uniform(1e-3, 1e-1)};
  c.wi = u(rng) < 0.25 ? Vec3{} : vector(10);
  c.wj = u(rng) < 0.25 ? c.wi : vector(10);
  if (u(rng) < 0.2) return c;  // a blank history
  const double scale = log_uniform(1e-9, 1e-3);
  for (int v = 0; v < Law::history_size; ++v) c.history[v] = scale * (2 * u(rng) - 1);
  if constexpr (Law::Tangential::history_size > 0) c.history[3] = u(rng) < 0.5 ? 1 : 0;
  return c;
}

template <class Law>
class LanesLaw : public ::testing::Test {};

template <class Normal, class Damping, class Tangential, class Rolling, class Cohesion>
using Slots = ContactLaw<Normal, Damping, Tangential, Rolling, Cohesion, double>;
template <class L>
using InFloat = ContactLaw<typename L::Normal, typename L::Damping, typename L::Tangential,
                           typename L::Rolling, typename L::Cohesion, float>;
using HookeBare = Slots<HookeNormal, NoDamping, NoTangential, NoRolling, NoCohesion>;
using HookeHistory =
    Slots<HookeNormal, RestitutionDamping, LinearHistoryTangential, NoRolling, NoCohesion>;
using HertzMindlin =
    Slots<HertzNormal, RestitutionDamping, MindlinTangential, NoRolling, NoCohesion>;
using HertzConstantTorque =
    Slots<HertzNormal, ViscoelasticDamping, MindlinTangential, ConstantTorqueRolling, NoCohesion>;
using HertzEpsdSjkr =
    Slots<HertzNormal, RestitutionDamping, MindlinTangential, EpsdRolling, SjkrCohesion>;
using HookeEpsdSjkr =
    Slots<HookeNormal, ViscoelasticDamping, LinearHistoryTangential, EpsdRolling, SjkrCohesion>;
using Laws =
    ::testing::Types<HookeBare, HookeHistory, HertzMindlin, HertzConstantTorque, HertzEpsdSjkr,
                     HookeEpsdSjkr, InFloat<HookeHistory>, InFloat<HertzMindlin>,
                     InFloat<HertzConstantTorque>, InFloat<HertzEpsdSjkr>>;
TYPED_TEST_SUITE(LanesLaw, Laws);

/// Evaluates `batches` of kLanes random contacts in lanes and one by one; counts the lanes that
/// slid after the step.
template <class Law>
int expect_lanes_match_scalar(Real dt, int batches, unsigned seed) {
  using S = typename Law::Scalar;
  using L = Lanes<S, kLanes>;
  using R = Lanes<Real, kLanes>;
  static_assert(Law::evaluates_in_lanes);
  std::mt19937_64 rng(seed);
  int sliding = 0;
  for (int batch = 0; batch < batches; ++batch) {
    Contact<Law> contacts[kLanes];
    ContactPairParamsT<L> params;
    Vec4T<R> xi, vi, xj, vj;
    Vec3T<R> wi, wj;
    L history[Law::history_size > 0 ? Law::history_size : 1];
    for (int l = 0; l < kLanes; ++l) {
      const Contact<Law>& c = contacts[l] = random_contact<Law>(rng);
      for_each_param(params, c.params, [l](L& to, Real from) { to.set(l, S(from)); });
      set_lane<Real, kLanes>(xi, l, c.xi);
      set_lane<Real, kLanes>(vi, l, c.vi);
      set_lane<Real, kLanes>(xj, l, c.xj);
      set_lane<Real, kLanes>(vj, l, c.vj);
      set_lane<Real, kLanes>(wi, l, c.wi);
      set_lane<Real, kLanes>(wj, l, c.wj);
      for (int v = 0; v < Law::history_size; ++v) history[v].set(l, S(c.history[v]));
    }
    ContactPointT<R> point;
    R arm;
    const Vec3T<R> d = xyz(xj) - xyz(xi);
    describe_pair<Law>(point, arm, d, norm2(d), xi, vi, wi, xj, vj, wj);
    const ContactForce<L> in_lanes = Law::evaluate(params, point_cast<L>(point), history, L(S(dt)));
    for (int l = 0; l < kLanes; ++l) {
      S own[Law::history_size > 0 ? Law::history_size : 1];
      for (int v = 0; v < Law::history_size; ++v) own[v] = S(contacts[l].history[v]);
      const Contact<Law>& c = contacts[l];
      ContactPoint one;
      Real one_arm;
      const Vec3 one_d = xyz(c.xj) - xyz(c.xi);
      describe_pair<Law>(one, one_arm, one_d, norm2(one_d), c.xi, c.vi, c.wi, c.xj, c.vj, c.wj);
      EXPECT_GT(one.overlap, 0) << "the contacts are built to overlap";
      EXPECT_TRUE(same_bits(arm[l], one_arm) && same_bits(point.overlap[l], one.overlap) &&
                  same_bits(point.overlap_rate[l], one.overlap_rate))
          << "contact point, batch " << batch << " lane " << l;
      const typename Law::Force alone =
          Law::evaluate(params_cast<S>(c.params), point_cast<S>(one), own, S(dt));
      const auto expect_vector = [&](const Vec3T<L>& lanes, const Vec3T<S>& scalar,
                                     const char* what) {
        EXPECT_TRUE(same_bits(lanes.x[l], scalar.x) && same_bits(lanes.y[l], scalar.y) &&
                    same_bits(lanes.z[l], scalar.z))
            << what << ", batch " << batch << " lane " << l << ": " << lanes.x[l] << " "
            << lanes.y[l] << " " << lanes.z[l] << " against " << scalar.x << " " << scalar.y << " "
            << scalar.z;
      };
      expect_vector(in_lanes.force, alone.force, "force");
      expect_vector(in_lanes.tangential, alone.tangential, "tangential force");
      expect_vector(in_lanes.rolling_torque, alone.rolling_torque, "rolling torque");
      for (int v = 0; v < Law::history_size; ++v)
        EXPECT_TRUE(same_bits(history[v][l], own[v]))
            << "history value " << v << ", batch " << batch << " lane " << l << ": "
            << history[v][l] << " against " << own[v];
      if constexpr (Law::Tangential::history_size > 0) sliding += own[3] != 0;
    }
  }
  return sliding;
}

TYPED_TEST(LanesLaw, EachLaneIsTheScalarLawsBits) {
  const int contacts = 200 * kLanes;
  const int sliding = expect_lanes_match_scalar<TypeParam>(1e-5, 200, 11);
  if constexpr (TypeParam::Tangential::history_size > 0) {
    // both outcomes of the Coulomb test were compared
    EXPECT_GT(sliding, contacts / 20);
    EXPECT_LT(sliding, contacts - contacts / 20);
  }
}

TYPED_TEST(LanesLaw, ReadingTheStoredStateToo) { expect_lanes_match_scalar<TypeParam>(0, 50, 5); }

/// The integer a term's component k stands for, word + spill · 2^50 units.
__extension__ typedef __int128 Units;
Units units_of(const ExactTerm3& t, int k) {
  return static_cast<Units>(static_cast<std::int64_t>(t.words.word[k])) +
         static_cast<Units>(static_cast<std::int64_t>(t.spill[k])) * (Units(1) << 50);
}

TEST(LanesExactTerms, EachLaneIsTheScalarTerms) {
  using L = Lanes<double, kLanes>;
  const ExactUnits units{};  // 2^-44 N: one word up to 64 N
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int batch = 0; batch < 100; ++batch) {
    // odd batches within one word, rounded in the lanes; even ones with lanes that spill, beyond
    // the limit or NaN, which take every lane of the batch through the spilling path
    const bool spilling = batch % 2 == 0;
    Vec3T<L> lanes;
    Vec3 vectors[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      vectors[l] = {u(rng) * std::pow(10.0, 1.5 * u(rng)), u(rng) * 1e-12, u(rng)};
      if (spilling && l == 5) vectors[l].y = batch % 4 ? exact_spill_limit * units.force : -1e9;
      if (spilling && l == 6) vectors[l].z = nan;
      if (spilling && l == 3) vectors[l].x = 1e6 * u(rng);
      if (l == 7) vectors[l].x = (0.5 + batch) * units.force;  // a tie in units: to even
      if (l == 4)  // 0.75 · 2^50 units and a half: to even, the value kept when it spills
        vectors[l].y = (0.75 * exact_word_limit + 0.5 + batch % 3) * units.force;
      lanes.x.set(l, vectors[l].x);
      lanes.y.set(l, vectors[l].y);
      lanes.z.set(l, vectors[l].z);
    }
    const ExactTermLanes<kLanes> terms = exact_terms(lanes, units.per_force);
    EXPECT_EQ(terms.spills, spilling) << "batch " << batch;
    for (int l = 0; l < kLanes; ++l) {
      const ExactTerm3 want = exact_terms(vectors[l], units.per_force);
      const ExactTerm3 got = terms.lane(l);
      EXPECT_EQ(got.representable, want.representable) << "batch " << batch << " lane " << l;
      if (!want.representable) continue;
      for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(units_of(got, k) == units_of(want, k))
            << "batch " << batch << " lane " << l << " component " << k;
    }
  }
}

}  // namespace
}  // namespace gpudem::test
