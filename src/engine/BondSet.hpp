#pragma once
/// The parallel bonds of a particle system (docs/architecture.md, "Bonds"): one record of
/// bond_value::width values per neighbour-list entry, beside the contact history and carried
/// over a rebuild, through migration and checkpoints the same way, keyed by the partner's global
/// id. Each end keeps its own record of a bond and both advance it identically. Empty (no
/// arrays, no work) for a scene without [[bond]] tables. Include the backend's ParallelFor header
/// first.
#include <cstdint>
#include <vector>

#include "core/Scene.hpp"
#include "engine/BondKernels.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/HistoryCarryOver.hpp"
#include "engine/HostCopies.hpp"

namespace gpudem {

template <class Space, class S>
class BondSet {
 public:
  /// `clods` and `pairs`: per table, its clod spheres and listed pairs (EngineSetup).
  BondSet(const std::vector<BondSettings>& tables, const std::vector<std::vector<Real4>>& clods,
          const std::vector<std::vector<ListedBond>>& pairs)
      : empty_(tables.empty()), carried_(bond_value::width) {
    std::vector<BondParamsT<S>> types;
    std::vector<BondRule> rules;
    std::vector<Real4> all_clods;
    std::vector<BondKey> all_pairs;
    for (std::size_t k = 0; k < tables.size(); ++k) {
      const BondSettings& t = tables[k];
      host_types_.push_back(BondParams{t.young, shear_modulus(t.young, t.poisson), t.radius_factor,
                                       t.tensile_strength, t.shear_strength, t.damping_ratio});
      types.push_back(bond_params_cast<S>(host_types_.back()));
      const std::vector<Real4> mine = k < clods.size() ? clods[k] : std::vector<Real4>{};
      const std::vector<ListedBond> listed =
          k < pairs.size() ? pairs[k] : std::vector<ListedBond>{};
      rules.push_back(BondRule{t.a, t.b, t.gap, static_cast<std::uint32_t>(all_clods.size()),
                               static_cast<std::uint32_t>(mine.size()),
                               static_cast<std::uint32_t>(all_pairs.size()),
                               static_cast<std::uint32_t>(listed.size())});
      all_clods.insert(all_clods.end(), mine.begin(), mine.end());
      for (const ListedBond& b : listed) all_pairs.push_back({b.lower, b.higher});
    }
    types_.upload(types);
    rules_.upload(rules);
    clods_.upload(all_clods);
    pairs_.upload(all_pairs);
  }

  /// The parameters of [[bond]] table k.
  const BondParams& type(std::size_t k) const { return host_types_.at(k); }

  /// No [[bond]] tables: nothing is stored or computed.
  bool empty() const { return empty_; }

  /// The records, one per neighbour-list entry; null when empty.
  const S* records() const { return empty_ ? nullptr : records_.data(); }
  S* records() { return empty_ ? nullptr : records_.data(); }
  DeviceArray<S, Space>& record_array() { return records_; }
  const DeviceArray<S, Space>& record_array() const { return records_; }

  /// Makes the bonds of the rules on owned particles' list entries (each end its record).
  template <class P>
  void create(const BondRows<P>& rows, std::size_t owned) {
    parallel_for(
        Space{}, owned,
        bond_kernels::Create<P, S>{rows, rules_.data(), static_cast<std::uint32_t>(rules_.size()),
                                   clods_.data(), pairs_.data(), records_.data()});
  }

  /// Adds the owned particles' bond loads to force and torque, the bonds advanced by dt.
  template <class P>
  void add_loads(const BondRows<P>& rows, std::size_t owned, Real dt, Vec3T<S>* force,
                 Vec3T<S>* torque, bool torque_written) {
    parallel_for(Space{}, owned,
                 bond_kernels::AddLoads<P, S>{rows, types_.data(), records_.data(),
                                              static_cast<S>(dt), force, torque, torque_written});
  }

  /// Intact bonds whose ends this rank owns, each end counting ½.
  double half_count(const std::uint32_t* offsets, std::size_t owned) const {
    return reduce_sum(Space{}, owned, bond_kernels::HalfBonds<S>{offsets, records_.data()});
  }

  /// The owned ends' halves of the bonds' elastic energy [J].
  template <class P>
  double half_energy(const BondRows<P>& rows, std::size_t owned) const {
    return reduce_sum(Space{}, owned,
                      bond_kernels::HalfEnergy<P, S>{rows, types_.data(), records_.data()});
  }

  /// The widest surface gap of a bond of an owned particle [m].
  template <class P>
  double widest_gap(const BondRows<P>& rows, std::size_t owned) const {
    return reduce_max(Space{}, owned, Real(-INFINITY),
                      bond_kernels::WidestGap<P, S>{rows, records_.data()});
  }

  /// Keeps the owned particles' bonds keyed by partner id for the remap, then frees the records.
  template <class KeyOf>
  void keep(std::size_t owned, const std::uint32_t* offsets, KeyOf key_of) {
    carried_.keep(owned, offsets, records_.data(), key_of);
    release(records_);
  }

  /// The kept rows (ParticleSystem's migration appends the arrivals' rows).
  CsrRows<Space, ParticleId, S>& kept_rows() { return carried_.rows(); }
  const CsrRows<Space, ParticleId, S>& kept_rows() const { return carried_.rows(); }

  /// The new list's records: the kept bonds of each particle's previous row, or none (`carry`
  /// false: the first list); the kept rows are freed.
  template <class KeyOf>
  void remap(std::size_t owned, const std::uint32_t* offsets, std::size_t entries, KeyOf key_of,
             const std::uint32_t* previous_row, bool carry) {
    records_.resize(entries * bond_value::width);
    if (carry)
      carried_.remap(owned, offsets, key_of, previous_row, records_.data());
    else
      parallel_for(Space{}, records_.size(), Fill<S>{records_.data(), S{}});
    carried_.release();
  }

  std::size_t bytes() const { return records_.bytes() + carried_.bytes(); }

 private:
  bool empty_;
  DeviceArray<BondParamsT<S>, Space> types_;  ///< per [[bond]] table
  DeviceArray<BondRule, Space> rules_;        ///< per [[bond]] table
  DeviceArray<Real4, Space> clods_;           ///< the tables' clod spheres, table by table
  DeviceArray<BondKey, Space> pairs_;         ///< the tables' listed pairs, table by table
  DeviceArray<S, Space> records_;             ///< bond_value::width per neighbour-list entry
  HistoryCarryOver<Space, ParticleId, S> carried_;
  std::vector<BondParams> host_types_;  ///< types_ in Real, on the host
};

}  // namespace gpudem
