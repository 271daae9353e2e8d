// Start-up shares (engine/ShareRouting.hpp, core/RowShare.hpp, comm/StartupShares.hpp) on however
// many ranks this runs (1, 2 and 4 through ctest): every rank builds the same particles and
// history, takes its share, and routes it; what arrives is compared with a brute-force selection of
// the whole set by owner, field by field.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "comm/Decomposition.hpp"
#include "comm/MpiDomain.hpp"
#include "comm/MpiRankGroup.hpp"
#include "core/InputError.hpp"
#include "core/ParticleGather.hpp"
#include "core/RowShare.hpp"
#include "engine/ShareRouting.hpp"
#include "support/MpiRank.hpp"

namespace gpudem {
namespace {

using test::comm_rank;
using test::comm_size;

/// A domain of this communicator's ranks: 4 × 4 × 4 coarse cells of the unit cube dealt round
/// robin.
MpiDomain world_domain() {
  PeriodicBox box;
  box.lo = Vec3{0, 0, 0};
  box.length = Vec3{1, 1, 1};
  const CoarseGrid cells = CoarseGrid::over(box, Real(0.25));
  std::vector<int> owner(cells.count());
  for (std::size_t c = 0; c < owner.size(); ++c)
    owner[c] = static_cast<int>(c * 7 % 11) % comm_size();
  return MpiDomain(MPI_COMM_WORLD, Decomposition::from_owners(cells, owner, comm_size()), Real(0.1),
                   false);
}

/// `n` particles at random places in the unit cube, every field distinct, ids shuffled; the
/// same on every rank.
ParticleStore random_particles(std::size_t n, std::vector<Real4>& list_positions) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> u(0, 1);
  std::vector<ParticleId> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = 1000 + 3 * i;
  std::shuffle(ids.begin(), ids.end(), rng);
  ParticleStore p;
  list_positions.clear();
  for (std::size_t i = 0; i < n; ++i) {
    p.add(ids[i], Vec3{u(rng), u(rng), u(rng)}, Real(0.01) + u(rng) * Real(0.01),
          static_cast<MaterialId>(i % 3), Vec3{u(rng), u(rng), u(rng)}, 1 + u(rng));
    p.angular_velocity.back() = Vec3{u(rng), u(rng), u(rng)};
    p.force.back() = Vec3{u(rng), u(rng), u(rng)};
    p.torque.back() = Vec3{u(rng), u(rng), u(rng)};
    list_positions.push_back({u(rng), u(rng), u(rng), p.position_radius.back().w});
  }
  return p;
}

/// Index of each id in `p`.
std::map<ParticleId, std::size_t> index_by_id(const ParticleStore& p) {
  std::map<ParticleId, std::size_t> index;
  for (std::size_t i = 0; i < p.size(); ++i) index[p.id[i]] = i;
  return index;
}

bool same(Real4 a, Real4 b) { return a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w; }
bool same(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/// Checks that `routed` holds exactly the particles of `all` whose place (`where`) this rank
/// owns, in the order of `all` (the shares in rank order, each in its order), each with all its
/// fields (and its list position when `list` is given).
void expect_owned_particles(const ParticleStore& all, const std::vector<Real4>& where,
                            const std::vector<Real4>* list, const RoutedParticles& routed,
                            const MpiDomain& domain) {
  std::vector<ParticleId> expected;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (domain.owner_of(xyz(where[i])) == comm_rank()) expected.push_back(all.id[i]);
  ASSERT_EQ(routed.particles.id, expected);
  const std::map<ParticleId, std::size_t> index = index_by_id(all);
  const ParticleStore& p = routed.particles;
  ASSERT_EQ(routed.list_position_radius.size(), list ? p.size() : 0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const std::size_t i = index.at(p.id[k]);
    EXPECT_TRUE(same(p.position_radius[k], all.position_radius[i])) << "id " << p.id[k];
    EXPECT_TRUE(same(p.velocity_inv_mass[k], all.velocity_inv_mass[i])) << "id " << p.id[k];
    EXPECT_TRUE(same(p.angular_velocity[k], all.angular_velocity[i])) << "id " << p.id[k];
    EXPECT_TRUE(same(p.force[k], all.force[i])) << "id " << p.id[k];
    EXPECT_TRUE(same(p.torque[k], all.torque[i])) << "id " << p.id[k];
    EXPECT_EQ(p.material[k], all.material[i]) << "id " << p.id[k];
    if (list) {
      EXPECT_TRUE(same(routed.list_position_radius[k], (*list)[i])) << "id " << p.id[k];
    }
  }
}

TEST(RowShare, SharesCoverEveryRowOnceInRankOrder) {
  for (const std::size_t rows : {0, 1, 5, 64, 1001})
    for (const int ranks : {1, 2, 3, 4, 7}) {
      std::size_t next = 0;
      for (int r = 0; r < ranks; ++r) {
        const RowRange share = share_of_rows(rows, r, ranks);
        EXPECT_EQ(share.first, next) << rows << " rows, rank " << r << " of " << ranks;
        EXPECT_LE(share.count, rows / ranks + 1);
        EXPECT_GE(share.count, rows / ranks);
        next += share.count;
      }
      EXPECT_EQ(next, rows) << rows << " rows on " << ranks << " ranks";
    }
  const std::size_t huge = std::size_t(1) << 62;  // ⌊rows·rank/ranks⌋ must not overflow
  EXPECT_EQ(share_of_rows(huge, 2, 4).first, huge / 2);
}

/// Particle counts to route: many, fewer than four ranks (some shares empty), none.
constexpr std::size_t kParticleCounts[] = {500, 3, 0};

TEST(ShareRouting, ParticlesReachTheOwnerOfTheirPosition) {
  const MpiDomain domain = world_domain();
  for (const std::size_t n : kParticleCounts) {
    SCOPED_TRACE(std::to_string(n) + " particles");
    std::vector<Real4> list;
    const ParticleStore all = random_particles(n, list);
    const RoutedParticles routed =
        route_to_owners(share_of(all, comm_rank(), comm_size()), {}, domain);
    expect_owned_particles(all, all.position_radius, nullptr, routed, domain);
  }
}

TEST(ShareRouting, RestoredParticlesReachTheOwnerOfTheirListPosition) {
  const MpiDomain domain = world_domain();
  for (const std::size_t n : kParticleCounts) {
    SCOPED_TRACE(std::to_string(n) + " particles");
    std::vector<Real4> list;
    const ParticleStore all = random_particles(n, list);
    const RowRange mine = share_of_rows(all.size(), comm_rank(), comm_size());
    const RoutedParticles routed =
        route_to_owners(share_of(all, comm_rank(), comm_size()), rows_of(list, mine), domain);
    expect_owned_particles(all, list, &list, routed, domain);
  }
}

TEST(ShareRouting, SharesWithoutForcesArriveWithZeroForces) {
  const MpiDomain domain = world_domain();
  std::vector<Real4> list;
  ParticleStore share = share_of(random_particles(100, list), comm_rank(), comm_size());
  share.force.clear();
  share.torque.clear();
  const RoutedParticles routed = route_to_owners(share, {}, domain);
  for (std::size_t k = 0; k < routed.particles.size(); ++k) {
    EXPECT_TRUE(same(routed.particles.force[k], Vec3{}));
    EXPECT_TRUE(same(routed.particles.torque[k], Vec3{}));
  }
}

/// Pair, wall and mesh records of the particles `ids` (several per particle, values that name
/// the record), width 3.
ContactHistory history_of(const std::vector<ParticleId>& ids) {
  ContactHistory h;
  h.width = 3;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const Real v = static_cast<Real>(ids[i]);
    for (std::size_t k = 1; k <= i % 3; ++k) {
      const Real pair[3] = {v, static_cast<Real>(k), 0.5};
      h.add_pair(ids[i], ids[(i + k) % ids.size()], pair);
    }
    if (i % 2 == 0) {
      const Real wall[3] = {v, 1, 0.25};
      h.add_wall(ids[i], static_cast<std::uint32_t>(i % 4), wall);
    }
    if (i % 5 == 0) {
      const Real mesh[3] = {v, 2, 0.125};
      h.add_mesh(ids[i], static_cast<std::uint32_t>(i), mesh);
    }
  }
  return h;
}

/// Every record of `h` as (kind, owner, key, values).
using Record = std::tuple<int, ParticleId, std::uint64_t, std::vector<Real>>;
std::vector<Record> records(const ContactHistory& h) {
  std::vector<Record> out;
  share_detail::for_each_record(
      h, [&](share_detail::RecordKind kind, ParticleId owner, std::uint64_t key, const Real* v) {
        out.emplace_back(static_cast<int>(kind), owner, key, std::vector<Real>(v, v + h.width));
      });
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ShareRouting, HistoryRecordsReachTheRankOfTheirOwner) {
  const MpiDomain domain = world_domain();
  for (const std::size_t n : kParticleCounts) {
    SCOPED_TRACE(std::to_string(n) + " particles");
    std::vector<Real4> list;
    const ParticleStore all = random_particles(n, list);
    const ContactHistory history = history_of(all.id);
    std::vector<ParticleId> owned;
    for (std::size_t i = 0; i < all.size(); ++i)
      if (domain.owner_of(xyz(all.position_radius[i])) == comm_rank()) owned.push_back(all.id[i]);
    const ContactHistory mine =
        route_history(share_of(history, comm_rank(), comm_size()), history.width, owned, domain);
    EXPECT_EQ(mine.width, history.width);
    ASSERT_TRUE(mine.lengths_agree());
    std::vector<Record> expected;
    for (const Record& r : records(history))
      if (std::count(owned.begin(), owned.end(), std::get<1>(r))) expected.push_back(r);
    EXPECT_EQ(records(mine), expected);
  }
}

TEST(ShareRouting, RecordOfAParticleNoRankOwnsIsRefusedOnEveryRank) {
  const MpiDomain domain = world_domain();
  std::vector<Real4> list;
  const ParticleStore all = random_particles(50, list);
  ContactHistory history = history_of(all.id);
  const Real values[3] = {1, 2, 3};
  history.add_wall(424242, 0, values);  // no particle has this id
  std::vector<ParticleId> owned;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (domain.owner_of(xyz(all.position_radius[i])) == comm_rank()) owned.push_back(all.id[i]);
  try {
    route_history(share_of(history, comm_rank(), comm_size()), history.width, owned, domain);
    ADD_FAILURE() << "rank " << comm_rank() << " accepted a record of an unknown particle";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("particle id 424242"), std::string::npos) << e.what();
  }
}

