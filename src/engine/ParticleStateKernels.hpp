#pragma once
/// Per-particle functors for parallel_for over the engine's state arrays, whose positions and
/// radii are held in the state scalar P (double, or float in the float policy) and read in Real.
#include <cstddef>
#include <cstdint>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/ParallelFor.hpp"
#include "engine/PeriodicBox.hpp"

namespace gpudem {

/// Wraps particle i's position into the box along its periodic axes, rounded to P
/// (PeriodicBox::wrap_rounded).
template <class P>
struct WrapPositions {
  Vec4T<P>* position_radius;
  PeriodicBox box;
  GPUDEM_HD void operator()(std::size_t i) const {
    const Vec3T<P> p = box.wrap_rounded<P>(vec_cast<Real>(xyz(position_radius[i])));
    position_radius[i].x = p.x;
    position_radius[i].y = p.y;
    position_radius[i].z = p.z;
  }
};

/// out[i] = in[i] in Real.
template <class P>
struct CopyInReal {
  const Vec4T<P>* in;
  Real4* out;
  GPUDEM_HD void operator()(std::size_t i) const { out[i] = vec4_cast<Real>(in[i]); }
};

/// The radius of particle i, for reductions.
template <class P>
struct Radius {
  const Vec4T<P>* position_radius;
  GPUDEM_HD Real operator()(std::size_t i) const { return position_radius[i].w; }
};

/// |v|² of particle i [m²/s²].
template <class P>
struct SquaredSpeed {
  const Vec4T<P>* velocity_inv_mass;
  GPUDEM_HD Real operator()(std::size_t i) const {
    const Vec4T<P> v = velocity_inv_mass[i];
    return Real(v.x) * Real(v.x) + Real(v.y) * Real(v.y) + Real(v.z) * Real(v.z);
  }
};

/// slot_of[i] = the cell-order slot of owned particle i (index_of_slot[slot] = i).
struct SlotOfOwned {
  const std::uint32_t* index_of_slot;
  std::size_t owned;
  std::uint32_t* slot_of;
  GPUDEM_HD void operator()(std::size_t slot) const {
    const std::uint32_t i = index_of_slot[slot];
    if (i < owned) slot_of[i] = static_cast<std::uint32_t>(slot);
  }
};

}  // namespace gpudem
