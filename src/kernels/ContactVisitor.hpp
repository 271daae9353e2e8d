#pragma once
/// Walks every contact of one particle — neighbours from the Verlet list, then plane walls —
/// and hands each touching one to a visitor (`visit(sample)`), and each listed partner that
/// is not touching to `visit.separated(slot)`. Forces, energies and counters are all
/// visitors, so the contact geometry lives in one place.
#include <cstdint>

#include "core/Config.hpp"
#include "core/ParticleStore.hpp"
#include "core/Vec3.hpp"
#include "kernels/LinearContact.hpp"
#include "kernels/PeriodicBox.hpp"
#include "kernels/PlaneWall.hpp"

namespace gpudem {

/// Read-only particle arrays a contact evaluation needs (pointers into one memory space).
struct ParticleView {
  const Real4* position_radius;
  const Real4* velocity_inv_mass;
  const Vec3* angular_velocity;
  const MaterialId* material;
};

/// Everything besides particles that a contact sweep needs.
struct ContactScene {
  const std::uint32_t* neighbor_offsets;  ///< CSR offsets, n + 1
  const std::uint32_t* neighbor_index;    ///< full neighbour list
  const LinearPairParams* pair_params;    ///< material_count² entries
  std::uint32_t material_count;
  const PlaneWall* walls;
  std::uint32_t wall_count;
  PeriodicBox box;
  const Vec3* pair_spring;  ///< tangential spring per neighbour-list entry
  const Vec3* wall_spring;  ///< tangential spring per (particle, wall): slot i·wall_count + w
};

/// Base for visitors that ignore partners out of contact.
struct IgnoreSeparated {
  GPUDEM_HD void separated(std::uint32_t) {}
  GPUDEM_HD void separated_from_wall(std::uint32_t) {}
};

/// One touching contact as seen from particle i.
struct ContactSample {
  ContactKinematics kinematics;
  Real arm;         ///< lever arm on i: r_i − δ/2, along kinematics.normal [m]
  Real min_radius;  ///< smaller radius of the pair (r_i for walls) [m]
  const LinearPairParams* params;
  std::int32_t wall;   ///< wall index, or −1 for a particle partner
  std::uint32_t slot;  ///< index of this contact's history (pair or wall spring array)
  Vec3 spring;         ///< tangential spring ξ stored at the end of the last step
};

/// Calls visit(sample) for each contact of particle i with positive overlap.
template <class Visitor>
GPUDEM_HD void for_each_contact(std::uint32_t i, const ParticleView& p, const ContactScene& s,
                                Visitor& visit) {
  const Real4 xi = p.position_radius[i];
  const Real4 vi = p.velocity_inv_mass[i];
  const Vec3 wi = p.angular_velocity[i];
  const MaterialId mi = p.material[i];
  for (std::uint32_t k = s.neighbor_offsets[i]; k < s.neighbor_offsets[i + 1]; ++k) {
    const std::uint32_t j = s.neighbor_index[k];
    const Real4 xj = p.position_radius[j];
    const Vec3 d = s.box.minimum_image(xyz(xj) - xyz(xi));
    const Real dist2 = norm2(d);
    const Real reach = xi.w + xj.w;
    if (dist2 >= reach * reach || dist2 == 0) {
      visit.separated(k);
      continue;
    }
    const Real dist = sqrt(dist2);
    ContactSample c;
    c.kinematics.normal = (Real(1) / dist) * d;
    c.kinematics.overlap = reach - dist;
    c.arm = xi.w - Real(0.5) * c.kinematics.overlap;
    const Real arm_j = xj.w - Real(0.5) * c.kinematics.overlap;
    const Real4 vj = p.velocity_inv_mass[j];
    const Vec3 ui = xyz(vi) + cross(wi, c.arm * c.kinematics.normal);
    const Vec3 uj = xyz(vj) + cross(p.angular_velocity[j], -arm_j * c.kinematics.normal);
    c.kinematics.velocity = ui - uj;
    c.kinematics.reduced_mass = Real(1) / (vi.w + vj.w);
    c.kinematics.relative_spin = wi - p.angular_velocity[j];
    c.kinematics.rolling_radius = xi.w * xj.w / (xi.w + xj.w);
    const Real inertia_i = sphere_inertia(xi.w, vi.w), inertia_j = sphere_inertia(xj.w, vj.w);
    c.kinematics.reduced_inertia = inertia_i * inertia_j / (inertia_i + inertia_j);
    c.min_radius = xi.w < xj.w ? xi.w : xj.w;
    c.params = &s.pair_params[mi * s.material_count + p.material[j]];
    c.wall = -1;
    c.slot = k;
    c.spring = s.pair_spring[k];
    visit(c);
  }
  for (std::uint32_t w = 0; w < s.wall_count; ++w) {
    const PlaneWall& wall = s.walls[w];
    const Real overlap = wall_overlap(wall, xyz(xi), xi.w);
    const std::uint32_t slot = i * s.wall_count + w;
    if (overlap <= 0) {
      visit.separated_from_wall(slot);
      continue;
    }
    ContactSample c;
    c.kinematics.normal = -wall.normal;
    c.kinematics.overlap = overlap;
    c.arm = xi.w - Real(0.5) * overlap;
    c.kinematics.velocity = xyz(vi) + cross(wi, c.arm * c.kinematics.normal);
    c.kinematics.reduced_mass = Real(1) / vi.w;
    c.kinematics.relative_spin = wi;
    c.kinematics.rolling_radius = xi.w;
    c.kinematics.reduced_inertia = sphere_inertia(xi.w, vi.w);
    c.min_radius = xi.w;
    c.params = &s.pair_params[mi * s.material_count + wall.material];
    c.wall = static_cast<std::int32_t>(w);
    c.slot = slot;
    c.spring = s.wall_spring[slot];
    visit(c);
  }
}

}  // namespace gpudem
