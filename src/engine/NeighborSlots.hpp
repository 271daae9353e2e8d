#pragma once
/// The host search's test of a run of consecutive cell-order slots against one particle, as plain
/// data, so that the units compiled for AVX-512 and AVX2 (NeighborSlotsAvx512.cpp,
/// NeighborSlotsAvx2.cpp) can take it without including any inline function of the engine. Host
/// code only.
#include <cstdint>

namespace gpudem {

/// Particle `self` (centre and radius p) and what its partners are tested with.
struct SlotTest {
  const double* position_radius;  ///< x, y, z, radius of each slot, in cell order
  double p[4];                    ///< the particle's x, y, z, radius
  std::uint32_t self;             ///< its own slot, never a partner
  double skin;                    ///< [m] added to every pair's contact distance
  double length[3];               ///< [m] the box's edge lengths
  bool periodic[3];               ///< the axes on which distances take the nearest image
};

/// Slack past the kept slots that slots_within_avx512 and slots_within_avx2 may overwrite.
inline constexpr std::uint32_t kSlotsWithinSlack = 8;

/// Writes to out, in ascending order, the slots j in [begin, end), j != self, whose particle q
/// is within p.w + q.w + skin of p (|d|² < cutoff², d = x_q − x_p at its nearest image on the
/// periodic axes), and returns how many; the same slots as NeighborSearch::within (the same
/// operations on every lane). out must hold end − begin + kSlotsWithinSlack values. Defined
/// only where GPUDEM_HOST_LANES; call it only where host_runs_x86_64_v4().
std::uint32_t slots_within_avx512(const SlotTest& test, std::uint32_t begin, std::uint32_t end,
                                  std::uint32_t* out);
/// The same four slots at a time in AVX2; call it only where host_runs_x86_64_v3().
std::uint32_t slots_within_avx2(const SlotTest& test, std::uint32_t begin, std::uint32_t end,
                                std::uint32_t* out);

}  // namespace gpudem
