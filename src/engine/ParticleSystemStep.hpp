#pragma once
/// ParticleSystem's time step (ParticleSystem.hpp, which includes this file after the class):
/// kick, drift, the forces of the new positions and the pistons' push, the second kick; the
/// substeps of a base step and the speed that chooses them (dt = "adaptive").
#include "engine/ParticleSystem.hpp"

namespace gpudem {

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::compute_forces(const std::uint32_t* list, std::size_t count) {
  S* push = nullptr;
  if (!pistons_.empty()) {
    if (wall_push_.size() != owned_ * wall_count()) wall_push_.resize(owned_ * wall_count());
    push = wall_push_.data();
  }
  law_->compute(contact_inputs(), setup_.gravity, step_dt(),
                {force_.data(), torque_.data(), overlap_ratio_.data(), history_pointers(), push},
                list, count);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::set_substeps(std::uint32_t substeps) {
  if (clock_.substep != 0 || substeps == 0)
    throw std::logic_error("set_substeps: only between base steps, and at least one");
  clock_.substeps = substeps;
}

template <class Space, class P, class S>
double ParticleSystem<Space, P, S>::fastest_speed() const {
  const Real fastest2 =
      reduce_max(Space{}, owned_, Real(0), SquaredSpeed<P>{velocity_inv_mass_.data()});
  double fastest = domain_.group().max<double>(std::sqrt(fastest2));
  for (const WallMotion& m : pistons_.motion()) fastest = std::max(fastest, std::fabs(m.velocity));
  return fastest;
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::step() {
  Stopwatch watch;
  const Real dt = step_dt();
  const bool verlet = setup_.integrator == IntegratorKind::VelocityVerlet;
  kick(verlet ? Real(0.5) * dt : dt);
  drift(dt);
  clock_.advance();
  if (!meshes_.empty()) meshes_.set_time(clock_.time(setup_.dt));
  times_.integrate += lap(watch);
  const bool rebuild_now = needs_rebuild();
  times_.neighbors += lap(watch);
  if (rebuild_now) {
    rebuild();  // charges its own parts
    lap(watch);
    compute_forces_after_rebuild();
  } else if (domain_.ranks() > 1) {
    refresh_ghosts_computing_interior(watch);
  } else {
    compute_forces();
  }
  measure_pistons();
  times_.forces += lap(watch);
  if (verlet) kick(Real(0.5) * dt);
  times_.integrate += lap(watch);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::compute_forces_after_rebuild() {
  if (domain_.ranks() == 1) return compute_forces();
  compute_forces(ghost_rows_.interior(), ghost_rows_.interior_count());
  compute_forces(ghost_rows_.boundary(), ghost_rows_.boundary_count());
  add_bond_loads(step_dt());
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::kick(Real h) {
  if (spins())
    kick_with<true>(h);
  else
    kick_with<false>(h);
  pistons_.kick(h);
}

template <class Space, class P, class S>
template <bool kRotate>
void ParticleSystem<Space, P, S>::kick_with(Real h) {
  parallel_for(Space{}, owned_,
               Kick<kRotate, S, P>{velocity_inv_mass_.data(), angular_velocity_.data(),
                                   force_.data(), torque_.data(), position_radius_.data(), h,
                                   material_.data(), motion_.data()},
               LaunchSlot::integrate);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::drift(Real dt) {
  parallel_for(Space{}, owned_, Drift<P>{position_radius_.data(), velocity_inv_mass_.data(), dt},
               LaunchSlot::integrate);
  if (pistons_.empty()) return;
  pistons_.drift(dt);
  walls_.upload(pistons_.walls());
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::measure_pistons() {
  if (pistons_.empty()) return;
  std::vector<double> units(pistons_.count());
  for (std::size_t k = 0; k < units.size(); ++k)
    units[k] = reduce_sum(Space{}, owned_,
                          PushUnits<S>{wall_push_.data(), wall_count(), pistons_.piston(k).wall,
                                       pistons_.push_unit(k)});
  domain_.group().sum(units);
  for (std::size_t k = 0; k < units.size(); ++k) pistons_.set_push_units(k, units[k]);
}

}  // namespace gpudem
