#pragma once
/// The step engine for one execution space and one contact law (DESIGN §4): this rank's owned
/// particles followed by ghost copies of other ranks' particles, stepped with the rank's
/// DomainLink (one rank when the setup names none). The same code is instantiated for HostSpace and
/// CudaSpace and for every valid law (EngineFactory.hpp). Include the backend's ParallelFor header
/// first.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/Stopwatch.hpp"
#include "kernels/ArrayKernels.hpp"
#include "kernels/CellList.hpp"
#include "kernels/ContactForces.hpp"
#include "kernels/DeviceArray.hpp"
#include "kernels/Diagnostics.hpp"
#include "kernels/DomainLink.hpp"
#include "kernels/GhostExchange.hpp"
#include "kernels/HistoryCarryOver.hpp"
#include "kernels/HostCopies.hpp"
#include "kernels/Integrators.hpp"
#include "kernels/LaunchTuning.hpp"
#include "kernels/MeshWalls.hpp"
#include "kernels/NeighborList.hpp"
#include "kernels/ParticleMigration.hpp"
#include "kernels/ParticleStaging.hpp"
#include "kernels/ParticleStateKernels.hpp"
#include "kernels/Permute.hpp"
#include "kernels/RankCells.hpp"
#include "kernels/ShareRouting.hpp"
#include "kernels/StepEngine.hpp"

namespace gpudem {

/// The engine of one backend (Space) and contact law, with the particle state (positions,
/// velocities, spins) held in scalar P: Real in the double and mixed policies, float in the
/// float policy, converted to Real wherever it is read and rounded to P where it is written.
template <class Space, class Law, class P = Real>
class StepEngineImpl final : public StepEngine {
  using State = typename Law::State;
  using ForceVec = Vec3T<typename Law::Scalar>;  ///< forces and torques, in the law's scalar
  using State4 = Vec4T<P>;                       ///< position and radius, velocity and 1/m
  using StateVec = Vec3T<P>;                     ///< angular velocity
  static constexpr std::uint32_t kHistoryWidth = Law::history_size;

 public:
  explicit StepEngineImpl(const EngineSetup& setup)
      : setup_(setup),
        one_rank_(setup.box),
        domain_(setup.domain ? *setup.domain : one_rank_),
        meshes_(setup.meshes, setup.box),
        steps_(setup.start_step) {
    pair_params_.upload(converted(setup.pair_params, params_cast<typename Law::Scalar>));
    walls_.upload(setup.walls);
    if (!meshes_.empty()) meshes_.set_time(steps_ * setup.dt);
  }

  void set_particles(const ParticleStore& share) override {
    upload_particles(share);  // the first rebuild migrates each particle to its owner
    count_particles(share.id);
    has_list_ = false;
    rebuild();
    compute_forces();
  }

  void restore_particles(const ParticleStore& share, const std::vector<Real4>& list_positions,
                         std::uint64_t removed, std::uint64_t list_build_step) override {
    if (list_positions.size() != share.size() || share.force.size() != share.size() ||
        share.torque.size() != share.size())
      throw std::invalid_argument("restore_particles: arrays differ in length");
    count_particles(share.id);
    list_build_step_ = list_build_step;
    if (domain_.ranks() == 1) {
      restore_owned(share, list_positions);
    } else {
      const RoutedParticles mine = route_to_owners(share, list_positions, domain_);
      restore_owned(mine.particles, mine.list_position_radius);
    }
    removed_ = removed;
  }

  void get_particles(ParticleStore& p) const override { read_owned_particles(owned_arrays(), p); }

  void get_contact_history(ContactHistory& history) const override {
    HistoryValues values;
    values.pair = flat_values<kHistoryWidth>(pair_history_);
    values.wall = flat_values<kHistoryWidth>(wall_history_);
    values.mesh = flat_values<kHistoryWidth>(meshes_.entry_history());
    history = collect_history(contact_slots(), kHistoryWidth, values);
  }

  void set_contact_history(ContactHistory share) override {
    const HistoryValues values = scatter_share(std::move(share), contact_slots());
    if constexpr (kHistoryWidth > 0) {
      pair_history_.upload(states_of<kHistoryWidth, State>(values.pair));
      wall_history_.upload(states_of<kHistoryWidth, State>(values.wall));
      if (!meshes_.empty()) meshes_.set_history(states_of<kHistoryWidth, State>(values.mesh));
    }
  }

  void get_list_positions(std::vector<Real4>& position_radius) const override {
    position_radius = download_in_real(position_at_build_);
  }
  std::uint64_t list_build_step() const override { return list_build_step_; }

  std::size_t particle_count() const override { return global_count_; }
  std::size_t owned_count() const override { return owned_; }

  void get_list_lengths(std::vector<std::uint32_t>& lengths) const override {
    const std::vector<std::uint32_t> offsets =
        download_values<Space>(neighbors_.offsets(), has_list_ ? owned_ + 1 : 0);
    lengths.assign(owned_, 0);
    for (std::size_t i = 0; i + 1 < offsets.size(); ++i) lengths[i] = offsets[i + 1] - offsets[i];
  }

  StagedParticles& stage_particles() override {
    staging_.stage(owned_arrays());
    staging_.expected_tally = {global_count_, expected_id_sum_};
    return staging_;
  }

