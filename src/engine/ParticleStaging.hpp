#pragma once
/// The owned particles of one step copied aside for output (StagedParticles, StepEngine.hpp),
/// so that a snapshot is written while the engine steps on. Host backend: the copy is made when
/// staged. CUDA backend: the copies go to page-locked host buffers on a stream of their own,
/// ordered after the kernels already launched and before those launched later (a blocking
/// stream), and collect() waits for them; the device needs no second copy of the particles.
/// Every field of the table (core/ParticleFields.hpp) is copied.
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/DeviceArray.hpp"
#include "engine/ParticleColumns.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

/// The engine's particle arrays, of which the first `owned` rows are the owned particles.
template <class Space, class P, class S>
struct OwnedParticleArrays {
  const ParticleColumns<Space, P, S>& columns;
  std::size_t owned;
};

/// `out` holds the owned particles in Real: read in place from host arrays, or copied from
/// the device first (blocking).
template <class Space, class P, class S>
void read_owned_particles(const OwnedParticleArrays<Space, P, S>& a, ParticleStore& out) {
  if constexpr (std::is_same_v<Space, HostSpace>) {
    fill_particle_store(a.columns.pointers(), a.owned, out);
  } else {
    const ParticleVectors<P, S> rows = a.columns.template download_rows<field_use::any>(0, a.owned);
    fill_particle_store(pointers_of(rows), a.owned, out);
  }
}

template <class Space, class P, class S>
class ParticleStaging;

/// Host backend: stage() copies the particles; collect() hands the copy over.
template <class P, class S>
class ParticleStaging<HostSpace, P, S> final : public StagedParticles {
 public:
  void stage(const OwnedParticleArrays<HostSpace, P, S>& a) { read_owned_particles(a, copy_); }

  /// Swaps the copy into `particles`: their old buffers are reused by the next stage().
  void collect(ParticleStore& particles) override { std::swap(particles, copy_); }

 private:
  ParticleStore copy_;
};

/// Holders for FieldTuple: one pinned host buffer of each field's values.
template <class P, class S>
struct PinnedPerField {
  template <class F>
  using type = PinnedBuffer<FieldValue<F, P, S>>;
};

/// CUDA backend: stage() queues the copies into pinned buffers; collect() waits for them and
/// fills the particle store on the calling thread.
template <class P, class S>
class ParticleStaging<CudaSpace, P, S> final : public StagedParticles {
 public:
  void stage(const OwnedParticleArrays<CudaSpace, P, S>& a) {
    owned_ = a.owned;
    device_ = cuda::current_device();
    for_each_particle_field([&](auto field) {
      using F = decltype(field);
      PinnedBuffer<FieldValue<F, P, S>>& to = buffers_.template get<F>();
      to.resize(owned_);
      copy_async(a.columns.template get<F>(), to, owned_, stream_);
    });
  }

  void collect(ParticleStore& particles) override {
    cuda::select_device(device_);  // the calling thread may not have chosen the engine's device
    stream_.synchronize();
    ParticlePointers<P, S> rows;
    for_each_particle_field([&](auto field) {
      using F = decltype(field);
      rows.template get<F>() = buffers_.template get<F>().data();
    });
    fill_particle_store(rows, owned_, particles);
  }

 private:
  std::size_t owned_ = 0;
  int device_ = 0;
  CudaStream stream_;
  ParticleFieldTable::Tuple<PinnedPerField<P, S>> buffers_;
};

}  // namespace gpudem
