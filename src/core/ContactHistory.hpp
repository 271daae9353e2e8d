#pragma once
/// Contact history independent of particle order and memory space: the history values of
/// the contacts that hold any (tangential spring, sliding flag, rolling spring, as the
/// contact law declares), keyed by global particle ids (docs/architecture.md, "Contact history").
/// This is what checkpoints store and what a later migration of particles between ranks will carry.
/// The engine converts it to and from its history arrays (one record per neighbour-list entry, one
/// per particle and wall) with collect_history and scatter_history on host copies.
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
  /// Particle–mesh records: (mesh_owner[k], mesh_triangle[k], mesh_values[k·width .. +width)),
  /// the triangle index counting over the scene's meshes in order (each mesh's non-degenerate
  /// triangles in file order).
  std::vector<ParticleId> mesh_owner;
  std::vector<std::uint32_t> mesh_triangle;
  std::vector<Real> mesh_values;

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
  void add_mesh(ParticleId owner, std::uint32_t triangle, const Real* values) {
    mesh_owner.push_back(owner);
    mesh_triangle.push_back(triangle);
    mesh_values.insert(mesh_values.end(), values, values + width);
  }
  bool empty() const { return pair_owner.empty() && wall_owner.empty() && mesh_owner.empty(); }
  /// True when each kind of record has its keys and `width` values per record in full.
  bool lengths_agree() const {
    return pair_partner.size() == pair_owner.size() &&
           pair_values.size() == pair_owner.size() * width &&
           wall_index.size() == wall_owner.size() &&
           wall_values.size() == wall_owner.size() * width &&
           mesh_triangle.size() == mesh_owner.size() &&
           mesh_values.size() == mesh_owner.size() * width;
  }
};

/// Where the history records of an engine live, as host copies: global ids in the engine's
/// particle order (its `rows` owned particles, then the ghost copies of other ranks'), the
/// neighbour list of the owned particles in CSR form (the partners of particle i are slots
/// neighbors[offsets[i] .. offsets[i + 1])), the number of walls and the mesh candidate lists
/// (triangles mesh_triangles[mesh_offsets[i] .. mesh_offsets[i + 1]) for particle i). Pair
/// record e belongs to list entry e, wall record i·wall_count + w to owned particle i and wall
/// w, mesh record e to candidate entry e.
struct ContactSlots {
  std::vector<ParticleId> id;
  std::size_t rows = 0;  ///< owned particles: the first `rows` of id
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> neighbors;
  std::uint32_t wall_count = 0;
  std::vector<std::uint32_t> mesh_offsets;  ///< rows + 1 values, or none without meshes
  std::vector<std::uint32_t> mesh_triangles;
  std::uint32_t triangle_count = 0;  ///< triangles in all meshes
};

/// An engine's history values as flat host arrays, `width` values per record: one record per
/// neighbour-list entry, per (particle, wall) and per mesh candidate entry (ContactSlots).
struct HistoryValues {
  std::vector<Real> pair;
  std::vector<Real> wall;
  std::vector<Real> mesh;
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

/// The candidate entry of `owner` (a slot) on triangle `triangle`.
inline std::uint32_t mesh_entry(const ContactSlots& slots, std::uint32_t owner,
                                std::uint32_t triangle) {
  if (triangle >= slots.triangle_count)
    reject("triangle index " + std::to_string(triangle) + " but the meshes have " +
           std::to_string(slots.triangle_count) + " triangles");
  for (std::uint32_t e = slots.mesh_offsets[owner]; e < slots.mesh_offsets[owner + 1]; ++e)
    if (slots.mesh_triangles[e] == triangle) return e;
  reject("particle " + std::to_string(slots.id[owner]) + " is not near triangle " +
         std::to_string(triangle));
}

/// Copies record k of `from` (`width` values) to record `to` of `into`.
inline void copy_record(const std::vector<Real>& from, std::size_t k, std::vector<Real>& into,
                        std::size_t to, std::uint32_t width) {
  for (std::uint32_t v = 0; v < width; ++v) into[to * width + v] = from[k * width + v];
}

}  // namespace history_detail

