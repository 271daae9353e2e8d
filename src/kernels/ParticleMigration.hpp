#pragma once
/// Migration (DESIGN §4): on a rebuild step, owned particles whose position another rank owns
/// travel there with all their state and their contact history: the wall records, the
/// records of their own side of each particle contact, keyed by the partner's global id, and
/// their mesh records, keyed by triangle index, so that they find their contacts again in the
/// new rank's lists. Host code over host copies of the leaving particles only: the engine finds
/// and gathers them on the device and appends those that arrive.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "kernels/DomainLink.hpp"

namespace gpudem {

/// Particles that travel between ranks, as host copies (state in scalar P), with their pair history
/// as rows keyed by partner id: particle i's records are row_partner / row_history [row_offsets[i],
/// row_offsets[i + 1]), and its mesh history as rows keyed by triangle index in mesh_offsets the
/// same way.
template <class State, class P>
struct MigratingParticles {
  std::vector<Vec4T<P>> position_radius;
  std::vector<Vec4T<P>> velocity_inv_mass;
  std::vector<Vec3T<P>> angular_velocity;
  std::vector<ParticleId> id;
  std::vector<MaterialId> material;
  std::vector<State> wall_history;  ///< wall_count records per particle
  std::vector<std::uint32_t> row_offsets{0};
  std::vector<ParticleId> row_partner;
  std::vector<State> row_history;
  std::vector<std::uint32_t> mesh_offsets{0};
  std::vector<std::uint32_t> mesh_triangle;
  std::vector<State> mesh_history;

  std::size_t size() const { return id.size(); }
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

/// Particle i of `p` as bytes: its state, its wall records, then its row count and rows, then
/// its mesh row count and mesh rows.
template <class State, class P>
void pack(const MigratingParticles<State, P>& p, std::size_t i, std::uint32_t walls,
          std::vector<char>& out) {
  put(out, p.position_radius[i]);
  put(out, p.velocity_inv_mass[i]);
  put(out, p.angular_velocity[i]);
  put(out, p.id[i]);
  put(out, p.material[i]);
  for (std::uint32_t w = 0; w < walls; ++w) put(out, p.wall_history[i * walls + w]);
  put(out, p.row_offsets[i + 1] - p.row_offsets[i]);
  for (std::uint32_t e = p.row_offsets[i]; e < p.row_offsets[i + 1]; ++e) {
    put(out, p.row_partner[e]);
    put(out, p.row_history[e]);
  }
  put(out, p.mesh_offsets[i + 1] - p.mesh_offsets[i]);
  for (std::uint32_t e = p.mesh_offsets[i]; e < p.mesh_offsets[i + 1]; ++e) {
    put(out, p.mesh_triangle[e]);
    put(out, p.mesh_history[e]);
  }
}

/// Appends the particles packed in `in` to `p`.
template <class State, class P>
void unpack(const std::vector<char>& in, std::uint32_t walls, MigratingParticles<State, P>& p) {
  std::size_t at = 0;
  while (at < in.size()) {
    p.position_radius.push_back(take<Vec4T<P>>(in, at));
    p.velocity_inv_mass.push_back(take<Vec4T<P>>(in, at));
    p.angular_velocity.push_back(take<Vec3T<P>>(in, at));
    p.id.push_back(take<ParticleId>(in, at));
    p.material.push_back(take<MaterialId>(in, at));
    for (std::uint32_t w = 0; w < walls; ++w) p.wall_history.push_back(take<State>(in, at));
    const auto rows = take<std::uint32_t>(in, at);
    for (std::uint32_t e = 0; e < rows; ++e) {
      p.row_partner.push_back(take<ParticleId>(in, at));
      p.row_history.push_back(take<State>(in, at));
    }
    p.row_offsets.push_back(static_cast<std::uint32_t>(p.row_partner.size()));
    const auto mesh_rows = take<std::uint32_t>(in, at);
    for (std::uint32_t e = 0; e < mesh_rows; ++e) {
      p.mesh_triangle.push_back(take<std::uint32_t>(in, at));
      p.mesh_history.push_back(take<State>(in, at));
    }
    p.mesh_offsets.push_back(static_cast<std::uint32_t>(p.mesh_triangle.size()));
  }
}

}  // namespace migration_detail

/// Sends particle k of `leaving` (which has `walls` wall records per particle) to rank
/// destination[k] and returns the particles the other ranks sent here, in the order of the
/// sending ranks, each sender's in its order. Collective.
template <class State, class P>
MigratingParticles<State, P> exchange_migrants(const MigratingParticles<State, P>& leaving,
                                               const std::vector<int>& destination,
                                               std::uint32_t walls, const DomainLink& domain) {
  RankBuffers outgoing(domain.ranks());
  for (std::size_t k = 0; k < leaving.size(); ++k)
    migration_detail::pack(leaving, k, walls, outgoing[destination[k]]);
  RankBuffers incoming;
  domain.exchange(outgoing, incoming);
  MigratingParticles<State, P> arrived;
  for (const std::vector<char>& bytes : incoming) migration_detail::unpack(bytes, walls, arrived);
  return arrived;
}

}  // namespace gpudem
