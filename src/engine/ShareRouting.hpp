#pragma once
/// Start-up on several ranks (docs/architecture.md, "One time step"): each rank hands the engine a
/// share of the particles and of their contact history (any subset; the shares together hold each
/// particle and each record once, e.g. the rows of a file that each rank reads by slices), and this
/// host code sends every particle to the rank that owns it and every history record to the rank
/// that owns the record's owner particle, over DomainLink::exchange. Besides its share and what it
/// owns, a rank holds only the records passing through it as the directory rank of their owner
/// id (about a P-th of all when ids are spread evenly); buffers are sized exactly and freed once
/// read.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/ContactHistory.hpp"
#include "core/ParticleFields.hpp"
#include "core/ParticleStore.hpp"
#include "engine/DomainLink.hpp"
#include "engine/ParticleMigration.hpp"

namespace gpudem {

/// The particles a rank owns after routing, with their list positions when routed by them.
struct RoutedParticles {
  ParticleStore particles;
  std::vector<Real4> list_position_radius;  ///< empty unless routed by list positions
};

namespace share_detail {

using migration_detail::put;
using migration_detail::take;

/// A routed particle's row: its checkpointed fields (forces and torques zero where the share
/// has none).
using RoutedRow = WireRow<field_use::checkpoint, Real, Real>;

/// Bytes of one routed particle: its row, then its list position when routed by them.
inline std::size_t particle_bytes(bool with_list) {
  return RoutedRow::bytes + (with_list ? sizeof(Real4) : 0);
}

/// Particle i of `share` (whose row pointers are `rows`) as bytes, then its list position
/// when `list` is not empty.
inline void pack_particle(const ParticlePointers<Real, Real>& rows, const std::vector<Real4>& list,
                          std::size_t i, std::vector<char>& out) {
  const std::size_t at = out.size();
  out.resize(at + RoutedRow::bytes);
  RoutedRow::write(rows, i, out.data() + at);
  if (!list.empty()) put(out, list[i]);
}

/// Reads the particles packed in `in` into rows [first, ...) of `out`, which has room for
/// them; returns the row after the last.
inline std::size_t unpack_particles(const std::vector<char>& in, bool with_list, std::size_t first,
                                    RoutedParticles& out) {
  const ParticlePointers<Real, Real> rows = row_pointers(out.particles);
  std::size_t at = 0, k = first;
  for (; at < in.size(); ++k) {
    RoutedRow::read(in.data() + at, rows, k);
    at += RoutedRow::bytes;
    if (with_list) out.list_position_radius[k] = take<Real4>(in, at);
  }
  return k;
}

/// The three kinds of history record, as packed.
enum class RecordKind : std::uint8_t { pair, wall, mesh };

/// One record as bytes: kind, owner id, key (partner id, wall or triangle index), values.
inline void pack_record(RecordKind kind, ParticleId owner, std::uint64_t key, const Real* values,
                        std::uint32_t width, std::vector<char>& out) {
  put(out, kind);
  put(out, owner);
  put(out, key);
  for (std::uint32_t k = 0; k < width; ++k) put(out, values[k]);
}

/// Bytes of one record as pack_record writes it.
inline std::size_t record_bytes(std::uint32_t width) {
  return sizeof(RecordKind) + sizeof(ParticleId) + sizeof(std::uint64_t) + width * sizeof(Real);
}

/// Sizes each buffer of `buffers` for `counts[q]` more items of `bytes` each.
inline void reserve_buffers(RankBuffers& buffers, const std::vector<std::size_t>& counts,
                            std::size_t bytes) {
  for (std::size_t q = 0; q < buffers.size(); ++q)
    buffers[q].reserve(buffers[q].size() + counts[q] * bytes);
}

/// Calls visit(kind, owner, key, values) for every record of `history`.
template <class Visit>
void for_each_record(const ContactHistory& h, Visit&& visit) {
  const std::uint32_t w = h.width;
  for (std::size_t k = 0; k < h.pair_owner.size(); ++k)
    visit(RecordKind::pair, h.pair_owner[k], h.pair_partner[k], h.pair_values.data() + k * w);
  for (std::size_t k = 0; k < h.wall_owner.size(); ++k)
    visit(RecordKind::wall, h.wall_owner[k], h.wall_index[k], h.wall_values.data() + k * w);
  for (std::size_t k = 0; k < h.mesh_owner.size(); ++k)
    visit(RecordKind::mesh, h.mesh_owner[k], h.mesh_triangle[k], h.mesh_values.data() + k * w);
}

/// Calls visit(kind, owner, key, values) for every record packed in `in`.
template <class Visit>
void for_each_packed_record(const std::vector<char>& in, std::uint32_t width, Visit&& visit) {
  std::vector<Real> values(width);
  std::size_t at = 0;
  while (at < in.size()) {
    const auto kind = take<RecordKind>(in, at);
    const auto owner = take<ParticleId>(in, at);
    const auto key = take<std::uint64_t>(in, at);
    for (std::uint32_t k = 0; k < width; ++k) values[k] = take<Real>(in, at);
    visit(kind, owner, key, values.data());
  }
}

/// Makes room in `h` for the records packed in `buffers`, counted by kind.
inline void reserve_records(ContactHistory& h, const RankBuffers& buffers, std::uint32_t width) {
  std::size_t count[3] = {0, 0, 0};
  const std::size_t stride = record_bytes(width);
  for (const std::vector<char>& bytes : buffers)
    for (std::size_t at = 0; at < bytes.size(); at += stride) {
      std::size_t kind_at = at;
      ++count[static_cast<int>(take<RecordKind>(bytes, kind_at))];
    }
  const auto pair = static_cast<std::size_t>(RecordKind::pair);
  const auto wall = static_cast<std::size_t>(RecordKind::wall);
  const auto mesh = static_cast<std::size_t>(RecordKind::mesh);
  h.pair_owner.reserve(count[pair]);
  h.pair_partner.reserve(count[pair]);
  h.pair_values.reserve(count[pair] * width);
  h.wall_owner.reserve(count[wall]);
  h.wall_index.reserve(count[wall]);
  h.wall_values.reserve(count[wall] * width);
  h.mesh_owner.reserve(count[mesh]);
  h.mesh_triangle.reserve(count[mesh]);
  h.mesh_values.reserve(count[mesh] * width);
}

inline void add_record(ContactHistory& h, RecordKind kind, ParticleId owner, std::uint64_t key,
                       const Real* values) {
  if (kind == RecordKind::pair)
    h.add_pair(owner, key, values);
  else if (kind == RecordKind::wall)
    h.add_wall(owner, static_cast<std::uint32_t>(key), values);
  else
    h.add_mesh(owner, static_cast<std::uint32_t>(key), values);
}

/// The rank that keeps the directory entry of a particle id.
inline int directory_rank(ParticleId id, int ranks) {
  return static_cast<int>(id % static_cast<ParticleId>(ranks));
}

/// On each rank, the owner rank of every id whose directory rank it is, from the ids each rank
/// owns. Collective.
inline std::unordered_map<ParticleId, int> owner_directory(const std::vector<ParticleId>& owned,
                                                           const DomainLink& domain) {
  RankBuffers outgoing(domain.ranks()), incoming;
  for (const ParticleId id : owned) put(outgoing[directory_rank(id, domain.ranks())], id);
  domain.group().exchange(outgoing, incoming);
  std::unordered_map<ParticleId, int> directory;
  for (int q = 0; q < domain.ranks(); ++q)
    for (std::size_t at = 0; at < incoming[q].size();)
      directory[take<ParticleId>(incoming[q], at)] = q;
  return directory;
}

}  // namespace share_detail

/// Throws std::invalid_argument on every rank with the message of the lowest rank whose
/// `problem` is not empty; returns when none has one. Collective.
inline void throw_first_problem(const std::string& problem, const DomainLink& domain) {
  if (const std::optional<std::string> first = first_message(domain.group(), problem))
    throw std::invalid_argument(*first);
}

/// Sends particle i of `share` to the rank that owns list_positions[i] (or its position when
/// `list_positions` is empty), with its list position when there is one; returns the
/// particles this rank owns, the ranks' shares in rank order, each in its order. Forces and
/// torques travel along (zero where `share` has none). Collective.
inline RoutedParticles route_to_owners(const ParticleStore& share,
                                       const std::vector<Real4>& list_positions,
                                       const DomainLink& domain) {
  const bool with_list = !list_positions.empty();
  if (with_list && list_positions.size() != share.size())
    throw std::invalid_argument("route_to_owners: list positions and particles differ in number");
  const std::vector<Real4>& where = with_list ? list_positions : share.position_radius;
  const std::size_t bytes_each = share_detail::particle_bytes(with_list);
  std::vector<int> owner(share.size());
  std::vector<std::size_t> count(domain.ranks(), 0);
  for (std::size_t i = 0; i < share.size(); ++i) ++count[owner[i] = domain.owner_of(xyz(where[i]))];
  RankBuffers outgoing(domain.ranks()), incoming;
  share_detail::reserve_buffers(outgoing, count, bytes_each);
  const ParticlePointers<Real, Real> rows = row_pointers(share);
  for (std::size_t i = 0; i < share.size(); ++i)
    share_detail::pack_particle(rows, list_positions, i, outgoing[owner[i]]);
  std::vector<int>().swap(owner);
  domain.group().exchange(outgoing, incoming);
  RankBuffers().swap(outgoing);
  RoutedParticles routed;
  std::size_t arriving = 0;
  for (const std::vector<char>& bytes : incoming) arriving += bytes.size() / bytes_each;
  resize_rows(routed.particles, arriving);
  if (with_list) routed.list_position_radius.resize(arriving);
  std::size_t next = 0;
  for (std::vector<char>& bytes : incoming) {
    next = share_detail::unpack_particles(bytes, with_list, next, routed);
    std::vector<char>().swap(bytes);
  }
  return routed;
}

/// The records of every rank's `share` (`width` values per record on every rank) whose owner
/// particle is one of `owned` (this rank's particles), ordered by the directory rank they came
/// through, then by sending rank, then as in the sender's share. Each record first goes to the
/// directory rank of its owner id (id mod ranks), which has learned from every rank the ids it
/// owns and forwards the record to the owner's rank. `share` is taken by value and freed once
/// packed, and every buffer is sized exactly and freed once read, so that a rank holds at most
/// about two copies of its share's records at a time. The caller makes sure every non-empty
/// share has `width` values per record (on every rank, or the records cannot be read back).
/// Throws std::invalid_argument on every rank when a record's owner is a particle no rank
/// owns. Collective.
inline ContactHistory route_history(ContactHistory share, std::uint32_t width,
                                    const std::vector<ParticleId>& owned,
                                    const DomainLink& domain) {
  using namespace share_detail;
  const std::size_t bytes_each = record_bytes(width);
  const std::unordered_map<ParticleId, int> directory = owner_directory(owned, domain);
  std::vector<std::size_t> count(domain.ranks(), 0);
  for_each_record(share, [&](RecordKind, ParticleId owner, std::uint64_t, const Real*) {
    ++count[directory_rank(owner, domain.ranks())];
  });
  RankBuffers to_directory(domain.ranks()), at_directory;
  reserve_buffers(to_directory, count, bytes_each);
  for_each_record(share, [&](RecordKind kind, ParticleId owner, std::uint64_t key, const Real* v) {
    pack_record(kind, owner, key, v, width, to_directory[directory_rank(owner, domain.ranks())]);
  });
  share = ContactHistory{};
  domain.group().exchange(to_directory, at_directory);
  RankBuffers().swap(to_directory);

  std::string problem;
  count.assign(domain.ranks(), 0);
  for (const std::vector<char>& bytes : at_directory)
    for_each_packed_record(
        bytes, width, [&](RecordKind, ParticleId owner, std::uint64_t, const Real*) {
          const auto found = directory.find(owner);
          if (found != directory.end())
            ++count[found->second];
          else if (problem.empty())
            problem =
                "contact history: particle id " + std::to_string(owner) + " is not in the engine";
        });
  throw_first_problem(problem, domain);
  RankBuffers to_owner(domain.ranks()), at_owner;
  reserve_buffers(to_owner, count, bytes_each);
  for (std::vector<char>& bytes : at_directory) {
    for_each_packed_record(
        bytes, width, [&](RecordKind kind, ParticleId owner, std::uint64_t key, const Real* v) {
          pack_record(kind, owner, key, v, width, to_owner[directory.at(owner)]);
        });
    std::vector<char>().swap(bytes);
  }
  domain.group().exchange(to_owner, at_owner);
  RankBuffers().swap(to_owner);

  ContactHistory mine;
  mine.width = width;
  reserve_records(mine, at_owner, width);
  for (std::vector<char>& bytes : at_owner) {
    for_each_packed_record(
        bytes, width, [&](RecordKind kind, ParticleId owner, std::uint64_t key, const Real* v) {
          add_record(mine, kind, owner, key, v);
        });
    std::vector<char>().swap(bytes);
  }
  return mine;
}

}  // namespace gpudem