  void step() override {
    Stopwatch watch;
    const Real dt = setup_.dt;
    const bool verlet = setup_.integrator == IntegratorKind::VelocityVerlet;
    kick(verlet ? Real(0.5) * dt : dt);
    drift(dt);
    ++steps_;
    if (!meshes_.empty()) meshes_.set_time(steps_ * dt);
    times_.integrate += lap(watch);
    const bool rebuild_now = needs_rebuild();
    times_.neighbors += lap(watch);
    if (rebuild_now) {
      rebuild();  // charges its own parts
      lap(watch);
      compute_forces();
    } else if (domain_.ranks() > 1) {
      refresh_ghosts_computing_interior(watch);
    } else {
      compute_forces();
    }
    times_.forces += lap(watch);
    if (verlet) kick(Real(0.5) * dt);
    times_.integrate += lap(watch);
  }

  void rebuild_neighbors() override {
    rebuild();
    compute_forces();
  }

  bool find_unhealthy(double limit, HealthFailure& failure) const override {
    const bool here = find_unhealthy_here(limit, failure);
    if (domain_.ranks() == 1) return here;
    const int first = domain_.first_rank_with(here);
    if (first == domain_.ranks()) return false;
    std::vector<char> bytes(sizeof(HealthFailure));
    std::memcpy(bytes.data(), &failure, sizeof(HealthFailure));
    domain_.broadcast(bytes, first);
    std::memcpy(&failure, bytes.data(), sizeof(HealthFailure));
    return true;
  }

  Diagnostics diagnostics() const override {
    double contact_share = 0;
    Diagnostics d = local_diagnostics(contact_share);
    if (domain_.ranks() > 1) sum_over_ranks(d, contact_share);
    d.particle_count = global_count_;
    return d;
  }

  std::vector<MeshSurface> mesh_surfaces() const override {
    if (meshes_.empty()) return {};
    std::vector<MeshSurface> surfaces(meshes_.count());
    for (std::uint32_t m = 0; m < meshes_.count(); ++m) {
      surfaces[m].vertices = meshes_.current_vertices(m);
      surfaces[m].triangles = meshes_.setup_triangles(m);
    }
    const std::vector<double> load = triangle_loads();
    std::size_t t = 0;
    for (MeshSurface& surface : surfaces)
      for (std::size_t k = 0; k < surface.triangles.size(); ++k, ++t)
        surface.triangle_force.push_back(Vec3{load[3 * t], load[3 * t + 1], load[3 * t + 2]});
    return surfaces;
  }

  /// Times the force, neighbour-list and integration launches at each candidate block size and
  /// keeps, for each, the one the slowest rank runs fastest (LaunchTuning.hpp); leaves the state
  /// as it was: the forces are timed on scratch outputs and history, the list is built into a
  /// scratch list, the kick and drift run with a zero step. Collective; nothing to tune on the
  /// host.
  std::string tune_launches() override {
    if constexpr (has_block_sizes(Space{})) {
      const MaxOverRanks max_all = max_over_ranks(domain_);
      std::vector<double> shortfall{tuning_memory_shortfall()};
      max_all(shortfall);
      if (shortfall[0] > 0)
        return launch_tuning_report(launch_tuning(), true) +
               " (defaults, not timed: the timing scratch needs " +
               std::to_string(static_cast<long long>(shortfall[0] / (1 << 20)) + 1) +
               " MiB more device memory than a rank has free)";
      const auto timed = [](auto&& work) {
        return [&work](unsigned) { return seconds_to_run(Space{}, work); };
      };
      ForceScratch scratch(owned_, pair_history_.size(), wall_history_.size(),
                           meshes_.entry_count());
      tune_block_size(launch_tuning(), LaunchSlot::forces,
                      timed([&] { compute_forces_into(scratch); }), max_all);
      NeighborList<Space> list;
      tune_block_size(launch_tuning(), LaunchSlot::neighbor_list,
                      timed([&] { build_list_into(list, ghosts_.ghosts()); }), max_all);
      tune_block_size(launch_tuning(), LaunchSlot::integrate, timed([&] {
                        kick(0);
                        drift(0);
                      }),
                      max_all);
    }
    return launch_tuning_report(launch_tuning(), has_block_sizes(Space{}));
  }

  std::uint64_t removed_count() const override { return removed_; }
  std::uint64_t rebuild_count() const override { return rebuilds_; }
  StepTimes step_times() const override { return times_; }

  std::vector<MemoryUse> memory_use() const override {
    return {{"position, radius", position_radius_.bytes()},
            {"velocity, inverse mass", velocity_inv_mass_.bytes()},
            {"angular velocity", angular_velocity_.bytes()},
            {"id, material", id_.bytes() + material_.bytes()},
            {"force, torque", force_.bytes() + torque_.bytes()},
            {"overlap ratio", overlap_ratio_.bytes()},
            {"position at list build", position_at_build_.bytes()},
            {"neighbour list", neighbors_.memory_bytes()},
            {"pair history", pair_history_.bytes()},
            {"wall history", wall_history_.bytes()},
            {"cell list", cells_.memory_bytes()},
            {"history carry-over", carry_over_bytes()},
            {"rebuild scratch", scratch_bytes()},
            {"ghost buffers",
             ghosts_.memory_bytes() + ghost_rows_.memory_bytes() + rank_cells_.memory_bytes()},
            {"meshes", meshes_.memory_bytes()}};
  }

  std::string backend_name() const override { return Space::name; }

 private:
  /// The arrays a snapshot or get_particles reads; the owned particles are their first rows.
  OwnedParticleArrays<Space, P, typename Law::Scalar> owned_arrays() const {
    return {position_radius_,  velocity_inv_mass_,
            angular_velocity_, force_,
            torque_,           id_,
            material_,         owned_};
  }

  ParticleArrays<P> arrays() {
    return ParticleArrays<P>{position_radius_.data(), velocity_inv_mass_.data(),
                             angular_velocity_.data(), id_.data(), material_.data()};
  }

