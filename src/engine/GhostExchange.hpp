#pragma once
/// Ghost particles (docs/architecture.md, "One time step", plan then execute): on a rebuild step
/// `plan` decides which owned particles each other rank needs (those within the ghost width of its
/// cells, asked of the DomainLink for the particles the device finds near another rank's cells),
/// sends their full records (the `ghost` fields of the particle field table,
/// core/ParticleFields.hpp) once and keeps the plan; every other step `update` (or `begin_update`,
/// work, `finish_update`) sends only the fields a contact evaluation reads (the `refresh` fields,
/// position and radius, velocity and inverse mass, and the spin when the law uses it), packed in
/// the engine's memory space, one non-blocking message per rank. Ghosts occupy the slots after the
/// owned particles, in the order of the ranks that sent them.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/Config.hpp"
#include "core/ParticleFields.hpp"
#include "core/Vec3.hpp"
#include "engine/ArrayKernels.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/DomainLink.hpp"
#include "engine/ParallelFor.hpp"
#include "engine/RankCells.hpp"

namespace gpudem {

namespace ghost_kernels {

/// Everything a ghost holds, as sent on a rebuild step: the WireRow of the ghost fields.
template <class P, class S>
using GhostRow = WireRow<field_use::ghost, P, S>;

template <class P, class S>
struct PackRecords {
  ParticlePointers<P, S> from;
  const std::uint32_t* index;
  char* out;
  GPUDEM_HD void operator()(std::size_t k) const {
    GhostRow<P, S>::write(from, index[k], out + k * GhostRow<P, S>::bytes);
  }
};

template <class P, class S>
struct UnpackRecords {
  const char* in;
  ParticlePointers<P, S> to;
  std::size_t first;  ///< slot of the first ghost
  GPUDEM_HD void operator()(std::size_t k) const {
    GhostRow<P, S>::read(in + k * GhostRow<P, S>::bytes, to, first + k);
  }
};

/// Per-step fields of one ghost: those of the table refreshed on every step, with the spin
/// when kSpin, as `width` values of the state scalar P (their WireRow, component by component).
template <bool kSpin, class P, class S>
struct StepFields {
  static constexpr unsigned use = field_use::refresh | (kSpin ? field_use::spin_refresh : 0u);
  static constexpr std::size_t bytes = WireRow<use, P, S>::bytes;
  static_assert(bytes % sizeof(P) == 0, "refreshed fields hold values of the state scalar");
  static constexpr int width = static_cast<int>(bytes / sizeof(P));

