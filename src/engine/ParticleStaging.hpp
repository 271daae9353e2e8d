#pragma once
/// The owned particles of one step copied aside for output (StagedParticles, StepEngine.hpp),
/// so that a snapshot is written while the engine steps on. Host backend: the copy is made when
/// staged. CUDA backend: the copies go to page-locked host buffers on a stream of their own,
/// ordered after the kernels already launched and before those launched later (a blocking
/// stream), and collect() waits for them; the device needs no second copy of the particles.
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/DeviceArray.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

/// The engine's per-particle arrays a snapshot holds; the first `owned` rows are the owned
/// particles. The state is in scalar P, forces and torques in the law's scalar S.
template <class Space, class P, class S>
struct OwnedParticleArrays {
  const DeviceArray<Vec4T<P>, Space>& position_radius;
  const DeviceArray<Vec4T<P>, Space>& velocity_inv_mass;
  const DeviceArray<Vec3T<P>, Space>& angular_velocity;
  const DeviceArray<Vec3T<S>, Space>& force;
  const DeviceArray<Vec3T<S>, Space>& torque;
  const DeviceArray<ParticleId, Space>& id;
  const DeviceArray<MaterialId, Space>& material;
  std::size_t owned;
};

/// The first n values of `from`, converted to Real, into `to`.
template <class S>
void assign_in_real(const Vec3T<S>* from, std::size_t n, std::vector<Vec3>& to) {
  to.resize(n);
  for (std::size_t k = 0; k < n; ++k) to[k] = vec_cast<Real>(from[k]);
}

template <class S>
void assign_in_real(const Vec4T<S>* from, std::size_t n, std::vector<Real4>& to) {
  to.resize(n);
  for (std::size_t k = 0; k < n; ++k) to[k] = vec4_cast<Real>(from[k]);
}

/// Particle rows in host memory, in the engine's scalars (state P, loads S).
template <class P, class S>
struct HostParticleRows {
  const Vec4T<P>* position_radius;
  const Vec4T<P>* velocity_inv_mass;
  const Vec3T<P>* angular_velocity;
  const Vec3T<S>* force;
  const Vec3T<S>* torque;
  const ParticleId* id;
  const MaterialId* material;
  std::size_t count;
};

/// `out` holds the rows, converted to Real.
template <class P, class S>
void fill_particle_store(const HostParticleRows<P, S>& rows, ParticleStore& out) {
  const std::size_t n = rows.count;
  assign_in_real(rows.position_radius, n, out.position_radius);
  assign_in_real(rows.velocity_inv_mass, n, out.velocity_inv_mass);
  assign_in_real(rows.angular_velocity, n, out.angular_velocity);
  out.id.assign(rows.id, rows.id + n);
  out.material.assign(rows.material, rows.material + n);
  assign_in_real(rows.force, n, out.force);
  assign_in_real(rows.torque, n, out.torque);
}

/// `out` holds the owned particles in Real: read in place from host arrays, or copied from
/// the device first (blocking).
template <class Space, class P, class S>
void read_owned_particles(const OwnedParticleArrays<Space, P, S>& a, ParticleStore& out) {
  if constexpr (std::is_same_v<Space, HostSpace>) {
    fill_particle_store<P, S>(
        {a.position_radius.data(), a.velocity_inv_mass.data(), a.angular_velocity.data(),
         a.force.data(), a.torque.data(), a.id.data(), a.material.data(), a.owned},
        out);
  } else {
    std::vector<Vec4T<P>> position_radius, velocity_inv_mass;
    std::vector<Vec3T<P>> angular_velocity;
    std::vector<Vec3T<S>> force, torque;
    std::vector<ParticleId> id;
    std::vector<MaterialId> material;
    a.position_radius.download(position_radius, a.owned);
    a.velocity_inv_mass.download(velocity_inv_mass, a.owned);
    a.angular_velocity.download(angular_velocity, a.owned);
    a.force.download(force, a.owned);
    a.torque.download(torque, a.owned);
    a.id.download(id, a.owned);
    a.material.download(material, a.owned);
    fill_particle_store<P, S>(
        {position_radius.data(), velocity_inv_mass.data(), angular_velocity.data(), force.data(),
         torque.data(), id.data(), material.data(), a.owned},
        out);
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

/// CUDA backend: stage() queues the copies into pinned buffers; collect() waits for them and
/// fills the particle store on the calling thread.
template <class P, class S>
class ParticleStaging<CudaSpace, P, S> final : public StagedParticles {
 public:
  void stage(const OwnedParticleArrays<CudaSpace, P, S>& a) {
    owned_ = a.owned;
    device_ = cuda::current_device();
    queue_copy(a.position_radius, position_radius_);
    queue_copy(a.velocity_inv_mass, velocity_inv_mass_);
    queue_copy(a.angular_velocity, angular_velocity_);
    queue_copy(a.force, force_);
    queue_copy(a.torque, torque_);
    queue_copy(a.id, id_);
    queue_copy(a.material, material_);
  }

  void collect(ParticleStore& particles) override {
    cuda::select_device(device_);  // the calling thread may not have chosen the engine's device
    stream_.synchronize();
    fill_particle_store<P, S>(
        {position_radius_.data(), velocity_inv_mass_.data(), angular_velocity_.data(),
         force_.data(), torque_.data(), id_.data(), material_.data(), owned_},
        particles);
  }

 private:
  template <class T>
  void queue_copy(const DeviceArray<T, CudaSpace>& from, PinnedBuffer<T>& to) {
    to.resize(owned_);
    copy_async(from, to, owned_, stream_);
  }

  std::size_t owned_ = 0;
  int device_ = 0;
  CudaStream stream_;
  PinnedBuffer<Vec4T<P>> position_radius_, velocity_inv_mass_;
  PinnedBuffer<Vec3T<P>> angular_velocity_;
  PinnedBuffer<Vec3T<S>> force_, torque_;
  PinnedBuffer<ParticleId> id_;
  PinnedBuffer<MaterialId> material_;
};

}  // namespace gpudem