  /// scatter_history for this rank's `share` of the records (freed on return): on several
  /// ranks each record is sent to the rank that owns its owner particle first, and a problem on
  /// any rank (another width, arrays of different lengths, an unknown particle, a pair not in
  /// the list) is thrown on every rank.
  HistoryValues scatter_share(ContactHistory share, const ContactSlots& slots) const {
    if (domain_.ranks() == 1) return scatter_history(slots, kHistoryWidth, share);
    std::string problem;
    if (!share.empty() && share.width != kHistoryWidth)
      problem = "contact history: it holds " + std::to_string(share.width) +
                " values per contact but this contact law keeps " + std::to_string(kHistoryWidth);
    else if (!share.lengths_agree())
      problem = "contact history: the arrays of one kind of contact differ in length";
    throw_first_problem(problem, domain_);
    const std::vector<ParticleId> owned(slots.id.begin(), slots.id.begin() + slots.rows);
    HistoryValues values;
    try {
      values = scatter_history(slots, kHistoryWidth,
                               route_history(std::move(share), kHistoryWidth, owned, domain_));
    } catch (const std::invalid_argument& e) {
      problem = e.what();
    }
    throw_first_problem(problem, domain_);
    return values;
  }

  /// The particle count over all ranks and the checksum of their ids, from this rank's share
  /// of the ids. Collective.
  void count_particles(const std::vector<ParticleId>& share_ids) {
    global_count_ = domain_.wrapping_sum(share_ids.size());
    expected_id_sum_ = domain_.wrapping_sum(tally_of(share_ids).id_sum);
  }

  /// Checks that no particle was lost or duplicated between ranks against the expected tally;
  /// throws std::runtime_error saying what differs. Collective.
  void check_particles_conserved() const {
    std::vector<ParticleId> ids;
    id_.download(ids);
    ids.resize(owned_);
    const ParticleTally found{domain_.wrapping_sum(owned_),
                              domain_.wrapping_sum(tally_of(ids).id_sum)};
    const std::string problem =
        conservation_problem(found, {global_count_, expected_id_sum_}, domain_.ranks());
    if (!problem.empty()) throw std::runtime_error(problem);
  }

  /// restore_particles for this rank's particles `p` and their list positions.
  void restore_owned(const ParticleStore& p, const std::vector<Real4>& list_positions) {
    upload_particles(p);
    upload_rounded(list_positions, position_at_build_);
    DeviceArray<ForceVec, Space> saved_force, saved_torque;
    upload_rounded(p.force, saved_force);
    upload_rounded(p.torque, saved_torque);
    build_list_at_saved_positions(saved_force, saved_torque);
    compute_forces();  // for the overlap ratios; the forces and history it leaves are replaced
    force_.swap(saved_force);
    torque_.swap(saved_torque);
    zero_history();
  }

  /// Uploads the particle arrays of `p` as the owned particles and sizes the owned particles'
  /// work arrays; torques zero (a law without spin never writes them, and a grown device
  /// array's new rows hold whatever its memory held), wall histories zero.
  void upload_particles(const ParticleStore& p) {
    upload_rounded(p.position_radius, position_radius_);
    upload_rounded(p.velocity_inv_mass, velocity_inv_mass_);
    upload_rounded(p.angular_velocity, angular_velocity_);
    id_.upload(p.id);
    material_.upload(p.material);
    owned_ = p.size();
    force_.resize(owned_);
    torque_.resize(owned_);
    parallel_for(Space{}, owned_, Fill<ForceVec>{torque_.data(), ForceVec{}});
    overlap_ratio_.resize(owned_);
    if constexpr (kHistoryWidth > 0) {
      wall_history_.resize(owned_ * wall_count());
      parallel_for(Space{}, wall_history_.size(), Fill<State>{wall_history_.data(), State{}});
    }
  }

  /// The neighbour list of a restored state, built at the saved positions of the last build
  /// (position_at_build_) as the saved engine built it, with ghosts at their saved positions
  /// too; the particles then take their saved current state again, ghosts included.
  void build_list_at_saved_positions(DeviceArray<ForceVec, Space>& force,
                                     DeviceArray<ForceVec, Space>& torque) {
    position_radius_.swap(position_at_build_);
    iota(previous_index_, owned_);
    sort_owned_by_cell();
    permute_array(cells_.order(), owned_, position_at_build_);
    permute_array(cells_.order(), owned_, force);
    permute_array(cells_.order(), owned_, torque);
    build_list(receive_ghosts());
    split_ghost_rows();
    if (!meshes_.empty()) meshes_.set_time(list_build_step_ * setup_.dt);
    rebuild_mesh_candidates(false);
    if (!meshes_.empty()) meshes_.set_time(steps_ * setup_.dt);
    parallel_for(Space{}, owned_,
                 SwapValues<State4>{position_radius_.data(), position_at_build_.data()});
    if (domain_.ranks() > 1) ghosts_.update(domain_, arrays(), owned_);
    if constexpr (kHistoryWidth > 0) pair_history_.resize(neighbors_.pairs_kept());
    zero_history();
    has_list_ = true;
  }

  /// Σ over owned particles of column `column` of a per-(particle, column) load array.
  Vec3 column_sum(const DeviceArray<Vec3, Space>& load, std::uint32_t columns,
                  std::uint32_t column) const {
    Vec3 sum;
    for (int k = 0; k < 3; ++k)
      axis(sum, k) = reduce_sum(Space{}, owned_, LoadComponent{load.data(), columns, column, k});
    return sum;
  }

  Real largest_radius() const {
    return reduce_max(Space{}, owned_, Real(0), Radius<P>{position_radius_.data()});
  }

