#pragma once
/// The part of the global box one rank bins into cells: its block grown by the ghost width
/// (docs/architecture.md, "Ranks"). Positions stay in the global box's coordinates everywhere
/// (wrapped on periodic axes, displacements by minimum image); only binning looks at them through
/// the region.
#include <cmath>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/PeriodicBox.hpp"

namespace gpudem {

struct BinRegion {
  Vec3 lo;      ///< [m] lower corner
  Vec3 length;  ///< [m] edge lengths
  /// The region spans the whole of periodic axis k, and its cells wrap around it.
  bool periodic[3] = {false, false, false};
};

/// The region of a run on one rank: the whole box.
inline BinRegion whole_box_region(const PeriodicBox& box) {
  BinRegion r;
  r.lo = box.lo;
  r.length = box.length;
  for (int k = 0; k < 3; ++k) r.periodic[k] = box.periodic[k];
  return r;
}

/// Coordinate x along axis k of its periodic image nearest the region, for an axis periodic in
/// the box but not in the region (unchanged on any other axis): the image in
/// [lo − g/2, lo + length + g/2) with g = L − length the gap the region leaves on the axis.
GPUDEM_HD inline Real region_image(const PeriodicBox& box, const BinRegion& region, int k, Real x) {
  if (!box.periodic[k] || region.periodic[k]) return x;
  const Real L = axis(box.length, k);
  const Real start = axis(region.lo, k) - Real(0.5) * (L - axis(region.length, k));
  return x - L * floor((x - start) / L);
}

}  // namespace gpudem
