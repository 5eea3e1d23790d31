/* unorm8_neon.h - the vector kernels' lane helpers on AArch64 NEON: a
 * lane mask as bits, and sr__unorm8 on four lanes packed as the
 * framebuffer's bytes.  The NEON twins of the SSE2 forms in
 * simd_kernel.h and line.c, for the triangle kernels' NEON instance and
 * the line fast path; raster stage, tile worker threads.  Little-endian
 * AArch64 only (the includer checks).
 *
 * Exactness: equal to the scalar sr__unorm8 for every input.  min(1, v)
 * (FMIN) is at most 1 or NaN; the product and sum are the scalar ones in
 * its order (the build uses -ffp-contract=off, so they are not fused);
 * the unsigned conversion (FCVTZU) truncates as the scalar cast does and
 * sends NaN and negatives to 0 - where the scalar clamp to 0 gives
 * 0 x 255 + 0.5, also 0 - and at most 255.5 truncates to 255, so the
 * narrowing moves keep every value. */
#ifndef SR_UNORM8_NEON_H
#define SR_UNORM8_NEON_H

#include "simd_types.h"

#include <arm_neon.h>
#include <stdint.h>

/* One bit per lane of a mask of whole lanes (lane 0 = bit 0), as SSE's
 * movemask gives for such masks. */
static inline __attribute__((always_inline)) int sr__neon_bits(v4i m)
{
    const uint32x4_t weight = { 1, 2, 4, 8 };
    return (int)vaddvq_u32(vandq_u32((uint32x4_t)m, weight));
}

/* sr__unorm8 on each lane, as 16-bit lanes. */
static inline __attribute__((always_inline)) uint16x4_t sr__neon_unorm8(v4f c)
{
    float32x4_t v = vminq_f32(vdupq_n_f32(1.0f), (float32x4_t)c);
    float32x4_t s = vaddq_f32(vmulq_f32(v, vdupq_n_f32(255.0f)), vdupq_n_f32(0.5f));
    return vmovn_u32(vcvtq_u32_f32(s));
}

/* One pixel's r, g, b, a lanes as its framebuffer word. */
static inline __attribute__((always_inline)) uint32_t sr__neon_pack_unorm8(v4f c)
{
    uint16x4_t q = sr__neon_unorm8(c);
    return vget_lane_u32(vreinterpret_u32_u8(vmovn_u16(vcombine_u16(q, q))), 0);
}

/* Four pixels' r, g, b, a (one vector per channel) as four framebuffer
 * words. */
static inline __attribute__((always_inline)) v4i sr__neon_pack4_unorm8(const v4f c[4])
{
    uint8x16_t x = vcombine_u8(vmovn_u16(vcombine_u16(sr__neon_unorm8(c[0]), sr__neon_unorm8(c[1]))),
                               vmovn_u16(vcombine_u16(sr__neon_unorm8(c[2]), sr__neon_unorm8(c[3]))));
    /* Bytes R0..3 G0..3 B0..3 A0..3, gathered to R G B A per pixel. */
    const uint8x16_t order = { 0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15 };
    return (v4i)vqtbl1q_u8(x, order);
}

#endif
