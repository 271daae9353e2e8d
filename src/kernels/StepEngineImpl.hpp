#pragma once
/// The step engine for one execution space and one contact law (DESIGN §4 on one rank): the
/// same code is instantiated for HostSpace and CudaSpace and for every valid law
/// (EngineFactory.hpp). Include the backend's ParallelFor header first.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "kernels/ArrayKernels.hpp"
#include "kernels/CellList.hpp"
#include "kernels/ContactForces.hpp"
#include "kernels/DeviceArray.hpp"
#include "kernels/Diagnostics.hpp"
#include "kernels/Integrators.hpp"
#include "kernels/MeshWalls.hpp"
#include "kernels/NeighborList.hpp"
#include "kernels/Permute.hpp"
#include "kernels/StepEngine.hpp"

namespace gpudem {

/// 1 for particles outside the non-periodic box, else 0 (sort key that moves leavers last).
struct LeaverKey {
  const Real4* position_radius;
  PeriodicBox box;
  std::uint64_t* key;
  std::uint32_t* index;
  GPUDEM_HD void operator()(std::size_t i) const {
    key[i] = box.outside(xyz(position_radius[i])) ? 1 : 0;
    index[i] = static_cast<std::uint32_t>(i);
  }
};

struct IsLeaver {
  const Real4* position_radius;
  PeriodicBox box;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return box.outside(xyz(position_radius[i])) ? Real(1) : Real(0);
  }
};

/// Maps positions into the box along periodic axes.
struct WrapPositions {
  Real4* position_radius;
  PeriodicBox box;
  GPUDEM_HD void operator()(std::size_t i) const {
    const Vec3 p = box.wrap(xyz(position_radius[i]));
    position_radius[i].x = p.x;
    position_radius[i].y = p.y;
    position_radius[i].z = p.z;
  }
};

struct Radius {
  const Real4* position_radius;
  GPUDEM_HD Real operator()(std::size_t i) const { return position_radius[i].w; }
};

struct ReadValue {
  const Real* value;
  GPUDEM_HD Real operator()(std::size_t i) const { return value[i]; }
};

struct Iota {
  std::uint32_t* out;
  GPUDEM_HD void operator()(std::size_t k) const { out[k] = static_cast<std::uint32_t>(k); }
};

/// out row k = in row order[k], rows of `width` values (per-particle wall histories).
template <class T>
struct GatherRows {
  const std::uint32_t* order;
  const T* in;
  T* out;
  std::uint32_t width;
  GPUDEM_HD void operator()(std::size_t k) const {
    for (std::uint32_t w = 0; w < width; ++w) out[k * width + w] = in[order[k] * width + w];
  }
};

/// Carries contact history over a neighbour rebuild: for each new list entry of particle k,
/// the history of the old entry of the same particle (old index previous_index[k]) with the
/// same partner global id, or zero for a new contact. Contact history is keyed by global id,
/// never by position in a list.
template <class State>
struct RemapPairHistory {
  const std::uint32_t* offsets;
  const std::uint32_t* neighbors;
  const ParticleId* id;
  const std::uint32_t* previous_index;
  const std::uint32_t* previous_offsets;
  const std::uint32_t* previous_neighbors;
  const ParticleId* previous_id;
  const State* previous_history;
  State* history;
  GPUDEM_HD void operator()(std::size_t k) const {
    const std::uint32_t old = previous_index[k];
    for (std::uint32_t e = offsets[k]; e < offsets[k + 1]; ++e) {
      const ParticleId partner = id[neighbors[e]];
      State carried{};
      for (std::uint32_t f = previous_offsets[old]; f < previous_offsets[old + 1]; ++f)
        if (previous_id[previous_neighbors[f]] == partner) {
          carried = previous_history[f];
          break;
        }
      history[e] = carried;
    }
  }
};

template <class Space, class Law>
class StepEngineImpl final : public StepEngine {
  using State = typename Law::State;
  static constexpr std::uint32_t kHistoryWidth = Law::history_size;

 public:
  explicit StepEngineImpl(const EngineSetup& setup)
      : setup_(setup), meshes_(setup.meshes), steps_(setup.start_step) {
    pair_params_.upload(setup.pair_params);
    walls_.upload(setup.walls);
    if (!meshes_.empty()) meshes_.set_time(steps_ * setup.dt);
  }

  void set_particles(const ParticleStore& p) override {
    upload_particles(p);
    has_list_ = false;
    rebuild();
    compute_forces();
  }

