#pragma once
/// The law-dependent part of a time step, behind one interface: the particle system
/// (ParticleSystem.hpp) owns the particles, lists and history storage and hands a ForceCompute
/// pointers into them; the ForceCompute of a contact law (ContactForceCompute.hpp) runs the
/// contact sweep over them. Only the ForceCompute is instantiated per law: the particle system
/// is compiled once per backend and precision policy. Host code sees no law type here.
#include <cstddef>
#include <cstdint>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/ContactVisitor.hpp"
#include "engine/MeshWalls.hpp"
#include "engine/PeriodicBox.hpp"
#include "engine/PlaneWall.hpp"

namespace gpudem {

/// The contact history arrays of the particles: history_width() values of the law's scalar S
/// per neighbour-list entry, per (particle, plane wall) slot i·wall_count + w and per mesh
/// candidate-list entry; all null for a law without history. S is const where they are read.
template <class S>
struct HistoryPointers {
  S* pair;
  S* wall;
  S* mesh;
};

/// What a contact sweep reads, in the particle system's memory space: every particle array
/// (spins included: the law decides whether it reads them), the neighbour list, the walls and
/// meshes, and the history stored at the end of the last step.
template <class P, class S>
struct ContactInputs {
  ParticleView<P> particles;
  std::size_t owned;                      ///< particles with a list row
  const std::uint32_t* neighbor_offsets;  ///< CSR offsets, owned + 1
  const std::uint32_t* neighbor_index;    ///< full neighbour list
  std::uint64_t list_builds;              ///< the list's build count: a new count, a new list
  std::uint32_t material_count;
  const PlaneWall* walls;
  std::uint32_t wall_count;
  const std::uint32_t* wall_reach;  ///< per owned particle (WallReach.hpp); null without walls
  PeriodicBox box;
  MeshView mesh;
  HistoryPointers<const S> history;
  /// Per neighbour-list entry, the bond record (BondSet.hpp): a bonded pair has no contact;
  /// null without bonds.
  const S* bond_records = nullptr;
};

/// Where a force evaluation writes, per owned particle: force and torque in the law's scalar,
/// the worst overlap ratio (health check), and the advanced contact history; with pistons
/// (WallPistons.hpp), each particle's push on each plane wall, per slot i·wall_count + w.
template <class S>
struct ForceOutputs {
  Vec3T<S>* force;
  Vec3T<S>* torque;
  Real* overlap_ratio;
  HistoryPointers<S> history;
  S* wall_push = nullptr;  ///< [N] null: not wanted
};

/// Per-particle contact terms of the diagnostics (ContactTerms in Diagnostics.hpp).
struct ContactTermOutputs {
  Real* contacts;     ///< per particle: its share of the contact count
  Real* energy;       ///< per particle: its share of the elastic energy [J]
  Vec3* body_force;   ///< per (particle, body): plane walls, then meshes [N]
  Vec3* mesh_torque;  ///< per (particle, mesh) [N m]
};

/// The contact law of a particle system in memory space Space, state scalar P and law scalar S.
template <class Space, class P, class S>
class ForceCompute {
 public:
  virtual ~ForceCompute() = default;
  /// History values the law keeps per contact (0: none).
  virtual std::uint32_t history_width() const = 0;
  /// Whether the law reads spins and exerts torques.
  virtual bool needs_spin() const = 0;
  /// Bytes the law holds between steps: its pair constants and, on the host, the pair-once
  /// sweep's per-particle groups and sums.
  virtual std::size_t memory_bytes() const = 0;
  /// Contacts one thread evaluates at once: 8 where the host sweep runs in AVX-512 lanes
  /// (PairLanesForces.hpp), else 1.
  virtual int contact_lanes() const = 0;
  /// Forces of the particles subset[0, count) (all of 0..count when subset is null): contact
  /// forces plus gravity, torques, overlap ratios, the history advanced by dt into `out`.
  virtual void compute(const ContactInputs<P, S>& in, const Vec3& gravity, Real dt,
                       const ForceOutputs<S>& out, const std::uint32_t* subset,
                       std::size_t count) const = 0;
  /// After compute() on the host, which evaluates each pair once and advances only that end's
  /// history: copies it, mirrored, to the other end, so that every list entry holds its
  /// contact's history. Call, with the list those sweeps read, before anything else reads the
  /// history they wrote or the list changes. Nothing when nothing is pending (always on CUDA,
  /// whose sweeps advance both ends).
  virtual void mirror_pair_history(const ContactInputs<P, S>& in) const = 0;
  /// The diagnostics' contact terms of particles [0, count), the history read, not advanced: each
  /// owned pair at its lower index, where the last sweep left its history (no mirror needed).
  virtual void contact_terms(const ContactInputs<P, S>& in, std::size_t count,
                             const ContactTermOutputs& out) const = 0;
  /// The load of particles [0, count) on each mesh candidate-list entry (ContactTerms).
  virtual void mesh_entry_loads(const ContactInputs<P, S>& in, std::size_t count,
                                Vec3* entry_load) const = 0;
};

}  // namespace gpudem
