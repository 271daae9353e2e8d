/// slots_within_avx512 (NeighborSlots.hpp), compiled for -march=x86-64-v4: eight slots a test.
/// It must hold that function and nothing else (lanes_objects_hold_only_sweeps checks), so it
/// includes no header of the engine's but NeighborSlots.hpp.
#include <immintrin.h>

#include "engine/NeighborSlots.hpp"

namespace gpudem {

std::uint32_t slots_within_avx512(const SlotTest& t, std::uint32_t begin, std::uint32_t end,
                                  std::uint32_t* out) {
  const __m512d px = _mm512_set1_pd(t.p[0]), py = _mm512_set1_pd(t.p[1]);
  const __m512d pz = _mm512_set1_pd(t.p[2]), pw = _mm512_set1_pd(t.p[3]);
  const __m512d skin = _mm512_set1_pd(t.skin);
  // Eight slots' (x, y, z, r) as four vectors of two slots each, turned into x, y, z and r.
  const __m512i first_half = _mm512_setr_epi64(0, 4, 8, 12, 1, 5, 9, 13);
  const __m512i second_half = _mm512_setr_epi64(2, 6, 10, 14, 3, 7, 11, 15);
  const __m512i low_quads = _mm512_setr_epi64(0, 1, 2, 3, 8, 9, 10, 11);
  const __m512i high_quads = _mm512_setr_epi64(4, 5, 6, 7, 12, 13, 14, 15);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i self = _mm256_set1_epi32(static_cast<int>(t.self));
  std::uint32_t kept = 0;
  for (std::uint32_t j = begin; j < end; j += 8) {
    const std::uint32_t n = end - j < 8 ? end - j : 8;
    const double* q = t.position_radius + 4 * static_cast<std::size_t>(j);
    __m512d pairs[4];  // slots 2k and 2k + 1; masked past the run, which reads nothing there
    for (int k = 0; k < 4; ++k) {
      const __mmask8 valid = n > 2u * k + 1 ? 0xFF : n > 2u * k ? 0x0F : 0x00;
      pairs[k] = _mm512_maskz_loadu_pd(valid, q + 8 * k);
    }
    const __m512d xy_low = _mm512_permutex2var_pd(pairs[0], first_half, pairs[1]);
    const __m512d zr_low = _mm512_permutex2var_pd(pairs[0], second_half, pairs[1]);
    const __m512d xy_high = _mm512_permutex2var_pd(pairs[2], first_half, pairs[3]);
    const __m512d zr_high = _mm512_permutex2var_pd(pairs[2], second_half, pairs[3]);
    __m512d d[3] = {_mm512_sub_pd(_mm512_permutex2var_pd(xy_low, low_quads, xy_high), px),
                    _mm512_sub_pd(_mm512_permutex2var_pd(xy_low, high_quads, xy_high), py),
                    _mm512_sub_pd(_mm512_permutex2var_pd(zr_low, low_quads, zr_high), pz)};
    const __m512d r = _mm512_permutex2var_pd(zr_low, high_quads, zr_high);
    for (int k = 0; k < 3; ++k)
      if (t.periodic[k]) {  // d −= L floor(d / L + 1/2)
        const __m512d length = _mm512_set1_pd(t.length[k]);
        const __m512d x = _mm512_add_pd(_mm512_div_pd(d[k], length), _mm512_set1_pd(0.5));
        const __m512d images =  // floor(x), written over x in every lane
            _mm512_mask_roundscale_pd(x, 0xFF, x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
        d[k] = _mm512_sub_pd(d[k], _mm512_mul_pd(length, images));
      }
    const __m512d dist2 =
        _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(d[0], d[0]), _mm512_mul_pd(d[1], d[1])),
                      _mm512_mul_pd(d[2], d[2]));
    const __m512d cutoff = _mm512_add_pd(_mm512_add_pd(pw, r), skin);
    const __m256i slot = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(j)), lane);
    const __mmask8 within = _mm512_cmp_pd_mask(dist2, _mm512_mul_pd(cutoff, cutoff), _CMP_LT_OQ) &
                            _mm256_cmpneq_epi32_mask(slot, self) &
                            static_cast<__mmask8>((1u << n) - 1);
    // Compressed in a register and stored whole: a compressing store is slow on some CPUs.
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + kept),
                        _mm256_maskz_compress_epi32(within, slot));
    kept += static_cast<std::uint32_t>(__builtin_popcount(within));
  }
  return kept;
}

}  // namespace gpudem
