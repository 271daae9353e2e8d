#pragma once
/// Ghost particles (DESIGN §4, plan then execute): on a rebuild step `plan` decides which owned
/// particles each other rank needs (those within the ghost width of its cells, asked of the
/// DomainLink), sends their full records once and keeps the plan; every other step `update`
/// sends only the fields a contact evaluation reads (position and radius, velocity and inverse
/// mass, and the spin when the law uses it), packed in the engine's memory space, one message
/// per rank. Ghosts occupy the slots after the owned particles, in the order of the ranks that
/// sent them.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "kernels/ArrayKernels.hpp"
#include "kernels/DeviceArray.hpp"
#include "kernels/DomainLink.hpp"
#include "kernels/ParallelFor.hpp"

namespace gpudem {

/// Pointers to the engine's per-particle arrays (owned particles, then ghosts), in Space memory.
struct ParticleArrays {
  Real4* position_radius;
  Real4* velocity_inv_mass;
  Vec3* angular_velocity;
  ParticleId* id;
  MaterialId* material;
};

/// Everything a ghost holds, as sent on a rebuild step.
struct GhostRecord {
  Real4 position_radius;
  Real4 velocity_inv_mass;
  Vec3 angular_velocity;
  ParticleId id;
  MaterialId material;
};

namespace ghost_kernels {

struct PackRecords {
  ParticleArrays from;
  const std::uint32_t* index;
  GhostRecord* out;
  GPUDEM_HD void operator()(std::size_t k) const {
    const std::uint32_t i = index[k];
    out[k] = GhostRecord{from.position_radius[i], from.velocity_inv_mass[i],
                         from.angular_velocity[i], from.id[i], from.material[i]};
  }
};

struct UnpackRecords {
  const GhostRecord* in;
  ParticleArrays to;
  std::size_t first;  ///< slot of the first ghost
  GPUDEM_HD void operator()(std::size_t k) const {
    const GhostRecord& r = in[k];
    to.position_radius[first + k] = r.position_radius;
    to.velocity_inv_mass[first + k] = r.velocity_inv_mass;
    to.angular_velocity[first + k] = r.angular_velocity;
    to.id[first + k] = r.id;
    to.material[first + k] = r.material;
  }
};

/// Per-step fields of one ghost: 8 values, or 11 with the spin.
template <bool kSpin>
struct StepFields {
  static constexpr int width = kSpin ? 11 : 8;
  GPUDEM_HD static void write(const ParticleArrays& a, std::uint32_t i, Real* out) {
    const Real4 x = a.position_radius[i], v = a.velocity_inv_mass[i];
    const Real values[8] = {x.x, x.y, x.z, x.w, v.x, v.y, v.z, v.w};
    for (int c = 0; c < 8; ++c) out[c] = values[c];
    if constexpr (kSpin) {
      const Vec3 w = a.angular_velocity[i];
      out[8] = w.x;
      out[9] = w.y;
      out[10] = w.z;
    }
  }
  GPUDEM_HD static void read(const Real* in, const ParticleArrays& a, std::size_t slot) {
    a.position_radius[slot] = Real4{in[0], in[1], in[2], in[3]};
    a.velocity_inv_mass[slot] = Real4{in[4], in[5], in[6], in[7]};
    if constexpr (kSpin) a.angular_velocity[slot] = Vec3{in[8], in[9], in[10]};
  }
};

template <bool kSpin>
struct PackFields {
  ParticleArrays from;
  const std::uint32_t* index;
  Real* out;
  GPUDEM_HD void operator()(std::size_t k) const {
    StepFields<kSpin>::write(from, index[k], out + k * StepFields<kSpin>::width);
  }
};

template <bool kSpin>
struct UnpackFields {
  const Real* in;
  ParticleArrays to;
  std::size_t first;
  GPUDEM_HD void operator()(std::size_t k) const {
    StepFields<kSpin>::read(in + k * StepFields<kSpin>::width, to, first + k);
  }
};

}  // namespace ghost_kernels

template <class Space, bool kSpin>
class GhostExchange {
  using Fields = ghost_kernels::StepFields<kSpin>;

