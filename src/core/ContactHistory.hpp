#pragma once
/// Contact history independent of particle order and memory space: the history values of
/// the contacts that hold any (tangential spring, sliding flag, rolling spring, as the
/// contact law declares), keyed by global particle ids (DESIGN §3). This is what checkpoints
/// store and what a later migration of particles between ranks will carry. The engine
/// converts it to and from its history arrays (one record per neighbour-list entry, one per
/// particle and wall) with collect_history and scatter_history on host copies.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/Config.hpp"

namespace gpudem {

struct ContactHistory {
  /// History values per contact: the contact law's history size (0: the law keeps none).
  std::uint32_t width = 0;
  /// Particle–particle records, one per ordered pair: each particle owns the history of its
  /// own side of a contact, so a touching pair appears twice (owner, partner) and (partner,
  /// owner). Record k is (pair_owner[k], pair_partner[k], pair_values[k·width .. +width)).
  std::vector<ParticleId> pair_owner;
  std::vector<ParticleId> pair_partner;
  std::vector<Real> pair_values;
  /// Particle–wall records: (wall_owner[k], wall_index[k], wall_values[k·width .. +width)),
  /// the wall index being its position in Scene::walls.
  std::vector<ParticleId> wall_owner;
  std::vector<std::uint32_t> wall_index;
  std::vector<Real> wall_values;

  void add_pair(ParticleId owner, ParticleId partner, const Real* values) {
    pair_owner.push_back(owner);
    pair_partner.push_back(partner);
    pair_values.insert(pair_values.end(), values, values + width);
  }
  void add_wall(ParticleId owner, std::uint32_t wall, const Real* values) {
    wall_owner.push_back(owner);
    wall_index.push_back(wall);
    wall_values.insert(wall_values.end(), values, values + width);
  }
};

/// Where the history records of an engine live, as host copies: global ids in the engine's
/// particle order (its `rows` owned particles, then the ghost copies of other ranks'), the
/// neighbour list of the owned particles in CSR form (the partners of particle i are slots
/// neighbors[offsets[i] .. offsets[i + 1])) and the number of walls. Pair record e belongs to
/// list entry e, wall record i·wall_count + w to owned particle i and wall w.
struct ContactSlots {
  std::vector<ParticleId> id;
  std::size_t rows = 0;  ///< owned particles: the first `rows` of id
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> neighbors;
  std::uint32_t wall_count = 0;
};

namespace history_detail {

[[noreturn]] inline void reject(const std::string& what) {
  throw std::invalid_argument("contact history: " + what);
}

inline bool nonzero(const Real* values, std::uint32_t width) {
  for (std::uint32_t k = 0; k < width; ++k)
    if (values[k] != 0) return true;
  return false;
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
  if (h.pair_partner.size() != h.pair_owner.size() ||
      h.pair_values.size() != h.pair_owner.size() * h.width ||
      h.wall_index.size() != h.wall_owner.size() ||
      h.wall_values.size() != h.wall_owner.size() * h.width)
    reject("the arrays of one kind of contact differ in length");
}

}  // namespace history_detail

/// The records of `pair_values` and `wall_values` (`width` values per contact, flat) that
/// are not all zero, keyed by global ids.
inline ContactHistory collect_history(const ContactSlots& slots, std::uint32_t width,
                                      const std::vector<Real>& pair_values,
                                      const std::vector<Real>& wall_values) {
  using history_detail::nonzero;
  ContactHistory history;
  history.width = width;
  if (width == 0) return history;
  for (std::size_t i = 0; i < slots.rows; ++i) {
    for (std::uint32_t e = slots.offsets[i]; e < slots.offsets[i + 1]; ++e)
      if (nonzero(&pair_values[e * width], width))
        history.add_pair(slots.id[i], slots.id[slots.neighbors[e]], &pair_values[e * width]);
    for (std::uint32_t w = 0; w < slots.wall_count; ++w) {
      const Real* values = &wall_values[(i * slots.wall_count + w) * width];
      if (nonzero(values, width)) history.add_wall(slots.id[i], w, values);
    }
  }
  return history;
}

/// Flat history arrays (`width` values per contact) for `slots`, holding the records of
/// `history` and zero elsewhere. Throws std::invalid_argument for a history of another width
/// (written under another contact law), an unknown particle id, a pair that is not in the
/// neighbour list or a wall index >= slots.wall_count.
inline void scatter_history(const ContactSlots& slots, std::uint32_t width,
                            const ContactHistory& history, std::vector<Real>& pair_values,
                            std::vector<Real>& wall_values) {
  using namespace history_detail;
  const bool empty = history.pair_owner.empty() && history.wall_owner.empty();
  if (history.width != width && !empty)
    reject("it holds " + std::to_string(history.width) +
           " values per contact but this contact law keeps " + std::to_string(width));
  check_lengths(history);
  std::unordered_map<ParticleId, std::uint32_t> slot;
  for (std::size_t i = 0; i < slots.rows; ++i) slot[slots.id[i]] = static_cast<std::uint32_t>(i);
  pair_values.assign(slots.neighbors.size() * width, 0);
  wall_values.assign(slots.rows * slots.wall_count * width, 0);
  for (std::size_t k = 0; k < history.pair_owner.size(); ++k) {
    const std::uint32_t owner = slot_of(slot, history.pair_owner[k]);
    const std::size_t e = pair_entry(slots, owner, history.pair_partner[k]);
    for (std::uint32_t v = 0; v < width; ++v)
      pair_values[e * width + v] = history.pair_values[k * width + v];
  }
  for (std::size_t k = 0; k < history.wall_owner.size(); ++k) {
    if (history.wall_index[k] >= slots.wall_count)
      reject("wall index " + std::to_string(history.wall_index[k]) + " but there are " +
             std::to_string(slots.wall_count) + " walls");
    const std::size_t record = slot_of(slot, history.wall_owner[k]) * slots.wall_count +
                               history.wall_index[k];
    for (std::uint32_t v = 0; v < width; ++v)
      wall_values[record * width + v] = history.wall_values[k * width + v];
  }
}

}  // namespace gpudem
