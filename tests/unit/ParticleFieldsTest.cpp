// The particle field table (core/ParticleFields.hpp) and what it drives on the host backend
// (engine/ParticleColumns.hpp): the wire row of each use holds exactly its fields' values in
// table order, a row written and read back is the same bits, a missing field travels as zeros,
// the host store and the engine's arrays follow the table's uses, and the memory report
// groups fields by label.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/ParticleFields.hpp"
#include "core/ParticleStore.hpp"
#include "engine/ParallelFor.hpp"
// The backend's parallel_for header must come first: the columns' permutation calls it.
#include "engine/ParticleColumns.hpp"

namespace gpudem {
namespace {

using particle_field::AngularVelocity;
using particle_field::Force;
using particle_field::Id;
using particle_field::PositionRadius;
using particle_field::Torque;
using particle_field::VelocityInvMass;
using MaterialField = particle_field::Material;

/// Names of the fields whose uses meet `Use`, in the order the table visits them.
template <unsigned Use>
std::vector<std::string> names_of() {
  std::vector<std::string> names;
  for_each_particle_field<Use>([&](auto field) { names.push_back(field.name); });
  return names;
}

TEST(ParticleFields, EachUseSelectsItsFieldsInTableOrder) {
  using V = std::vector<std::string>;
  EXPECT_EQ(names_of<field_use::any>(),
            (V{"position_radius", "velocity_inv_mass", "angular_velocity", "id", "material",
               "force", "torque"}));
  EXPECT_EQ(names_of<field_use::ghost>(),
            (V{"position_radius", "velocity_inv_mass", "angular_velocity", "id", "material"}));
  EXPECT_EQ(names_of<field_use::persistent>(), names_of<field_use::ghost>());
  EXPECT_EQ(names_of<field_use::refresh>(), (V{"position_radius", "velocity_inv_mass"}));
  EXPECT_EQ(names_of<field_use::spin_refresh>(), (V{"angular_velocity"}));
  EXPECT_EQ(names_of<field_use::checkpoint>(), names_of<field_use::any>());
}

TEST(ParticleFields, RowBytesAreTheSumOfTheFieldsValues) {
  // Ghost row, double state: 2 × 32 + 24 + 8 + 4; float state: 2 × 16 + 12 + 8 + 4.
  EXPECT_EQ((WireRow<field_use::ghost, double, double>::bytes), 100u);
  EXPECT_EQ((WireRow<field_use::ghost, float, float>::bytes), 56u);
  // Every field in Real (start-up routing): the ghost row plus force and torque.
  EXPECT_EQ((WireRow<field_use::checkpoint, double, double>::bytes), 148u);
  // Mixed policy: state in double, loads in float.
  EXPECT_EQ((WireRow<field_use::checkpoint, double, float>::bytes), 124u);
  EXPECT_EQ((WireRow<field_use::refresh | field_use::spin_refresh, float, float>::bytes),
            11 * sizeof(float));
}

/// Two particles with values that name their field and row.
struct TwoParticles {
  std::vector<Vec4T<float>> position_radius{{1, 2, 3, 0.5f}, {4, 5, 6, 0.25f}};
  std::vector<Vec4T<float>> velocity_inv_mass{{-1, -2, -3, 8}, {-4, -5, -6, 16}};
  std::vector<Vec3T<float>> angular_velocity{{0.1f, 0.2f, 0.3f}, {0.4f, 0.5f, 0.6f}};
  std::vector<ParticleId> id{77, 0xfedcba9876543210ull};
  std::vector<MaterialId> material{3, 9};
  std::vector<Vec3T<double>> force{{1e3, 2e3, 3e3}, {4e3, 5e3, 6e3}};
  std::vector<Vec3T<double>> torque{{7, 8, 9}, {10, 11, 12}};

