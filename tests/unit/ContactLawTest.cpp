// The composition of contact-law slots: every valid combination builds an engine on each
// backend and obeys Newton's third law; invalid ones are refused; a switched-off slot costs
// nothing (the Hooke-only kernel runs with no spin, torque or history arrays at all).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/ContactModel.hpp"
#include "engine/ContactForces.hpp"
#include "engine/ParallelFor.hpp"
#include "support/Backends.hpp"

namespace gpudem::test {
namespace {

using HookeOnly = ContactLawOf<NormalLaw::Hooke, DampingLaw::Restitution, TangentialLaw::None,
                               RollingLaw::None, CohesionLaw::None>;
using HertzMindlinEpsd = ContactLawOf<NormalLaw::Hertz, DampingLaw::Restitution,
                                      TangentialLaw::Mindlin, RollingLaw::Epsd, CohesionLaw::None>;

/// Pair constants with every field set, so any slot has what it reads.
ContactPairParams all_fields() {
  ContactPairParams p;
  p.hooke_stiffness = 1e4;
  p.hooke_tangential_stiffness = 2.0 / 7.0 * 1e4;
  p.effective_young = 5e6;
  p.effective_shear = 2e6;
  p.restitution_beta = 0.2;
  p.viscoelastic_time = 1e-5;
  p.friction_static = 0.5;
  p.friction_dynamic = 0.4;
  p.rolling_friction = 0.1;
  p.rolling_damping = 0.3;
  p.cohesion_energy_density = 1e3;
  p.surface_energy = 0.05;
  return p;
}

/// Two overlapping spheres of different sizes moving and spinning, plus a floor they touch.
EngineSetup two_sphere_setup(const ContactModel& model) {
  EngineSetup s;
  s.box.lo = {-1, -1, -1};
  s.box.length = {2, 2, 2};
  s.dt = 1e-6;
  s.skin = 1e-3;
  s.contact_model = model;
  s.material_count = 1;
  s.pair_params = {all_fields()};
  return s;
}

ParticleStore two_spheres() {
  ParticleStore p;
  p.add(1, {0, 0, 0}, 0.010, 0, {0.3, -0.1, 0.2}, 1 / 0.01);
  p.add(2, {0.0175, 0.002, -0.001}, 0.008, 0, {-0.2, 0.4, 0.0}, 1 / 0.005);
  p.angular_velocity = {{1, -2, 3}, {-4, 0.5, 2}};
  return p;
}

/// Each enum value selects the slot of the same name (SlotOf lists slots in enum order).
TEST(ContactLawSlots, FollowEnumOrder) {
  using All = ContactLawOf<NormalLaw::Hertz, DampingLaw::Viscoelastic, TangentialLaw::Mindlin,
                           RollingLaw::Epsd, CohesionLaw::Sjkr>;
  static_assert(std::is_same_v<All::Normal, HertzNormal>);
  static_assert(std::is_same_v<All::Damping, ViscoelasticDamping>);
  static_assert(std::is_same_v<All::Tangential, MindlinTangential>);
  static_assert(std::is_same_v<All::Rolling, EpsdRolling>);
  static_assert(std::is_same_v<All::Cohesion, SjkrCohesion>);
  using Middle =
      ContactLawOf<NormalLaw::Hooke, DampingLaw::Restitution, TangentialLaw::LinearHistory,
                   RollingLaw::ConstantTorque, CohesionLaw::None>;
  static_assert(std::is_same_v<Middle::Normal, HookeNormal>);
  static_assert(std::is_same_v<Middle::Damping, RestitutionDamping>);
  static_assert(std::is_same_v<Middle::Tangential, LinearHistoryTangential>);
  static_assert(std::is_same_v<Middle::Rolling, ConstantTorqueRolling>);
  static_assert(std::is_same_v<Middle::Cohesion, NoCohesion>);
  using First = ContactLawOf<NormalLaw::Hooke, DampingLaw::None, TangentialLaw::None,
                             RollingLaw::None, CohesionLaw::None>;
  static_assert(std::is_same_v<First::Damping, NoDamping>);
  static_assert(std::is_same_v<First::Tangential, NoTangential>);
  static_assert(std::is_same_v<First::Rolling, NoRolling>);
  SUCCEED() << "checked at compile time";
}

TEST(ContactLawFlags, DeclareHistoryAndSpin) {
  EXPECT_EQ(HookeOnly::history_size, 0);
  EXPECT_FALSE(HookeOnly::needs_spin);
  EXPECT_FALSE(HookeOnly::needs_effective_radius);
  EXPECT_EQ(HookeOnly::extra_bytes_per_contact, 0);
  EXPECT_EQ(HertzMindlinEpsd::history_size, 7);  // ξ (3), sliding flag, rolling spring (3)
  EXPECT_TRUE(HertzMindlinEpsd::needs_spin);
  EXPECT_EQ(HertzMindlinEpsd::extra_bytes_per_contact, 7 * 8 + 3 * 8);
  EXPECT_EQ(sizeof(HertzMindlinEpsd::State), 7 * sizeof(Real));
}

/// The Hooke-only force kernel on null spin, torque and history pointers: it can only pass
/// if it never touches them. Its force is k_n δ (restitution damping: the spheres are at rest).
TEST(ContactLawCost, HookeOnlyKernelReadsNoSpinTorqueOrHistory) {
  const ContactPairParams params = all_fields();
  const std::vector<Real4> x{{0, 0, 0, 0.01}, {0.019, 0, 0, 0.01}};
  const std::vector<Real4> v{{0, 0, 0, 100}, {0, 0, 0, 100}};
  const std::vector<MaterialId> material{0, 0};
  const std::vector<std::uint32_t> offsets{0, 1, 2}, neighbors{1, 0};
  PeriodicBox box;
  box.lo = {-1, -1, -1};
  box.length = {2, 2, 2};
  const ParticleView<Real> view{x.data(), v.data(), nullptr, material.data()};
  const ContactScene<HookeOnly> scene{
      offsets.data(), neighbors.data(), &params, 1,          nullptr, 0, box,
      nullptr,        nullptr,          nullptr, MeshView{}, nullptr};
  std::vector<Vec3> force(2);
  std::vector<Real> ratio(2);
  parallel_for(HostSpace{}, 2,
               ComputeForces<HookeOnly, Real>{view,
                                              scene,
                                              Vec3{},
                                              Real(1e-6),
                                              {nullptr, nullptr, nullptr},
                                              force.data(),
                                              nullptr,
                                              ratio.data(),
                                              nullptr});
  const double expected = params.hooke_stiffness * 0.001;
  EXPECT_NEAR(force[0].x, -expected, 1e-9 * expected);
  EXPECT_NEAR(force[1].x, expected, 1e-9 * expected);
}

class EveryContactLaw : public BackendTest {};

/// Each valid model builds, evaluates equal and opposite pair forces (first contact step, no
/// history yet) and steps without producing non-finite values.
TEST_P(EveryContactLaw, BuildsAndObeysNewtonsThirdLaw) {
  for (const ContactModel& model : valid_contact_models()) {
    SCOPED_TRACE(contact_model_name(model));
    auto engine = make_engine(two_sphere_setup(model));
    ParticleStore p = two_spheres();
    engine->set_particles(p);
    engine->get_particles(p);
    ASSERT_EQ(p.size(), 2u);
    const Vec3 sum = p.force[0] + p.force[1];
    EXPECT_GT(norm(p.force[0]), 0);
    EXPECT_LT(norm(sum), 1e-12 * norm(p.force[0]));
    for (int n = 0; n < 10; ++n) engine->step();
    HealthFailure failure;
    EXPECT_FALSE(engine->find_unhealthy(0.5, failure));
  }
}

/// Largest |a − b| / |b| over the two spheres' forces, and over their torques.
std::pair<double, double> relative_differences(const ParticleStore& a, const ParticleStore& b) {
  double force = 0, torque = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    force = std::max(force, norm(a.force[i] - b.force[i]) / norm(b.force[i]));
    if (norm(b.torque[i]) > 0)
      torque = std::max(torque, norm(a.torque[i] - b.torque[i]) / norm(b.torque[i]));
  }
  return {force, torque};
}

/// Each valid model in mixed precision gives the forces and torques of double precision to
/// float rounding, on the first contact step and after ten steps of history: within 1e-5 (a
/// few dozen roundings of 6e-8 each), and not bit for bit (the law really runs in float).
TEST_P(EveryContactLaw, MixedPrecisionAgreesWithDoubleToFloatRounding) {
  for (const ContactModel& model : valid_contact_models()) {
    SCOPED_TRACE(contact_model_name(model));
    EngineSetup setup = two_sphere_setup(model);
    auto exact = make_engine(setup);
    setup.precision = Precision::Mixed;
    auto mixed = make_engine(setup);
    exact->set_particles(two_spheres());
    mixed->set_particles(two_spheres());
    for (int n = 0; n <= 10; n += 10) {
      for (int k = 0; k < n; ++k) {
        exact->step();
        mixed->step();
      }
      ParticleStore a, b;
      mixed->get_particles(a);
      exact->get_particles(b);
      const auto [force, torque] = relative_differences(a, b);
      EXPECT_GT(force, 0) << "after " << n << " steps";
      EXPECT_LE(force, 1e-5) << "after " << n << " steps";
      EXPECT_LE(torque, 1e-5) << "after " << n << " steps";
    }
  }
}

TEST_P(EveryContactLaw, RefusesAnInvalidCombination) {
  ContactModel hooke_mindlin;
  hooke_mindlin.tangential = TangentialLaw::Mindlin;
  ASSERT_FALSE(is_valid_contact_model(hooke_mindlin));
  EXPECT_THROW(make_engine(two_sphere_setup(hooke_mindlin)), std::invalid_argument);
}

GPUDEM_INSTANTIATE_BACKENDS(EveryContactLaw);

TEST(CompiledContactLaws, APatternMatchesItsChoicesAndAnyWhereItSaysSo) {
  // hertz / any damping / mindlin / any rolling / none
  const ContactModelPattern pattern{{1, -1, 2, -1, 0}};
  const ContactModel hertz_mindlin{NormalLaw::Hertz, DampingLaw::Viscoelastic,
                                   TangentialLaw::Mindlin, RollingLaw::Epsd, CohesionLaw::None};
  EXPECT_TRUE(pattern.matches(hertz_mindlin));
  ContactModel other = hertz_mindlin;
  other.cohesion = CohesionLaw::Sjkr;
  EXPECT_FALSE(pattern.matches(other));
  other = hertz_mindlin;
  other.normal = NormalLaw::Hooke;
  EXPECT_FALSE(pattern.matches(other));
  other = hertz_mindlin;
  other.tangential = TangentialLaw::None;
  EXPECT_FALSE(pattern.matches(other));
}

TEST(CompiledContactLaws, TheDefaultBuildCompilesEveryValidLawAndNoOther) {
  std::size_t compiled = 0;
  for (int n = 0; n < 2; ++n)
    for (int d = 0; d < 3; ++d)
      for (int t = 0; t < 3; ++t)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            const ContactModel m{static_cast<NormalLaw>(n), static_cast<DampingLaw>(d),
                                 static_cast<TangentialLaw>(t), static_cast<RollingLaw>(r),
                                 static_cast<CohesionLaw>(c)};
            EXPECT_EQ(is_compiled_contact_model(m), is_valid_contact_model(m))
                << contact_model_name(m);
            compiled += is_compiled_contact_model(m) ? 1 : 0;
          }
  EXPECT_EQ(compiled, 78u);
  EXPECT_EQ(compiled_contact_models_text(), "every valid law");
}

