/* triangle_simd.c - the vector half-space kernels (raster stage), the
 * same source (simd_kernel.h) compiled for AVX-512 (sixteen-lane block
 * rows), AVX2 (eight-lane rows) and the baseline instruction set (four-lane
 * groups, as all three use for small triangles); sr__raster_simd_select
 * picks by what the CPU has.  On AArch64 the baseline is NEON, which every
 * core has: the four-lane copy alone, as the base level. */
#include "raster/triangle_simd.h"

#include "fragment/fragment.h"
#include "fragment/light_lanes.h"
#include "raster/block.h"
#include "raster/depth_lanes.h"

#include <stdlib.h>
#include <string.h>

/* How a vector walk reads its triangle, a constant in each instance of
 * simd_kernel.h's walks: textured color (simd_tex.h, AVX-512 only), and
 * edge values in 32-bit lanes, where every value in the box fits
 * (sr__rect_fits32), rather than in double lanes. */
typedef enum sr_walk_flags {
    SR_WALK_PLAIN = 0,
    SR_WALK_TEXTURED = 1 << 0,
    SR_WALK_NARROW = 1 << 1,
} sr_walk_flags;

/* The lane packing below writes r, g, b, a as one little-endian word. */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && \
    (defined(__x86_64__) || defined(__i386__))
#define SR_HAVE_SIMD_KERNEL 1
#define SR_SIMD_KERNEL_X86 1
#include <immintrin.h>

/* sr__light on sixteen lanes for the AVX-512 instance's PHONG stamps
 * (w16_phong in simd_wide16.h). */
#include "fragment/light_lanes16.h"

#define SR_SIMD_FN(name) name##_avx512
#define SR_SIMD_TARGET SR_TARGET_AVX512
#define SR_SIMD_WIDE 1
#define SR_SIMD_WIDE16 1 /* two block rows in sixteen lanes */
#include "raster/simd_kernel.h"
#undef SR_SIMD_FN
#undef SR_SIMD_TARGET
#undef SR_SIMD_WIDE
#undef SR_SIMD_WIDE16

#define SR_SIMD_FN(name) name##_avx2
#define SR_SIMD_TARGET __attribute__((target("avx2")))
#define SR_SIMD_WIDE 1 /* the eight-lane rows of simd_wide.h */
#include "raster/simd_kernel.h"
#undef SR_SIMD_FN
#undef SR_SIMD_TARGET
#undef SR_SIMD_WIDE

#define SR_SIMD_FN(name) name##_base
#define SR_SIMD_TARGET
#include "raster/simd_kernel.h"
#undef SR_SIMD_FN
#undef SR_SIMD_TARGET

#elif defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && \
    defined(__aarch64__) && defined(__ARM_NEON)
#define SR_HAVE_SIMD_KERNEL 1
#include "raster/unorm8_neon.h"

#define SR_SIMD_FN(name) name##_neon
#define SR_SIMD_TARGET
#define SR_SIMD_NEON 1
#include "raster/simd_kernel.h"
#undef SR_SIMD_FN
#undef SR_SIMD_TARGET
#undef SR_SIMD_NEON
#endif

sr_simd_level sr__simd_cpu_level(void)
{
#if defined(SR_SIMD_KERNEL_X86)
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("avx2")) {
        return SR_SIMD_BASE;
    }
    bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
                  __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl") &&
                  __builtin_cpu_supports("popcnt");
    return avx512 ? SR_SIMD_AVX512 : SR_SIMD_AVX2;
#elif defined(SR_HAVE_SIMD_KERNEL)
    return SR_SIMD_BASE; /* NEON */
#else
    return SR_SIMD_OFF;
#endif
}

sr_raster_fn sr__raster_simd_select(const sr_draw_state *ds)
{
#if defined(SR_SIMD_KERNEL_X86)
    switch (ds->simd) {
    case SR_SIMD_AVX512: return select_avx512(ds);
    case SR_SIMD_AVX2: return select_avx2(ds);
    case SR_SIMD_BASE: return select_base(ds);
    default:           return NULL;
    }
#elif defined(SR_HAVE_SIMD_KERNEL)
    return ds->simd == SR_SIMD_BASE ? select_neon(ds) : NULL;
#else
    (void)ds;
    return NULL;
#endif
}
