// The mixed precision policy against double on the same scenes: positions and velocities stay
// double, the contact laws, their history and the force sums run in float. Its forces on a
// random polydisperse Hertz–Mindlin bed are those of double to float rounding, it holds the
// history and the forces in half the bytes, and a falling bed ends in the same state in the
// mean (the flow is chaotic, so particles are not compared one by one).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/RandomBed.hpp"

namespace gpudem::test {
namespace {

/// A few dozen float roundings (unit roundoff 6e-8) of the largest force in the bed.
constexpr double kFloatAgreement = 1e-5;

class MixedPrecision : public BackendTest {
 protected:
  /// Engines for `setup` in double and in mixed precision.
  std::pair<std::unique_ptr<StepEngine>, std::unique_ptr<StepEngine>> engines(
      EngineSetup setup) const {
    setup.precision = Precision::Double;
    auto exact = make_engine(setup);
    setup.precision = Precision::Mixed;
    return {std::move(exact), make_engine(setup)};
  }
};

/// Forces and torques of the two engines, compared by particle id: within float rounding of
/// the largest, and not identical.
void expect_float_rounding_apart(const StepEngine& exact, const StepEngine& mixed,
                                 const char* when) {
  ParticleStore a, b;
  exact.get_particles(a);
  mixed.get_particles(b);
  ASSERT_EQ(a.size(), b.size());
  const double force = relative_spread(a, b, &ParticleStore::force);
  const double torque = relative_spread(a, b, &ParticleStore::torque);
  ::testing::Test::RecordProperty(std::string("force_spread_") + when, significant(force));
  ::testing::Test::RecordProperty(std::string("torque_spread_") + when, significant(torque));
  EXPECT_GT(force, 0) << when;
  EXPECT_LE(force, kFloatAgreement) << when;
  EXPECT_LE(torque, kFloatAgreement) << when;
}

TEST_P(MixedPrecision, ForcesOfARandomBedAreDoublesToFloatRounding) {
  const Scene scene = hertz_mindlin_box({0.08, 0.08, 0.08}, 1200, 2.5e-3);
  const ParticleStore particles = overlapping_bed(scene);
  auto [exact, mixed] = engines(make_engine_setup(scene, particles));
  exact->set_particles(particles);
  mixed->set_particles(particles);
  ASSERT_GT(exact->diagnostics().contact_count, particles.size() / 2);
  expect_float_rounding_apart(*exact, *mixed, "initial");
  exact->step();
  mixed->step();
  expect_float_rounding_apart(*exact, *mixed, "after_one_step");
}

/// Bytes of the array `name` in an engine's memory report.
std::size_t bytes_of(const StepEngine& engine, const std::string& name) {
  for (const MemoryUse& use : engine.memory_use())
    if (name == use.name) return use.bytes;
  ADD_FAILURE() << "no array named " << name;
  return 0;
}

TEST_P(MixedPrecision, HoldsHistoryAndForcesInHalfTheBytes) {
  const Scene scene = hertz_mindlin_box({0.08, 0.08, 0.08}, 1200, 2.5e-3);
  const ParticleStore particles = overlapping_bed(scene);
  auto [exact, mixed] = engines(make_engine_setup(scene, particles));
  exact->set_particles(particles);
  mixed->set_particles(particles);
  for (const char* name : {"pair history", "wall history", "force, torque"}) {
    SCOPED_TRACE(name);
    ASSERT_GT(bytes_of(*exact, name), 0u);
    EXPECT_EQ(2 * bytes_of(*mixed, name), bytes_of(*exact, name));
  }
  EXPECT_EQ(bytes_of(*mixed, "position, radius"), bytes_of(*exact, "position, radius"));
}

TEST_P(MixedPrecision, FallingBedIsTheSameInTheMean) {
  const Scene scene = hertz_mindlin_box({0.06, 0.06, 0.12}, 2000, 2e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  auto [exact, mixed] = engines(make_engine_setup(scene, particles));
  exact->set_particles(particles);
  mixed->set_particles(particles);
  const double start = exact->diagnostics().potential_gravity;
  for (int n = 0; n < 10000; ++n) {
    exact->step();
    mixed->step();
  }
  const Diagnostics e = exact->diagnostics(), m = mixed->diagnostics();
  const double fall = start - e.potential_gravity;  // energy the bed released falling
  RecordProperty("potential_difference_over_fall",
                 significant(std::abs(e.potential_gravity - m.potential_gravity) / fall));
  RecordProperty("contacts_double", significant(double(e.contact_count)));
  RecordProperty("contacts_mixed", significant(double(m.contact_count)));
  ASSERT_GT(fall, 0);
  ASSERT_GT(e.contact_count, particles.size());  // the bed has landed
  EXPECT_LT(std::abs(e.potential_gravity - m.potential_gravity), 0.01 * fall);
  EXPECT_NEAR(double(m.contact_count), double(e.contact_count), 0.05 * e.contact_count);
  const double exact_kinetic = e.kinetic_translational + e.kinetic_rotational;
  const double mixed_kinetic = m.kinetic_translational + m.kinetic_rotational;
  EXPECT_LT(std::abs(exact_kinetic - mixed_kinetic), 0.01 * fall);
}

GPUDEM_INSTANTIATE_BACKENDS(MixedPrecision);

}  // namespace
}  // namespace gpudem::test
