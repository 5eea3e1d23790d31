/* light_lanes16.h - sr__light on sixteen lanes: light16, the body of
 * light_lanes_body.h on AVX-512 vectors, for the sixteen-lane Gouraud
 * vertex stage (geometry/vertex_wide.c) and the sixteen-lane PHONG stamps
 * (raster/simd_wide16.h).  x86-64 with GCC or Clang: the includers compile
 * it for AVX-512 by target attribute and call it only on CPUs that have
 * it. */
#ifndef SR_LIGHT_LANES16_H
#define SR_LIGHT_LANES16_H

#include "pipeline.h"

#include <immintrin.h>

static inline __attribute__((always_inline)) SR_TARGET_AVX512 v16f v16_sel(v16i m, v16f a, v16f b)
{
    return (v16f)((m & (v16i)a) | (~m & (v16i)b));
}

/* Correctly rounded, as sqrtf. */
static inline __attribute__((always_inline)) SR_TARGET_AVX512 v16f v16_sqrt(v16f x)
{
    return (v16f)_mm512_sqrt_ps((__m512)x);
}

#define SR_LL_F v16f
#define SR_LL_I v16i
#define SR_LL_SEL v16_sel
#define SR_LL_SQRT v16_sqrt
#define SR_LL_NAME light16
#define SR_LL_TARGET SR_TARGET_AVX512
#include "fragment/light_lanes_body.h"

#endif