  void zero_history() {
    parallel_for(Space{}, pair_history_.size(), Fill<State>{pair_history_.data(), State{}});
    parallel_for(Space{}, wall_history_.size(), Fill<State>{wall_history_.data(), State{}});
  }

  /// Host copies of the ids (owned, then ghosts) and the owned particles' neighbour list,
  /// for contact-history conversions.
  ContactSlots contact_slots() const {
    ContactSlots slots;
    id_.download(slots.id);
    slots.rows = owned_;
    slots.offsets = download_values<Space>(neighbors_.offsets(), has_list_ ? owned_ + 1 : 0);
    slots.neighbors =
        download_values<Space>(neighbors_.neighbors(), has_list_ ? neighbors_.pairs_kept() : 0);
    if (slots.offsets.empty()) slots.offsets.assign(owned_ + 1, 0);
    slots.wall_count = wall_count();
    if (meshes_.empty()) return slots;
    slots.mesh_offsets = meshes_.entry_offsets();
    slots.mesh_triangles = meshes_.entry_triangles();
    if (slots.mesh_offsets.empty()) slots.mesh_offsets.assign(owned_ + 1, 0);
    slots.triangle_count = meshes_.triangle_count();
    return slots;
  }

  /// The particle arrays the law reads; spins only when it needs them.
  ParticleView<P> particle_view() const {
    return ParticleView<P>{position_radius_.data(), velocity_inv_mass_.data(),
                           Law::needs_spin ? angular_velocity_.data() : nullptr, material_.data()};
  }

  /// Every particle array, spins included (diagnostics).
  ParticleView<P> state_view() const {
    return ParticleView<P>{position_radius_.data(), velocity_inv_mass_.data(),
                           angular_velocity_.data(), material_.data()};
  }

  ContactScene<Law> contact_scene() const {
    return ContactScene<Law>{
        neighbors_.offsets(), neighbors_.neighbors(), pair_params_.data(), setup_.material_count,
        walls_.data(),        wall_count(),           setup_.box,          pair_history_.data(),
        wall_history_.data(), meshes_.view(),         meshes_.history()};
  }

  void kick(Real h) {
    parallel_for(Space{}, owned_,
                 Kick<Law::needs_spin, typename Law::Scalar, P>{
                     velocity_inv_mass_.data(), angular_velocity_.data(), force_.data(),
                     torque_.data(), position_radius_.data(), h},
                 LaunchSlot::integrate);
  }

  void drift(Real dt) {
    parallel_for(Space{}, owned_, Drift<P>{position_radius_.data(), velocity_inv_mass_.data(), dt},
                 LaunchSlot::integrate);
  }

  /// Outputs and history of a force evaluation whose results are thrown away (launch tuning).
  struct ForceScratch {
    ForceScratch(std::size_t owned, std::size_t pairs, std::size_t wall_slots, std::size_t mesh)
        : force(owned),
          torque(owned),
          overlap_ratio(owned),
          pair(pairs),
          wall(wall_slots),
          mesh(mesh) {}
    /// The bytes the constructor allocates.
    static std::size_t bytes(std::size_t owned, std::size_t pairs, std::size_t wall_slots,
                             std::size_t mesh) {
      return owned * (2 * sizeof(ForceVec) + sizeof(Real)) +
             (pairs + wall_slots + mesh) * sizeof(State);
    }
    DeviceArray<ForceVec, Space> force, torque;
    DeviceArray<Real, Space> overlap_ratio;
    DeviceArray<State, Space> pair, wall, mesh;
  };

  /// Bytes by which the device memory that launch tuning allocates (a ForceScratch and a second
  /// neighbour list, with an eighth more for the list's sort scratch and growth) exceeds the
  /// free device memory; 0 when it fits.
  double tuning_memory_shortfall() const {
    const double needed = double(ForceScratch::bytes(owned_, pair_history_.size(),
                                                     wall_history_.size(), meshes_.entry_count())) +
                          1.125 * double(neighbors_.memory_bytes());
    return std::max(0.0, needed - double(cuda::free_device_memory()));
  }

  std::uint32_t wall_count() const { return static_cast<std::uint32_t>(setup_.walls.size()); }

  /// The forces of every owned particle.
  void compute_forces() { parallel_for(Space{}, owned_, force_kernel(), LaunchSlot::forces); }

  /// The forces of the owned particles list[0, count).
  void compute_forces(const std::uint32_t* list, std::size_t count) {
    parallel_for(Space{}, count, AtIndices<ComputeForces<Law, P>>{list, force_kernel()},
                 LaunchSlot::forces);
  }

  /// The forces of the current state written to `scratch`, the engine's state untouched.
  void compute_forces_into(ForceScratch& scratch) {
    parallel_for(
        Space{}, owned_,
        force_kernel({scratch.pair.data(), scratch.wall.data(), scratch.mesh.data()},
                     scratch.force.data(), scratch.torque.data(), scratch.overlap_ratio.data()),
        LaunchSlot::forces);
  }

  /// The per-particle force functor over this engine's arrays.
  ComputeForces<Law, P> force_kernel() {
    return force_kernel({pair_history_.data(), wall_history_.data(), meshes_.history()},
                        force_.data(), torque_.data(), overlap_ratio_.data());
  }

  /// The per-particle force functor reading this engine's state, advancing the contact history
  /// into `history` and writing its results to the given arrays.
  ComputeForces<Law, P> force_kernel(const HistoryArrays<Law>& history, ForceVec* force,
                                     ForceVec* torque, Real* overlap_ratio) {
    return ComputeForces<Law, P>{particle_view(), contact_scene(), setup_.gravity, setup_.dt,
                                 history,         force,           torque,         overlap_ratio};
  }

