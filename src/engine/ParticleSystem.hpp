#pragma once
/// The particle system of one execution space and precision policy: this rank's owned particles
/// followed by ghost copies of other ranks' particles, stepped with the rank's DomainLink (one
/// rank when the setup names none), everything done to them as particles (integration, sorting,
/// migration, ghosts, neighbour lists, history storage and carry-over, staging, diagnostics'
/// reductions, tuning, memory report). The contact law is a ForceCompute it is given
/// (ForceCompute.hpp): the system is compiled once per backend and policy, not per law.
/// Include the backend's ParallelFor header first.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/StepClock.hpp"
#include "core/Stopwatch.hpp"
#include "engine/ArrayKernels.hpp"
#include "engine/BondSet.hpp"
#include "engine/CellList.hpp"
#include "engine/ContactForces.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/Diagnostics.hpp"
#include "engine/DomainLink.hpp"
#include "engine/ForceCompute.hpp"
#include "engine/ForceScratch.hpp"
#include "engine/GhostExchange.hpp"
#include "engine/HistoryCarryOver.hpp"
#include "engine/HostCopies.hpp"
#include "engine/Integrators.hpp"
#include "engine/LaunchTuning.hpp"
#include "engine/MeshWalls.hpp"
#include "engine/NeighborList.hpp"
#include "engine/ParticleColumns.hpp"
#include "engine/ParticleMigration.hpp"
#include "engine/ParticleStaging.hpp"
#include "engine/ParticleStateKernels.hpp"
#include "engine/Permute.hpp"
#include "engine/RankCells.hpp"
#include "engine/ShareRouting.hpp"
#include "engine/StepEngine.hpp"
#include "engine/WallPistons.hpp"
#include "engine/WallReach.hpp"

namespace gpudem {

/// The particle system of one backend (Space), with the particle state (positions, velocities,
/// spins) held in scalar P: Real in the double and mixed policies, float in the float policy,
/// converted to Real wherever it is read and rounded to P where it is written; forces, torques
/// and contact history in the law's scalar S.
template <class Space, class P, class S>
class ParticleSystem final : public StepEngine {
  using ForceVec = Vec3T<S>;  ///< forces and torques, in the law's scalar
  using State4 = Vec4T<P>;    ///< position and radius, velocity and 1/m
  using StateVec = Vec3T<P>;  ///< angular velocity

 public:
  using LawView = ContactViewScalar<S>;  ///< the state scalar of the views the law reads

  ParticleSystem(const EngineSetup& setup, std::unique_ptr<ForceCompute<Space, LawView, S>> law)
      : setup_(setup),
        law_(std::move(law)),
        width_(law_->history_width()),
        one_rank_(setup.box),
        domain_(setup.domain ? *setup.domain : one_rank_),
        pistons_(setup.walls, setup.pistons, setup.gravity),
        carried_pairs_(width_),
        meshes_(setup.meshes, setup.box, width_),
        bonds_(setup.bonds, setup.clods, setup.bond_pairs),
        ghosts_(law_->needs_spin() || !setup.bonds.empty()),
        clock_{setup.start_step} {
    walls_.upload(pistons_.walls());
    motion_.upload(setup.material_motion);
    if (!meshes_.empty()) meshes_.set_time(clock_.time(setup.dt));
  }

  void set_particles(const ParticleStore& share) override;

  void restore_particles(const ParticleStore& share, const std::vector<Real4>& list_positions,
                         std::uint64_t removed, StepClock list_build) override;

  void get_particles(ParticleStore& p) const override { read_owned_particles(owned_arrays(), p); }

  void get_contact_history(ContactHistory& history) const override;
  void set_contact_history(ContactHistory share) override;

  void create_bonds() override;
  void get_bonds(ContactHistory& bonds, std::uint64_t& made) const override;
  void set_bonds(ContactHistory bonds, std::uint64_t made) override;
  void continue_bonds(ContactHistory bonds, std::uint64_t made) override;
  BondLines bond_lines() const override;

  std::vector<WallMotion> wall_motion() const override { return pistons_.motion(); }

  void set_wall_motion(const std::vector<WallMotion>& motion) override;

  void get_list_positions(std::vector<Real4>& position_radius) const override {
    position_radius = download_in_real(position_at_build_);
  }
  StepClock list_build_clock() const override { return list_build_clock_; }