TEST(ContactSlots, KeywordsAndHistorySizesComeFromTheSlotTypes) {
  EXPECT_EQ(normal_law_names(), (std::vector<std::string>{"hooke", "hertz"}));
  EXPECT_EQ(tangential_law_names(),
            (std::vector<std::string>{"none", "linear_history", "mindlin"}));
  EXPECT_EQ(
      contact_history_width(ContactModel{NormalLaw::Hertz, DampingLaw::None, TangentialLaw::Mindlin,
                                         RollingLaw::Epsd, CohesionLaw::None}),
      7u);
  EXPECT_EQ(
      contact_history_width(ContactModel{NormalLaw::Hooke, DampingLaw::None, TangentialLaw::None,
                                         RollingLaw::ConstantTorque, CohesionLaw::Sjkr}),
      0u);
  // ξ (3), sliding flag, rolling spring (3), JKR's formed flag
  EXPECT_EQ(
      contact_history_width(ContactModel{NormalLaw::Hertz, DampingLaw::None, TangentialLaw::Mindlin,
                                         RollingLaw::Epsd, CohesionLaw::Jkr}),
      8u);
  // The CMake option GPUDEM_CONTACT_LAWS names the same choices in the same order.
  std::string slots;
  for (const auto* names : {&normal_law_names(), &damping_law_names(), &tangential_law_names(),
                            &rolling_law_names(), &cohesion_law_names()}) {
    for (std::size_t k = 0; k < names->size(); ++k) slots += (k ? " " : "") + (*names)[k];
    slots += "|";
  }
  EXPECT_EQ(slots, GPUDEM_CONTACT_LAW_CHOICES);
}

}  // namespace
}  // namespace gpudem::test
