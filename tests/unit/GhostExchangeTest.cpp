// Ghost exchange (engine/GhostExchange.hpp) on three fake ranks in one process
// (support/FakeDomain.hpp), slabs along x of a real Decomposition: the plan gives each rank
// exactly the other ranks' particles within the ghost width of its slab, found here by plain
// geometry, with their full records bit for bit, in the order of the sending ranks; a refresh
// then carries the owners' new positions and velocities (and spins only when asked), and leaves
// ids and materials alone. Typed over the state scalar (double, float) and the spin.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/GhostExchange.hpp"
#include "support/FakeDomain.hpp"

namespace gpudem {
namespace {

constexpr int kRanks = 3;
constexpr Real kGhostWidth = 0.2;
constexpr int kPerRank = 9;

template <class StateScalar, bool kSpin>
struct Case {
  using P = StateScalar;
  static constexpr bool spin = kSpin;
};

/// x ∈ [0, 3) in slabs [r, r + 1) of 4 coarse cells each (edge 0.25 >= the ghost width).
Decomposition slabs() {
  CoarseGrid cells;
  cells.length = Vec3{3, 1, 1};
  cells.n[0] = 12, cells.n[1] = 4, cells.n[2] = 4;
  return Decomposition::grid(cells, {std::vector<int>{0, 4, 8, 12}, {0, 4}, {0, 4}});
}

/// Offsets along x within a slab: near both faces, within and beyond the ghost width.
constexpr double kOffset[kPerRank] = {0.02, 0.1, 0.19, 0.21, 0.5, 0.79, 0.81, 0.9, 0.98};

/// Particle k of rank r: a state that names it.
template <class P>
struct Particle {
  Vec4T<P> position_radius;
  Vec4T<P> velocity_inv_mass;
  Vec3T<P> angular_velocity;
  ParticleId id;
  MaterialId material;
};

template <class P>
Particle<P> particle(int r, int k) {
  const P x = P(r + kOffset[k]);
  return {Vec4T<P>{x, P(0.1 + 0.09 * k), P(0.9 - 0.08 * k), P(0.01)},
          Vec4T<P>{P(r + 0.5), P(k), P(-k * 0.25), P(3.0)},
          Vec3T<P>{P(10 * r + k), P(0.5), P(-1.5)}, static_cast<ParticleId>(100 * r + k),
          static_cast<MaterialId>((r + k) % 2)};
}

/// Whether rank `r` needs a particle at x of another rank: within the ghost width of its slab.
bool is_ghost_on(int r, double x) {
  const double below = r - x, above = x - (r + 1);
  return std::max({below, above, 0.0}) <= kGhostWidth;
}

/// The host arrays of one rank: owned particles, then room for ghosts.
template <class P>
struct Arrays {
  std::vector<Vec4T<P>> position_radius, velocity_inv_mass;
  std::vector<Vec3T<P>> angular_velocity;
  std::vector<ParticleId> id;
  std::vector<MaterialId> material;

  void add(const Particle<P>& p) {
    position_radius.push_back(p.position_radius);
    velocity_inv_mass.push_back(p.velocity_inv_mass);
    angular_velocity.push_back(p.angular_velocity);
    id.push_back(p.id);
    material.push_back(p.material);
  }
  void resize(std::size_t n) {
    position_radius.resize(n), velocity_inv_mass.resize(n), angular_velocity.resize(n);
    id.resize(n), material.resize(n);
  }
  /// Pointers to the arrays (none to forces and torques, which ghosts do not hold).
  ParticlePointers<P, P> pointers() {
    ParticlePointers<P, P> p{};
    p.template get<particle_field::PositionRadius>() = position_radius.data();
    p.template get<particle_field::VelocityInvMass>() = velocity_inv_mass.data();
    p.template get<particle_field::AngularVelocity>() = angular_velocity.data();
    p.template get<particle_field::Id>() = id.data();
    p.template get<particle_field::Material>() = material.data();
    return p;
  }
};

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <class C>
class GhostExchangeOnFakeRanks : public ::testing::Test {};
using Cases = ::testing::Types<Case<double, false>, Case<double, true>, Case<float, false>,
                               Case<float, true>>;
TYPED_TEST_SUITE(GhostExchangeOnFakeRanks, Cases);

TYPED_TEST(GhostExchangeOnFakeRanks, PlanSendsWhatGeometryAsksAndARefreshCarriesTheState) {
  using P = typename TypeParam::P;
  const Decomposition decomposition = slabs();
  std::vector<std::vector<ParticleId>> got(kRanks), wanted(kRanks);
  std::vector<int> record_mismatches(kRanks), refresh_mismatches(kRanks);
  test::run_on_fake_domain(decomposition, kGhostWidth, [&](test::FakeDomain& domain) {
    const int r = domain.rank();
    Arrays<P> a;
    for (int k = 0; k < kPerRank; ++k) a.add(particle<P>(r, k));
    RankCells<HostSpace> cells;
    cells.update(domain.cell_ownership(), r);
    GhostExchange<HostSpace, P, P> ghosts(TypeParam::spin);
    const std::size_t count = ghosts.plan(domain, cells, a.pointers(), kPerRank);
    a.resize(kPerRank + count);
    ghosts.fill(a.pointers(), kPerRank);
    for (int q = 0; q < kRanks; ++q)
      for (int k = 0; k < kPerRank; ++k)
        if (q != r && is_ghost_on(r, q + kOffset[k])) wanted[r].push_back(100 * q + k);
    for (std::size_t g = kPerRank; g < a.id.size(); ++g) {
      got[r].push_back(a.id[g]);
      const Particle<P> p = particle<P>(static_cast<int>(a.id[g] / 100), a.id[g] % 100);
      record_mismatches[r] += !same_bits(a.position_radius[g], p.position_radius) ||
                              !same_bits(a.velocity_inv_mass[g], p.velocity_inv_mass) ||
                              !same_bits(a.angular_velocity[g], p.angular_velocity) ||
                              a.material[g] != p.material;
    }
    // The owners move and spin; a refresh carries it to the ghosts.
    for (int k = 0; k < kPerRank; ++k) {
      a.position_radius[k].y += P(0.001);
      a.velocity_inv_mass[k].x = P(-7 * k);
      a.angular_velocity[k].z = P(42 + k);
    }
    ghosts.update(domain, a.pointers(), kPerRank);
    for (std::size_t g = kPerRank; g < a.id.size(); ++g) {
      const int k = static_cast<int>(a.id[g] % 100);
      Particle<P> p = particle<P>(static_cast<int>(a.id[g] / 100), k);
      p.position_radius.y += P(0.001);
      p.velocity_inv_mass.x = P(-7 * k);
      const P spin_z = TypeParam::spin ? P(42 + k) : p.angular_velocity.z;
      refresh_mismatches[r] += !same_bits(a.position_radius[g], p.position_radius) ||
                               !same_bits(a.velocity_inv_mass[g], p.velocity_inv_mass) ||
                               a.angular_velocity[g].z != spin_z ||
                               a.id[g] != static_cast<ParticleId>(100 * (a.id[g] / 100) + k);
    }
  });
  for (int r = 0; r < kRanks; ++r) {
    EXPECT_FALSE(wanted[r].empty()) << "rank " << r;
    EXPECT_EQ(got[r], wanted[r]) << "rank " << r;
    EXPECT_EQ(record_mismatches[r], 0) << "rank " << r;
    EXPECT_EQ(refresh_mismatches[r], 0) << "rank " << r;
  }
}

}  // namespace
}  // namespace gpudem
