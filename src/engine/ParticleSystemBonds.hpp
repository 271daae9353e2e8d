#pragma once
/// ParticleSystem's parallel bonds (ParticleSystem.hpp, which includes this file after the
/// class; BondSet.hpp): made at a run's start or taken from its bed, their loads added after
/// the contact forces, their reach checked before each rebuild, read and set as keyed records
/// for checkpoints.
#include <cstdio>
#include <set>
#include <string>
#include <tuple>

#include "engine/ParticleSystem.hpp"

namespace gpudem {

/// `slots` with its pair entries only: bond records are kept per neighbour-list entry.
inline ContactSlots pair_slots_only(ContactSlots slots) {
  slots.wall_count = 0;
  slots.mesh_offsets.clear();
  slots.mesh_triangles.clear();
  return slots;
}

template <class Space, class P, class S>
BondRows<P> ParticleSystem<Space, P, S>::bond_rows() const {
  return {state_view(), id_.data(), neighbors_.offsets(), neighbors_.neighbors(), setup_.box};
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::add_bond_loads(Real dt) {
  if (bonds_.empty()) return;
  bonds_.add_loads(bond_rows(), owned_, dt, force_.data(), torque_.data(), law_->needs_spin());
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::create_bonds() {
  if (bonds_.empty()) return;
  bonds_.create(bond_rows(), owned_);
  check_listed_bonds();
  const double widest = domain_.group().max<double>(bonds_.widest_gap(bond_rows(), owned_));
  if (widest > 0.5 * setup_.skin)
    throw std::invalid_argument(
        "a listed pair was bonded across a surface gap of " + std::to_string(widest) +
        " m, more than half the neighbour skin (" + std::to_string(setup_.skin) +
        " m) within which bonds hold: list closer pairs or raise neighbor.skin");
  bonds_made_ = static_cast<std::uint64_t>(
      std::llround(domain_.group().sum<double>(bonds_.half_count(neighbors_.offsets(), owned_))));
  evaluate_with_bond_loads();
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::continue_bonds(ContactHistory bonds, std::uint64_t made) {
  set_bonds(std::move(bonds), made);
  evaluate_with_bond_loads();
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::evaluate_with_bond_loads() {
  compute_forces(nullptr, owned_);
  add_bond_loads(0);  // the bonds' loads as they stand, nothing advanced
  measure_pistons();
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::check_bond_reach() const {
  const double widest = domain_.group().max<double>(bonds_.widest_gap(bond_rows(), owned_));
  if (widest < 0.9 * setup_.skin) return;
  char text[320];
  std::snprintf(text, sizeof text,
                "a bond stretched to a surface gap of %.4g m, near the neighbour reach (skin "
                "%.4g m) beyond which its ends would lose each other: raise neighbor.skin, or "
                "give the [[bond]] a tensile_strength that breaks it before",
                widest, setup_.skin);
  throw std::runtime_error(text);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::check_listed_bonds() const {
  std::uint64_t listed = 0;
  for (const std::vector<ListedBond>& pairs : setup_.bond_pairs) listed += pairs.size();
  if (listed == 0) return;
  ContactHistory made;
  std::uint64_t count = 0;
  get_bonds(made, count);
  std::set<std::tuple<Real, ParticleId, ParticleId>> here;  // (table, lower, higher)
  for (std::size_t k = 0; k < made.pair_owner.size(); ++k)
    here.insert({made.pair_values[k * made.width + bond_value::type], made.pair_owner[k],
                 made.pair_partner[k]});
  std::vector<ParticleId> ids;
  id_.download(ids);
  const std::set<ParticleId> owned(ids.begin(), ids.begin() + owned_);
  std::uint64_t lowers_here = 0;
  std::string problem;
  for (std::size_t t = 0; t < setup_.bond_pairs.size(); ++t)
    for (const ListedBond& b : setup_.bond_pairs[t]) {
      if (owned.count(b.lower) == 0) continue;
      ++lowers_here;
      if (problem.empty() && here.count({Real(t), b.lower, b.higher}) == 0)
        problem = setup_.bonds[t].pairs + ":" + std::to_string(b.line) + ": the pair " +
                  std::to_string(b.lower) + ", " + std::to_string(b.higher) +
                  " was not bonded: particle " + std::to_string(b.higher) +
                  " is not in the scene, or the two are more than the neighbour skin apart, or "
                  "an earlier [[bond]] table bonded them";
    }
  throw_first_problem(problem, domain_);
  const std::uint64_t found = domain_.group().sum<std::uint64_t>(lowers_here);
  if (found != listed)
    throw std::invalid_argument(std::to_string(listed - found) + " of the " +
                                std::to_string(listed) +
                                " pairs the [[bond]] tables list name a particle id (the lower "
                                "of the pair) that the scene does not have");
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::get_bonds(ContactHistory& bonds, std::uint64_t& made) const {
  made = bonds_made_;
  bonds = ContactHistory{};
  if (bonds_.empty()) return;
  bonds.width = bond_value::width;
  if (!has_list_) return;
  HistoryValues values;
  values.pair = history_in_real(bonds_.record_array());
  bonds = collect_history(pair_slots_only(contact_slots()), bond_value::width, values);
}

template <class Space, class P, class S>
void ParticleSystem<Space, P, S>::set_bonds(ContactHistory share, std::uint64_t made) {
  const std::uint32_t width = bonds_.empty() ? 0 : bond_value::width;
  if (share.empty()) share.width = width;
  const HistoryValues values =
      scatter_share(std::move(share), pair_slots_only(contact_slots()), width);
  bonds_made_ = made;
  if (!bonds_.empty()) upload_history(values.pair, bonds_.record_array());
}

template <class Space, class P, class S>
BondLines ParticleSystem<Space, P, S>::bond_lines() const {
  BondLines lines;
  if (bonds_.empty() || !has_list_) return lines;
  const std::vector<Real4> x = download_in_real(position_radius_);
  std::vector<ParticleId> id;
  id_.download(id);
  const std::vector<std::uint32_t> offsets =
      download_values<Space>(neighbors_.offsets(), owned_ + 1);
  const std::vector<std::uint32_t> partner =
      download_values<Space>(neighbors_.neighbors(), offsets.back());
  const std::vector<S> stored =
      download_values<Space>(bonds_.records(), offsets.back() * bond_value::width);
  for (std::size_t i = 0; i < owned_; ++i)
    for (std::uint32_t e = offsets[i]; e < offsets[i + 1]; ++e) {
      const std::uint32_t j = partner[e];
      double record[bond_value::width];
      for (std::uint32_t v = 0; v < bond_value::width; ++v)
        record[v] = stored[std::size_t(e) * bond_value::width + v];
      if (record[bond_value::rest_length] == 0 || id[i] > id[j]) continue;
      const Vec3 d = setup_.box.minimum_image(xyz(x[j]) - xyz(x[i]));
      const BondParams& p = bonds_.type(static_cast<std::size_t>(record[bond_value::type]));
      const double stretch = norm(d) - record[bond_value::rest_length];
      const BondReading reading = read_bond(p, std::min(x[i].w, x[j].w), stretch, record);
      lines.ids.insert(lines.ids.end(), {id[i], id[j]});
      lines.points.insert(lines.points.end(), {xyz(x[i]), xyz(x[i]) + d});
      lines.normal_force.push_back(reading.normal_force);
      lines.strength_used.push_back(reading.stress.strength_used(p));
    }
  return lines;
}

}  // namespace gpudem
