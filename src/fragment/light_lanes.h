/* light_lanes.h - sr__light (shade.c) on four lanes at once, for the
 * vertex stage's Gouraud lighting (vertex.c) and the Phong vector kernel
 * (simd_kernel.h).  Written with GCC/Clang vector extensions: SSE on x86,
 * NEON on AArch64, whatever the compiler makes of them elsewhere.  The body, and how it
 * keeps sr__light's bits, is light_lanes_body.h, shared with the
 * sixteen-lane instance of vertex_wide.c. */
#ifndef SR_LIGHT_LANES_H
#define SR_LIGHT_LANES_H

#include "pipeline.h"

#include <math.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#elif defined(__aarch64__) && defined(__ARM_NEON)
#include <arm_neon.h>
#endif


static inline __attribute__((always_inline)) v4f sr__v4_sel(v4i m, v4f a, v4f b)
{
    return (v4f)((m & (v4i)a) | (~m & (v4i)b));
}

/* Correctly rounded, as sqrtf. */
static inline __attribute__((always_inline)) v4f sr__v4_sqrt(v4f x)
{
#if defined(__SSE__)
    return (v4f)_mm_sqrt_ps((__m128)x);
#elif defined(__aarch64__) && defined(__ARM_NEON)
    return (v4f)vsqrtq_f32((float32x4_t)x);
#else
    v4f r = x; /* each lane is written below; GCC 12 warns of r unset otherwise */
    for (int k = 0; k < 4; k++) {
        r[k] = sqrtf(x[k]);
    }
    return r;
#endif
}

#define SR_LL_F v4f
#define SR_LL_I v4i
#define SR_LL_SEL sr__v4_sel
#define SR_LL_SQRT sr__v4_sqrt
#define SR_LL_NAME sr__light_lanes
#define SR_LL_TARGET
#include "fragment/light_lanes_body.h"

#endif