  std::size_t particle_count() const override { return global_count_; }
  std::size_t owned_count() const override { return owned_; }

  void get_list_lengths(std::vector<std::uint32_t>& lengths) const override;

  StagedParticles& stage_particles() override {
    staging_.stage(owned_arrays());
    staging_.expected_tally = {global_count_, expected_id_sum_};
    return staging_;
  }

  void set_substeps(std::uint32_t substeps) override;

  double fastest_speed() const override;

  void step() override;

  void rebuild_neighbors() override {
    rebuild();
    compute_forces_after_rebuild();
    measure_pistons();
  }

  bool find_unhealthy(double limit, HealthFailure& failure) const override;

  Diagnostics diagnostics() const override;

  std::vector<MeshSurface> mesh_surfaces() const override;

  /// Times the force, neighbour-list and integration launches at each candidate block size and
  /// keeps, for each, the one the slowest rank runs fastest (LaunchTuning.hpp); leaves the state
  /// as it was: the forces are timed on scratch outputs and history, the list is built into a
  /// scratch list, the kick and drift run with a zero step. Collective; nothing to tune on the
  /// host.
  std::string tune_launches() override;

  std::uint64_t removed_count() const override { return removed_; }
  std::uint64_t rebuild_count() const override { return rebuilds_; }
  StepTimes step_times() const override { return times_; }

  std::vector<MemoryUse> memory_use() const override;

  std::string backend_name() const override { return Space::name; }
  int contact_lanes() const override { return law_->contact_lanes(); }

 private:
  /// The arrays a snapshot or get_particles reads; the owned particles are their first rows.
  OwnedParticleArrays<Space, P, S> owned_arrays() const { return {columns_, owned_}; }

  ParticlePointers<P, S> arrays() { return columns_.pointers(); }

  /// scatter_history for this rank's `share` of the records (freed on return): on several
  /// ranks each record is sent to the rank that owns its owner particle first, and a problem on
  /// any rank (another width, arrays of different lengths, an unknown particle, a pair not in
  /// the list) is thrown on every rank.
  HistoryValues scatter_share(ContactHistory share, const ContactSlots& slots,
                              std::uint32_t width) const;

  /// The particle count over all ranks and the checksum of their ids, from this rank's share
  /// of the ids. Collective.
  void count_particles(const std::vector<ParticleId>& share_ids);

  /// Checks that no particle was lost or duplicated between ranks against the expected tally;
  /// throws std::runtime_error saying what differs. Collective.
  void check_particles_conserved() const;

  /// restore_particles for this rank's particles `p` and their list positions.
  void restore_owned(const ParticleStore& p, const std::vector<Real4>& list_positions);

  /// Uploads the particle arrays of `p` as the owned particles and sizes the owned particles'
  /// work arrays; torques zero (a law without spin never writes them, and a grown device
  /// array's new rows hold whatever its memory held), wall histories zero.
  void upload_particles(const ParticleStore& p);

  /// The neighbour list of a restored state, built at the saved positions of the last build
  /// (position_at_build_) as the saved engine built it, with ghosts at their saved positions
  /// too; the particles then take their saved current state again, ghosts included.
  void build_list_at_saved_positions(DeviceArray<ForceVec, Space>& force,
                                     DeviceArray<ForceVec, Space>& torque);

  /// Σ over owned particles of each column of a per-(particle, column) load array.
  std::vector<Vec3> column_sums(const DeviceArray<Vec3, Space>& load, std::uint32_t columns) const {
    std::vector<Vec3> sums(columns);
    sum_columns(Space{}, load.data(), owned_, columns, sums.data());
    return sums;
  }

  Real largest_radius() const {
    return reduce_max(Space{}, owned_, Real(0), Radius<P>{position_radius_.data()});
  }

  void zero_history() {
    parallel_for(Space{}, pair_history_.size(), Fill<S>{pair_history_.data(), S{}});
    parallel_for(Space{}, wall_history_.size(), Fill<S>{wall_history_.data(), S{}});
  }

  /// Host copies of the ids (owned, then ghosts) and the owned particles' neighbour list,
  /// for contact-history conversions.
  ContactSlots contact_slots() const;

  /// Every particle array, spins included.
  ParticleView<P> state_view() const {
    return ParticleView<P>{position_radius_.data(), velocity_inv_mass_.data(),
                           angular_velocity_.data(), material_.data()};
  }