  void restore_particles(const ParticleStore& p, const std::vector<Real4>& list_positions,
                         std::uint64_t removed) override {
    if (list_positions.size() != p.size() || p.force.size() != p.size() ||
        p.torque.size() != p.size())
      throw std::invalid_argument("restore_particles: arrays differ in length");
    upload_particles(p);
    position_at_build_.upload(list_positions);
    DeviceArray<Vec3, Space> saved_force, saved_torque;
    saved_force.upload(p.force);
    saved_torque.upload(p.torque);
    build_list_at_saved_positions(saved_force, saved_torque);
    compute_forces();  // for the overlap ratios; the forces and history it leaves are replaced
    force_.swap(saved_force);
    torque_.swap(saved_torque);
    zero_history();
    removed_ = removed;
  }

  void get_particles(ParticleStore& p) const override {
    position_radius_.download(p.position_radius);
    velocity_inv_mass_.download(p.velocity_inv_mass);
    angular_velocity_.download(p.angular_velocity);
    force_.download(p.force);
    torque_.download(p.torque);
    id_.download(p.id);
    material_.download(p.material);
  }

  void get_contact_history(ContactHistory& history) const override {
    history = collect_history(contact_slots(), kHistoryWidth, flat_values(pair_history_),
                              flat_values(wall_history_));
  }

  void set_contact_history(const ContactHistory& history) override {
    std::vector<Real> pair_values, wall_values;
    scatter_history(contact_slots(), kHistoryWidth, history, pair_values, wall_values);
    if constexpr (kHistoryWidth > 0) {
      upload_states(pair_values, pair_history_);
      upload_states(wall_values, wall_history_);
    }
  }

  void get_list_positions(std::vector<Real4>& position_radius) const override {
    position_at_build_.download(position_radius);
  }

  std::size_t particle_count() const override { return id_.size(); }

  void step() override {
    const Real dt = setup_.dt;
    const bool verlet = setup_.integrator == IntegratorKind::VelocityVerlet;
    kick(verlet ? Real(0.5) * dt : dt);
    parallel_for(Space{}, size(), Drift{position_radius_.data(), velocity_inv_mass_.data(), dt});
    ++steps_;
    if (!meshes_.empty()) meshes_.set_time(steps_ * dt);
    if (needs_rebuild()) rebuild();
    compute_forces();
    if (verlet) kick(Real(0.5) * dt);
  }

  void rebuild_neighbors() override {
    rebuild();
    compute_forces();
  }

  bool find_unhealthy(double limit, HealthFailure& failure) const override {
    const HealthScore score{position_radius_.data(), velocity_inv_mass_.data(),
                            overlap_ratio_.data()};
    if (reduce_max(Space{}, size(), Real(0), score) <= limit) return false;
    ParticleStore host;
    get_particles(host);
    std::vector<Real> ratio;
    overlap_ratio_.download(ratio);
    const HealthScore host_score{host.position_radius.data(), host.velocity_inv_mass.data(),
                                 ratio.data()};
    for (std::size_t i = 0; i < host.size(); ++i) {
      const Real s = host_score(i);
      if (s <= limit) continue;
      failure =
          HealthFailure{host.id[i], xyz(host.position_radius[i]), ratio[i],
                        s == kNonFiniteScore, ratio[i] == kMeshOverflowScore};
      return true;
    }
    return false;
  }

  Diagnostics diagnostics() const override {
    Diagnostics d;
    const std::size_t n = size();
    const ParticleView view = particle_view();
    d.particle_count = n;
    d.kinetic_translational =
        reduce_sum(Space{}, n, TranslationalEnergy{velocity_inv_mass_.data()});
    d.kinetic_rotational =
        reduce_sum(Space{}, n,
                   RotationalEnergy{velocity_inv_mass_.data(), position_radius_.data(),
                                    angular_velocity_.data()});
    d.potential_gravity = reduce_sum(
        Space{}, n,
        GravityEnergy{velocity_inv_mass_.data(), position_radius_.data(), setup_.gravity});
    DeviceArray<Real, Space> contacts(n), energy(n);
    const std::uint32_t bodies = wall_count() + meshes_.count();
    DeviceArray<Vec3, Space> body_force(n * bodies), mesh_torque(n * meshes_.count());
    parallel_for(Space{}, n,
                 ContactTerms<Law>{view, contact_scene(), contacts.data(), energy.data(),
                                   body_force.data(), mesh_torque.data()});
    d.potential_elastic = reduce_sum(Space{}, n, ReadValue{energy.data()});
    d.contact_count =
        static_cast<std::uint64_t>(std::llround(reduce_sum(Space{}, n, ReadValue{contacts.data()})));
    d.max_overlap_ratio = reduce_max(Space{}, n, Real(0), ReadValue{overlap_ratio_.data()});
    for (std::uint32_t w = 0; w < wall_count(); ++w)
      d.wall_force.push_back(column_sum(body_force, bodies, w));
    for (std::uint32_t m = 0; m < meshes_.count(); ++m) {
      d.mesh_force.push_back(column_sum(body_force, bodies, wall_count() + m));
      d.mesh_torque.push_back(column_sum(mesh_torque, meshes_.count(), m));
    }
    return d;
  }

