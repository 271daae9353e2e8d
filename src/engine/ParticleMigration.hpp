#pragma once
/// Migration (docs/architecture.md, "One time step"): on a rebuild step, owned particles whose
/// position another rank owns travel there with all their state and their contact history: the wall
/// records, the records of their own side of each particle contact, keyed by the partner's global
/// id, and their mesh records, keyed by triangle index, so that they find their contacts again in
/// the new rank's lists. Host code over host copies of the leaving particles only: the engine finds
/// and gathers them on the device and appends those that arrive.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/Config.hpp"
#include "core/ParticleFields.hpp"
#include "core/Vec3.hpp"
#include "engine/DomainLink.hpp"
#include "engine/ParticleColumns.hpp"

namespace gpudem {

/// Particles that travel between ranks, as host copies of their persistent fields (the
/// engine's scalars: state P, loads S), with their pair history as rows keyed by partner id:
/// particle i's records are row_partner / row_history [row_offsets[i], row_offsets[i + 1]), and
/// its mesh history as rows keyed by triangle index in mesh_offsets the same way, and its bonds
/// as rows keyed by partner id in bond_offsets. Each history record is `history_width` values of
/// scalar S, each bond record `bond_width` (0: the scene has no bonds).
template <class S, class P>
struct MigratingParticles {
  using Row = WireRow<field_use::persistent, P, S>;

  std::uint32_t history_width = 0;
  ParticleVectors<P, S> fields;  ///< the persistent fields (the others empty)
  std::vector<S> wall_history;   ///< wall_count records per particle
  std::vector<std::uint32_t> row_offsets{0};
  std::vector<ParticleId> row_partner;
  std::vector<S> row_history;
  std::vector<std::uint32_t> mesh_offsets{0};
  std::vector<std::uint32_t> mesh_triangle;
  std::vector<S> mesh_history;
  std::uint32_t bond_width = 0;
  std::vector<std::uint32_t> bond_offsets{0};
  std::vector<ParticleId> bond_partner;
  std::vector<S> bond_values;

  template <class F>
  auto& field() {
    return fields.template get<F>();
  }
  template <class F>
  const auto& field() const {
    return fields.template get<F>();
  }
  std::size_t size() const { return field<particle_field::Id>().size(); }

  /// Appends particle i's fields (Row::bytes) to `out`.
  void pack_fields(std::size_t i, std::vector<char>& out) const {
    const std::size_t at = out.size();
    out.resize(at + Row::bytes);
    Row::write(pointers_of(fields), i, out.data() + at);
  }