  /// The history arrays of the particles' contacts, to read.
  HistoryPointers<const S> history_pointers() const {
    return {pair_history_.data(), wall_history_.data(), meshes_.history()};
  }

  /// The history arrays of the particles' contacts, to advance.
  HistoryPointers<S> history_pointers() {
    return {pair_history_.data(), wall_history_.data(), meshes_.history()};
  }

  /// What the contact law reads: the state, the lists, the walls and meshes, the history.
  ContactInputs<LawView, S> contact_inputs() const {
    return ContactInputs<LawView, S>{contact_view<S>(state_view()),
                                     owned_,
                                     neighbors_.offsets(),
                                     neighbors_.neighbors(),
                                     neighbors_.builds(),
                                     setup_.material_count,
                                     walls_.data(),
                                     wall_count(),
                                     wall_count() > 0 ? wall_reach_.data() : nullptr,
                                     setup_.box,
                                     meshes_.view(),
                                     history_pointers(),
                                     bonds_.records()};
  }

  /// What the bond kernels read: every particle array, the owned particles' list rows, the ids.
  BondRows<P> bond_rows() const;

  /// Adds the bonds' loads to the owned particles' forces, the bonds advanced by dt.
  void add_bond_loads(Real dt);

  /// Throws std::runtime_error when a bond has stretched so far that the next list may miss its
  /// partner: a surface gap of 0.9 skin or more. Collective.
  void check_bond_reach() const;

  /// Throws std::invalid_argument, naming its file and line, for a pair a [[bond]] table lists
  /// that create_bonds did not bond by that table. Collective.
  void check_listed_bonds() const;
  /// The forces, with the bonds' loads as they stand (not advanced), and the pistons' push.
  void evaluate_with_bond_loads();

  /// Whether the particles' spins change: the law or the bonds exert torques.
  bool spins() const { return law_->needs_spin() || !bonds_.empty(); }

  /// Velocities (and spins) by h times the accelerations, the pistons' too.
  void kick(Real h);

  template <bool kRotate>
  void kick_with(Real h);

  /// Positions by dt times the velocities, the pistons' too.
  void drift(Real dt);

  /// Each piston's push, summed in its units over the owned particles of all ranks
  /// (WallPistons.hpp). Collective.
  void measure_pistons();

  using ForceScratch = ForceScratchOf<Space, S>;

  /// Bytes by which the device memory that launch tuning allocates (a ForceScratch and a second
  /// neighbour list, with an eighth more for the list's sort scratch and growth) exceeds the
  /// free device memory; 0 when it fits.
  double tuning_memory_shortfall() const;

  std::uint32_t wall_count() const { return static_cast<std::uint32_t>(setup_.walls.size()); }

  /// The forces of every owned particle, bonds included.
  void compute_forces() {
    compute_forces(nullptr, owned_);
    add_bond_loads(step_dt());
  }

  /// The step of the base step in progress: dt / substeps.
  Real step_dt() const { return setup_.dt / clock_.substeps; }

  /// The forces of the owned particles list[0, count) (all of 0..count when list is null).
  void compute_forces(const std::uint32_t* list, std::size_t count);

  /// Brings every list entry's history up to date after pair-once sweeps (ForceCompute::
  /// mirror_pair_history, which writes the records the law holds pending): called before the
  /// history is read, kept or freed, and before the list or the particles change. Const, as
  /// no contact's history changes, but it writes records: not for concurrent callers.
  void settle_pair_history() const { law_->mirror_pair_history(contact_inputs()); }

  /// The forces of the current state written to `scratch`, the engine's state untouched.
  void compute_forces_into(ForceScratch& scratch);

  /// Refreshes the ghosts' per-step fields while the forces of the owned particles whose rows
  /// read no ghost are computed, then computes the others' forces. Each particle's force is
  /// the same sum as in compute_forces(); only the particles' order differs.
  void refresh_ghosts_computing_interior(Stopwatch& watch);

  /// After a rebuild, the forces swept as the next steps sweep them (on several ranks, interior
  /// rows first): the host keeps one grouping and selection of entries per list (PairOnceSweep).
  void compute_forces_after_rebuild();

  bool find_unhealthy_here(double limit, HealthFailure& failure) const;

  /// The diagnostics of this rank's particles; `contact_share` is its (fractional) share of
  /// the contact count, a pair counting half on each side.
  Diagnostics local_diagnostics(double& contact_share) const;

