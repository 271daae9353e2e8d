// The CUDA backend against the host backend on the same scene, in double precision: the forces
// and torques of a random polydisperse bed (Hertz–Mindlin, constant-torque rolling) agree to
// 1e-12 of the largest force before and after one step, and a 10^4-sphere bed falling for
// 10^4 steps on each ends in the same state in the mean: potential and kinetic energy within
// 1 % of the energy the fall released, contact count within 5 %. Both backends sum each particle's
// contacts in the same (partner-id) order, so only the rounding of single operations differs
// (fused multiply-adds on the device); the settling flow is chaotic, so its particles are not
// compared one by one. Skipped where no CUDA device is visible.
#include <gtest/gtest.h>

#include "core/ParticleSources.hpp"
#include "engine/CudaMemory.hpp"
#include "engine/SceneSetup.hpp"
#include "support/Format.hpp"
#include "support/RandomBed.hpp"

namespace gpudem::test {
namespace {

constexpr double kForceAgreement = 1e-12;  ///< of the largest force (torque) in the bed

bool cuda_device_visible() { return cuda::compiled_in() && cuda::device_count() > 0; }

/// Forces and torques of host and CUDA engines, compared by particle id.
void expect_same_loads(const StepEngine& host, const StepEngine& device, const char* when) {
  const LoadSpread spread = recorded_load_spread(host, device, when);
  EXPECT_LE(spread.force, kForceAgreement) << when;
  EXPECT_LE(spread.torque, kForceAgreement) << when;
}

TEST(BackendAgreement, ForcesOfARandomBedAgreeBeforeAndAfterOneStep) {
  if (!cuda_device_visible()) GTEST_SKIP() << "no CUDA device on this machine";
  const Scene scene = hertz_mindlin_box({0.08, 0.08, 0.08}, 1200, 2.5e-3);
  const ParticleStore particles = overlapping_bed(scene);
  const EngineSetup setup = make_engine_setup(scene, particles);
  auto host = make_host_engine(setup);
  auto device = make_cuda_engine(setup);
  host->set_particles(particles);
  device->set_particles(particles);
  const std::uint64_t contacts = host->diagnostics().contact_count;
  RecordProperty("contacts", significant(double(contacts)));
  ASSERT_GT(contacts, particles.size() / 2);  // the comparison sees contact forces
  expect_same_loads(*host, *device, "initial");
  host->step();
  device->step();
  expect_same_loads(*host, *device, "after_one_step");
}

TEST(BackendAgreement, FallingBedIsTheSameInTheMean) {
  if (!cuda_device_visible()) GTEST_SKIP() << "no CUDA device on this machine";
  Scene scene = hertz_mindlin_box({0.1, 0.1, 0.2}, 10000, 2e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  const EngineSetup setup = make_engine_setup(scene, particles);
  auto host = make_host_engine(setup);
  auto device = make_cuda_engine(setup);
  host->set_particles(particles);
  device->set_particles(particles);
  expect_same_in_the_mean(*host, *device, 10000, "host", "cuda");
}

}  // namespace
}  // namespace gpudem::test
