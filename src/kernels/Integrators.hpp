#pragma once
/// Time integration of translation and rotation for spheres (I = 2/5·m·r²).
///   velocity Verlet:  v += ½dt·F/m; x += dt·v; F(x, v); v += ½dt·F/m
///   symplectic Euler: v += dt·F/m; x += dt·v; F(x, v)
/// with the same kick for ω using T/I. Forces depend on velocity (dashpots), so the Verlet
/// variant evaluates them with the half-step velocity, as is usual in DEM.
#include <cmath>

#include "core/Config.hpp"
#include "core/ParticleStore.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// v += h·F/m and, when the contact law exerts torques (kRotate), ω += h·T/I, in Real from
/// forces and torques held in scalar S.
template <bool kRotate, class S>
struct Kick {
  Real4* velocity_inv_mass;
  Vec3* angular_velocity;
  const Vec3T<S>* force;
  const Vec3T<S>* torque;
  const Real4* position_radius;
  Real h;
  GPUDEM_HD void operator()(std::size_t i) const {
    Real4& v = velocity_inv_mass[i];
    const Vec3 f = vec_cast<Real>(force[i]);
    v.x += h * v.w * f.x;
    v.y += h * v.w * f.y;
    v.z += h * v.w * f.z;
    if constexpr (kRotate)
      angular_velocity[i] +=
          (h / sphere_inertia(position_radius[i].w, v.w)) * vec_cast<Real>(torque[i]);
  }
};

/// x += dt·v.
struct Drift {
  Real4* position_radius;
  const Real4* velocity_inv_mass;
  Real dt;
  GPUDEM_HD void operator()(std::size_t i) const {
    const Real4 v = velocity_inv_mass[i];
    Real4& x = position_radius[i];
    x.x += dt * v.x;
    x.y += dt * v.y;
    x.z += dt * v.z;
  }
};

/// |x − x_at_build|², the squared distance moved since the last neighbour build.
struct DisplacementSquared {
  const Real4* position_radius;
  const Real4* position_at_build;
  GPUDEM_HD Real operator()(std::size_t i) const {
    return norm2(xyz(position_radius[i]) - xyz(position_at_build[i]));
  }
};

}  // namespace gpudem
