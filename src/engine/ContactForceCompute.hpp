#pragma once
/// The ForceCompute of one contact law (ForceCompute.hpp): the law's pair constants in the
/// system's memory space, and the contact sweeps (forces, diagnostics' terms, mesh loads) as
/// launches of the law's functors; the host's force sweeps evaluate each pair once
/// (PairOnceSweep). The history arrays the particle system stores as flat values
/// are read as the law's records (ContactState: history_size values, nothing else). Include the
/// backend's ParallelFor header first.
#include <type_traits>
#include <vector>

#include "core/ContactParams.hpp"
#include "engine/ContactForces.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/Diagnostics.hpp"
#include "engine/ForceCompute.hpp"
#include "engine/HostCopies.hpp"
#include "engine/LaunchTuning.hpp"
#include "engine/PairOnceSweep.hpp"

namespace gpudem {

template <class Space, class Law, class P>
class ContactForceCompute final : public ForceCompute<Space, P, typename Law::Scalar> {
  using S = typename Law::Scalar;
  using State = typename Law::State;
  static_assert(Law::history_size == 0 || sizeof(State) == Law::history_size * sizeof(S),
                "a history record is the law's history_size values, nothing else");

 public:
  /// `pair_params`: the constants of each material pair, material_count² entries, row-major;
  /// `exact_units` and `host_lanes`: the units of the host sweep's integer sums and the most
  /// contacts it evaluates at once (PairOnceSweep).
  ContactForceCompute(const std::vector<ContactPairParams>& pair_params,
                      const ExactUnits& exact_units, int host_lanes)
      : pair_once_(exact_units, host_lanes) {
    pair_params_.upload(converted(pair_params, params_cast<S>));
  }

  std::uint32_t history_width() const override { return Law::history_size; }
  bool needs_spin() const override { return Law::needs_spin; }
  std::size_t memory_bytes() const override { return pair_params_.bytes() + pair_once_.bytes(); }
  int contact_lanes() const override {
    return std::is_same_v<Space, HostSpace> ? pair_once_.contact_lanes() : 1;
  }

  /// On the host each pair is evaluated once and the pair loads are summed as integers
  /// (PairOnceForces.hpp).
  void compute(const ContactInputs<P, S>& in, const Vec3& gravity, Real dt,
               const ForceOutputs<S>& out, const std::uint32_t* subset,
               std::size_t count) const override {
    const ForceSweep<Law, P> sweep{
        view(in),   scene(in),         gravity,       dt,     records(out.history), out.force,
        out.torque, out.overlap_ratio, out.wall_push, subset,
    };
    if constexpr (std::is_same_v<Space, HostSpace>)
      pair_once_.run(PairOnceForces<Law, P>{sweep}, count,
                     {in.owned, in.neighbor_offsets, in.neighbor_index, in.list_builds});
    else
      parallel_for(Space{}, count, ComputeForces<Law, P>{sweep}, LaunchSlot::forces);
  }

  void mirror_pair_history(const ContactInputs<P, S>& in) const override {
    if constexpr (std::is_same_v<Space, HostSpace>)
      pair_once_.mirror({in.owned, in.neighbor_offsets, in.neighbor_index, in.list_builds});
  }

  void contact_terms(const ContactInputs<P, S>& in, std::size_t count,
                     const ContactTermOutputs& out) const override {
    parallel_for(Space{}, count,
                 ContactTerms<Law, P>{view(in), scene(in), owned(in), out.contacts, out.energy,
                                      out.body_force, out.mesh_torque, nullptr});
  }

  void mesh_entry_loads(const ContactInputs<P, S>& in, std::size_t count,
                        Vec3* entry_load) const override {
    parallel_for(Space{}, count,
                 ContactTerms<Law, P>{view(in), scene(in), owned(in), nullptr, nullptr, nullptr,
                                      nullptr, entry_load});
  }

 private:
  /// The particle arrays the law reads; spins only when it needs them.
  static ParticleView<P> view(const ContactInputs<P, S>& in) {
    if constexpr (Law::needs_spin)
      return in.particles;
    else
      return without_spin(in.particles);
  }

  /// The history values as the law's records, written.
  static HistoryArrays<Law> records(const HistoryPointers<S>& h) {
    return {reinterpret_cast<State*>(h.pair), reinterpret_cast<State*>(h.wall),
            reinterpret_cast<State*>(h.mesh)};
  }

  /// The history values as the law's records, read.
  static const State* records(const S* values) { return reinterpret_cast<const State*>(values); }

  static std::uint32_t owned(const ContactInputs<P, S>& in) {
    return static_cast<std::uint32_t>(in.owned);
  }

  ContactScene<Law> scene(const ContactInputs<P, S>& in) const {
    return ContactScene<Law>{in.neighbor_offsets,
                             in.neighbor_index,
                             pair_params_.data(),
                             in.material_count,
                             in.walls,
                             in.wall_count,
                             in.box,
                             in.wall_reach,
                             records(in.history.pair),
                             records(in.history.wall),
                             in.mesh,
                             records(in.history.mesh),
                             in.bond_records};
  }

  DeviceArray<typename Law::Params, Space> pair_params_;
  mutable PairOnceSweep<Law, P> pair_once_;  ///< the host's sweeps (unused on CUDA)
};

}  // namespace gpudem
