#pragma once
/// Ghost particles (DESIGN §4, plan then execute): on a rebuild step `plan` decides which owned
/// particles each other rank needs (those within the ghost width of its cells, asked of the
/// DomainLink), sends their full records once and keeps the plan; every other step `update`
/// (or `begin_update`, work, `finish_update`) sends only the fields a contact evaluation reads
/// (position and radius, velocity and inverse mass, and the spin when the law uses it), packed
/// in the engine's memory space, one non-blocking message per rank. Ghosts occupy the slots
/// after the owned particles, in the order of the ranks that sent them.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <utility>
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

/// flag[r] = 1 when row r of an owned particles' CSR neighbour list holds a ghost (an index
/// >= owned), else 0, for r < owned; flag[owned] = 0.
struct ReadsGhost {
  const std::uint32_t* offsets;
  const std::uint32_t* neighbors;
  std::uint32_t owned;
  std::uint32_t* flag;
  GPUDEM_HD void operator()(std::size_t r) const {
    std::uint32_t reads = 0;
    if (r < owned)
      for (std::uint32_t e = offsets[r]; e < offsets[r + 1]; ++e)
        if (neighbors[e] >= owned) reads = 1;
    flag[r] = reads;
  }
};

/// Row r to its place in the boundary rows (before[r] boundary rows precede it) or the interior
/// rows, from the exclusive scan `before` of ReadsGhost's flags.
struct ScatterRows {
  const std::uint32_t* before;
  std::uint32_t* interior;
  std::uint32_t* boundary;
  GPUDEM_HD void operator()(std::size_t r) const {
    const auto row = static_cast<std::uint32_t>(r);
    if (before[r + 1] != before[r])
      boundary[before[r]] = row;
    else
      interior[r - before[r]] = row;
  }
};

}  // namespace ghost_kernels

/// The owned particles split by whether their neighbour-list row reads a ghost: the interior
/// ones' forces can be computed while the ghosts' fields are in flight, the boundary ones'
/// after they arrived. Both lists ascending, in Space memory.
template <class Space>
class GhostRowSplit {
 public:
  /// Splits rows [0, owned) of the CSR list (offsets, neighbors) over owned particles
  /// [0, owned) and ghosts from `owned` on.
  void build(const std::uint32_t* offsets, const std::uint32_t* neighbors, std::size_t owned) {
    before_.resize(owned + 1);
    parallel_for(Space{}, owned + 1,
                 ghost_kernels::ReadsGhost{offsets, neighbors, static_cast<std::uint32_t>(owned),
                                           before_.data()});
    const std::size_t boundary = exclusive_scan(Space{}, before_.data(), before_.data(), owned + 1);
    interior_.resize(owned - boundary);
    boundary_.resize(boundary);
    parallel_for(Space{}, owned,
                 ghost_kernels::ScatterRows{before_.data(), interior_.data(), boundary_.data()});
  }

  const std::uint32_t* interior() const { return interior_.data(); }
  std::size_t interior_count() const { return interior_.size(); }
  const std::uint32_t* boundary() const { return boundary_.data(); }
  std::size_t boundary_count() const { return boundary_.size(); }
  std::size_t memory_bytes() const {
    return before_.bytes() + interior_.bytes() + boundary_.bytes();
  }

 private:
  DeviceArray<std::uint32_t, Space> before_;  ///< boundary rows before each row
  DeviceArray<std::uint32_t, Space> interior_;
  DeviceArray<std::uint32_t, Space> boundary_;
};

/// Pinned host copies of the refresh buffers, for a DomainLink that takes host memory only:
/// none for host memory.
template <class Space>
struct HaloStaging {};

template <>
struct HaloStaging<CudaSpace> {
  PinnedBuffer<Real> send;
  PinnedBuffer<Real> receive;
  CudaStream stream;
};

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
    const std::size_t row_bytes = Fields::width * sizeof(Real);
    send_bytes_.assign(domain.ranks(), 0);
    receive_bytes_.assign(domain.ranks(), 0);
    for (int q = 0; q < domain.ranks(); ++q) {
      send_bytes_[q] = send_count_[q] * row_bytes;
      receive_bytes_[q] = incoming[q].size() / sizeof(GhostRecord) * row_bytes;
    }
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
    begin_update(domain, particles);
    finish_update(domain, particles, owned);
  }

  /// First half of `update`: packs the planned particles' per-step fields and posts the
  /// messages; the ghost slots keep their values until finish_update. Device buffers go to
  /// the DomainLink as they are when it takes them, else through pinned host copies.
  void begin_update(const DomainLink& domain, const ParticleArrays& particles) {
    if (in_flight_) throw std::logic_error("GhostExchange: a refresh is already in flight");
    in_flight_ = true;
    packed_fields_.resize(send_index_.size() * Fields::width);
    fields_.resize(ghosts() * Fields::width);
    parallel_for(
        Space{}, send_index_.size(),
        ghost_kernels::PackFields<kSpin>{particles, send_index_.data(), packed_fields_.data()});
    staged_ = kDeviceMemory && !domain.device_buffers();
    if constexpr (kDeviceMemory) {
      if (staged_) return post_staged(domain);
      cuda::synchronize_device();  // the packing kernel has written what MPI reads
    }
    pending_ = domain.start_exchange(bytes_of(packed_fields_.data()), send_bytes_,
                                     bytes_of(fields_.data()), receive_bytes_);
  }

  /// Second half of `update`: waits for the messages and writes the received fields into the
  /// slots [owned, owned + ghosts()).
  void finish_update(const DomainLink& domain, const ParticleArrays& particles, std::size_t owned) {
    if (!in_flight_) throw std::logic_error("GhostExchange: finish_update without begin_update");
    in_flight_ = false;
    domain.finish_exchange(std::move(pending_));
    if constexpr (kDeviceMemory) {
      // Queued on a blocking stream: the unpacking kernel below waits for it.
      if (staged_) copy_async(staging_.receive, fields_, fields_.size(), staging_.stream);
    }
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
  static constexpr bool kDeviceMemory = std::is_same_v<Space, CudaSpace>;

  /// The packed fields copied to pinned memory (waiting for the copy), then the messages
  /// posted from and into pinned memory.
  void post_staged(const DomainLink& domain) {
    staging_.send.resize(packed_fields_.size());
    staging_.receive.resize(fields_.size());
    copy_async(packed_fields_, staging_.send, packed_fields_.size(), staging_.stream);
    staging_.stream.synchronize();
    pending_ = domain.start_exchange(bytes_of(staging_.send.data()), send_bytes_,
                                     bytes_of(staging_.receive.data()), receive_bytes_);
  }

  static const char* bytes_of(const Real* values) { return reinterpret_cast<const char*>(values); }
  static char* bytes_of(Real* values) { return reinterpret_cast<char*>(values); }

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
  DeviceArray<GhostRecord, Space> received_;      ///< records of the last plan, rank by rank
  // Per-step buffers, kept so that a step allocates nothing once they have grown.
  std::vector<std::size_t> send_bytes_;     ///< per rank, per refresh
  std::vector<std::size_t> receive_bytes_;  ///< per rank, per refresh
  DeviceArray<Real, Space> packed_fields_;
  DeviceArray<Real, Space> fields_;
  HaloStaging<Space> staging_;
  bool in_flight_ = false;  ///< between begin_update and finish_update
  bool staged_ = false;     ///< the refresh in flight goes through staging_
  std::unique_ptr<PendingExchange> pending_;
};

}  // namespace gpudem
