/* rows_avx512.h - a row of 4, 8 or 16 samples of a framebuffer buffer in
 * 32-bit lanes, only the lanes of a mask (raster stage, tile worker
 * threads; the AVX-512 level only): the stamps of simd_wide16.h and
 * simd_tiny.h and the four-sample path of msaa_wide.h load and store
 * through these.  A buffer has `size`-byte elements: 4-byte words load as
 * they are, D16's 2-byte depth samples zero-extended into the lanes and
 * narrowed back on the store (depth_lanes.h).  The size is a constant for
 * color, so only depth pays the test. */
#ifndef SR_ROWS_AVX512_H
#define SR_ROWS_AVX512_H

#include "simd_types.h"

#include <immintrin.h>
#include <stddef.h>

#define SR_ROW_FN SR_TARGET_AVX512 static inline __attribute__((always_inline))

/* A row extracted from a wider register is kept in a register of its own
 * before its masked store: otherwise the compiler folds the two into a
 * masked vextract to memory, which some CPUs fault on at an unmapped page
 * even in lanes the mask leaves off (a masked move does not), so a
 * buffer ending at a page boundary crashed the last row. */
#define SR_IN_REGISTER(v) __asm__("" : "+v"(v))

SR_ROW_FN __m128i sr__row4_load(const void *buf, int size, size_t at, __mmask8 m)
{
    if (size == 2) {
        /* A 128-bit register holds eight 16-bit lanes: the mask's upper
         * four bits, which the 32-bit load ignores, would read past the row. */
        return _mm_cvtepu16_epi32(_mm_maskz_loadu_epi16(m & 0xF, (const uint16_t *)buf + at));
    }
    return _mm_maskz_loadu_epi32(m, (const uint32_t *)buf + at);
}

SR_ROW_FN __m256i sr__row8_load(const void *buf, int size, size_t at, __mmask8 m)
{
    if (size == 2) {
        return _mm256_cvtepu16_epi32(_mm_maskz_loadu_epi16(m, (const uint16_t *)buf + at));
    }
    return _mm256_maskz_loadu_epi32(m, (const uint32_t *)buf + at);
}

SR_ROW_FN __m512i sr__row16_load(const void *buf, int size, size_t at, __mmask16 m)
{
    if (size == 2) {
        return _mm512_cvtepu16_epi32(_mm256_maskz_loadu_epi16(m, (const uint16_t *)buf + at));
    }
    return _mm512_maskz_loadu_epi32(m, (const uint32_t *)buf + at);
}

SR_ROW_FN void sr__row4_store(void *buf, int size, size_t at, __mmask8 m, __m128i v)
{
    SR_IN_REGISTER(v);
    if (size == 2) {
        _mm_mask_cvtepi32_storeu_epi16((uint16_t *)buf + at, m, v);
    } else {
        _mm_mask_storeu_epi32((uint32_t *)buf + at, m, v);
    }
}

SR_ROW_FN void sr__row8_store(void *buf, int size, size_t at, __mmask8 m, __m256i v)
{
    SR_IN_REGISTER(v);
    if (size == 2) {
        _mm256_mask_cvtepi32_storeu_epi16((uint16_t *)buf + at, m, v);
    } else {
        _mm256_mask_storeu_epi32((uint32_t *)buf + at, m, v);
    }
}

SR_ROW_FN void sr__row16_store(void *buf, int size, size_t at, __mmask16 m, __m512i v)
{
    if (size == 2) {
        _mm512_mask_cvtepi32_storeu_epi16((uint16_t *)buf + at, m, v);
    } else {
        _mm512_mask_storeu_epi32((uint32_t *)buf + at, m, v);
    }
}

#undef SR_ROW_FN
#undef SR_IN_REGISTER

#endif