  /// Refreshes the ghosts' per-step fields while the forces of the owned particles whose rows
  /// read no ghost are computed, then computes the others' forces. Each particle's force is
  /// the same sum as in compute_forces(); only the particles' order differs.
  void refresh_ghosts_computing_interior(Stopwatch& watch) {
    ghosts_.begin_update(domain_, arrays());
    times_.ghosts += lap(watch);
    compute_forces(ghost_rows_.interior(), ghost_rows_.interior_count());
    times_.forces += lap(watch);
    ghosts_.finish_update(domain_, arrays(), owned_);
    times_.ghosts += lap(watch);
    times_.halo_bytes += ghosts_.refresh_bytes();
    ++times_.refreshes;
    compute_forces(ghost_rows_.boundary(), ghost_rows_.boundary_count());
  }

  bool find_unhealthy_here(double limit, HealthFailure& failure) const {
    const HealthScore<P> score{state_view(), overlap_ratio_.data()};
    if (reduce_max(Space{}, owned_, Real(0), score) <= limit) return false;
    ParticleStore host;
    get_particles(host);
    std::vector<Real> ratio;
    overlap_ratio_.download(ratio);
    const HealthScore<Real> host_score{
        {host.position_radius.data(), host.velocity_inv_mass.data(), nullptr, nullptr},
        ratio.data()};
    for (std::size_t i = 0; i < host.size(); ++i) {
      const Real s = host_score(i);
      if (s <= limit) continue;
      failure = HealthFailure{host.id[i], xyz(host.position_radius[i]), ratio[i],
                              s == kNonFiniteScore, ratio[i] == kMeshOverflowScore};
      return true;
    }
    return false;
  }

  /// The diagnostics of this rank's particles; `contact_share` is its (fractional) share of
  /// the contact count, a pair counting half on each side.
  Diagnostics local_diagnostics(double& contact_share) const {
    Diagnostics d;
    const std::size_t n = owned_;
    const ParticleView<P> view = particle_view();
    d.kinetic_translational = reduce_sum(Space{}, n, TranslationalEnergy<P>{state_view()});
    d.kinetic_rotational = reduce_sum(Space{}, n, RotationalEnergy<P>{state_view()});
    d.potential_gravity = reduce_sum(Space{}, n, GravityEnergy<P>{state_view(), setup_.gravity});
    DeviceArray<Real, Space> contacts(n), energy(n);
    const std::uint32_t bodies = wall_count() + meshes_.count();
    DeviceArray<Vec3, Space> body_force(n * bodies), mesh_torque(n * meshes_.count());
    parallel_for(Space{}, n,
                 ContactTerms<Law, P>{view, contact_scene(), contacts.data(), energy.data(),
                                      body_force.data(), mesh_torque.data()});
    d.potential_elastic = reduce_sum(Space{}, n, ReadValue{energy.data()});
    contact_share = reduce_sum(Space{}, n, ReadValue{contacts.data()});
    d.contact_count = static_cast<std::uint64_t>(std::llround(contact_share));
    d.max_overlap_ratio = reduce_max(Space{}, n, Real(0), ReadValue{overlap_ratio_.data()});
    for (std::uint32_t w = 0; w < wall_count(); ++w)
      d.wall_force.push_back(column_sum(body_force, bodies, w));
    for (std::uint32_t m = 0; m < meshes_.count(); ++m) {
      d.mesh_force.push_back(column_sum(body_force, bodies, wall_count() + m));
      d.mesh_torque.push_back(column_sum(mesh_torque, meshes_.count(), m));
    }
    return d;
  }

  /// The force the particles of all ranks exert on each triangle of all meshes, as x, y, z
  /// per global triangle index [N]: the loads of this rank's mesh contacts (MeshEntryLoads)
  /// added up per triangle on the host, then summed over the ranks. Collective.
  std::vector<double> triangle_loads() const {
    std::size_t triangles = 0;
    for (std::uint32_t m = 0; m < meshes_.count(); ++m)
      triangles += meshes_.setup_triangles(m).size();
    const std::vector<std::uint32_t> triangle_of_entry = meshes_.entry_triangles();
    DeviceArray<Vec3, Space> entry_load(triangle_of_entry.size());
    parallel_for(Space{}, owned_,
                 MeshEntryLoads<Law, P>{particle_view(), contact_scene(), entry_load.data()});
    std::vector<Vec3> entry_host;
    entry_load.download(entry_host);
    std::vector<double> load(3 * triangles, 0.0);
    for (std::size_t e = 0; e < entry_host.size(); ++e)
      for (int k = 0; k < 3; ++k) load[3 * triangle_of_entry[e] + k] += axis(entry_host[e], k);
    domain_.sum(load);
    return load;
  }

  /// Sums (and for the overlap, maximises) a rank's diagnostics over all ranks.
  void sum_over_ranks(Diagnostics& d, double contact_share) const {
    std::vector<double> v = {contact_share, d.kinetic_translational, d.kinetic_rotational,
                             d.potential_gravity, d.potential_elastic};
    const auto append = [&v](const std::vector<Vec3>& loads) {
      for (const Vec3& f : loads) v.insert(v.end(), {f.x, f.y, f.z});
    };
    append(d.wall_force);
    append(d.mesh_force);
    append(d.mesh_torque);
    domain_.sum(v);
    d.contact_count = static_cast<std::uint64_t>(std::llround(v[0]));
    d.kinetic_translational = v[1];
    d.kinetic_rotational = v[2];
    d.potential_gravity = v[3];
    d.potential_elastic = v[4];
    std::size_t k = 5;
    for (std::vector<Vec3>* loads : {&d.wall_force, &d.mesh_force, &d.mesh_torque})
      for (Vec3& f : *loads) {
        f = Vec3{v[k], v[k + 1], v[k + 2]};
        k += 3;
      }
    d.max_overlap_ratio = domain_.max(d.max_overlap_ratio);
  }