 public:
  /// Plans the exchange from the owned particles' positions and sends their records; returns
  /// the number of ghosts received, to be written by `fill` once the caller has made room for
  /// them after its `owned` particles. Collective.
  std::size_t plan(const DomainLink& domain, const ParticleArrays& particles, std::size_t owned) {
    const std::vector<Real4> position = download_values<Space>(particles.position_radius, owned);
    std::vector<std::vector<std::uint32_t>> to_rank(domain.ranks());
    std::vector<int> ranks;
    for (std::size_t i = 0; i < owned; ++i) {
      domain.ghost_ranks(xyz(position[i]), ranks);
      for (const int q : ranks) to_rank[q].push_back(static_cast<std::uint32_t>(i));
    }
    std::vector<std::uint32_t> index;
    send_count_.assign(domain.ranks(), 0);
    for (int q = 0; q < domain.ranks(); ++q) {
      send_count_[q] = to_rank[q].size();
      index.insert(index.end(), to_rank[q].begin(), to_rank[q].end());
    }
    send_index_.upload(index);
    DeviceArray<GhostRecord, Space> packed(index.size());
    parallel_for(Space{}, index.size(),
                 ghost_kernels::PackRecords{particles, send_index_.data(), packed.data()});
    RankBuffers incoming;
    RankBuffers outgoing;
    split(packed, sizeof(GhostRecord), outgoing);
    domain.exchange(outgoing, incoming);
    receive_count_.assign(domain.ranks(), 0);
    for (int q = 0; q < domain.ranks(); ++q)
      receive_count_[q] = incoming[q].size() / sizeof(GhostRecord);
    join(incoming, received_);
    return received_.size();
  }

  /// Writes the records received by `plan` into slots [owned, owned + ghosts()).
  void fill(const ParticleArrays& particles, std::size_t owned) const {
    parallel_for(Space{}, received_.size(),
                 ghost_kernels::UnpackRecords{received_.data(), particles, owned});
  }

  /// Sends the planned particles' per-step fields and writes those received into the ghost
  /// slots. Collective.
  void update(const DomainLink& domain, const ParticleArrays& particles, std::size_t owned) {
    const int width = Fields::width;
    packed_fields_.resize(send_index_.size() * width);
    parallel_for(
        Space{}, send_index_.size(),
        ghost_kernels::PackFields<kSpin>{particles, send_index_.data(), packed_fields_.data()});
    split(packed_fields_, width * sizeof(Real), outgoing_);
    incoming_.resize(domain.ranks());
    for (int q = 0; q < domain.ranks(); ++q)
      incoming_[q].resize(receive_count_[q] * width * sizeof(Real));
    domain.exchange_known(outgoing_, incoming_);
    join(incoming_, fields_);
    parallel_for(Space{}, ghosts(),
                 ghost_kernels::UnpackFields<kSpin>{fields_.data(), particles, owned});
  }

  std::size_t ghosts() const { return received_.size(); }
  /// Bytes one refresh sends (the halo volume of this rank per step).
  std::size_t refresh_bytes() const { return send_index_.size() * Fields::width * sizeof(Real); }
  std::size_t memory_bytes() const {
    return send_index_.bytes() + received_.bytes() + packed_fields_.bytes() + fields_.bytes();
  }

 private:
  /// The packed rows as one byte buffer per rank, `row_bytes` per row, in the plan's order.
  template <class T>
  void split(const DeviceArray<T, Space>& packed, std::size_t row_bytes, RankBuffers& out) const {
    std::vector<T> host;
    packed.download(host);
    const char* bytes = reinterpret_cast<const char*>(host.data());
    out.resize(send_count_.size());
    std::size_t offset = 0;
    for (std::size_t q = 0; q < send_count_.size(); ++q) {
      out[q].assign(bytes + offset, bytes + offset + send_count_[q] * row_bytes);
      offset += send_count_[q] * row_bytes;
    }
  }

  /// The buffers of all ranks, in rank order, as one array in Space memory.
  template <class T>
  static void join(const RankBuffers& incoming, DeviceArray<T, Space>& out) {
    std::size_t bytes = 0;
    for (const std::vector<char>& b : incoming) bytes += b.size();
    std::vector<T> host(bytes / sizeof(T));
    char* cursor = reinterpret_cast<char*>(host.data());
    for (const std::vector<char>& b : incoming) {
      if (!b.empty()) std::memcpy(cursor, b.data(), b.size());
      cursor += b.size();
    }
    out.upload(host);
  }

  DeviceArray<std::uint32_t, Space> send_index_;  ///< owned particles to send, rank by rank
  std::vector<std::size_t> send_count_;           ///< per rank
  std::vector<std::size_t> receive_count_;        ///< ghosts from each rank
  DeviceArray<GhostRecord, Space> received_;      ///< records of the last plan, rank by rank
  // Per-step buffers, kept so that a step allocates nothing once they have grown.
  DeviceArray<Real, Space> packed_fields_;
  DeviceArray<Real, Space> fields_;
  RankBuffers outgoing_;
  RankBuffers incoming_;
};

}  // namespace gpudem