  std::uint64_t removed_count() const override { return removed_; }
  std::uint64_t rebuild_count() const override { return rebuilds_; }

  std::size_t memory_bytes() const override {
    return position_radius_.bytes() + velocity_inv_mass_.bytes() + angular_velocity_.bytes() +
           force_.bytes() + torque_.bytes() + id_.bytes() + material_.bytes() +
           overlap_ratio_.bytes() + position_at_build_.bytes() + pair_history_.bytes() +
           wall_history_.bytes() + scratch_bytes() + cells_.memory_bytes() +
           neighbors_.memory_bytes() + meshes_.memory_bytes();
  }

  std::string backend_name() const override { return Space::name; }

 private:
  std::size_t size() const { return id_.size(); }

  /// Uploads the particle arrays and sizes the per-particle work arrays; wall histories zero,
  /// torques zero (a law without spin never writes them).
  void upload_particles(const ParticleStore& p) {
    position_radius_.upload(p.position_radius);
    velocity_inv_mass_.upload(p.velocity_inv_mass);
    angular_velocity_.upload(p.angular_velocity);
    id_.upload(p.id);
    material_.upload(p.material);
    const std::size_t n = p.size();
    force_.resize(n);
    torque_.resize(n);
    overlap_ratio_.resize(n);
    parallel_for(Space{}, n, Fill<Vec3>{torque_.data(), Vec3{}});
    if constexpr (kHistoryWidth > 0) {
      wall_history_.resize(n * wall_count());
      parallel_for(Space{}, wall_history_.size(), Fill<State>{wall_history_.data(), State{}});
    }
  }

  /// The neighbour list of a restored state, built at the saved positions of the last build
  /// (position_at_build_): binning them reproduces the saved cell order, so the permutation is
  /// the identity for a state saved by this engine; it is applied anyway, to the forces too,
  /// so any order stays consistent.
  void build_list_at_saved_positions(DeviceArray<Vec3, Space>& force,
                                     DeviceArray<Vec3, Space>& torque) {
    const std::size_t n = size();
    previous_index_.resize(n);
    cells_.bin(position_at_build_.data(), n, setup_.box, setup_.skin);
    reorder(cells_.order(), n);
    permute_array(cells_.order(), n, position_at_build_);
    permute_array(cells_.order(), n, force);
    permute_array(cells_.order(), n, torque);
    neighbors_.build(cells_, position_at_build_.data(), n, setup_.box, setup_.skin);
    meshes_.rebuild(position_at_build_.data(), n, largest_radius(), setup_.skin,
                    previous_index_.data(), false);
    if constexpr (kHistoryWidth > 0) pair_history_.resize(neighbors_.pairs_kept());
    zero_history();
    has_list_ = true;
  }

  /// Σ over particles of column `column` of a per-(particle, column) load array.
  Vec3 column_sum(const DeviceArray<Vec3, Space>& load, std::uint32_t columns,
                  std::uint32_t column) const {
    Vec3 sum;
    for (int k = 0; k < 3; ++k)
      axis(sum, k) =
          reduce_sum(Space{}, size(), LoadComponent{load.data(), columns, column, k});
    return sum;
  }

  Real largest_radius() const {
    return reduce_max(Space{}, size(), Real(0), Radius{position_radius_.data()});
  }

  void zero_history() {
    parallel_for(Space{}, pair_history_.size(), Fill<State>{pair_history_.data(), State{}});
    parallel_for(Space{}, wall_history_.size(), Fill<State>{wall_history_.data(), State{}});
  }

  /// Host copy of a history array as kHistoryWidth values per contact.
  std::vector<Real> flat_values(const DeviceArray<State, Space>& states) const {
    std::vector<State> host;
    states.download(host);
    std::vector<Real> values;
    values.reserve(host.size() * kHistoryWidth);
    for (const State& s : host) values.insert(values.end(), s.value, s.value + kHistoryWidth);
    return values;
  }

