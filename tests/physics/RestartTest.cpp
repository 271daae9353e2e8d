// Restart equivalence through the engine API and a checkpoint file: a frictional bed settling
// on a floor, run 2T straight, equals bit for bit the run of T, checkpointed, restored into a
// fresh engine and run T more. Restoring without the contact history must change the result,
// so the comparison is sensitive to the tangential springs. History naming contacts the engine
// does not hold, or written by a law keeping another number of values per contact, is
// rejected.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "comm/Checkpoint.hpp"
#include "core/ContactModel.hpp"
#include "core/ParticleSources.hpp"
#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SameBits.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

namespace fs = std::filesystem;

/// Steps in T: particles inserted up to 5 cm above the floor have fallen onto it and onto
/// each other (hundreds of springs, several neighbour rebuilds) by then.
constexpr int kStepsT = 1500;

/// 300 particles in a 5 cm periodic column above a floor, friction 0.8.
Scene bed_scene() {
  Scene scene = basic_scene({0, 0, 0}, {0.05, 0.05, 0.2}, 2000, 0.2, 0.8);
  scene.domain.periodic = {true, true, false};
  scene.simulation.dt_auto = false;
  scene.simulation.dt = 5e-5;
  WallSettings floor;
  floor.name = "floor";
  floor.normal = {0, 0, 1};
  scene.walls.push_back(floor);
  ParticleSource source;
  source.region_min = {0, 0, 0};
  source.region_max = {0.05, 0.05, 0.05};
  source.count = 300;
  source.radius.mean = 2.5e-3;
  source.radius.spread = 0.5e-3;
  scene.sources.push_back(source);
  return scene;
}

/// The engine state a checkpoint holds, as the runner collects it.
Checkpoint capture(const StepEngine& engine, std::uint64_t step, const EngineSetup& setup) {
  Checkpoint c;
  engine.get_particles(c.particles);
  engine.get_list_positions(c.list_position_radius);
  c.list_build = engine.list_build_clock();
  engine.get_contact_history(c.history);
  c.step = step;
  c.time = step * setup.dt;
  c.removed = engine.removed_count();
  c.dt = setup.dt;
  c.skin = setup.skin;
  return c;
}

/// Largest absolute difference over positions [m], velocities [m/s] and spins [rad/s] of the
/// particles with the same global id (both stores must hold the same ids).
double largest_difference(const ParticleStore& a, const ParticleStore& b) {
  std::map<ParticleId, std::size_t> row_of;
  for (std::size_t j = 0; j < b.size(); ++j) row_of[b.id[j]] = j;
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::size_t j = row_of.at(a.id[i]);
    worst = std::max(worst, norm(xyz(a.position_radius[i]) - xyz(b.position_radius[j])));
    worst = std::max(worst, norm(xyz(a.velocity_inv_mass[i]) - xyz(b.velocity_inv_mass[j])));
    worst = std::max(worst, norm(a.angular_velocity[i] - b.angular_velocity[j]));
  }
  return worst;
}

class Restart : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (IsSkipped()) return;
    scene_ = bed_scene();
    create_particles(scene_, particles_);
    setup_ = make_engine_setup(scene_, particles_);
    dir_ = fs::temp_directory_path() / ("gpudem_restart_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::unique_ptr<StepEngine> started() const {
    auto engine = make_engine(setup_);
    engine->set_particles(particles_);
    return engine;
  }

  static void run(StepEngine& engine, int steps) {
    for (int n = 0; n < steps; ++n) engine.step();
  }

  /// A fresh engine restored from the checkpoint file, with or without its contact history.
  std::unique_ptr<StepEngine> restored(const Checkpoint& c, bool with_history) const {
    auto engine = make_engine(setup_);
    engine->restore_particles(c.particles, c.list_position_radius, c.removed, c.list_build);
    engine->set_contact_history(with_history ? c.history : ContactHistory{});
    return engine;
  }

  Scene scene_;
  ParticleStore particles_;
  EngineSetup setup_;
  fs::path dir_;
};

