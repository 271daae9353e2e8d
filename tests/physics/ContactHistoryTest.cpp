// Contact history survives neighbour rebuilds: the tangential springs of a loaded, resting
// pile are carried over by partner global id when particles are re-sorted and lists rebuilt.
// Its width, the values per contact a checkpoint stores, is the contact law's history size:
// contact_history_width (what a restart expects of a scene) equals ContactLawOf::history_size
// for every valid model, and the engine of each model hands out records of that width.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "core/ContactModel.hpp"
#include "core/ParticleSources.hpp"
#include "core/contact/ContactLaw.hpp"
#include "engine/ExactSum.hpp"
#include "engine/SceneSetup.hpp"
#include "engine/SizeClassGrid.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

class ContactHistory : public BackendTest {};

std::map<ParticleId, Vec3> forces_by_id(const StepEngine& engine) {
  ParticleStore p;
  engine.get_particles(p);
  std::map<ParticleId, Vec3> out;
  for (std::size_t i = 0; i < p.size(); ++i) out[p.id[i]] = p.force[i];
  return out;
}

TEST_P(ContactHistory, SpringsSurviveRebuild) {
  // A small frictional bed at rest: friction carries part of the contact loads.
  Scene scene = basic_scene({0, 0, 0}, {0.05, 0.05, 0.2}, 2000, 0.2, 0.8);
  scene.domain.periodic = {true, true, false};
  add_floor(scene);
  add_box_source(scene, {0, 0, 0}, {0.05, 0.05, 0.05}, 300, 2.5e-3, 0.5e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  for (int n = 0; n < 40000; ++n) engine->step();  // KE falls below 1e-7 of the potential

  const auto before = forces_by_id(*engine);
  double weight = 0;  // the largest particle weight: the load scale of the bed
  for (const Real4& v : particles.velocity_inv_mass)
    weight = std::max(weight, norm(scene.simulation.gravity) / v.w);
  const std::uint64_t rebuilds = engine->rebuild_count();
  engine->rebuild_neighbors();
  EXPECT_EQ(engine->rebuild_count(), rebuilds + 1);
  const auto after = forces_by_id(*engine);
  ASSERT_EQ(before.size(), after.size());
  double worst = 0;
  for (const auto& [id, f] : before) worst = std::max(worst, norm(after.at(id) - f));
  // Springs advance by v_t·dt in the re-evaluation and the bed is at rest, so the net forces
  // (zero at equilibrium) stay tiny; dropping the springs would unbalance contacts carrying a
  // good part of a weight.
  RecordProperty("force_change_over_weight", significant(worst / weight));
  EXPECT_LT(worst, 1e-4 * weight) << "largest weight " << weight;
}

// Two touching 1 mm grains, one sliding past and spinning against the other: after a few
// steps every spring a law keeps is loaded, so each side of the contact holds a record.
TEST_P(ContactHistory, EngineRecordsAsManyValuesPerContactAsItsLawKeeps) {
  Scene scene = basic_scene({0, 0, 0}, {0.01, 0.01, 0.01}, 2000, 0.5, 0.5);
  scene.materials[0].rolling_friction = 0.1;  // μ_r > 0: an EPSD spring has stiffness
  scene.simulation.gravity = {0, 0, 0};
  scene.simulation.dt_auto = false;
  scene.simulation.dt = 1e-6;  // s: 5 steps leave the 10 µm overlap nearly unchanged
  const double radius = 1e-3;
  const double inv_mass = 1 / (scene.materials[0].density * 4.0 / 3.0 * M_PI * std::pow(radius, 3));
  ParticleStore pair;
  pair.add(1, {0.004, 0.005, 0.005}, radius, 0, {}, inv_mass);
  pair.add(2, {0.004 + 1.99 * radius, 0.005, 0.005}, radius, 0, {0, 0.01, 0}, inv_mass);
  pair.angular_velocity[1] = {1, 1, 1};  // rad/s: rolling and twisting against grain 1
  for (const ContactModel& model : valid_contact_models()) {
    scene.contact.model = model;
    auto engine = make_engine(make_engine_setup(scene, pair));
    engine->set_particles(pair);
    for (int n = 0; n < 5; ++n) engine->step();
    gpudem::ContactHistory history;
    engine->get_contact_history(history);
    const std::uint32_t width = contact_history_width(model);
    EXPECT_EQ(history.width, width) << contact_model_name(model);
    // Both grains hold their side of the one contact; a law without history holds none.
    const std::size_t records = width > 0 ? 2 : 0;
    EXPECT_EQ(history.pair_owner.size(), records) << contact_model_name(model);
    EXPECT_EQ(history.pair_values.size(), records * width) << contact_model_name(model);
    EXPECT_TRUE(history.wall_owner.empty()) << contact_model_name(model);
  }
}

/// Bytes of the array `name` in an engine's memory report.
std::size_t reported_bytes(const StepEngine& engine, const std::string& name) {
  for (const MemoryUse& use : engine.memory_use())
    if (name == use.name) return use.bytes;
  ADD_FAILURE() << "no array named " << name;
  return 0;
}

/// Records in the engine's history that are not zero, counted on host copies.
std::size_t loaded_pair_records(const StepEngine& engine) {
  gpudem::ContactHistory history;
  engine.get_contact_history(history);
  return history.pair_owner.size();
}

/// Bytes of a rebuild's history carry-over for n particles with `loaded` pair records of
/// `record` bytes: the row offsets, then each record with its partner's id.
std::size_t carry_over_bytes(std::size_t n, std::size_t loaded, std::size_t record) {
  return (n + 1) * sizeof(std::uint32_t) + loaded * (sizeof(ParticleId) + record);
}

// The memory a run holds is known before its first rebuild: a rebuild at unchanged positions
// (the same list) allocates the history carry-over, which the report counts from the start, so
// the engine's total does not change. The carry-over is one record per loaded spring with its
// partner's id, plus row offsets.
TEST_P(ContactHistory, MemoryReportBeforeARebuildCountsItsCarryOver) {
  Scene scene = basic_scene({0, 0, 0}, {0.05, 0.05, 0.05}, 2000, 0.2, 0.8);
  scene.materials[0].young = 1e6;
  add_box_source(scene, {0, 0, 0}, {0.05, 0.05, 0.05}, 400, 2.5e-3, 0.5e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles.position_radius[i].w *= 1.3;  // overlapping: a list with entries
    particles.velocity_inv_mass[i].x = 0.01 * static_cast<double>(i % 7);  // loaded springs
  }
  auto engine = make_engine(make_engine_setup(scene, particles));
  engine->set_particles(particles);
  const std::size_t before = engine->memory_bytes();
  const std::size_t loaded = loaded_pair_records(*engine);
  ASSERT_GT(loaded, particles.size());
  const std::size_t record = contact_history_width(scene.contact.model) * sizeof(double);
  EXPECT_EQ(reported_bytes(*engine, "history carry-over"),
            carry_over_bytes(particles.size(), loaded, record));
  engine->rebuild_neighbors();
  EXPECT_EQ(loaded_pair_records(*engine), loaded);
  EXPECT_EQ(engine->memory_bytes(), before);
}

/// Bytes of one pair of materials' law constants, at most.
constexpr std::size_t kPairConstantBytes = 512;

/// The bytes each report line of a one-rank engine without meshes needs, from its particle
/// count, list length, walls and loaded springs: state (positions, velocities, spins) in the
/// policy's state scalar (`state` bytes), forces and history in its law scalar (`scalar`
/// bytes), a cell range per cell at most (kMaxCellsPerParticle cells per particle and one cell
/// per empty size class at most).
std::map<std::string, std::size_t> needed_bytes(const StepEngine& engine, std::size_t walls,
                                                std::size_t width, std::size_t scalar,
                                                std::size_t state, Backend backend) {
  const std::size_t n = engine.owned_count(), record = width * scalar;
  std::vector<std::uint32_t> lengths;
  engine.get_list_lengths(lengths);
  std::size_t entries = 0;
  for (const std::uint32_t length : lengths) entries += length;
  const std::size_t index = sizeof(std::uint32_t);
  const std::size_t cells = kMaxCellsPerParticle * n + kMaxSizeClasses;
  // On the host, each particle's pair-once group, two integer sums and worst ratio left by its
  // partners, and the entries it evaluates: three bounds and two words per entry of its row, the
  // entry and its partner (one sweep of all particles).
  const std::size_t pair_once =
      backend == Backend::Host
          ? n * (sizeof(std::uint64_t) + 2 * (sizeof(ExactWords3) + sizeof(ExactSpill3)) +
                 sizeof(Real)) +
                (3 * n + 2 * entries) * index
          : 0;
  return {{"position, radius", n * 4 * state},
          {"velocity, inverse mass", n * 4 * state},
          {"angular velocity", n * 3 * state},
          {"id, material", n * (sizeof(ParticleId) + sizeof(MaterialId))},
          {"force, torque", n * 6 * scalar},
          {"overlap ratio", n * sizeof(Real)},
          {"position at list build", n * 4 * state},
          {"neighbour list", (n + 1 + entries) * index},
          {"pair history", entries * record},
          {"wall history", n * walls * record},
          {"walls in reach", walls > 0 ? n * index : 0},
          {"cell list", n * index + (cells + 1) * index},
          {"history carry-over", carry_over_bytes(n, loaded_pair_records(engine), record)},
          {"rebuild scratch", n * index},  // each particle's row in the previous list
          {"ghost buffers", 0},
          {"meshes", 0},
          // one material
          {"contact law", kPairConstantBytes + pair_once}};
}

// After a poured bed has settled through many rebuilds, no array of the engine is larger than
// what it needs: one list entry per neighbour, history per entry and per wall, and a carry-over
// of the loaded springs only (not of every list entry). Holding a second list or history, or a
// list with room to grow, exceeds these sizes.
TEST_P(ContactHistory, SettledBedHoldsNoMoreThanItsArraysNeed) {
  Scene scene = basic_scene({0, 0, 0}, {0.05, 0.05, 0.2}, 2000, 0.2, 0.8);
  scene.materials[0].young = 1e6;
  scene.domain.periodic = {true, true, false};
  add_floor(scene);
  add_box_source(scene, {0, 0, 0}, {0.05, 0.05, 0.07}, 800, 2.5e-3, 0.5e-3);
  ParticleStore particles;
  create_particles(scene, particles);
  const std::size_t width = contact_history_width(scene.contact.model);
  for (const Precision precision : {Precision::Double, Precision::Mixed, Precision::Float}) {
    const char* name = precision == Precision::Double  ? "double"
                       : precision == Precision::Mixed ? "mixed"
                                                       : "float";
    SCOPED_TRACE(name);
    const std::size_t scalar = precision == Precision::Double ? sizeof(double) : sizeof(float);
    const std::size_t state = precision == Precision::Float ? sizeof(float) : sizeof(double);
    EngineSetup setup = make_engine_setup(scene, particles);
    setup.precision = precision;
    auto engine = make_engine(setup);
    engine->set_particles(particles);
    for (int n = 0; n < 6000; ++n) engine->step();
    ASSERT_GE(engine->rebuild_count(), 5u);
    const auto needed =
        needed_bytes(*engine, scene.walls.size(), width, scalar, state, GetParam().backend);
    std::size_t total = 0;
    for (const MemoryUse& use : engine->memory_use()) {
      ASSERT_EQ(needed.count(use.name), 1u) << "unexpected array " << use.name;
      EXPECT_LE(use.bytes, needed.at(use.name)) << use.name;
      total += needed.at(use.name);
    }
    EXPECT_LE(engine->memory_bytes(), total);
    RecordProperty(std::string(name) + "_bytes_per_particle",
                   significant(double(engine->memory_bytes()) / particles.size()));
  }
}

GPUDEM_INSTANTIATE_BACKENDS(ContactHistory);

// ---- history width of each contact law ------------------------------------------------------

constexpr std::size_t kNormalLaws = 2, kDampingLaws = 3, kTangentialLaws = 3, kRollingLaws = 3,
                      kCohesionLaws = 3;
constexpr std::size_t kSlotCombinations =
    kNormalLaws * kDampingLaws * kTangentialLaws * kRollingLaws * kCohesionLaws;

/// Combination `I` of slot choices, numbered in enum order with cohesion varying fastest.
template <std::size_t I>
constexpr int kernel_history_size() {
  constexpr std::size_t c = I % kCohesionLaws;
  constexpr std::size_t r = I / kCohesionLaws % kRollingLaws;
  constexpr std::size_t t = I / (kCohesionLaws * kRollingLaws) % kTangentialLaws;
  constexpr std::size_t d = I / (kCohesionLaws * kRollingLaws * kTangentialLaws) % kDampingLaws;
  constexpr std::size_t n = I / (kCohesionLaws * kRollingLaws * kTangentialLaws * kDampingLaws);
  return ContactLawOf<static_cast<NormalLaw>(n), static_cast<DampingLaw>(d),
                      static_cast<TangentialLaw>(t), static_cast<RollingLaw>(r),
                      static_cast<CohesionLaw>(c)>::history_size;
}

template <std::size_t... I>
constexpr std::array<int, sizeof...(I)> kernel_history_sizes(std::index_sequence<I...>) {
  return {kernel_history_size<I>()...};
}

/// The number kernel_history_size gives the combination of `m`.
std::size_t combination_number(const ContactModel& m) {
  std::size_t number = static_cast<std::size_t>(m.normal);
  number = number * kDampingLaws + static_cast<std::size_t>(m.damping);
  number = number * kTangentialLaws + static_cast<std::size_t>(m.tangential);
  number = number * kRollingLaws + static_cast<std::size_t>(m.rolling);
  return number * kCohesionLaws + static_cast<std::size_t>(m.cohesion);
}

TEST(ContactHistoryWidth, IsTheKernelLawsHistorySizeForEveryValidModel) {
  constexpr auto sizes = kernel_history_sizes(std::make_index_sequence<kSlotCombinations>{});
  ASSERT_EQ(normal_law_names().size() * damping_law_names().size() * tangential_law_names().size() *
                rolling_law_names().size() * cohesion_law_names().size(),
            kSlotCombinations)
      << "a slot gained a choice";
  for (const ContactModel& m : valid_contact_models())
    EXPECT_EQ(contact_history_width(m), static_cast<std::uint32_t>(sizes[combination_number(m)]))
        << contact_model_name(m);
}

TEST(ContactHistoryWidth, CountsTheTangentialSpringAndFlagTheRollingSpringAndJkrsFlag) {
  ContactModel m;  // hooke/restitution/linear_history/none/none
  EXPECT_EQ(contact_history_width(m), 4u);
  m.rolling = RollingLaw::ConstantTorque;
  EXPECT_EQ(contact_history_width(m), 4u);
  m.rolling = RollingLaw::Epsd;
  EXPECT_EQ(contact_history_width(m), 7u);
  m.tangential = TangentialLaw::None;
  EXPECT_EQ(contact_history_width(m), 3u);
  m.rolling = RollingLaw::None;
  m.cohesion = CohesionLaw::Sjkr;
  EXPECT_EQ(contact_history_width(m), 0u);
  m = {NormalLaw::Hertz, DampingLaw::Viscoelastic, TangentialLaw::Mindlin, RollingLaw::Epsd,
       CohesionLaw::Sjkr};
  EXPECT_EQ(contact_history_width(m), 7u);
  m.cohesion = CohesionLaw::Jkr;  // the flag of a contact that has formed
  EXPECT_EQ(contact_history_width(m), 8u);
}

}  // namespace
}  // namespace gpudem::test