  static void upload_states(const std::vector<Real>& values, DeviceArray<State, Space>& states) {
    std::vector<State> host(values.size() / kHistoryWidth);
    for (std::size_t k = 0; k < host.size(); ++k)
      for (std::uint32_t v = 0; v < kHistoryWidth; ++v)
        host[k].value[v] = values[k * kHistoryWidth + v];
    states.upload(host);
  }

  /// Host copies of the ids and the neighbour list, for contact-history conversions.
  ContactSlots contact_slots() const {
    ContactSlots slots;
    id_.download(slots.id);
    slots.offsets = download_raw(neighbors_.offsets(), has_list_ ? size() + 1 : 0);
    slots.neighbors = download_raw(neighbors_.neighbors(), has_list_ ? neighbors_.pairs_kept() : 0);
    if (slots.offsets.empty()) slots.offsets.assign(size() + 1, 0);
    slots.wall_count = wall_count();
    return slots;
  }

  /// Host copy of n values at `data` in Space memory.
  template <class T>
  static std::vector<T> download_raw(const T* data, std::size_t n) {
    DeviceArray<T, Space> copy(n);
    parallel_for(Space{}, n, CopyArray<T>{data, copy.data()});
    std::vector<T> host;
    copy.download(host);
    return host;
  }

  /// The particle arrays the law reads; spins only when it needs them.
  ParticleView particle_view() const {
    return ParticleView{position_radius_.data(), velocity_inv_mass_.data(),
                        Law::needs_spin ? angular_velocity_.data() : nullptr, material_.data()};
  }

  ContactScene<Law> contact_scene() const {
    return ContactScene<Law>{neighbors_.offsets(), neighbors_.neighbors(), pair_params_.data(),
                             setup_.material_count, walls_.data(),         wall_count(),
                             setup_.box,            pair_history_.data(),  wall_history_.data(),
                             meshes_.view(),        meshes_.history()};
  }

  void kick(Real h) {
    parallel_for(Space{}, size(),
                 Kick<Law::needs_spin>{velocity_inv_mass_.data(), angular_velocity_.data(),
                                       force_.data(), torque_.data(), position_radius_.data(), h});
  }

  std::uint32_t wall_count() const { return static_cast<std::uint32_t>(setup_.walls.size()); }

  void compute_forces() {
    parallel_for(Space{}, size(),
                 ComputeForces<Law>{particle_view(),
                                    contact_scene(),
                                    setup_.gravity,
                                    setup_.dt,
                                    {pair_history_.data(), wall_history_.data(), meshes_.history()},
                                    force_.data(),
                                    torque_.data(),
                                    overlap_ratio_.data()});
  }

  /// The lists stay valid while no particle and no mesh vertex moved more than skin/2.
  bool needs_rebuild() const {
    const Real moved2 =
        reduce_max(Space{}, size(), Real(0),
                   DisplacementSquared{position_radius_.data(), position_at_build_.data()});
    const Real half_skin = Real(0.5) * setup_.skin;
    return moved2 > half_skin * half_skin || meshes_.moved_beyond(half_skin);
  }

  /// Wraps periodic images, removes particles that left the box, sorts by cell, rebuilds the
  /// neighbour list and carries the contact history over to it.
  void rebuild() {
    parallel_for(Space{}, size(), WrapPositions{position_radius_.data(), setup_.box});
    std::swap(neighbors_, previous_neighbors_);
    previous_id_.resize(size());
    parallel_for(Space{}, size(), CopyArray<ParticleId>{id_.data(), previous_id_.data()});
    previous_index_.resize(size());
    parallel_for(Space{}, size(), Iota{previous_index_.data()});
    remove_leavers();
    const std::size_t n = size();
    cells_.bin(position_radius_.data(), n, setup_.box, setup_.skin);
    reorder(cells_.order(), n);
    neighbors_.build(cells_, position_radius_.data(), n, setup_.box, setup_.skin);
    meshes_.rebuild(position_radius_.data(), n, largest_radius(), setup_.skin,
                    previous_index_.data(), has_list_);
    remap_pair_history();
    position_at_build_.resize(n);
    parallel_for(Space{}, n, CopyArray<Real4>{position_radius_.data(), position_at_build_.data()});
    ++rebuilds_;
  }