  /// The force the particles of all ranks exert on each triangle of all meshes, as x, y, z
  /// per global triangle index [N]: the loads of this rank's mesh contacts (ContactTerms)
  /// added up per triangle on the host, then summed over the ranks. Collective.
  std::vector<double> triangle_loads() const;

  /// Sums (and for the overlap, maximises) a rank's diagnostics over all ranks.
  void sum_over_ranks(Diagnostics& d, double contact_share) const;

  /// Seconds since the watch's last lap. With EngineSetup::exact_phase_times it first waits
  /// for the device, so that a part's time holds its own kernels and not only their launches.
  double lap(Stopwatch& watch) const {
    if constexpr (std::is_same_v<Space, CudaSpace>)
      if (setup_.exact_phase_times) cuda::synchronize_device();
    return watch.lap();
  }

  /// The lists stay valid while no particle on any rank and no mesh vertex moved more than
  /// skin/2.
  bool needs_rebuild() const;

  /// Wraps periodic images, removes particles that left the box, migrates particles to the
  /// ranks that own their positions, sorts by cell, exchanges ghosts, rebuilds the neighbour
  /// list and carries the contact history over to it.
  void rebuild();

  /// Keeps each owned particle's list row as (partner id, history) records for the remap, only
  /// those that are not fresh, then frees the pair history (the remap writes a new one); keeps
  /// the mesh candidates as (triangle, history) records.
  void keep_previous_rows();

  /// The key of each entry of the current neighbour list: its partner's global id.
  PartnerIdKey partner_ids() const { return PartnerIdKey{neighbors_.neighbors(), id_.data()}; }

  /// Removes the owned particles outside the box (removed_ counts them over all ranks) and
  /// sends those that another rank owns there with their state and history. One stable sort by
  /// RelocationKey moves both to the end, the leaving ones grouped by destination and the
  /// removed ones last (the others keep their order); only they are read back, and the
  /// particles that arrive are appended.
  void relocate_particles();

  /// How many of the keys are at least `least`.
  std::size_t count_keys_from(const DeviceArray<std::uint64_t, Space>& key,
                              std::uint64_t least) const;

  /// Drops the last `count` owned particles, which left the box; removed_ and the expected
  /// particle count and id checksum follow the removals on all ranks. Collective.
  void drop_last(std::size_t count);

  /// Host copies of the owned particles [first, owned_) with their kept history rows.
  MigratingParticles<S, P> owned_from(std::size_t first, std::uint32_t walls) const;

  /// Appends `arrived` to the owned particles, their history rows after the kept ones
  /// (previous_index_ pointing there); torques zero (a law without spin never writes them).
  void append_owned(const MigratingParticles<S, P>& arrived, std::uint32_t walls);

  void sort_owned_by_cell();

  /// Plans the ghosts and puts them after the owned particles (on several ranks); returns
  /// their number.
  std::size_t receive_ghosts();

  /// Builds the owned particles' neighbour rows over owned particles and `ghosts` ghosts,
  /// each row ordered by partner id so that no sum depends on particle order or rank count.
  void build_list(std::size_t ghosts) { build_list_into(neighbors_, ghosts); }

  /// build_list into `list`. The sorted positions and slots of a build over ghosts are freed
  /// afterwards.
  void build_list_into(NeighborList<Space>& list, std::size_t ghosts);

  /// On several ranks, splits the new list's rows by whether they read a ghost.
  void split_ghost_rows();

  /// The owned particles' mesh candidates, with the kept rows' history when `carry`.
  void rebuild_mesh_candidates(bool carry);

  /// Each owned particle's plane walls in reach (WallReach.hpp); blanks its others' history.
  void find_wall_reach();
  void blank_walls_out_of_reach();

  /// The new list's pair history: the kept records of each particle's previous row (all fresh
  /// on the first build); the kept rows are then freed.
  void remap_pair_history();

  /// Applies the permutation `order` (slot k takes particle order[k]) to every per-particle
  /// array of the owned particles whose value must survive a rebuild (forces are recomputed
  /// right after).
  void reorder(const std::uint32_t* order, std::size_t n);