  /// Seconds since the watch's last lap. With EngineSetup::exact_phase_times it first waits
  /// for the device, so that a part's time holds its own kernels and not only their launches.
  double lap(Stopwatch& watch) const {
    if constexpr (std::is_same_v<Space, CudaSpace>)
      if (setup_.exact_phase_times) cuda::synchronize_device();
    return watch.lap();
  }

  /// The lists stay valid while no particle on any rank and no mesh vertex moved more than
  /// skin/2.
  bool needs_rebuild() const {
    const Real moved2 =
        reduce_max(Space{}, owned_, Real(0),
                   DisplacementSquared<P>{position_radius_.data(), position_at_build_.data()});
    const Real half_skin = Real(0.5) * setup_.skin;
    return domain_.max(moved2) > half_skin * half_skin || meshes_.moved_beyond(half_skin);
  }

  /// Wraps periodic images, removes particles that left the box, migrates particles to the
  /// ranks that own their positions, sorts by cell, exchanges ghosts, rebuilds the neighbour
  /// list and carries the contact history over to it.
  void rebuild() {
    Stopwatch watch;
    domain_.begin_rebuild();
    keep_previous_rows();
    times_.neighbors += lap(watch);
    resize_shared(owned_);  // the ghosts are planned anew
    parallel_for(Space{}, owned_, WrapPositions<P>{position_radius_.data(), setup_.box});
    relocate_particles();
#ifndef NDEBUG
    check_particles_conserved();
#endif
    times_.migration += lap(watch);
    sort_owned_by_cell();
    times_.neighbors += lap(watch);
    const std::size_t ghosts = receive_ghosts();
    times_.ghosts += lap(watch);
    build_list(ghosts);
    split_ghost_rows();
    rebuild_mesh_candidates(has_list_);
    remap_pair_history();
    list_build_step_ = steps_;
    position_at_build_.resize(owned_);
    parallel_for(Space{}, owned_,
                 CopyArray<State4>{position_radius_.data(), position_at_build_.data()});
    times_.neighbors += lap(watch);
    ++rebuilds_;
  }

  /// Keeps each owned particle's list row as (partner id, history) records for the remap, only
  /// those that are not fresh, then frees the pair history (the remap writes a new one); keeps
  /// the mesh candidates as (triangle, history) records.
  void keep_previous_rows() {
    iota(previous_index_, owned_);
    if constexpr (kHistoryWidth > 0) {
      if (has_list_) {
        meshes_.keep_rows();
        carried_pairs_.keep(owned_, neighbors_.offsets(), pair_history_.data(), partner_ids());
      }
      release(pair_history_);
    }
  }

  /// The key of each entry of the current neighbour list: its partner's global id.
  PartnerIdKey partner_ids() const { return PartnerIdKey{neighbors_.neighbors(), id_.data()}; }

  /// Removes the owned particles outside the box (removed_ counts them over all ranks) and
  /// sends those that another rank owns there with their state and history. One stable sort by
  /// RelocationKey moves both to the end, the leaving ones grouped by destination and the
  /// removed ones last (the others keep their order); only they are read back, and the
  /// particles that arrive are appended.
  void relocate_particles() {
    const bool several = domain_.ranks() > 1;
    if (several) rank_cells_.update(domain_.cell_ownership(), domain_.rank());
    const std::size_t n = owned_;
    const auto removed_key = static_cast<std::uint64_t>(domain_.ranks()) + 1;
    DeviceArray<std::uint64_t, Space> key(n);
    DeviceArray<std::uint32_t, Space> index(n);
    parallel_for(Space{}, n,
                 rank_cell_kernels::RelocationKey<P>{
                     several ? rank_cells_.view() : RankCellsView{}, setup_.box, removed_key,
                     position_radius_.data(), key.data(), index.data()});
    const std::size_t moving = count_keys_from(key, 1);
    const std::size_t removed = count_keys_from(key, removed_key);
    if (moving > 0) {
      sort_by_key(Space{}, key.data(), index.data(), n, bits_for(removed_key));
      reorder(index.data(), n);
    }
    drop_last(removed);
    if (!several) return;
    const std::size_t leaving = moving - removed;
    std::vector<int> destination;
    for (const std::uint64_t k : download_values<Space>(key.data() + (owned_ - leaving), leaving))
      destination.push_back(static_cast<int>(k - 1));
    const std::uint32_t walls = kHistoryWidth > 0 ? wall_count() : 0;
    const MigratingParticles<State, P> arrived =
        exchange_migrants(owned_from(owned_ - leaving, walls), destination, walls, domain_);
    resize_owned(owned_ - leaving);
    append_owned(arrived, walls);
  }

  /// How many of the keys are at least `least`.
  std::size_t count_keys_from(const DeviceArray<std::uint64_t, Space>& key,
                              std::uint64_t least) const {
    return static_cast<std::size_t>(std::llround(
        reduce_sum(Space{}, key.size(), rank_cell_kernels::KeyAtLeast{key.data(), least})));
  }

  /// Drops the last `count` owned particles, which left the box; removed_ and the expected
  /// particle count and id checksum follow the removals on all ranks. Collective.
  void drop_last(std::size_t count) {
    const std::uint64_t all_removed = domain_.wrapping_sum(count);
    removed_ += all_removed;
    global_count_ -= all_removed;
    if (all_removed == 0) return;
    const std::uint64_t removed_ids =
        tally_of(download_values<Space>(id_.data() + (owned_ - count), count)).id_sum;
    resize_owned(owned_ - count);
    expected_id_sum_ -= domain_.wrapping_sum(removed_ids);
  }