  void remap_pair_history() {
    if constexpr (kHistoryWidth > 0) {
      DeviceArray<State, Space> fresh(neighbors_.pairs_kept());
      if (has_list_) {
        parallel_for(Space{}, size(),
                     RemapPairHistory<State>{neighbors_.offsets(), neighbors_.neighbors(),
                                             id_.data(), previous_index_.data(),
                                             previous_neighbors_.offsets(),
                                             previous_neighbors_.neighbors(), previous_id_.data(),
                                             pair_history_.data(), fresh.data()});
      } else {
        parallel_for(Space{}, fresh.size(), Fill<State>{fresh.data(), State{}});
      }
      pair_history_.swap(fresh);
    }
    has_list_ = true;
  }

  void remove_leavers() {
    const std::size_t n = size();
    const auto leavers = static_cast<std::size_t>(
        std::llround(reduce_sum(Space{}, n, IsLeaver{position_radius_.data(), setup_.box})));
    if (leavers == 0) return;
    sort_key_.resize(n);
    sort_index_.resize(n);
    parallel_for(
        Space{}, n,
        LeaverKey{position_radius_.data(), setup_.box, sort_key_.data(), sort_index_.data()});
    sort_by_key(Space{}, sort_key_.data(), sort_index_.data(), n);
    reorder(sort_index_.data(), n);
    resize(n - leavers);
    removed_ += leavers;
  }

  /// Applies the permutation `order` (slot k takes particle order[k]) to every per-particle
  /// array whose value must survive a rebuild (forces are recomputed right after).
  void reorder(const std::uint32_t* order, std::size_t n) {
    permute_array(order, n, position_radius_);
    permute_array(order, n, velocity_inv_mass_);
    permute_array(order, n, angular_velocity_);
    permute_array(order, n, id_);
    permute_array(order, n, material_);
    permute_array(order, n, previous_index_);
    if constexpr (kHistoryWidth > 0) {
      DeviceArray<State, Space> rows(n * wall_count());
      parallel_for(Space{}, n,
                   GatherRows<State>{order, wall_history_.data(), rows.data(), wall_count()});
      wall_history_.swap(rows);
    }
  }

  template <class T>
  void permute_array(const std::uint32_t* order, std::size_t n, DeviceArray<T, Space>& a) {
    DeviceArray<T, Space> out(n);
    permute(Space{}, order, a.data(), out.data(), n);
    a.swap(out);
  }

  void resize(std::size_t n) {
    position_radius_.resize(n);
    velocity_inv_mass_.resize(n);
    angular_velocity_.resize(n);
    id_.resize(n);
    material_.resize(n);
    force_.resize(n);
    torque_.resize(n);
    overlap_ratio_.resize(n);
    previous_index_.resize(n);
    if constexpr (kHistoryWidth > 0) wall_history_.resize(n * wall_count());
  }

  std::size_t scratch_bytes() const {
    return sort_key_.bytes() + sort_index_.bytes() + previous_index_.bytes() +
           previous_id_.bytes() + previous_neighbors_.memory_bytes();
  }

  EngineSetup setup_;
  DeviceArray<ContactPairParams, Space> pair_params_;
  DeviceArray<PlaneWall, Space> walls_;
  DeviceArray<Real4, Space> position_radius_;
  DeviceArray<Real4, Space> velocity_inv_mass_;
  DeviceArray<Vec3, Space> angular_velocity_;
  DeviceArray<Vec3, Space> force_;
  DeviceArray<Vec3, Space> torque_;
  DeviceArray<ParticleId, Space> id_;
  DeviceArray<MaterialId, Space> material_;
  DeviceArray<Real, Space> overlap_ratio_;
  DeviceArray<Real4, Space> position_at_build_;
  DeviceArray<std::uint64_t, Space> sort_key_;
  DeviceArray<std::uint32_t, Space> sort_index_;
  DeviceArray<State, Space> pair_history_;  ///< per neighbour-list entry (empty: no history)
  DeviceArray<State, Space> wall_history_;  ///< per (particle, wall) (empty: no history)
  DeviceArray<std::uint32_t, Space> previous_index_;  ///< index before this rebuild's reorders
  DeviceArray<ParticleId, Space> previous_id_;
  CellList<Space> cells_;
  NeighborList<Space> neighbors_;
  NeighborList<Space> previous_neighbors_;
  MeshWalls<Space, Law> meshes_;
  std::uint64_t steps_ = 0;  ///< the run's step count (the meshes' clock)
  bool has_list_ = false;
  std::uint64_t removed_ = 0;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace gpudem
