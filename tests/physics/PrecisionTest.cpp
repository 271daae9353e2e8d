// The mixed precision policy against double on the same scenes: positions and velocities stay
// double, the contact laws, their history and the force sums run in float. Its forces on a
// random polydisperse Hertz–Mindlin bed are those of double to float rounding, it holds the
// history and the forces in half the bytes, and a falling bed ends in the same state in the
// mean (the flow is chaotic, so particles are not compared one by one). The float policy also
// stores the particle state in float: given a state that float represents exactly, its forces
// are those of mixed bit for bit (the storage is its only difference), it holds the state in
// half the bytes, and a falling bed ends as in double in the mean.
#include <gtest/gtest.h>

#include <cstring>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/RandomBed.hpp"

namespace gpudem::test {
namespace {

/// A few dozen float roundings (unit roundoff 6e-8) of the largest force in the bed.
constexpr double kFloatAgreement = 1e-5;

class MixedPrecision : public BackendTest {
 protected:
  /// Engines for `scene` in precision `a` and in precision `b`, both holding `particles`.
  std::pair<std::unique_ptr<StepEngine>, std::unique_ptr<StepEngine>> started_engines(
      const Scene& scene, const ParticleStore& particles, Precision a = Precision::Double,
      Precision b = Precision::Mixed) const {
    EngineSetup setup = make_engine_setup(scene, particles);
    setup.precision = a;
    auto first = make_engine(setup);
    setup.precision = b;
    auto second = make_engine(setup);
    first->set_particles(particles);
    second->set_particles(particles);
    return {std::move(first), std::move(second)};
  }
};

/// Forces and torques of the two engines, compared by particle id: within float rounding of
/// the largest, and not identical.
void expect_float_rounding_apart(const StepEngine& exact, const StepEngine& mixed,
                                 const char* when) {
  const LoadSpread spread = recorded_load_spread(exact, mixed, when);
  EXPECT_GT(spread.force, 0) << when;
  EXPECT_LE(spread.force, kFloatAgreement) << when;
  EXPECT_LE(spread.torque, kFloatAgreement) << when;
}

TEST_P(MixedPrecision, ForcesOfARandomBedAreDoublesToFloatRounding) {
  const Scene scene = hertz_mindlin_box({0.08, 0.08, 0.08}, 1200, 2.5e-3);
  const ParticleStore particles = overlapping_bed(scene);
  auto [exact, mixed] = started_engines(scene, particles);
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

/// Each array named holds in `halved` half the bytes it holds in `full` (and some).
void expect_half_the_bytes(const StepEngine& full, const StepEngine& halved,
                           std::initializer_list<const char*> names) {
  for (const char* name : names) {
    SCOPED_TRACE(name);
    ASSERT_GT(bytes_of(full, name), 0u);
    EXPECT_EQ(2 * bytes_of(halved, name), bytes_of(full, name));
  }
}

TEST_P(MixedPrecision, HoldsHistoryAndForcesInHalfTheBytes) {
  const Scene scene = hertz_mindlin_box({0.08, 0.08, 0.08}, 1200, 2.5e-3);
  const ParticleStore particles = overlapping_bed(scene);
  auto [exact, mixed] = started_engines(scene, particles);
  expect_half_the_bytes(*exact, *mixed, {"pair history", "wall history", "force, torque"});
  EXPECT_EQ(bytes_of(*mixed, "position, radius"), bytes_of(*exact, "position, radius"));
}

TEST_P(MixedPrecision, FallingBedIsTheSameInTheMean) {
  const Scene scene = hertz_mindlin_box({0.06, 0.06, 0.12}, 2000, 2e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  auto [exact, mixed] = started_engines(scene, particles);
  const Diagnostics landed = expect_same_in_the_mean(*exact, *mixed, 10000, "double", "mixed");
  EXPECT_GT(landed.contact_count, particles.size());  // the bed has landed
}

/// `particles` with every state value rounded to float, so that each policy holds it exactly.
ParticleStore rounded_to_float(ParticleStore particles) {
  const auto round4 = [](Real4& v) { v = vec4_cast<Real>(vec4_cast<float>(v)); };
  for (Real4& v : particles.position_radius) round4(v);
  for (Real4& v : particles.velocity_inv_mass) round4(v);
  for (Vec3& w : particles.angular_velocity) w = vec_cast<Real>(vec_cast<float>(w));
  return particles;
}

TEST_P(MixedPrecision, FloatForcesAreMixedForcesOfTheSameFloatState) {
  const Scene scene = hertz_mindlin_box({0.08, 0.08, 0.08}, 1200, 2.5e-3);
  const ParticleStore particles = rounded_to_float(overlapping_bed(scene));
  auto [mixed, single] = started_engines(scene, particles, Precision::Mixed, Precision::Float);
  ASSERT_GT(mixed->diagnostics().contact_count, particles.size() / 2);
  const LoadSpread spread = recorded_load_spread(*mixed, *single, "initial");
  EXPECT_EQ(spread.force, 0);
  EXPECT_EQ(spread.torque, 0);
  ParticleStore held;
  single->get_particles(held);
  std::map<ParticleId, std::size_t> given;
  for (std::size_t i = 0; i < particles.size(); ++i) given[particles.id[i]] = i;
  ASSERT_EQ(held.size(), particles.size());
  for (std::size_t i = 0; i < held.size(); ++i)
    ASSERT_EQ(0, std::memcmp(&held.position_radius[i],
                             &particles.position_radius[given.at(held.id[i])], sizeof(Real4)))
        << "the float engine changed the position of particle " << held.id[i]
        << ", which float represents exactly";
}

TEST_P(MixedPrecision, FloatHoldsTheParticleStateInHalfTheBytes) {
  const Scene scene = hertz_mindlin_box({0.08, 0.08, 0.08}, 1200, 2.5e-3);
  const ParticleStore particles = overlapping_bed(scene);
  auto [mixed, single] = started_engines(scene, particles, Precision::Mixed, Precision::Float);
  expect_half_the_bytes(
      *mixed, *single,
      {"position, radius", "velocity, inverse mass", "angular velocity", "position at list build"});
  EXPECT_EQ(bytes_of(*single, "pair history"), bytes_of(*mixed, "pair history"));
}

TEST_P(MixedPrecision, FloatFallingBedIsTheSameInTheMean) {
  const Scene scene = hertz_mindlin_box({0.06, 0.06, 0.12}, 2000, 2e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  auto [exact, single] = started_engines(scene, particles, Precision::Double, Precision::Float);
  const Diagnostics landed = expect_same_in_the_mean(*exact, *single, 10000, "double", "float");
  EXPECT_GT(landed.contact_count, particles.size());  // the bed has landed
}

GPUDEM_INSTANTIATE_BACKENDS(MixedPrecision);

}  // namespace
}  // namespace gpudem::test