  template <class T>
  static void permute_array(const std::uint32_t* order, std::size_t n, DeviceArray<T, Space>& a) {
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
  void resize_shared(std::size_t n) { columns_.resize_ghost_held(n); }

  void resize_owned(std::size_t n);

  std::size_t scratch_bytes() const { return previous_index_.bytes(); }

  template <class F>
  DeviceArray<FieldValue<F, P, S>, Space>& field() {
    return columns_.template get<F>();
  }

  /// Bytes of the kept rows (offsets, partner ids, records) that a rebuild now would allocate
  /// while it still holds the list and pair history (keep_previous_rows): counted between
  /// rebuilds too, when they are freed, so that the report shows the peak a run holds. (Those
  /// held, should a rebuild have stopped between keeping them and the remap.)
  std::size_t carry_over_bytes() const;

  EngineSetup setup_;
  std::unique_ptr<ForceCompute<Space, LawView, S>> law_;  ///< the contact law
  std::uint32_t width_;  ///< history values per contact (the law's)
  OneRankDomain one_rank_;
  DomainLink& domain_;                         ///< setup.domain, or one_rank_ when there is none
  DeviceArray<PlaneWall, Space> walls_;        ///< at their current positions
  DeviceArray<MaterialMotion, Space> motion_;  ///< per material (empty: all move freely)
  WallPistons pistons_;
  /// With pistons, each owned particle's push on each wall, per slot i·wall_count + w [N].
  DeviceArray<S, Space> wall_push_;
  /// Per particle, every field of the table: the owned_ owned particles, then, in the fields
  /// ghosts hold, the ghosts. The members below name the columns the engine's kernels read.
  ParticleColumns<Space, P, S> columns_;
  DeviceArray<State4, Space>& position_radius_ = field<particle_field::PositionRadius>();
  DeviceArray<State4, Space>& velocity_inv_mass_ = field<particle_field::VelocityInvMass>();
  DeviceArray<StateVec, Space>& angular_velocity_ = field<particle_field::AngularVelocity>();
  DeviceArray<ParticleId, Space>& id_ = field<particle_field::Id>();
  DeviceArray<MaterialId, Space>& material_ = field<particle_field::Material>();
  DeviceArray<ForceVec, Space>& force_ = field<particle_field::Force>();
  DeviceArray<ForceVec, Space>& torque_ = field<particle_field::Torque>();
  // Per owned particle, besides the table's fields.
  DeviceArray<Real, Space> overlap_ratio_;
  DeviceArray<State4, Space> position_at_build_;
  DeviceArray<S, Space> pair_history_;  ///< width_ per neighbour-list entry (empty: no history)
  DeviceArray<S, Space> wall_history_;  ///< width_ per (particle, wall) (empty: no history)
  DeviceArray<std::uint32_t, Space> wall_reach_;  ///< walls in reach at the last list build
  // Rebuild scratch.
  DeviceArray<std::uint32_t, Space> previous_index_;      ///< row of each particle's previous list
  HistoryCarryOver<Space, ParticleId, S> carried_pairs_;  ///< previous rows' history
  CellList<Space> cells_;
  NeighborList<Space> neighbors_;
  MeshWalls<Space, S> meshes_;
  BondSet<Space, S> bonds_;
  std::uint64_t bonds_made_ = 0;          ///< bonds the run started with, on all ranks
  ParticleStaging<Space, P, S> staging_;  ///< snapshot copies (host memory)
  GhostExchange<Space, P, S> ghosts_;
  GhostRowSplit<Space> ghost_rows_;  ///< owned particles by whether their rows read ghosts
  RankCells<Space> rank_cells_;      ///< the decomposition's cell map (several ranks)
  std::size_t owned_ = 0;
  std::uint64_t global_count_ = 0;     ///< particles on all ranks
  std::uint64_t expected_id_sum_ = 0;  ///< id_checksum of the particles on all ranks
  StepClock clock_;                    ///< where the run is (the meshes' clock)
  StepClock list_build_clock_;         ///< clock_ at the last neighbour-list build
  bool has_list_ = false;
  std::uint64_t removed_ = 0;  ///< on all ranks
  std::uint64_t rebuilds_ = 0;
  StepTimes times_;
};

}  // namespace gpudem

#include "engine/ParticleSystemBonds.hpp"
#include "engine/ParticleSystemRebuild.hpp"
#include "engine/ParticleSystemReport.hpp"
#include "engine/ParticleSystemRestore.hpp"
#include "engine/ParticleSystemStep.hpp"
