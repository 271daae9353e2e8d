/// slots_within_avx2 (NeighborSlots.hpp), compiled for -march=x86-64-v3: four slots a test. It
/// must hold that function and nothing else (avx2_lanes_objects_hold_only_sweeps checks), so it
/// includes no header of the engine's but NeighborSlots.hpp.
#include <immintrin.h>

#include "engine/NeighborSlots.hpp"

namespace gpudem {
namespace {

/// For each set of kept lanes (a 4-bit mask), the byte shuffle that moves their 32-bit slots to
/// the front, in lane order (zeros after them).
struct CompressShuffles {
  alignas(16) unsigned char bytes[16][16];
};

constexpr CompressShuffles compress_shuffles() {
  CompressShuffles table{};
  for (int mask = 0; mask < 16; ++mask) {
    int kept = 0;
    for (int lane = 0; lane < 4; ++lane)
      if (mask & (1 << lane)) {
        for (int b = 0; b < 4; ++b) table.bytes[mask][4 * kept + b] = 4 * lane + b;
        ++kept;
      }
    for (int b = 4 * kept; b < 16; ++b) table.bytes[mask][b] = 0x80;  // a zero byte
  }
  return table;
}

constexpr CompressShuffles kCompress = compress_shuffles();

}  // namespace

std::uint32_t slots_within_avx2(const SlotTest& t, std::uint32_t begin, std::uint32_t end,
                                std::uint32_t* out) {
  const __m256d px = _mm256_set1_pd(t.p[0]), py = _mm256_set1_pd(t.p[1]);
  const __m256d pz = _mm256_set1_pd(t.p[2]), pw = _mm256_set1_pd(t.p[3]);
  const __m256d skin = _mm256_set1_pd(t.skin);
  const __m128i lane = _mm_setr_epi32(0, 1, 2, 3);
  std::uint32_t kept = 0;
  for (std::uint32_t j = begin; j < end; j += 4) {
    const std::uint32_t n = end - j < 4 ? end - j : 4;
    const double* q = t.position_radius + 4 * static_cast<std::size_t>(j);
    __m256d slot[4];  // x, y, z, r of slots j to j + 3; zeros past the run, which reads nothing
    for (std::uint32_t k = 0; k < 4; ++k)
      slot[k] = k < n ? _mm256_loadu_pd(q + 4 * k) : _mm256_setzero_pd();
    const __m256d xz_low = _mm256_unpacklo_pd(slot[0], slot[1]);  // x0 x1 z0 z1
    const __m256d yr_low = _mm256_unpackhi_pd(slot[0], slot[1]);  // y0 y1 r0 r1
    const __m256d xz_high = _mm256_unpacklo_pd(slot[2], slot[3]);
    const __m256d yr_high = _mm256_unpackhi_pd(slot[2], slot[3]);
    __m256d d[3] = {_mm256_sub_pd(_mm256_permute2f128_pd(xz_low, xz_high, 0x20), px),
                    _mm256_sub_pd(_mm256_permute2f128_pd(yr_low, yr_high, 0x20), py),
                    _mm256_sub_pd(_mm256_permute2f128_pd(xz_low, xz_high, 0x31), pz)};
    const __m256d r = _mm256_permute2f128_pd(yr_low, yr_high, 0x31);
    for (int k = 0; k < 3; ++k)
      if (t.periodic[k]) {  // d −= L floor(d / L + 1/2)
        const __m256d length = _mm256_set1_pd(t.length[k]);
        const __m256d images =
            _mm256_floor_pd(_mm256_add_pd(_mm256_div_pd(d[k], length), _mm256_set1_pd(0.5)));
        d[k] = _mm256_sub_pd(d[k], _mm256_mul_pd(length, images));
      }
    const __m256d dist2 =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(d[0], d[0]), _mm256_mul_pd(d[1], d[1])),
                      _mm256_mul_pd(d[2], d[2]));
    const __m256d cutoff = _mm256_add_pd(_mm256_add_pd(pw, r), skin);
    unsigned within = static_cast<unsigned>(_mm256_movemask_pd(
                          _mm256_cmp_pd(dist2, _mm256_mul_pd(cutoff, cutoff), _CMP_LT_OQ))) &
                      ((1u << n) - 1);
    if (t.self - j < 4) within &= ~(1u << (t.self - j));
    const __m128i slots = _mm_add_epi32(_mm_set1_epi32(static_cast<int>(j)), lane);
    const __m128i shuffle =
        _mm_load_si128(reinterpret_cast<const __m128i*>(kCompress.bytes[within]));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + kept), _mm_shuffle_epi8(slots, shuffle));
    kept += static_cast<std::uint32_t>(__builtin_popcount(within));
  }
  return kept;
}

}  // namespace gpudem