  /// Host copies of the owned particles [first, owned_) with their kept history rows.
  MigratingParticles<State, P> owned_from(std::size_t first, std::uint32_t walls) const {
    const std::size_t count = owned_ - first;
    MigratingParticles<State, P> p;
    p.position_radius = download_values<Space>(position_radius_.data() + first, count);
    p.velocity_inv_mass = download_values<Space>(velocity_inv_mass_.data() + first, count);
    p.angular_velocity = download_values<Space>(angular_velocity_.data() + first, count);
    p.id = download_values<Space>(id_.data() + first, count);
    p.material = download_values<Space>(material_.data() + first, count);
    p.row_offsets.assign(count + 1, 0);
    p.mesh_offsets.assign(count + 1, 0);
    if constexpr (kHistoryWidth > 0) {
      p.wall_history = download_values<Space>(wall_history_.data() + first * walls, count * walls);
      if (!has_list_ || count == 0) return p;
      const std::uint32_t* rows = previous_index_.data() + first;
      carried_pairs_.rows().download(rows, count, p.row_offsets, p.row_partner, p.row_history);
      if (!meshes_.empty())
        meshes_.kept_rows().download(rows, count, p.mesh_offsets, p.mesh_triangle, p.mesh_history);
    }
    return p;
  }

  /// Appends `arrived` to the owned particles, their history rows after the kept ones
  /// (previous_index_ pointing there); torques zero (a law without spin never writes them).
  void append_owned(const MigratingParticles<State, P>& arrived, std::uint32_t walls) {
    const std::size_t first = owned_;
    resize_owned(first + arrived.size());
    upload_values<Space>(arrived.position_radius, position_radius_.data() + first);
    upload_values<Space>(arrived.velocity_inv_mass, velocity_inv_mass_.data() + first);
    upload_values<Space>(arrived.angular_velocity, angular_velocity_.data() + first);
    upload_values<Space>(arrived.id, id_.data() + first);
    upload_values<Space>(arrived.material, material_.data() + first);
    parallel_for(Space{}, owned_, Fill<ForceVec>{torque_.data(), ForceVec{}});
    // The arrivals' rows go after the kept ones (none without history: the index is then only
    // carried along by the sorts).
    const auto first_row = static_cast<std::uint32_t>(carried_pairs_.rows().rows());
    parallel_for(Space{}, arrived.size(), IotaFrom{previous_index_.data() + first, first_row});
    if constexpr (kHistoryWidth > 0) {
      upload_values<Space>(arrived.wall_history, wall_history_.data() + first * walls);
      if (!has_list_) return;
      carried_pairs_.rows().append(arrived.row_offsets, arrived.row_partner, arrived.row_history);
      if (meshes_.empty()) return;
      if (meshes_.kept_rows().rows() != first_row)
        throw std::logic_error("migration: the kept mesh rows and pair rows differ in count");
      meshes_.kept_rows().append(arrived.mesh_offsets, arrived.mesh_triangle, arrived.mesh_history);
    }
  }

  void sort_owned_by_cell() {
    cells_.bin(position_radius_.data(), owned_, setup_.box, setup_.skin, domain_.region());
    reorder(cells_.order(), owned_);
  }

  /// Plans the ghosts and puts them after the owned particles (on several ranks); returns
  /// their number.
  std::size_t receive_ghosts() {
    if (domain_.ranks() == 1) return 0;
    rank_cells_.update(domain_.cell_ownership(), domain_.rank());
    const std::size_t ghosts = ghosts_.plan(domain_, rank_cells_, arrays(), owned_);
    resize_shared(owned_ + ghosts);
    ghosts_.fill(arrays(), owned_);
    return ghosts;
  }

  /// Builds the owned particles' neighbour rows over owned particles and `ghosts` ghosts,
  /// each row ordered by partner id so that no sum depends on particle order or rank count.
  void build_list(std::size_t ghosts) { build_list_into(neighbors_, ghosts); }

  /// build_list into `list`. The sorted positions and slots of a build over ghosts are freed
  /// afterwards.
  void build_list_into(NeighborList<Space>& list, std::size_t ghosts) {
    if (ghosts == 0) {  // the storage order is the cell order of the last binning
      const NeighborRows rows{nullptr, owned_, nullptr, id_.data()};
      DeviceArray<Real4, Space> in_real;  // the positions in Real, when the state is not
      list.build(cells_, positions_in_real(in_real), owned_, setup_.box, setup_.skin, &rows);
      return;
    }
    const std::size_t total = owned_ + ghosts;
    cells_.bin(position_radius_.data(), total, setup_.box, setup_.skin, domain_.region());
    DeviceArray<Real4, Space> sorted_position(total);  // in Real, for the search
    permute_into_real(Space{}, cells_.order(), position_radius_.data(), sorted_position.data(),
                      total);
    DeviceArray<std::uint32_t, Space> slot_of_owned(owned_);
    parallel_for(Space{}, total, SlotOfOwned{cells_.order(), owned_, slot_of_owned.data()});
    const NeighborRows rows{slot_of_owned.data(), owned_, cells_.order(), id_.data()};
    list.build(cells_, sorted_position.data(), total, setup_.box, setup_.skin, &rows);
  }

  /// On several ranks, splits the new list's rows by whether they read a ghost.
  void split_ghost_rows() {
    if (domain_.ranks() > 1)
      ghost_rows_.build(neighbors_.offsets(), neighbors_.neighbors(), owned_);
  }

