#pragma once
/// ParticleSystem's rebuild (ParticleSystem.hpp, which includes this file after the class):
/// periodic wrapping, removal and migration of particles between ranks, the sort by cell,
/// ghosts, the neighbour and mesh lists and the history carried over to them.
#include "engine/ParticleSystem.hpp"

namespace gpudem {

template <class Space, class P, class S>
bool ParticleSystem<Space, P, S>::needs_rebuild() const {
  const Real moved2 =
      reduce_max(Space{}, owned_, Real(0),
                 DisplacementSquared<P>{position_radius_.data(), position_at_build_.data()});
  const Real half_skin = Real(0.5) * setup_.skin;
  return domain_.group().max<double>(moved2) > half_skin * half_skin ||
         meshes_.moved_beyond(half_skin);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::rebuild() {
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
  find_wall_reach();
  remap_pair_history();
  list_build_clock_ = clock_;
  position_at_build_.resize(owned_);
  parallel_for(Space{}, owned_,
               CopyArray<State4>{position_radius_.data(), position_at_build_.data()});
  times_.neighbors += lap(watch);
  ++rebuilds_;
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::keep_previous_rows() {
  settle_pair_history();
  iota(previous_index_, owned_);
  if (!bonds_.empty() && has_list_) {
    check_bond_reach();
    bonds_.keep(owned_, neighbors_.offsets(), partner_ids());
  }
  if (width_ > 0) {
    if (has_list_) {
      meshes_.keep_rows();
      carried_pairs_.keep(owned_, neighbors_.offsets(), pair_history_.data(), partner_ids());
    }
    release(pair_history_);
  }
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::relocate_particles() {
  const bool several = domain_.ranks() > 1;
  if (several) rank_cells_.update(domain_.cell_ownership(), domain_.rank());
  const std::size_t n = owned_;
  const auto removed_key = static_cast<std::uint64_t>(domain_.ranks()) + 1;
  DeviceArray<std::uint64_t, Space> key(n);
  DeviceArray<std::uint32_t, Space> index(n);
  parallel_for(Space{}, n,
               rank_cell_kernels::RelocationKey<P>{several ? rank_cells_.view() : RankCellsView{},
                                                   setup_.box, removed_key, position_radius_.data(),
                                                   key.data(), index.data()});
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
  const std::uint32_t walls = width_ > 0 ? wall_count() : 0;
  const MigratingParticles<S, P> arrived =
      exchange_migrants(owned_from(owned_ - leaving, walls), destination, walls, domain_);
  resize_owned(owned_ - leaving);
  append_owned(arrived, walls);
}

template <class Space, class P, class S>
std::size_t ParticleSystem<Space, P, S>::count_keys_from(
    const DeviceArray<std::uint64_t, Space>& key, std::uint64_t least) const {
  return static_cast<std::size_t>(std::llround(
      reduce_sum(Space{}, key.size(), rank_cell_kernels::KeyAtLeast{key.data(), least})));
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::drop_last(std::size_t count) {
  const std::uint64_t all_removed = domain_.group().sum<std::uint64_t>(count);
  removed_ += all_removed;
  global_count_ -= all_removed;
  if (all_removed == 0) return;
  const std::uint64_t removed_ids =
      tally_of(download_values<Space>(id_.data() + (owned_ - count), count)).id_sum;
  resize_owned(owned_ - count);
  expected_id_sum_ -= domain_.group().sum<std::uint64_t>(removed_ids);
}

template <class Space, class P, class S>
MigratingParticles<S, P> ParticleSystem<Space, P, S>::owned_from(std::size_t first,
                                                                 std::uint32_t walls) const {
  const std::size_t count = owned_ - first;
  MigratingParticles<S, P> p;
  p.history_width = width_;
  p.fields = columns_.template download_rows<field_use::persistent>(first, count);
  p.row_offsets.assign(count + 1, 0);
  p.mesh_offsets.assign(count + 1, 0);
  p.bond_offsets.assign(count + 1, 0);
  if (!bonds_.empty()) {
    p.bond_width = bond_value::width;
    if (has_list_ && count > 0)
      bonds_.kept_rows().download(previous_index_.data() + first, count, p.bond_offsets,
                                  p.bond_partner, p.bond_values);
  }
  if (width_ > 0) {
    p.wall_history = download_values<Space>(wall_history_.data() + first * walls * width_,
                                            count * walls * width_);
    if (!has_list_ || count == 0) return p;
    const std::uint32_t* rows = previous_index_.data() + first;
    carried_pairs_.rows().download(rows, count, p.row_offsets, p.row_partner, p.row_history);
    if (!meshes_.empty())
      meshes_.kept_rows().download(rows, count, p.mesh_offsets, p.mesh_triangle, p.mesh_history);
  }
  return p;
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::append_owned(const MigratingParticles<S, P>& arrived,
                                               std::uint32_t walls) {
  const std::size_t first = owned_;
  resize_owned(first + arrived.size());
  columns_.template upload_rows<field_use::persistent>(arrived.fields, first);
  parallel_for(Space{}, owned_, Fill<ForceVec>{torque_.data(), ForceVec{}});
  // The arrivals' rows go after the kept ones (none without history: the index is then only
  // carried along by the sorts).
  const auto first_row = static_cast<std::uint32_t>(width_ > 0 ? carried_pairs_.rows().rows()
                                                               : bonds_.kept_rows().rows());
  parallel_for(Space{}, arrived.size(), IotaFrom{previous_index_.data() + first, first_row});
  if (!bonds_.empty() && has_list_) {
    if (bonds_.kept_rows().rows() != first_row)
      throw std::logic_error("migration: the kept bond rows and pair rows differ in count");
    bonds_.kept_rows().append(arrived.bond_offsets, arrived.bond_partner, arrived.bond_values);
  }
  if (width_ > 0) {
    upload_values<Space>(arrived.wall_history, wall_history_.data() + first * walls * width_);
    if (!has_list_) return;
    carried_pairs_.rows().append(arrived.row_offsets, arrived.row_partner, arrived.row_history);
    if (meshes_.empty()) return;
    if (meshes_.kept_rows().rows() != first_row)
      throw std::logic_error("migration: the kept mesh rows and pair rows differ in count");
    meshes_.kept_rows().append(arrived.mesh_offsets, arrived.mesh_triangle, arrived.mesh_history);
  }
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::sort_owned_by_cell() {
  cells_.bin(position_radius_.data(), owned_, setup_.box, setup_.skin, domain_.region());
  reorder(cells_.order(), owned_);
}

template <class Space, class P, class S>
std::size_t ParticleSystem<Space, P, S>::receive_ghosts() {
  if (domain_.ranks() == 1) return 0;
  rank_cells_.update(domain_.cell_ownership(), domain_.rank());
  const std::size_t ghosts = ghosts_.plan(domain_, rank_cells_, arrays(), owned_);
  resize_shared(owned_ + ghosts);
  ghosts_.fill(arrays(), owned_);
  return ghosts;
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::build_list_into(NeighborList<Space>& list, std::size_t ghosts) {
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

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::split_ghost_rows() {
  if (domain_.ranks() > 1) ghost_rows_.build(neighbors_.offsets(), neighbors_.neighbors(), owned_);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::rebuild_mesh_candidates(bool carry) {
  if (meshes_.empty()) return;
  meshes_.rebuild(position_radius_.data(), owned_, domain_.group().max<double>(largest_radius()),
                  setup_.skin, domain_.region(), previous_index_.data(), carry);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::find_wall_reach() {
  if (wall_count() == 0) return;
  WallReachBits pistons;
  for (std::size_t k = 0; k < pistons_.count(); ++k) pistons.add(pistons_.piston(k).wall);
  wall_reach_.resize(owned_);
  parallel_for(Space{}, owned_,
               FindWallReach<P>{position_radius_.data(), walls_.data(), wall_count(), pistons,
                                Real(setup_.skin), wall_reach_.data()});
  blank_walls_out_of_reach();
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::blank_walls_out_of_reach() {
  if (wall_count() == 0 || width_ == 0) return;
  parallel_for(
      Space{}, owned_,
      BlankWallsOutOfReach<S>{wall_reach_.data(), wall_count(), width_, wall_history_.data()});
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::remap_pair_history() {
  if (width_ > 0) {
    DeviceArray<S, Space> fresh(neighbors_.pairs_kept() * width_);
    if (has_list_)
      carried_pairs_.remap(owned_, neighbors_.offsets(), partner_ids(), previous_index_.data(),
                           fresh.data());
    else
      parallel_for(Space{}, fresh.size(), Fill<S>{fresh.data(), S{}});
    pair_history_.swap(fresh);
    carried_pairs_.release();
  }
  if (!bonds_.empty())
    bonds_.remap(owned_, neighbors_.offsets(), neighbors_.pairs_kept(), partner_ids(),
                 previous_index_.data(), has_list_);
  has_list_ = true;
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::reorder(const std::uint32_t* order, std::size_t n) {
  columns_.permute_persistent(order, n);
  permute_array(order, n, previous_index_);
  if (width_ > 0) {
    const std::uint32_t values = wall_count() * width_;
    DeviceArray<S, Space> rows(n * values);
    parallel_for(Space{}, n, GatherRows<S>{order, wall_history_.data(), rows.data(), values});
    wall_history_.swap(rows);
  }
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::resize_owned(std::size_t n) {
  owned_ = n;
  resize_shared(n);
  columns_.resize_owned_only(n);
  overlap_ratio_.resize(n);
  previous_index_.resize(n);
  if (width_ > 0) wall_history_.resize(n * wall_count() * width_);
}
}  // namespace gpudem