  ParticlePointers<float, double> pointers() {
    ParticlePointers<float, double> p{};
    for_each_particle_field(
        [&](auto field) { p.template get<decltype(field)>() = decltype(field)::of(*this).data(); });
    return p;
  }
};

TEST(ParticleFields, AWireRowWrittenAndReadBackIsTheSameBits) {
  using Row = WireRow<field_use::checkpoint, float, double>;
  TwoParticles from;
  std::vector<char> bytes(Row::bytes);
  Row::write(from.pointers(), 1, bytes.data());
  // The first bytes are particle 1's position and radius, the last its torque.
  EXPECT_EQ(std::memcmp(bytes.data(), &from.position_radius[1], sizeof(Vec4T<float>)), 0);
  EXPECT_EQ(std::memcmp(bytes.data() + Row::bytes - sizeof(Vec3T<double>), &from.torque[1],
                        sizeof(Vec3T<double>)),
            0);
  TwoParticles to;
  Row::read(bytes.data(), to.pointers(), 0);
  for_each_particle_field([&](auto field) {
    using F = decltype(field);
    SCOPED_TRACE(F::name);
    EXPECT_EQ(std::memcmp(&F::of(to)[0], &F::of(from)[1], sizeof(F::of(from)[1])), 0);
  });
}

TEST(ParticleFields, AFieldWithoutValuesTravelsAsZeros) {
  using Row = WireRow<field_use::checkpoint, float, double>;
  TwoParticles from;
  ParticlePointers<float, double> p = from.pointers();
  p.get<Force>() = nullptr;
  std::vector<char> bytes(Row::bytes, 'x');
  Row::write(p, 0, bytes.data());
  TwoParticles to;
  Row::read(bytes.data(), to.pointers(), 1);
  EXPECT_EQ(to.force[1].x, 0.0);
  EXPECT_EQ(to.force[1].z, 0.0);
  EXPECT_EQ(to.torque[1].y, from.torque[0].y);
  EXPECT_EQ(to.id[1], from.id[0]);
}

TEST(ParticleFields, StoreAddsAppendsAndPointsAtEveryField) {
  ParticleStore a;
  a.add(5, {1, 2, 3}, 0.5, 2, {0, 0, -1}, 4);
  ParticleStore b;
  b.add(6, {4, 5, 6}, 0.25, 1, {1, 0, 0}, 8);
  a.append(b);
  for_each_particle_field([&](auto field) { EXPECT_EQ(field.of(a).size(), 2u) << field.name; });
  EXPECT_EQ(a.id[1], 6u);
  EXPECT_EQ(a.velocity_inv_mass[1].w, 8.0);
  EXPECT_EQ(a.torque[0].x, 0.0);
  a.force.clear();  // a share without forces
  const ParticlePointers<Real, Real> p = row_pointers(static_cast<const ParticleStore&>(a));
  EXPECT_EQ(p.get<Force>(), nullptr);
  EXPECT_EQ(p.get<Torque>(), a.torque.data());
  EXPECT_EQ(p.get<Id>(), a.id.data());
}

TEST(ParticleFields, ColumnsResizeSortAndReportByTheFieldsUses) {
  ParticleColumns<HostSpace, float, float> columns;
  columns.resize_ghost_held(5);
  columns.resize_owned_only(3);
  EXPECT_EQ(columns.get<PositionRadius>().size(), 5u);
  EXPECT_EQ(columns.get<MaterialField>().size(), 5u);
  EXPECT_EQ(columns.get<Force>().size(), 3u);
  EXPECT_EQ(columns.get<Torque>().size(), 3u);
  for (std::uint32_t k = 0; k < 3; ++k) {
    columns.get<Id>().data()[k] = 10 + k;
    columns.get<VelocityInvMass>().data()[k] = {float(k), 0, 0, 1};
    columns.get<Force>().data()[k] = {float(k), 0, 0};
  }
  const std::uint32_t order[] = {2, 0, 1};
  columns.permute_persistent(order, 3);
  EXPECT_EQ(columns.get<Id>().size(), 3u);
  EXPECT_EQ(columns.get<Id>().data()[0], 12u);
  EXPECT_EQ(columns.get<VelocityInvMass>().data()[1].x, 0.0f);
  EXPECT_EQ(columns.get<Force>().data()[0].x, 0.0f) << "forces are recomputed, not sorted";
  const ParticleVectors<float, float> rows = columns.download_rows<field_use::persistent>(1, 2);
  EXPECT_EQ(rows.get<Id>(), (std::vector<ParticleId>{10, 11}));
  EXPECT_TRUE(rows.get<Torque>().empty());
  std::vector<std::string> labels;
  for (const MemoryUse& use : columns.memory_use()) labels.push_back(use.name);
  EXPECT_EQ(labels,
            (std::vector<std::string>{"position, radius", "velocity, inverse mass",
                                      "angular velocity", "id, material", "force, torque"}));
}

}  // namespace
}  // namespace gpudem