TEST(ShareRouting, FirstProblemIsThrownOnEveryRank) {
  const MpiDomain domain = world_domain();
  const int last = comm_size() - 1;
  const std::string problem = comm_rank() == last ? "rank " + std::to_string(last) : "";
  try {
    throw_first_problem(problem, domain);
    ADD_FAILURE() << "no exception on rank " << comm_rank();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "rank " + std::to_string(last));
  }
  EXPECT_NO_THROW(throw_first_problem("", domain));
}

TEST(StartupShares, ErrorOfTheLowestFailingRankIsThrownOnEveryRank) {
  const int last = comm_size() - 1;
  try {
    agree_on_failure(MpiRankGroup(MPI_COMM_WORLD), [&] {
      if (comm_rank() >= last)
        throw InputError("bed.h5", 0, "", "rank " + std::to_string(comm_rank()));
      return 1;
    });
    ADD_FAILURE() << "no exception on rank " << comm_rank();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "bed.h5: rank " + std::to_string(last));
  }
  EXPECT_EQ(agree_on_failure(MpiRankGroup(MPI_COMM_WORLD), [] { return comm_rank() + 10; }),
            comm_rank() + 10);
  try {  // any other exception travels as a runtime_error, not as an input error
    agree_on_failure(MpiRankGroup(MPI_COMM_WORLD), [&] {
      if (comm_rank() == last) throw std::length_error("too long");
      return 1;
    });
    ADD_FAILURE() << "no exception on rank " << comm_rank();
  } catch (const InputError& e) {
    ADD_FAILURE() << "an input error: " << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "too long");
  }
}

TEST(StartupShares, GatheredParticlesAreEveryRanksShareInRankOrder) {
  for (const std::size_t n : {37, 3, 0}) {
    SCOPED_TRACE(std::to_string(n) + " particles");
    std::vector<Real4> list;
    const ParticleStore all = random_particles(n, list);
    const ParticleStore share = share_of(all, comm_rank(), comm_size());
    const ParticleStore gathered = gather_particles(MpiRankGroup(MPI_COMM_WORLD), share);
    EXPECT_EQ(gathered.id, all.id);
    ASSERT_EQ(gathered.size(), all.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
      EXPECT_TRUE(same(gathered.position_radius[i], all.position_radius[i]));
      EXPECT_TRUE(same(gathered.velocity_inv_mass[i], all.velocity_inv_mass[i]));
      EXPECT_TRUE(same(gathered.torque[i], all.torque[i]));
      EXPECT_EQ(gathered.material[i], all.material[i]);
    }
    EXPECT_EQ(MpiRankGroup(MPI_COMM_WORLD).sum<std::uint64_t>(share.size()), all.size());
  }
}

}  // namespace
}  // namespace gpudem