  /// Appends a particle with the fields packed at `in`.
  void unpack_fields(const char* in) {
    const std::size_t i = size();
    for_each_particle_field<field_use::persistent>(
        [&](auto f) { fields.template get<decltype(f)>().emplace_back(); });
    Row::read(in, pointers_of(fields), i);
  }
};

namespace migration_detail {

template <class T>
void put(std::vector<char>& out, const T& value) {
  const char* bytes = reinterpret_cast<const char*>(&value);
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

template <class T>
T take(const std::vector<char>& in, std::size_t& at) {
  T value;
  std::memcpy(&value, in.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

/// Record k (`width` values) of `records`, as bytes.
template <class S>
void put_record(std::vector<char>& out, const std::vector<S>& records, std::size_t k,
                std::uint32_t width) {
  for (std::uint32_t v = 0; v < width; ++v) put(out, records[k * width + v]);
}

/// Appends one record of `width` values from `in` to `records`.
template <class S>
void take_record(const std::vector<char>& in, std::size_t& at, std::uint32_t width,
                 std::vector<S>& records) {
  for (std::uint32_t v = 0; v < width; ++v) records.push_back(take<S>(in, at));
}

/// Particle i of `p` as bytes: its fields (WireRow), its wall records, then its row count and rows,
/// then its mesh row count and mesh rows, then, with bonds, its bond count and bonds.
template <class S, class P>
void pack(const MigratingParticles<S, P>& p, std::size_t i, std::uint32_t walls,
          std::vector<char>& out) {
  const std::uint32_t width = p.history_width;
  p.pack_fields(i, out);
  for (std::uint32_t w = 0; w < walls; ++w) put_record(out, p.wall_history, i * walls + w, width);
  put(out, p.row_offsets[i + 1] - p.row_offsets[i]);
  for (std::uint32_t e = p.row_offsets[i]; e < p.row_offsets[i + 1]; ++e) {
    put(out, p.row_partner[e]);
    put_record(out, p.row_history, e, width);
  }
  put(out, p.mesh_offsets[i + 1] - p.mesh_offsets[i]);
  for (std::uint32_t e = p.mesh_offsets[i]; e < p.mesh_offsets[i + 1]; ++e) {
    put(out, p.mesh_triangle[e]);
    put_record(out, p.mesh_history, e, width);
  }
  if (p.bond_width == 0) return;
  put(out, p.bond_offsets[i + 1] - p.bond_offsets[i]);
  for (std::uint32_t e = p.bond_offsets[i]; e < p.bond_offsets[i + 1]; ++e) {
    put(out, p.bond_partner[e]);
    put_record(out, p.bond_values, e, p.bond_width);
  }
}

/// Appends one particle's bond rows from `in` to `p`.
template <class S, class P>
void take_bonds(const std::vector<char>& in, std::size_t& at, MigratingParticles<S, P>& p) {
  const auto bonds = take<std::uint32_t>(in, at);
  for (std::uint32_t e = 0; e < bonds; ++e) {
    p.bond_partner.push_back(take<ParticleId>(in, at));
    take_record(in, at, p.bond_width, p.bond_values);
  }
  p.bond_offsets.push_back(static_cast<std::uint32_t>(p.bond_partner.size()));
}

/// Appends the particles packed in `in` to `p`.
template <class S, class P>
void unpack(const std::vector<char>& in, std::uint32_t walls, MigratingParticles<S, P>& p) {
  const std::uint32_t width = p.history_width;
  std::size_t at = 0;
  while (at < in.size()) {
    p.unpack_fields(in.data() + at);
    at += MigratingParticles<S, P>::Row::bytes;
    for (std::uint32_t w = 0; w < walls; ++w) take_record(in, at, width, p.wall_history);
    const auto rows = take<std::uint32_t>(in, at);
    for (std::uint32_t e = 0; e < rows; ++e) {
      p.row_partner.push_back(take<ParticleId>(in, at));
      take_record(in, at, width, p.row_history);
    }
    p.row_offsets.push_back(static_cast<std::uint32_t>(p.row_partner.size()));
    const auto mesh_rows = take<std::uint32_t>(in, at);
    for (std::uint32_t e = 0; e < mesh_rows; ++e) {
      p.mesh_triangle.push_back(take<std::uint32_t>(in, at));
      take_record(in, at, width, p.mesh_history);
    }
    p.mesh_offsets.push_back(static_cast<std::uint32_t>(p.mesh_triangle.size()));
    if (p.bond_width > 0) take_bonds(in, at, p);
  }
}

}  // namespace migration_detail

/// Sends particle k of `leaving` (which has `walls` wall records per particle) to rank
/// destination[k] and returns the particles the other ranks sent here, in the order of the
/// sending ranks, each sender's in its order. Collective.
template <class S, class P>
MigratingParticles<S, P> exchange_migrants(const MigratingParticles<S, P>& leaving,
                                           const std::vector<int>& destination, std::uint32_t walls,
                                           const DomainLink& domain) {
  RankBuffers outgoing(domain.ranks());
  for (std::size_t k = 0; k < leaving.size(); ++k)
    migration_detail::pack(leaving, k, walls, outgoing[destination[k]]);
  RankBuffers incoming;
  domain.group().exchange(outgoing, incoming);
  MigratingParticles<S, P> arrived;
  arrived.history_width = leaving.history_width;
  arrived.bond_width = leaving.bond_width;
  for (const std::vector<char>& bytes : incoming) migration_detail::unpack(bytes, walls, arrived);
  return arrived;
}

}  // namespace gpudem
