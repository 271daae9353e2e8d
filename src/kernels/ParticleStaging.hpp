#pragma once
/// The owned particles of one step copied aside for output (StagedParticles, StepEngine.hpp),
/// so that a snapshot is written while the engine steps on. Host backend: the copy is made when
/// staged. CUDA backend: the copies go to page-locked host buffers on a stream of their own,
/// ordered after the kernels already launched and before those launched later (a blocking
/// stream), and collect() waits for them; the device needs no second copy of the particles.
#include <utility>
#include <vector>

#include "kernels/DeviceArray.hpp"
#include "kernels/StepEngine.hpp"

namespace gpudem {

/// The engine's per-particle arrays a snapshot holds; the first `owned` rows are the owned
/// particles. Forces and torques are in the law's scalar S.
template <class Space, class S>
struct OwnedParticleArrays {
  const DeviceArray<Real4, Space>& position_radius;
  const DeviceArray<Real4, Space>& velocity_inv_mass;
  const DeviceArray<Vec3, Space>& angular_velocity;
  const DeviceArray<Vec3T<S>, Space>& force;
  const DeviceArray<Vec3T<S>, Space>& torque;
  const DeviceArray<ParticleId, Space>& id;
  const DeviceArray<MaterialId, Space>& material;
  std::size_t owned;
};

/// The first n values of `from`, converted to Real.
template <class S>
std::vector<Vec3> vec3_in_real(const Vec3T<S>* from, std::size_t n) {
  std::vector<Vec3> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = vec_cast<Real>(from[k]);
  return out;
}

template <class Space, class S>
class ParticleStaging;

/// Host backend: stage() copies the particles; collect() hands the copy over.
template <class S>
class ParticleStaging<HostSpace, S> final : public StagedParticles {
 public:
  void stage(const OwnedParticleArrays<HostSpace, S>& a) {
    const std::size_t n = a.owned;
    copy_first(a.position_radius, n, copy_.position_radius);
    copy_first(a.velocity_inv_mass, n, copy_.velocity_inv_mass);
    copy_first(a.angular_velocity, n, copy_.angular_velocity);
    copy_first(a.id, n, copy_.id);
    copy_first(a.material, n, copy_.material);
    copy_.force = vec3_in_real(a.force.data(), n);
    copy_.torque = vec3_in_real(a.torque.data(), n);
  }

  /// Swaps the copy into `particles`: their old buffers are reused by the next stage().
  void collect(ParticleStore& particles) override { std::swap(particles, copy_); }

 private:
  template <class T>
  static void copy_first(const DeviceArray<T, HostSpace>& from, std::size_t n, std::vector<T>& to) {
    to.assign(from.data(), from.data() + n);
  }

  ParticleStore copy_;
};

/// CUDA backend: stage() queues the copies into pinned buffers; collect() waits for them and
/// fills the particle store on the calling thread.
template <class S>
class ParticleStaging<CudaSpace, S> final : public StagedParticles {
 public:
  void stage(const OwnedParticleArrays<CudaSpace, S>& a) {
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
    assign(position_radius_, particles.position_radius);
    assign(velocity_inv_mass_, particles.velocity_inv_mass);
    assign(angular_velocity_, particles.angular_velocity);
    assign(id_, particles.id);
    assign(material_, particles.material);
    particles.force = vec3_in_real(force_.data(), owned_);
    particles.torque = vec3_in_real(torque_.data(), owned_);
  }

 private:
  template <class T>
  void queue_copy(const DeviceArray<T, CudaSpace>& from, PinnedBuffer<T>& to) {
    to.resize(owned_);
    copy_async(from, to, owned_, stream_);
  }

  template <class T>
  void assign(const PinnedBuffer<T>& from, std::vector<T>& to) const {
    to.assign(from.data(), from.data() + owned_);
  }

  std::size_t owned_ = 0;
  int device_ = 0;
  CudaStream stream_;
  PinnedBuffer<Real4> position_radius_, velocity_inv_mass_;
  PinnedBuffer<Vec3> angular_velocity_;
  PinnedBuffer<Vec3T<S>> force_, torque_;
  PinnedBuffer<ParticleId> id_;
  PinnedBuffer<MaterialId> material_;
};

}  // namespace gpudem