TEST_P(Restart, CheckpointedRunContinuesBitIdentically) {
  auto straight = started();
  run(*straight, 2 * kStepsT);
  ParticleStore expected;
  straight->get_particles(expected);

  auto first_leg = started();
  run(*first_leg, kStepsT);
  write_checkpoint(MPI_COMM_WORLD, dir_.string(), capture(*first_leg, kStepsT, setup_));
  const Checkpoint c = read_checkpoint(checkpoint_path(dir_.string()));
  EXPECT_EQ(c.history.width, 4u) << "linear_history keeps a spring and a sliding flag";
  ASSERT_GT(c.history.pair_owner.size(), 100u) << "the bed must hold tangential springs at T";
  ASSERT_GT(c.history.wall_owner.size(), 10u) << "and springs on the floor";

  auto second_leg = restored(c, true);
  const std::uint64_t rebuilds_before = second_leg->rebuild_count();
  run(*second_leg, kStepsT);
  EXPECT_GT(second_leg->rebuild_count(), rebuilds_before) << "T must include neighbour rebuilds";
  ParticleStore actual;
  second_leg->get_particles(actual);
  EXPECT_TRUE(same_bits(actual.id, expected.id)) << "particle order differs";
  EXPECT_TRUE(same_bits(actual.position_radius, expected.position_radius))
      << "largest difference " << largest_difference(actual, expected);
  EXPECT_TRUE(same_bits(actual.velocity_inv_mass, expected.velocity_inv_mass));
  EXPECT_TRUE(same_bits(actual.angular_velocity, expected.angular_velocity));
  EXPECT_EQ(second_leg->removed_count(), straight->removed_count());

  ContactHistory straight_history, restored_history;
  straight->get_contact_history(straight_history);
  second_leg->get_contact_history(restored_history);
  EXPECT_EQ(restored_history.width, straight_history.width);
  EXPECT_TRUE(same_bits(restored_history.pair_values, straight_history.pair_values));
  EXPECT_TRUE(same_bits(restored_history.wall_values, straight_history.wall_values));
}

TEST_P(Restart, RestartWithoutContactHistoryDiverges) {
  auto straight = started();
  run(*straight, 2 * kStepsT);
  ParticleStore expected;
  straight->get_particles(expected);

  auto first_leg = started();
  run(*first_leg, kStepsT);
  const Checkpoint c = capture(*first_leg, kStepsT, setup_);
  auto forgetful = restored(c, false);
  run(*forgetful, kStepsT);
  ParticleStore actual;
  forgetful->get_particles(actual);
  ASSERT_EQ(actual.size(), expected.size());
  const double difference = largest_difference(actual, expected);
  RecordProperty("difference_without_history", significant(difference));
  // An exact restart differs by 0. Dropping hundreds of loaded springs changes the motion
  // itself, far beyond rounding; 1e-6 (m, m/s or rad/s) is a floor well below that.
  EXPECT_GT(difference, 1e-6) << "the contact history made no difference";
}

/// Setting `history` throws std::invalid_argument with `needle` in its message.
void expect_rejected(StepEngine& engine, const ContactHistory& history, const std::string& needle) {
  try {
    engine.set_contact_history(history);
    ADD_FAILURE() << "a history expected to fail with '" << needle << "' was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST_P(Restart, HistoryOfContactsTheEngineDoesNotHoldIsRejected) {
  auto engine = started();
  const std::uint32_t width = contact_history_width(scene_.contact.model);
  const auto history = [width] {
    ContactHistory h;
    h.width = width;
    return h;
  };
  std::vector<Real> spring(width, 0);
  spring.at(0) = 1e-6;
  const ParticleId unknown = 1u << 30;
  ContactHistory unknown_owner = history();
  unknown_owner.add_pair(unknown, particles_.id[0], spring.data());
  expect_rejected(*engine, unknown_owner, std::to_string(unknown) + " is not in the engine");
  ContactHistory unknown_partner = history();
  unknown_partner.add_pair(particles_.id[0], unknown, spring.data());
  expect_rejected(*engine, unknown_partner, std::to_string(unknown) + " are not neighbours");
  ParticleStore p;
  engine->get_particles(p);
  std::size_t low = 0, high = 0;  // along z, which is not periodic: centimetres apart
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.position_radius[i].z < p.position_radius[low].z) low = i;
    if (p.position_radius[i].z > p.position_radius[high].z) high = i;
  }
  ASSERT_GT(p.position_radius[high].z - p.position_radius[low].z, 0.02);
  ContactHistory not_neighbours = history();
  not_neighbours.add_pair(p.id[low], p.id[high], spring.data());
  expect_rejected(*engine, not_neighbours, "are not neighbours");
  ContactHistory no_such_wall = history();
  no_such_wall.add_wall(p.id[0], 1, spring.data());  // the scene has one wall
  expect_rejected(*engine, no_such_wall, "wall index 1");
}

TEST_P(Restart, HistoryOfAnotherContactLawIsRejected) {
  auto engine = started();
  ContactHistory rolling_too;  // linear_history with an EPSD rolling spring: 7 values
  rolling_too.width = 7;
  const std::vector<Real> values{1e-6, 0, 0, 0, 1e-3, 0, 0};
  rolling_too.add_wall(particles_.id[0], 0, values.data());
  expect_rejected(*engine, rolling_too, "holds 7 values per contact but this contact law keeps 4");
}

GPUDEM_INSTANTIATE_BACKENDS_AND_PRECISIONS(Restart);

}  // namespace
}  // namespace gpudem::test
