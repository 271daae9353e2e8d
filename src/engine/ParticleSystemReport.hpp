#pragma once
/// ParticleSystem's reports (ParticleSystem.hpp, which includes this file after the class): the
/// health check, diagnostics and mesh loads reduced over ranks, launch tuning and the memory
/// report.
#include "engine/ParticleSystem.hpp"

namespace gpudem {

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::get_list_lengths(std::vector<std::uint32_t>& lengths) const {
  const std::vector<std::uint32_t> offsets =
      download_values<Space>(neighbors_.offsets(), has_list_ ? owned_ + 1 : 0);
  lengths.assign(owned_, 0);
  for (std::size_t i = 0; i + 1 < offsets.size(); ++i) lengths[i] = offsets[i + 1] - offsets[i];
}

template <class Space, class P, class S>
bool ParticleSystem<Space, P, S>::find_unhealthy(double limit, HealthFailure& failure) const {
  const bool here = find_unhealthy_here(limit, failure);
  if (domain_.ranks() == 1) return here;
  const int first = domain_.group().first_rank_with(here);
  if (first == domain_.ranks()) return false;
  failure = domain_.group().broadcast_value(failure, first);
  return true;
}

template <class Space, class P, class S>
Diagnostics ParticleSystem<Space, P, S>::diagnostics() const {
  double contact_share = 0;
  Diagnostics d = local_diagnostics(contact_share);
  if (domain_.ranks() > 1) sum_over_ranks(d, contact_share);
  d.particle_count = global_count_;
  if (!bonds_.empty()) {
    const double half = bonds_.half_count(neighbors_.offsets(), owned_);
    d.bond_count = static_cast<std::uint64_t>(std::llround(domain_.group().sum<double>(half)));
    d.broken_bond_count = bonds_made_ > d.bond_count ? bonds_made_ - d.bond_count : 0;
  }
  for (std::size_t k = 0; k < pistons_.count(); ++k)
    d.piston_motion.push_back(pistons_.motion()[pistons_.piston(k).wall]);
  return d;
}

template <class Space, class P, class S>
std::vector<MeshSurface> ParticleSystem<Space, P, S>::mesh_surfaces() const {
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

template <class Space, class P, class S>
std::string ParticleSystem<Space, P, S>::tune_launches() {
  if constexpr (has_block_sizes(Space{})) {
    const RankGroup& ranks = domain_.group();
    const double shortfall = ranks.max(tuning_memory_shortfall());
    if (shortfall > 0)
      return launch_tuning_report(launch_tuning(), true) +
             " (defaults, not timed: the timing scratch needs " +
             std::to_string(static_cast<long long>(shortfall / (1 << 20)) + 1) +
             " MiB more device memory than a rank has free)";
    const auto timed = [](auto&& work) {
      return [&work](unsigned) { return seconds_to_run(Space{}, work); };
    };
    ForceScratch scratch(owned_, pair_history_.size(), wall_history_.size(),
                         meshes_.history_values());
    tune_block_size(launch_tuning(), LaunchSlot::forces,
                    timed([&] { compute_forces_into(scratch); }), ranks);
    NeighborList<Space> list;
    tune_block_size(launch_tuning(), LaunchSlot::neighbor_list,
                    timed([&] { build_list_into(list, ghosts_.ghosts()); }), ranks);
    tune_block_size(launch_tuning(), LaunchSlot::integrate, timed([&] {
                      kick(0);
                      drift(0);
                    }),
                    ranks);
  }
  return launch_tuning_report(launch_tuning(), has_block_sizes(Space{}));
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::compute_forces_into(ForceScratch& scratch) {
  settle_pair_history();
  law_->compute(contact_inputs(), setup_.gravity, setup_.dt,
                {scratch.force.data(),
                 scratch.torque.data(),
                 scratch.overlap_ratio.data(),
                 {scratch.pair.data(), scratch.wall.data(), scratch.mesh.data()}},
                nullptr, owned_);
  settle_pair_history();  // into the scratch, before it is freed
}

template <class Space, class P, class S>
std::vector<MemoryUse> ParticleSystem<Space, P, S>::memory_use() const {
  std::vector<MemoryUse> use = columns_.memory_use();
  use.insert(use.end(), {{"overlap ratio", overlap_ratio_.bytes()},
                         {"position at list build", position_at_build_.bytes()},
                         {"neighbour list", neighbors_.memory_bytes()},
                         {"pair history", pair_history_.bytes()},
                         {"wall history", wall_history_.bytes()},
                         {"walls in reach", wall_reach_.bytes()},
                         {"cell list", cells_.memory_bytes()},
                         {"history carry-over", carry_over_bytes()},
                         {"rebuild scratch", scratch_bytes()},
                         {"ghost buffers", ghosts_.memory_bytes() + ghost_rows_.memory_bytes() +
                                               rank_cells_.memory_bytes()},
                         {"meshes", meshes_.memory_bytes()},
                         {"contact law", law_->memory_bytes()}});
  if (!bonds_.empty()) use.push_back({"bonds", bonds_.bytes()});
  return use;
}

template <class Space, class P, class S>
double ParticleSystem<Space, P, S>::tuning_memory_shortfall() const {
  const double needed =
      double(ForceScratch::bytes(owned_, pair_history_.size(), wall_history_.size(),
                                 meshes_.history_values())) +
      1.125 * double(neighbors_.memory_bytes());
  return std::max(0.0, needed - double(cuda::free_device_memory()));
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::refresh_ghosts_computing_interior(Stopwatch& watch) {
  ghosts_.begin_update(domain_, arrays());
  times_.ghosts += lap(watch);
  compute_forces(ghost_rows_.interior(), ghost_rows_.interior_count());
  times_.forces += lap(watch);
  ghosts_.finish_update(domain_, arrays(), owned_);
  times_.ghosts += lap(watch);
  times_.halo_bytes += ghosts_.refresh_bytes();
  ++times_.refreshes;
  compute_forces(ghost_rows_.boundary(), ghost_rows_.boundary_count());
  add_bond_loads(step_dt());
}

template <class Space, class P, class S>
bool ParticleSystem<Space, P, S>::find_unhealthy_here(double limit, HealthFailure& failure) const {
  const HealthScore<P> score{state_view(), overlap_ratio_.data()};
  if (reduce_max(Space{}, owned_, Real(0), score) <= limit) return false;
  ParticleStore host;
  get_particles(host);
  std::vector<Real> ratio;
  overlap_ratio_.download(ratio);
  const HealthScore<Real> host_score{
      {host.position_radius.data(), host.velocity_inv_mass.data(), nullptr, nullptr}, ratio.data()};
  for (std::size_t i = 0; i < host.size(); ++i) {
    const Real s = host_score(i);
    if (s <= limit) continue;
    failure =
        HealthFailure{host.id[i], xyz(host.position_radius[i]), ratio[i], s == kNonFiniteScore};
    return true;
  }
  return false;
}

template <class Space, class P, class S>
Diagnostics ParticleSystem<Space, P, S>::local_diagnostics(double& contact_share) const {
  Diagnostics d;
  const std::size_t n = owned_;
  d.kinetic_translational = reduce_sum(Space{}, n, TranslationalEnergy<P>{state_view()});
  d.kinetic_rotational = reduce_sum(Space{}, n, RotationalEnergy<P>{state_view()});
  d.potential_gravity = reduce_sum(Space{}, n, GravityEnergy<P>{state_view(), setup_.gravity});
  DeviceArray<Real, Space> contacts(n), energy(n);
  const std::uint32_t bodies = wall_count() + meshes_.count();
  DeviceArray<Vec3, Space> body_force(n * bodies), mesh_torque(n * meshes_.count());
  law_->contact_terms(contact_inputs(), n,
                      {contacts.data(), energy.data(), body_force.data(), mesh_torque.data()});
  d.potential_elastic = reduce_sum(Space{}, n, ReadValue{energy.data()});
  if (!bonds_.empty()) d.potential_elastic += bonds_.half_energy(bond_rows(), n);
  contact_share = reduce_sum(Space{}, n, ReadValue{contacts.data()});
  d.contact_count = static_cast<std::uint64_t>(std::llround(contact_share));
  d.max_overlap_ratio = reduce_max(Space{}, n, Real(0), ReadValue{overlap_ratio_.data()});
  const std::vector<Vec3> body = column_sums(body_force, bodies);
  d.wall_force.assign(body.begin(), body.begin() + wall_count());
  d.mesh_force.assign(body.begin() + wall_count(), body.end());
  d.mesh_torque = column_sums(mesh_torque, meshes_.count());
  return d;
}

template <class Space, class P, class S>
std::vector<double> ParticleSystem<Space, P, S>::triangle_loads() const {
  std::size_t triangles = 0;
  for (std::uint32_t m = 0; m < meshes_.count(); ++m)
    triangles += meshes_.setup_triangles(m).size();
  const std::vector<std::uint32_t> triangle_of_entry = meshes_.entry_triangles();
  DeviceArray<Vec3, Space> entry_load(triangle_of_entry.size());
  law_->mesh_entry_loads(contact_inputs(), owned_, entry_load.data());
  std::vector<Vec3> entry_host;
  entry_load.download(entry_host);
  std::vector<double> load(3 * triangles, 0.0);
  for (std::size_t e = 0; e < entry_host.size(); ++e)
    for (int k = 0; k < 3; ++k) load[3 * triangle_of_entry[e] + k] += axis(entry_host[e], k);
  domain_.group().sum(load);
  return load;
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::sum_over_ranks(Diagnostics& d, double contact_share) const {
  std::vector<double> v = {contact_share, d.kinetic_translational, d.kinetic_rotational,
                           d.potential_gravity, d.potential_elastic};
  const auto append = [&v](const std::vector<Vec3>& loads) {
    for (const Vec3& f : loads) v.insert(v.end(), {f.x, f.y, f.z});
  };
  append(d.wall_force);
  append(d.mesh_force);
  append(d.mesh_torque);
  domain_.group().sum(v);
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
  d.max_overlap_ratio = domain_.group().max<double>(d.max_overlap_ratio);
}

template <class Space, class P, class S>
std::size_t ParticleSystem<Space, P, S>::carry_over_bytes() const {
  if (width_ == 0) return 0;
  if (!has_list_ || pair_history_.size() != neighbors_.pairs_kept() * width_)
    return carried_pairs_.bytes();
  settle_pair_history();
  return carried_pairs_.bytes_to_keep(owned_, neighbors_.offsets(), pair_history_.data());
}
}  // namespace gpudem
