#pragma once
/// Contact history independent of particle order and memory space: the tangential springs ξ
/// of the contacts that hold one, keyed by global particle ids (DESIGN §3). This is what
/// checkpoints store and what a later migration of particles between ranks will carry. The
/// engine converts it to and from its spring arrays (one per neighbour-list entry, one per
/// particle and wall) with collect_history and scatter_history on host copies.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

struct ContactHistory {
  /// Particle–particle springs, one per ordered pair: each particle owns the spring of its
  /// own side of a contact, so a touching pair appears twice (owner, partner) and (partner,
  /// owner). Entry k is (pair_owner[k], pair_partner[k], pair_spring[k]).
  std::vector<ParticleId> pair_owner;
  std::vector<ParticleId> pair_partner;
  std::vector<Vec3> pair_spring;  ///< [m]
  /// Particle–wall springs: entry k is (wall_owner[k], wall_index[k], wall_spring[k]), the
  /// wall index being its position in Scene::walls.
  std::vector<ParticleId> wall_owner;
  std::vector<std::uint32_t> wall_index;
  std::vector<Vec3> wall_spring;  ///< [m]

  void add_pair(ParticleId owner, ParticleId partner, Vec3 spring) {
    pair_owner.push_back(owner);
    pair_partner.push_back(partner);
    pair_spring.push_back(spring);
  }
  void add_wall(ParticleId owner, std::uint32_t wall, Vec3 spring) {
    wall_owner.push_back(owner);
    wall_index.push_back(wall);
    wall_spring.push_back(spring);
  }
};

/// Where the springs of an engine live, as host copies: global ids in the engine's particle
/// order, the full neighbour list in CSR form (the partners of particle i are slots
/// neighbors[offsets[i] .. offsets[i + 1])) and the number of walls. Pair spring e belongs to
/// list entry e, wall spring i·wall_count + w to particle i and wall w.
struct ContactSlots {
  std::vector<ParticleId> id;
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> neighbors;
  std::uint32_t wall_count = 0;
};

/// The non-zero springs of `pair_spring` and `wall_spring`, keyed by global ids.
inline ContactHistory collect_history(const ContactSlots& slots,
                                      const std::vector<Vec3>& pair_spring,
                                      const std::vector<Vec3>& wall_spring) {
  const auto nonzero = [](const Vec3& s) { return s.x != 0 || s.y != 0 || s.z != 0; };
  ContactHistory history;
  for (std::size_t i = 0; i < slots.id.size(); ++i) {
    for (std::uint32_t e = slots.offsets[i]; e < slots.offsets[i + 1]; ++e)
      if (nonzero(pair_spring[e]))
        history.add_pair(slots.id[i], slots.id[slots.neighbors[e]], pair_spring[e]);
    for (std::uint32_t w = 0; w < slots.wall_count; ++w)
      if (nonzero(wall_spring[i * slots.wall_count + w]))
        history.add_wall(slots.id[i], w, wall_spring[i * slots.wall_count + w]);
  }
  return history;
}

namespace history_detail {

[[noreturn]] inline void reject(const std::string& what) {
  throw std::invalid_argument("contact history: " + what);
}

inline std::uint32_t slot_of(const std::unordered_map<ParticleId, std::uint32_t>& slots,
                             ParticleId id) {
  const auto found = slots.find(id);
  if (found == slots.end()) reject("particle id " + std::to_string(id) + " is not in the engine");
  return found->second;
}

/// The list entry of `owner` (a slot) whose partner has global id `partner`.
inline std::uint32_t pair_entry(const ContactSlots& slots, std::uint32_t owner,
                                ParticleId partner) {
  for (std::uint32_t e = slots.offsets[owner]; e < slots.offsets[owner + 1]; ++e)
    if (slots.id[slots.neighbors[e]] == partner) return e;
  reject("particles " + std::to_string(slots.id[owner]) + " and " + std::to_string(partner) +
         " are not neighbours");
}

inline void check_lengths(const ContactHistory& h) {
  if (h.pair_partner.size() != h.pair_owner.size() || h.pair_spring.size() != h.pair_owner.size() ||
      h.wall_index.size() != h.wall_owner.size() || h.wall_spring.size() != h.wall_owner.size())
    reject("the arrays of one kind of contact differ in length");
}

}  // namespace history_detail

/// Spring arrays for `slots` holding the springs of `history` and zero elsewhere. Throws
/// std::invalid_argument for an unknown particle id, a pair that is not in the neighbour list
/// or a wall index >= slots.wall_count.
inline void scatter_history(const ContactSlots& slots, const ContactHistory& history,
                            std::vector<Vec3>& pair_spring, std::vector<Vec3>& wall_spring) {
  using namespace history_detail;
  check_lengths(history);
  std::unordered_map<ParticleId, std::uint32_t> slot;
  for (std::size_t i = 0; i < slots.id.size(); ++i)
    slot[slots.id[i]] = static_cast<std::uint32_t>(i);
  pair_spring.assign(slots.neighbors.size(), Vec3{});
  wall_spring.assign(slots.id.size() * slots.wall_count, Vec3{});
  for (std::size_t k = 0; k < history.pair_owner.size(); ++k) {
    const std::uint32_t owner = slot_of(slot, history.pair_owner[k]);
    pair_spring[pair_entry(slots, owner, history.pair_partner[k])] = history.pair_spring[k];
  }
  for (std::size_t k = 0; k < history.wall_owner.size(); ++k) {
    if (history.wall_index[k] >= slots.wall_count)
      reject("wall index " + std::to_string(history.wall_index[k]) + " but there are " +
             std::to_string(slots.wall_count) + " walls");
    const std::size_t owner = slot_of(slot, history.wall_owner[k]);
    wall_spring[owner * slots.wall_count + history.wall_index[k]] = history.wall_spring[k];
  }
}

}  // namespace gpudem
