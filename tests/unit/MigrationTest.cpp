// Migration between ranks (ParticleMigration.hpp) on fake ranks in one process: each particle
// arrives at the rank it was sent to with its state, wall records, pair rows and mesh rows bit
// for bit, from the sending ranks in rank order, for history records of 0, 4 and 7 values, in
// each precision policy's scalars.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "engine/ParticleMigration.hpp"
#include "support/FakeRanks.hpp"
#include "support/SameBits.hpp"

namespace gpudem {
namespace {

/// A policy's scalars: S the law's (history), P the state's.
template <class LawScalar, class StateScalar>
struct Scalars {
  using S = LawScalar;
  using P = StateScalar;
};

constexpr std::uint32_t kWalls = 2;

/// Particle k of rank `from`: values that name their rank, particle and field, so that any
/// mix-up shows; rows of k % 3 pair records and k % 2 mesh records.
template <class S, class P>
void add_particle(MigratingParticles<S, P>& p, int from, int k) {
  const double base = 1000.0 * from + 10.0 * k;
  p.template field<particle_field::PositionRadius>().push_back(
      Vec4T<P>{P(base + 0.1), P(base + 0.2), P(base + 0.3), P(0.01)});
  p.template field<particle_field::VelocityInvMass>().push_back(
      Vec4T<P>{P(-base), P(base * 0.5), P(1.25), P(2.0)});
  p.template field<particle_field::AngularVelocity>().push_back(
      Vec3T<P>{P(base + 0.7), P(0.125), P(-3.5)});
  p.template field<particle_field::Id>().push_back(static_cast<ParticleId>(100 * from + k));
  p.template field<particle_field::Material>().push_back(static_cast<MaterialId>((from + k) % 3));
  const std::uint32_t w = p.history_width;
  for (std::uint32_t v = 0; v < kWalls * w; ++v) p.wall_history.push_back(S(base + 0.01 * v));
  for (int e = 0; e < k % 3; ++e) {
    p.row_partner.push_back(static_cast<ParticleId>(7000 + 10 * k + e));
    for (std::uint32_t v = 0; v < w; ++v) p.row_history.push_back(S(base + e + 0.001 * v));
  }
  p.row_offsets.push_back(static_cast<std::uint32_t>(p.row_partner.size()));
  for (int e = 0; e < k % 2; ++e) {
    p.mesh_triangle.push_back(static_cast<std::uint32_t>(40 + k));
    for (std::uint32_t v = 0; v < w; ++v) p.mesh_history.push_back(S(-base - 0.002 * v));
  }
  p.mesh_offsets.push_back(static_cast<std::uint32_t>(p.mesh_triangle.size()));
}

/// Rank r sends its particle k to rank (r + k + 1) % ranks: to itself when k + 1 is a multiple
/// of the rank count, which the exchange must deliver like any other message.
int destination_of(int r, int k, int ranks) { return (r + k + 1) % ranks; }

using test::same_bits;

template <class S, class P>
bool same_bits(const MigratingParticles<S, P>& a, const MigratingParticles<S, P>& b) {
  return same_bits(a.template field<particle_field::PositionRadius>(),
                   b.template field<particle_field::PositionRadius>()) &&
         same_bits(a.template field<particle_field::VelocityInvMass>(),
                   b.template field<particle_field::VelocityInvMass>()) &&
         same_bits(a.template field<particle_field::AngularVelocity>(),
                   b.template field<particle_field::AngularVelocity>()) &&
         a.template field<particle_field::Id>() == b.template field<particle_field::Id>() &&
         a.template field<particle_field::Material>() ==
             b.template field<particle_field::Material>() &&
         same_bits(a.wall_history, b.wall_history) && a.row_offsets == b.row_offsets &&
         a.row_partner == b.row_partner && same_bits(a.row_history, b.row_history) &&
         a.mesh_offsets == b.mesh_offsets && a.mesh_triangle == b.mesh_triangle &&
         same_bits(a.mesh_history, b.mesh_history);
}

template <class T>
class Migration : public ::testing::Test {};

using Policies =
    ::testing::Types<Scalars<double, double>, Scalars<float, double>, Scalars<float, float>>;
TYPED_TEST_SUITE(Migration, Policies);

TYPED_TEST(Migration, EachParticleArrivesWithItsHistoryBitForBit) {
  using S = typename TypeParam::S;
  using P = typename TypeParam::P;
  constexpr int kRanks = 3, kParticles = 5;
  for (const std::uint32_t width : {0u, 4u, 7u}) {
    SCOPED_TRACE("history width " + std::to_string(width));
    std::vector<MigratingParticles<S, P>> arrived(kRanks), expected(kRanks);
    for (MigratingParticles<S, P>& e : expected) e.history_width = width;
    for (int r = 0; r < kRanks; ++r)  // in the order the receivers get them: by sender, then k
      for (int k = 0; k < kParticles; ++k)
        add_particle(expected[destination_of(r, k, kRanks)], r, k);
    test::run_on_fake_ranks(kRanks, [&](test::FakeRankLink& link) {
      MigratingParticles<S, P> leaving;
      leaving.history_width = width;
      std::vector<int> destination;
      for (int k = 0; k < kParticles; ++k) {
        add_particle(leaving, link.rank(), k);
        destination.push_back(destination_of(link.rank(), k, kRanks));
      }
      arrived[link.rank()] = exchange_migrants(leaving, destination, kWalls, link);
    });
    for (int r = 0; r < kRanks; ++r) {
      EXPECT_EQ(arrived[r].history_width, width) << "rank " << r;
      EXPECT_EQ(arrived[r].size(), expected[r].size()) << "rank " << r;
      EXPECT_TRUE(same_bits(arrived[r], expected[r])) << "rank " << r;
    }
  }
}

TYPED_TEST(Migration, NothingLeavingSendsNothing) {
  using S = typename TypeParam::S;
  using P = typename TypeParam::P;
  std::vector<std::size_t> arrived(2, 99);
  test::run_on_fake_ranks(2, [&](test::FakeRankLink& link) {
    MigratingParticles<S, P> none;
    none.history_width = 7;
    arrived[link.rank()] = exchange_migrants(none, {}, kWalls, link).size();
  });
  EXPECT_EQ(arrived, (std::vector<std::size_t>{0, 0}));
}

}  // namespace
}  // namespace gpudem