/// The records of `values` that are not all zero, keyed by global ids (and triangle index).
inline ContactHistory collect_history(const ContactSlots& slots, std::uint32_t width,
                                      const HistoryValues& values) {
  using history_detail::nonzero;
  ContactHistory history;
  history.width = width;
  if (width == 0) return history;
  for (std::size_t i = 0; i < slots.rows; ++i) {
    for (std::uint32_t e = slots.offsets[i]; e < slots.offsets[i + 1]; ++e)
      if (nonzero(&values.pair[e * width], width))
        history.add_pair(slots.id[i], slots.id[slots.neighbors[e]], &values.pair[e * width]);
    for (std::uint32_t w = 0; w < slots.wall_count; ++w) {
      const Real* record = &values.wall[(i * slots.wall_count + w) * width];
      if (nonzero(record, width)) history.add_wall(slots.id[i], w, record);
    }
    if (slots.mesh_offsets.empty()) continue;
    for (std::uint32_t e = slots.mesh_offsets[i]; e < slots.mesh_offsets[i + 1]; ++e)
      if (nonzero(&values.mesh[e * width], width))
        history.add_mesh(slots.id[i], slots.mesh_triangles[e], &values.mesh[e * width]);
  }
  return history;
}

/// `history` with `value` appended to every record (width + 1): the records of a law whose
/// history is another's followed by one more value, e.g. JKR's formed flag after the springs.
inline ContactHistory with_value_appended(const ContactHistory& history, Real value) {
  ContactHistory out = history;
  out.width = history.width + 1;
  const auto extend = [&](const std::vector<Real>& in, std::size_t records, std::vector<Real>& to) {
    to.clear();
    for (std::size_t k = 0; k < records; ++k) {
      to.insert(to.end(), in.begin() + k * history.width, in.begin() + (k + 1) * history.width);
      to.push_back(value);
    }
  };
  extend(history.pair_values, history.pair_owner.size(), out.pair_values);
  extend(history.wall_values, history.wall_owner.size(), out.wall_values);
  extend(history.mesh_values, history.mesh_owner.size(), out.mesh_values);
  return out;
}

/// Flat history arrays (`width` values per contact) for `slots`, holding the records of
/// `history` and zero elsewhere. Throws std::invalid_argument for a history of another width
/// (written under another contact law), an unknown particle id, a pair that is not in the
/// neighbour list, a wall index >= slots.wall_count, a triangle index >= slots.triangle_count
/// or a triangle that is not in its particle's candidate list.
inline HistoryValues scatter_history(const ContactSlots& slots, std::uint32_t width,
                                     const ContactHistory& history) {
  using namespace history_detail;
  if (history.width != width && !history.empty())
    reject("it holds " + std::to_string(history.width) +
           " values per contact but this contact law keeps " + std::to_string(width));
  if (!history.lengths_agree()) reject("the arrays of one kind of contact differ in length");
  std::unordered_map<ParticleId, std::uint32_t> slot;
  for (std::size_t i = 0; i < slots.rows; ++i) slot[slots.id[i]] = static_cast<std::uint32_t>(i);
  HistoryValues values;
  values.pair.assign(slots.neighbors.size() * width, 0);
  values.wall.assign(slots.rows * slots.wall_count * width, 0);
  values.mesh.assign(slots.mesh_triangles.size() * width, 0);
  for (std::size_t k = 0; k < history.pair_owner.size(); ++k) {
    const std::uint32_t owner = slot_of(slot, history.pair_owner[k]);
    copy_record(history.pair_values, k, values.pair,
                pair_entry(slots, owner, history.pair_partner[k]), width);
  }
  for (std::size_t k = 0; k < history.wall_owner.size(); ++k) {
    if (history.wall_index[k] >= slots.wall_count)
      reject("wall index " + std::to_string(history.wall_index[k]) + " but there are " +
             std::to_string(slots.wall_count) + " walls");
    const std::size_t record =
        slot_of(slot, history.wall_owner[k]) * slots.wall_count + history.wall_index[k];
    copy_record(history.wall_values, k, values.wall, record, width);
  }
  for (std::size_t k = 0; k < history.mesh_owner.size(); ++k) {
    const std::uint32_t owner = slot_of(slot, history.mesh_owner[k]);
    copy_record(history.mesh_values, k, values.mesh,
                mesh_entry(slots, owner, history.mesh_triangle[k]), width);
  }
  return values;
}

}  // namespace gpudem
