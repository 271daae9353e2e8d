#pragma once
/// Time integration of translation and rotation for spheres (I = 2/5·m·r²).
///   velocity Verlet:  v += ½dt·F/m; x += dt·v; F(x, v); v += ½dt·F/m
///   symplectic Euler: v += dt·F/m; x += dt·v; F(x, v)
/// with the same kick for ω using T/I. Forces depend on velocity (dashpots), so the Verlet
/// variant evaluates them with the half-step velocity, as is usual in DEM.
#include <cmath>
#include <cstdint>

#include "core/Config.hpp"
#include "core/ParticleStore.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// How the kick treats the particles of one material (Material::fixed, ::velocity, ::drag).
struct MaterialMotion {
  std::uint32_t fixed = 0;  ///< 1: moved at `velocity`, whatever the loads
  Real drag = 0;            ///< c [1/s]
  Vec3 velocity{};          ///< [m/s], of a fixed material
};

/// v += h·F/m and, when the contact law exerts torques (kRotate), ω += h·T/I, in Real from
/// a state held in scalar P and forces and torques held in scalar S. With a material table
/// (motion, per material; null: every material moves freely), a particle of a fixed material
/// takes its material's velocity and ω = 0, and one of drag c is slowed by −c m v and
/// −c I ω, taken implicitly: v ← (v + h F/m)/(1 + c h), stable for any c h.
template <bool kRotate, class S, class P>
struct Kick {
  Vec4T<P>* velocity_inv_mass;
  Vec3T<P>* angular_velocity;
  const Vec3T<S>* force;
  const Vec3T<S>* torque;
  const Vec4T<P>* position_radius;
  Real h;
  const MaterialId* material = nullptr;
  const MaterialMotion* motion = nullptr;
  GPUDEM_HD void operator()(std::size_t i) const {
    Real4 v = vec4_cast<Real>(velocity_inv_mass[i]);
    const MaterialMotion m = motion ? motion[material[i]] : MaterialMotion{};
    if (m.fixed) {
      velocity_inv_mass[i] = vec4_cast<P>(Real4{m.velocity.x, m.velocity.y, m.velocity.z, v.w});
      angular_velocity[i] = Vec3T<P>{};
      return;
    }
    const Real slowed = m.drag == 0 ? Real(1) : Real(1) / (Real(1) + m.drag * h);  // the same 1
    const Vec3 f = vec_cast<Real>(force[i]);
    v.x = (v.x + h * v.w * f.x) * slowed;
    v.y = (v.y + h * v.w * f.y) * slowed;
    v.z = (v.z + h * v.w * f.z) * slowed;
    velocity_inv_mass[i] = vec4_cast<P>(v);
    if constexpr (kRotate) {
      const Real inertia = sphere_inertia<Real>(position_radius[i].w, v.w);
      const Vec3 w =
          vec_cast<Real>(angular_velocity[i]) + (h / inertia) * vec_cast<Real>(torque[i]);
      angular_velocity[i] = vec_cast<P>(slowed * w);
    }
  }
};

/// x += dt·v, in Real from a state held in scalar P.
template <class P>
struct Drift {
  Vec4T<P>* position_radius;
  const Vec4T<P>* velocity_inv_mass;
  Real dt;
  GPUDEM_HD void operator()(std::size_t i) const {
    const Real4 v = vec4_cast<Real>(velocity_inv_mass[i]);
    Real4 x = vec4_cast<Real>(position_radius[i]);
    x.x += dt * v.x;
    x.y += dt * v.y;
    x.z += dt * v.z;
    position_radius[i] = vec4_cast<P>(x);
  }
};

/// |x − x_at_build|², the squared distance moved since the last neighbour build.
template <class P>
struct DisplacementSquared {
  const Vec4T<P>* position_radius;
  const Vec4T<P>* position_at_build;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return norm2(vec_cast<Real>(xyz(position_radius[i])) -
                 vec_cast<Real>(xyz(position_at_build[i])));
  }
};

}  // namespace gpudem
