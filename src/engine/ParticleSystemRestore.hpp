#pragma once
/// ParticleSystem's particles and contact history set, read and restored (ParticleSystem.hpp,
/// which includes this file after the class): shares routed to their owners, a saved run's
/// neighbour list rebuilt at its saved positions, the particle tally.
#include "engine/ParticleSystem.hpp"

namespace gpudem {

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::set_particles(const ParticleStore& share) {
  settle_pair_history();    // while the list it was swept with is still here
  upload_particles(share);  // the first rebuild migrates each particle to its owner
  count_particles(share.id);
  has_list_ = false;
  rebuild();
  compute_forces_after_rebuild();
  measure_pistons();
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::restore_particles(const ParticleStore& share,
                                                    const std::vector<Real4>& list_positions,
                                                    std::uint64_t removed, StepClock list_build) {
  if (list_positions.size() != share.size() || share.force.size() != share.size() ||
      share.torque.size() != share.size())
    throw std::invalid_argument("restore_particles: arrays differ in length");
  settle_pair_history();  // while the list it was swept with is still here
  count_particles(share.id);
  list_build_clock_ = list_build;
  if (domain_.ranks() == 1) {
    restore_owned(share, list_positions);
  } else {
    const RoutedParticles mine = route_to_owners(share, list_positions, domain_);
    restore_owned(mine.particles, mine.list_position_radius);
  }
  removed_ = removed;
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::get_contact_history(ContactHistory& history) const {
  settle_pair_history();
  HistoryValues values;
  values.pair = history_in_real(pair_history_);
  values.wall = history_in_real(wall_history_);
  const std::vector<S> mesh = meshes_.entry_history();
  values.mesh.assign(mesh.begin(), mesh.end());
  history = collect_history(contact_slots(), width_, values);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::set_wall_motion(const std::vector<WallMotion>& motion) {
  if (motion.size() != setup_.walls.size())
    throw std::invalid_argument("set_wall_motion: " + std::to_string(motion.size()) +
                                " walls given, the scene has " +
                                std::to_string(setup_.walls.size()));
  pistons_.set_motion(motion);
  walls_.upload(pistons_.walls());
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::set_contact_history(ContactHistory share) {
  settle_pair_history();  // nothing left pending to write over the records set here
  const HistoryValues values = scatter_share(std::move(share), contact_slots(), width_);
  if (width_ > 0) {
    upload_history(values.pair, pair_history_);
    upload_history(values.wall, wall_history_);
    blank_walls_out_of_reach();  // as the last list build left the others
    if (!meshes_.empty())
      meshes_.set_history(std::vector<S>(values.mesh.begin(), values.mesh.end()));
  }
}

template <class Space, class P, class S>
HistoryValues ParticleSystem<Space, P, S>::scatter_share(ContactHistory share,
                                                         const ContactSlots& slots,
                                                         std::uint32_t width) const {
  if (domain_.ranks() == 1) return scatter_history(slots, width, share);
  std::string problem;
  if (!share.empty() && share.width != width)
    problem = "contact history: it holds " + std::to_string(share.width) +
              " values per contact but this contact law keeps " + std::to_string(width);
  else if (!share.lengths_agree())
    problem = "contact history: the arrays of one kind of contact differ in length";
  throw_first_problem(problem, domain_);
  const std::vector<ParticleId> owned(slots.id.begin(), slots.id.begin() + slots.rows);
  HistoryValues values;
  try {
    values = scatter_history(slots, width, route_history(std::move(share), width, owned, domain_));
  } catch (const std::invalid_argument& e) {
    problem = e.what();
  }
  throw_first_problem(problem, domain_);
  return values;
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::count_particles(const std::vector<ParticleId>& share_ids) {
  global_count_ = domain_.group().sum<std::uint64_t>(share_ids.size());
  expected_id_sum_ = domain_.group().sum<std::uint64_t>(tally_of(share_ids).id_sum);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::check_particles_conserved() const {
  std::vector<ParticleId> ids;
  id_.download(ids);
  ids.resize(owned_);
  const ParticleTally found{domain_.group().sum<std::uint64_t>(owned_),
                            domain_.group().sum<std::uint64_t>(tally_of(ids).id_sum)};
  const std::string problem =
      conservation_problem(found, {global_count_, expected_id_sum_}, domain_.ranks());
  if (!problem.empty()) throw std::runtime_error(problem);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::restore_owned(const ParticleStore& p,
                                                const std::vector<Real4>& list_positions) {
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

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::upload_particles(const ParticleStore& p) {
  columns_.template upload_store<field_use::persistent>(p);
  owned_ = p.size();
  columns_.resize_owned_only(owned_);
  parallel_for(Space{}, owned_, Fill<ForceVec>{torque_.data(), ForceVec{}});
  overlap_ratio_.resize(owned_);
  if (width_ > 0) {
    wall_history_.resize(owned_ * wall_count() * width_);
    parallel_for(Space{}, wall_history_.size(), Fill<S>{wall_history_.data(), S{}});
  }
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::build_list_at_saved_positions(
    DeviceArray<ForceVec, Space>& force, DeviceArray<ForceVec, Space>& torque) {
  position_radius_.swap(position_at_build_);
  iota(previous_index_, owned_);
  sort_owned_by_cell();
  permute_array(cells_.order(), owned_, position_at_build_);
  permute_array(cells_.order(), owned_, force);
  permute_array(cells_.order(), owned_, torque);
  build_list(receive_ghosts());
  split_ghost_rows();
  if (!meshes_.empty()) meshes_.set_time(list_build_clock_.time(setup_.dt));
  rebuild_mesh_candidates(false);
  if (!meshes_.empty()) meshes_.set_time(clock_.time(setup_.dt));
  find_wall_reach();
  parallel_for(Space{}, owned_,
               SwapValues<State4>{position_radius_.data(), position_at_build_.data()});
  if (domain_.ranks() > 1) ghosts_.update(domain_, arrays(), owned_);
  if (width_ > 0) pair_history_.resize(neighbors_.pairs_kept() * width_);
  zero_history();
  if (!bonds_.empty())
    bonds_.remap(owned_, neighbors_.offsets(), neighbors_.pairs_kept(), partner_ids(),
                 previous_index_.data(), false);
  has_list_ = true;
}

template <class Space, class P, class S>
ContactSlots ParticleSystem<Space, P, S>::contact_slots() const {
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
}  // namespace gpudem