  /// The owned particles' mesh candidates, with the kept rows' history when `carry`.
  void rebuild_mesh_candidates(bool carry) {
    if (meshes_.empty()) return;
    meshes_.rebuild(position_radius_.data(), owned_, domain_.max(largest_radius()), setup_.skin,
                    domain_.region(), previous_index_.data(), carry);
  }

  /// The new list's pair history: the kept records of each particle's previous row (all fresh
  /// on the first build); the kept rows are then freed.
  void remap_pair_history() {
    if constexpr (kHistoryWidth > 0) {
      DeviceArray<State, Space> fresh(neighbors_.pairs_kept());
      if (has_list_)
        carried_pairs_.remap(owned_, neighbors_.offsets(), partner_ids(), previous_index_.data(),
                             fresh.data());
      else
        parallel_for(Space{}, fresh.size(), Fill<State>{fresh.data(), State{}});
      pair_history_.swap(fresh);
      carried_pairs_.release();
    }
    has_list_ = true;
  }

  /// Applies the permutation `order` (slot k takes particle order[k]) to every per-particle
  /// array of the owned particles whose value must survive a rebuild (forces are recomputed
  /// right after).
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

  /// The owned particles' positions in Real for the neighbour search, in their storage order:
  /// the state itself when P is Real, else a converted copy in `scratch`.
  const Real4* positions_in_real(DeviceArray<Real4, Space>& scratch) const {
    if constexpr (std::is_same_v<P, Real>) {
      return position_radius_.data();
    } else {
      scratch.resize(owned_);
      parallel_for(Space{}, owned_, CopyInReal<P>{position_radius_.data(), scratch.data()});
      return scratch.data();
    }
  }

  static void iota(DeviceArray<std::uint32_t, Space>& a, std::size_t n) {
    a.resize(n);
    parallel_for(Space{}, n, Iota{a.data()});
  }

  /// Sizes the arrays that hold ghosts after the owned particles.
  void resize_shared(std::size_t n) {
    position_radius_.resize(n);
    velocity_inv_mass_.resize(n);
    angular_velocity_.resize(n);
    id_.resize(n);
    material_.resize(n);
  }

  void resize_owned(std::size_t n) {
    owned_ = n;
    resize_shared(n);
    force_.resize(n);
    torque_.resize(n);
    overlap_ratio_.resize(n);
    previous_index_.resize(n);
    if constexpr (kHistoryWidth > 0) wall_history_.resize(n * wall_count());
  }

  std::size_t scratch_bytes() const { return previous_index_.bytes(); }

  /// Bytes of the kept rows (offsets, partner ids, records) that a rebuild now would allocate
  /// while it still holds the list and pair history (keep_previous_rows): counted between
  /// rebuilds too, when they are freed, so that the report shows the peak a run holds. (Those
  /// held, should a rebuild have stopped between keeping them and the remap.)
  std::size_t carry_over_bytes() const {
    if constexpr (kHistoryWidth > 0) {
      if (!has_list_ || pair_history_.size() != neighbors_.pairs_kept())
        return carried_pairs_.bytes();
      return HistoryCarryOver<Space, ParticleId, State>::bytes_to_keep(owned_, neighbors_.offsets(),
                                                                       pair_history_.data());
    } else {
      return 0;
    }
  }

  EngineSetup setup_;
  OneRankDomain one_rank_;
  DomainLink& domain_;  ///< setup.domain, or one_rank_ when there is none
  DeviceArray<typename Law::Params, Space> pair_params_;
  DeviceArray<PlaneWall, Space> walls_;
  // Per particle: the owned_ owned particles, then (the first five) the ghosts.
  DeviceArray<State4, Space> position_radius_;
  DeviceArray<State4, Space> velocity_inv_mass_;
  DeviceArray<StateVec, Space> angular_velocity_;
  DeviceArray<ParticleId, Space> id_;
  DeviceArray<MaterialId, Space> material_;
  DeviceArray<ForceVec, Space> force_;
  DeviceArray<ForceVec, Space> torque_;
  DeviceArray<Real, Space> overlap_ratio_;
  DeviceArray<State4, Space> position_at_build_;
  DeviceArray<State, Space> pair_history_;  ///< per neighbour-list entry (empty: no history)
  DeviceArray<State, Space> wall_history_;  ///< per (particle, wall) (empty: no history)
  // Rebuild scratch.
  DeviceArray<std::uint32_t, Space> previous_index_;  ///< row of each particle's previous list
  HistoryCarryOver<Space, ParticleId, State> carried_pairs_;  ///< previous rows' history
  CellList<Space> cells_;
  NeighborList<Space> neighbors_;
  MeshWalls<Space, Law> meshes_;
  ParticleStaging<Space, P, typename Law::Scalar> staging_;  ///< snapshot copies (host memory)
  GhostExchange<Space, Law::needs_spin, P> ghosts_;
  GhostRowSplit<Space> ghost_rows_;  ///< owned particles by whether their rows read ghosts
  RankCells<Space> rank_cells_;      ///< the decomposition's cell map (several ranks)
  std::size_t owned_ = 0;
  std::uint64_t global_count_ = 0;     ///< particles on all ranks
  std::uint64_t expected_id_sum_ = 0;  ///< id_checksum of the particles on all ranks
  std::uint64_t steps_ = 0;            ///< the run's step count (the meshes' clock)
  std::uint64_t list_build_step_ = 0;  ///< steps_ at the last neighbour-list build
  bool has_list_ = false;
  std::uint64_t removed_ = 0;  ///< on all ranks
  std::uint64_t rebuilds_ = 0;
  StepTimes times_;
};

}  // namespace gpudem
