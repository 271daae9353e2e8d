#pragma once
/// The per-particle kernels of parallel bonds (core/contact/ParallelBond.hpp): bonds made along
/// the neighbour list, their loads gathered by each end (one thread per owned particle, its bonds
/// in its list order, no atomics), and the reductions of the diagnostics. A bond's values are a
/// record of bond_value::width values of the law's scalar S per neighbour-list entry; a record
/// whose rest length is 0 holds no bond.
#include <cstdint>

#include "core/Config.hpp"
#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"
#include "core/contact/ParallelBond.hpp"
#include "engine/ContactVisitor.hpp"
#include "engine/PeriodicBox.hpp"

namespace gpudem {

/// What the bond kernels read: every particle array in Real, the owned particles' list rows and
/// the ids that orient each bond.
template <class P>
struct BondRows {
  ParticleView<P> particles;
  const ParticleId* id;
  const std::uint32_t* offsets;
  const std::uint32_t* neighbors;
  PeriodicBox box;
};

/// The bond between a and b seen from a to b, its stretch L − L₀ formed in Real.
template <class S, class P>
GPUDEM_HD BondGeometry<S> bond_geometry(const BondRows<P>& rows, std::uint32_t a, std::uint32_t b,
                                        S rest_length) {
  const ParticleView<P>& p = rows.particles;
  const Real4 xa = p.position(a), xb = p.position(b), va = p.velocity(a), vb = p.velocity(b);
  const Vec3 wa = p.spin(a), wb = p.spin(b);
  const Vec3 d = rows.box.minimum_image(xyz(xb) - xyz(xa));
  const Real length = norm(d);
  const Vec3 n = (Real(1) / length) * d;
  const Real arm_a = length * xa.w / (xa.w + xb.w), arm_b = length - arm_a;
  const Real inertia_a = sphere_inertia(xa.w, va.w), inertia_b = sphere_inertia(xb.w, vb.w);
  BondGeometry<S> g;
  g.normal = vec_cast<S>(n);
  g.stretch = static_cast<S>(length - static_cast<Real>(rest_length));
  g.arm_a = static_cast<S>(arm_a);
  g.arm_b = static_cast<S>(arm_b);
  g.min_radius = static_cast<S>(xa.w < xb.w ? xa.w : xb.w);
  g.velocity = vec_cast<S>((xyz(vb) + cross(wb, -arm_b * n)) - (xyz(va) + cross(wa, arm_a * n)));
  g.spin = vec_cast<S>(wb - wa);
  g.reduced_mass = static_cast<S>(Real(1) / (va.w + vb.w));
  g.reduced_inertia = static_cast<S>(inertia_a * inertia_b / (inertia_a + inertia_b));
  return g;
}

/// A bond rule of the scene as the kernels read it: the two materials, the largest gap and the
/// table's clods, clods[first_clod .. first_clod + clod_count) (none: bonds anywhere); or the
/// pairs it lists, pairs[first_pair .. first_pair + pair_count), ordered (none: by materials).
struct BondRule {
  MaterialId a, b;
  Real gap;
  std::uint32_t first_clod = 0, clod_count = 0;
  std::uint32_t first_pair = 0, pair_count = 0;
};

/// The ids of a listed bond, lower first.
struct BondKey {
  ParticleId lower, higher;
};

/// True when rule r bonds particles at xa and xb as far as clods go: it has none, or one of its
/// clod spheres holds both centres.
GPUDEM_HD inline bool in_one_clod(const BondRule& r, const Real4* clods, const PeriodicBox& box,
                                  Vec3 xa, Vec3 xb) {
  if (r.clod_count == 0) return true;
  for (std::uint32_t c = r.first_clod; c < r.first_clod + r.clod_count; ++c) {
    const Real4 clod = clods[c];
    const Real r2 = clod.w * clod.w;
    if (norm2(box.minimum_image(xa - xyz(clod))) <= r2 &&
        norm2(box.minimum_image(xb - xyz(clod))) <= r2)
      return true;
  }
  return false;
}

/// True when rule r lists the pair (lower, higher): a binary search of its ordered pairs.
GPUDEM_HD inline bool is_listed(const BondRule& r, const BondKey* pairs, ParticleId lower,
                                ParticleId higher) {
  std::uint32_t lo = r.first_pair, hi = r.first_pair + r.pair_count;
  while (lo < hi) {
    const std::uint32_t mid = lo + (hi - lo) / 2;
    const BondKey k = pairs[mid];
    if (k.lower < lower || (k.lower == lower && k.higher < higher))
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < r.first_pair + r.pair_count && pairs[lo].lower == lower && pairs[lo].higher == higher;
}

/// True when rule r bonds particles a and b (ids ia < ib, materials ma, mb, surface gap `gap`,
/// centres xa, xb).
GPUDEM_HD inline bool rule_bonds(const BondRule& r, const BondKey* pairs, const Real4* clods,
                                 const PeriodicBox& box, ParticleId ia, ParticleId ib,
                                 MaterialId ma, MaterialId mb, Real gap, Vec3 xa, Vec3 xb) {
  if (r.pair_count > 0) return is_listed(r, pairs, ia, ib);
  const bool match = (ma == r.a && mb == r.b) || (ma == r.b && mb == r.a);
  return match && gap <= r.gap && in_one_clod(r, clods, box, xa, xb);
}

/// The bond on list entry e of owned particle i, seen from its lower-id end a: its geometry, its
/// [[bond]] table and whether i is a.
template <class S>
struct OrientedBond {
  BondGeometry<S> geometry;
  std::uint32_t type;
  bool from_i;
};

template <class S, class P>
GPUDEM_HD OrientedBond<S> oriented_bond(const BondRows<P>& rows, std::uint32_t i, std::uint32_t e,
                                        const S* record) {
  const std::uint32_t j = rows.neighbors[e];
  const bool from_i = rows.id[i] < rows.id[j];
  return {bond_geometry<S>(rows, from_i ? i : j, from_i ? j : i, record[bond_value::rest_length]),
          static_cast<std::uint32_t>(record[bond_value::type]), from_i};
}

namespace bond_kernels {

/// Makes, on each list entry of owned particle i, the bond of the first rule that bonds the
/// pair (rule_bonds); both ends find the same rule and rest length.
template <class P, class S>
struct Create {
  BondRows<P> rows;
  const BondRule* rules;
  std::uint32_t rule_count;
  const Real4* clods;
  const BondKey* pairs;
  S* records;
  GPUDEM_HD void operator()(std::size_t i) const {
    const ParticleView<P>& p = rows.particles;
    for (std::uint32_t e = rows.offsets[i]; e < rows.offsets[i + 1]; ++e) {
      const std::uint32_t j = rows.neighbors[e];
      const bool first = rows.id[i] < rows.id[j];
      const std::uint32_t a = first ? std::uint32_t(i) : j, b = first ? j : std::uint32_t(i);
      const Real4 xa = p.position(a), xb = p.position(b);
      const Real length = norm(rows.box.minimum_image(xyz(xb) - xyz(xa)));
      const Real gap = length - xa.w - xb.w;
      for (std::uint32_t k = 0; k < rule_count; ++k) {
        if (!rule_bonds(rules[k], pairs, clods, rows.box, rows.id[a], rows.id[b], p.material[a],
                        p.material[b], gap, xyz(xa), xyz(xb)))
          continue;
        S* record = records + std::size_t(e) * bond_value::width;
        for (std::uint32_t v = 0; v < bond_value::width; ++v) record[v] = S{};
        record[bond_value::rest_length] = static_cast<S>(length);
        record[bond_value::type] = static_cast<S>(k);
        break;
      }
    }
  }
};

/// Adds to force[i] and torque[i] the loads of owned particle i's bonds, advanced by dt; a bond
/// that breaks is cleared. torque[i] is first set to zero when the contact law writes no torque.
template <class P, class S>
struct AddLoads {
  BondRows<P> rows;
  const BondParamsT<S>* types;
  S* records;
  S dt;
  Vec3T<S>* force;
  Vec3T<S>* torque;
  bool torque_written;  ///< the contact law wrote torque[i] this step
  GPUDEM_HD void operator()(std::size_t i) const {
    Vec3T<S> f{}, t{};
    for (std::uint32_t e = rows.offsets[i]; e < rows.offsets[i + 1]; ++e) {
      S* record = records + std::size_t(e) * bond_value::width;
      if (record[bond_value::rest_length] == 0) continue;
      const OrientedBond<S> b = oriented_bond(rows, std::uint32_t(i), e, record);
      const BondLoad<S> load = evaluate_bond(types[b.type], b.geometry, record, dt);
      if (load.broken) {
        for (std::uint32_t v = 0; v < bond_value::width; ++v) record[v] = S{};
        continue;
      }
      f += b.from_i ? load.force : -load.force;
      t += b.from_i ? load.torque_a : load.torque_b;
    }
    force[i] += f;
    torque[i] = torque_written ? torque[i] + t : t;
  }
};

/// Owned particle i's intact bonds, each counting ½ (its partner counts the other half).
template <class S>
struct HalfBonds {
  const std::uint32_t* offsets;
  const S* records;
  GPUDEM_HD Real operator()(std::size_t i) const {
    Real count = 0;
    for (std::uint32_t e = offsets[i]; e < offsets[i + 1]; ++e)
      if (records[std::size_t(e) * bond_value::width + bond_value::rest_length] != 0)
        count += Real(0.5);
    return count;
  }
};

/// Half the elastic energy of owned particle i's bonds [J].
template <class P, class S>
struct HalfEnergy {
  BondRows<P> rows;
  const BondParamsT<S>* types;
  const S* records;
  GPUDEM_HD Real operator()(std::size_t i) const {
    Real energy = 0;
    for (std::uint32_t e = rows.offsets[i]; e < rows.offsets[i + 1]; ++e) {
      const S* record = records + std::size_t(e) * bond_value::width;
      if (record[bond_value::rest_length] == 0) continue;
      const OrientedBond<S> b = oriented_bond(rows, std::uint32_t(i), e, record);
      energy += Real(0.5) * static_cast<Real>(bond_energy(types[b.type], b.geometry, record));
    }
    return energy;
  }
};

/// The widest surface gap of owned particle i's bonds, L − r_i − r_j [m] (−inf without bonds).
template <class P, class S>
struct WidestGap {
  BondRows<P> rows;
  const S* records;
  GPUDEM_HD Real operator()(std::size_t i) const {
    const ParticleView<P>& p = rows.particles;
    Real widest = -INFINITY;
    const Real4 xi = p.position(i);
    for (std::uint32_t e = rows.offsets[i]; e < rows.offsets[i + 1]; ++e) {
      if (records[std::size_t(e) * bond_value::width + bond_value::rest_length] == 0) continue;
      const Real4 xj = p.position(rows.neighbors[e]);
      const Real gap = norm(rows.box.minimum_image(xyz(xj) - xyz(xi))) - xi.w - xj.w;
      widest = gap > widest ? gap : widest;
    }
    return widest;
  }
};

}  // namespace bond_kernels

}  // namespace gpudem