  GPUDEM_HD static void write(const ParticlePointers<P, S>& a, std::uint32_t i, P* out) {
    int c = 0;
    for_each_particle_field<use>([&](auto field) {
      using V = FieldValue<decltype(field), P, S>;
      using Parts = ValueComponents<V>;
      static_assert(std::is_same_v<typename Parts::Scalar, P>, "a refreshed field is not in P");
      const V value = a.template get<decltype(field)>()[i];
      for (int k = 0; k < Parts::count; ++k) out[c++] = Parts::get(value, k);
    });
  }
  GPUDEM_HD static void read(const P* in, const ParticlePointers<P, S>& a, std::size_t slot) {
    int c = 0;
    for_each_particle_field<use>([&](auto field) {
      using V = FieldValue<decltype(field), P, S>;
      using Parts = ValueComponents<V>;
      V value;
      for (int k = 0; k < Parts::count; ++k) Parts::set(value, k, in[c++]);
      a.template get<decltype(field)>()[slot] = value;
    });
  }
};

template <bool kSpin, class P, class S>
struct PackFields {
  ParticlePointers<P, S> from;
  const std::uint32_t* index;
  P* out;
  GPUDEM_HD void operator()(std::size_t k) const {
    using Fields = StepFields<kSpin, P, S>;
    Fields::write(from, index[k], out + k * Fields::width);
  }
};

template <bool kSpin, class P, class S>
struct UnpackFields {
  const P* in;
  ParticlePointers<P, S> to;
  std::size_t first;
  GPUDEM_HD void operator()(std::size_t k) const {
    using Fields = StepFields<kSpin, P, S>;
    Fields::read(in + k * Fields::width, to, first + k);
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

/// Pinned host copies of the refresh buffers (values of the state scalar P), for a DomainLink
/// that takes host memory only: none for host memory.
template <class Space, class P>
struct HaloStaging {};

template <class P>
struct HaloStaging<CudaSpace, P> {
  PinnedBuffer<P> send;
  PinnedBuffer<P> receive;
  CudaStream stream;
};

/// The ghosts of an engine whose state is in scalar P; the per-step refresh carries the spin
/// when the contact law reads it.
template <class Space, class P, class S>
class GhostExchange {
  using Arrays = ParticlePointers<P, S>;
  using Record = ghost_kernels::GhostRow<P, S>;

 public:
  explicit GhostExchange(bool spin) : spin_(spin) {}

  /// Plans the exchange from the owned particles' positions and sends their records; returns
  /// the number of ghosts received, to be written by `fill` once the caller has made room for
  /// them after its `owned` particles. Only the particles in cells near another rank's
  /// (`cells`, the domain's map) are asked of the domain, on the host. Collective.
  std::size_t plan(const DomainLink& domain, const RankCells<Space>& cells, const Arrays& particles,
                   std::size_t owned) {
    std::vector<std::uint32_t> candidate;
    std::vector<Vec4T<P>> position;
    cells.near_other_rank(particles.template get<particle_field::PositionRadius>(), owned,
                          candidate, position);
    std::vector<std::vector<std::uint32_t>> to_rank(domain.ranks());
    std::vector<int> ranks;
    for (std::size_t k = 0; k < candidate.size(); ++k) {
      domain.ghost_ranks(vec_cast<Real>(xyz(position[k])), ranks);
      for (const int q : ranks) to_rank[q].push_back(candidate[k]);
    }
    std::vector<std::uint32_t> index;
    send_count_.assign(domain.ranks(), 0);
    for (int q = 0; q < domain.ranks(); ++q) {
      send_count_[q] = to_rank[q].size();
      index.insert(index.end(), to_rank[q].begin(), to_rank[q].end());
    }
    send_index_.upload(index);
    DeviceArray<char, Space> packed(index.size() * Record::bytes);
    parallel_for(Space{}, index.size(),
                 ghost_kernels::PackRecords<P, S>{particles, send_index_.data(), packed.data()});
    RankBuffers incoming;
    RankBuffers outgoing;
    split(packed, Record::bytes, outgoing);
    domain.group().exchange(outgoing, incoming);
    const std::size_t row_bytes = width() * sizeof(P);
    send_bytes_.assign(domain.ranks(), 0);
    receive_bytes_.assign(domain.ranks(), 0);
    for (int q = 0; q < domain.ranks(); ++q) {
      send_bytes_[q] = send_count_[q] * row_bytes;
      receive_bytes_[q] = incoming[q].size() / Record::bytes * row_bytes;
    }
    join(incoming, received_);
    return ghosts();
  }

  /// Writes the records received by `plan` into slots [owned, owned + ghosts()).
  void fill(const Arrays& particles, std::size_t owned) const {
    parallel_for(Space{}, ghosts(),
                 ghost_kernels::UnpackRecords<P, S>{received_.data(), particles, owned});
  }

  /// Sends the planned particles' per-step fields and writes those received into the ghost
  /// slots. Collective.
  void update(const DomainLink& domain, const Arrays& particles, std::size_t owned) {
    begin_update(domain, particles);
    finish_update(domain, particles, owned);
  }

  /// First half of `update`: packs the planned particles' per-step fields and posts the
  /// messages; the ghost slots keep their values until finish_update. Device buffers go to
  /// the DomainLink as they are when it takes them, else through pinned host copies.
  void begin_update(const DomainLink& domain, const Arrays& particles) {
    if (in_flight_) throw std::logic_error("GhostExchange: a refresh is already in flight");
    in_flight_ = true;
    packed_fields_.resize(send_index_.size() * width());
    fields_.resize(ghosts() * width());
    if (spin_)
      pack_fields<true>(particles);
    else
      pack_fields<false>(particles);
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
  void finish_update(const DomainLink& domain, const Arrays& particles, std::size_t owned) {
    if (!in_flight_) throw std::logic_error("GhostExchange: finish_update without begin_update");
    in_flight_ = false;
    domain.finish_exchange(std::move(pending_));
    if constexpr (kDeviceMemory) {
      // Queued on a blocking stream: the unpacking kernel below waits for it.
      if (staged_) copy_async(staging_.receive, fields_, fields_.size(), staging_.stream);
    }
    if (spin_)
      unpack_fields<true>(particles, owned);
    else
      unpack_fields<false>(particles, owned);
  }

  std::size_t ghosts() const { return received_.size() / Record::bytes; }
  /// Bytes one refresh sends (the halo volume of this rank per step).
  std::size_t refresh_bytes() const { return send_index_.size() * width() * sizeof(P); }
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

  /// Values per particle in a refresh (ghost_kernels::StepFields).
  int width() const {
    return spin_ ? ghost_kernels::StepFields<true, P, S>::width
                 : ghost_kernels::StepFields<false, P, S>::width;
  }

  template <bool kSpin>
  void pack_fields(const Arrays& particles) {
    parallel_for(Space{}, send_index_.size(),
                 ghost_kernels::PackFields<kSpin, P, S>{particles, send_index_.data(),
                                                        packed_fields_.data()});
  }

  template <bool kSpin>
  void unpack_fields(const Arrays& particles, std::size_t owned) {
    parallel_for(Space{}, ghosts(),
                 ghost_kernels::UnpackFields<kSpin, P, S>{fields_.data(), particles, owned});
  }

  static const char* bytes_of(const P* values) { return reinterpret_cast<const char*>(values); }
  static char* bytes_of(P* values) { return reinterpret_cast<char*>(values); }

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

  bool spin_;                                     ///< the refresh carries the spin
  DeviceArray<std::uint32_t, Space> send_index_;  ///< owned particles to send, rank by rank
  std::vector<std::size_t> send_count_;           ///< per rank
  DeviceArray<char, Space> received_;             ///< records of the last plan, rank by rank
  // Per-step buffers, kept so that a step allocates nothing once they have grown.
  std::vector<std::size_t> send_bytes_;     ///< per rank, per refresh
  std::vector<std::size_t> receive_bytes_;  ///< per rank, per refresh
  DeviceArray<P, Space> packed_fields_;
  DeviceArray<P, Space> fields_;
  HaloStaging<Space, P> staging_;
  bool in_flight_ = false;  ///< between begin_update and finish_update
  bool staged_ = false;     ///< the refresh in flight goes through staging_
  std::unique_ptr<PendingExchange> pending_;
};

}  // namespace gpudem
