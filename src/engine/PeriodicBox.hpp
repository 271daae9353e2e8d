#pragma once
/// The global simulation box and its periodic axes: minimum-image displacements and wrapping.
#include <cmath>

#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

struct PeriodicBox {
  Vec3 lo;      ///< [m] lower corner
  Vec3 length;  ///< [m] edge lengths
  bool periodic[3] = {false, false, false};

  /// Displacement d reduced to its nearest periodic image on each periodic axis.
  GPUDEM_HD Vec3 minimum_image(Vec3 d) const {
    for (int k = 0; k < 3; ++k)
      if (periodic[k]) {
        const Real L = axis(length, k);
        axis(d, k) -= L * floor(axis(d, k) / L + Real(0.5));
      }
    return d;
  }

  /// The periodic image of p nearest `centre`: on each periodic axis
  /// x_k − L_k ⌊(x_k − c_k) / L_k + ½⌋, the other axes untouched (p itself, bit for bit, when no
  /// shift applies).
  GPUDEM_HD Vec3 image_near(Vec3 p, Vec3 centre) const {
    for (int k = 0; k < 3; ++k)
      if (periodic[k]) {
        const Real L = axis(length, k);
        axis(p, k) -= L * floor((axis(p, k) - axis(centre, k)) / L + Real(0.5));
      }
    return p;
  }

  /// True when some axis is periodic.
  GPUDEM_HD bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }

  /// Position mapped back into [lo, lo + length) on each periodic axis.
  GPUDEM_HD Vec3 wrap(Vec3 p) const {
    for (int k = 0; k < 3; ++k)
      if (periodic[k]) {
        const Real L = axis(length, k);
        Real s = axis(p, k) - axis(lo, k);
        s -= L * floor(s / L);
        if (s >= L) s -= L;  // floor rounding at the upper edge
        axis(p, k) = axis(lo, k) + s;
      }
    return p;
  }

  /// wrap(p) rounded to scalar P, still inside [lo, lo + length) on each periodic axis: a
  /// coordinate that rounding carries onto the upper edge (or below lo) is moved to the nearest
  /// value of P inside. Equal to wrap(p) when P is Real.
  template <class P>
  GPUDEM_HD Vec3T<P> wrap_rounded(Vec3 p) const {
    Vec3T<P> r = vec_cast<P>(wrap(p));
    for (int k = 0; k < 3; ++k)
      if (periodic[k]) {
        const Real low = axis(lo, k), high = low + axis(length, k);
        P& x = axis(r, k);
        while (Real(x) >= high) x = next_toward(x, static_cast<P>(low));
        while (Real(x) < low) x = next_toward(x, static_cast<P>(high));
      }
    return r;
  }

  /// True when p lies outside the box along a non-periodic axis.
  GPUDEM_HD bool outside(Vec3 p) const {
    for (int k = 0; k < 3; ++k)
      if (!periodic[k] && (axis(p, k) < axis(lo, k) || axis(p, k) > axis(lo, k) + axis(length, k)))
        return true;
    return false;
  }
};

}  // namespace gpudem
