/* fixed.h - the fixed-point formats of the rasterizer and their bit budgets.
 *
 * Window positions are snapped to 8 sub-pixel bits ("q8", S = 256 per pixel)
 * with round-to-nearest-even.  The guard band keeps window coordinates within
 * [-16384, 16384) px, so |X_q8| < 2^22.  Edge deltas are then < 2^23, an edge
 * value multiplies two deltas (< 2^46) and is held in int64; three of them sum
 * to area2 < 2^48, which a double holds exactly, so barycentrics
 * e_i / area2 are exact to one rounding (docs/raster-rules.md §2.2). */
#ifndef SR_FIXED_H
#define SR_FIXED_H

#include <stdint.h>

#define SR_SUBPIXEL_BITS 8
#define SR_SUBPIXEL_ONE  (1 << SR_SUBPIXEL_BITS)
#define SR_SUBPIXEL_HALF (SR_SUBPIXEL_ONE / 2)   /* pixel centre offset: 128 */

#define SR_GUARD_BAND_MIN (-16384)               /* px, window space */
#define SR_GUARD_BAND_MAX 16384

/* 128 x 128 pixel tiles: a tile's color and depth (128 KiB) stay in the
 * L2 cache while it is drawn, and against 64 x 64 ones fewer primitives
 * are drawn in two tiles or more and each tile's runs of records are
 * longer.  Measured faster in every bench scene but msaa4, whose 4-sample
 * tiles are 512 KiB: level alone, slower beside llvmpipe
 * (docs/performance.md). */
#define SR_TILE_ORDER 7
#define SR_TILE_SIZE  (1 << SR_TILE_ORDER)
#define SR_BLOCK_ORDER 3                         /* 8 x 8 blocks inside a tile */
#define SR_BLOCK_SIZE (1 << SR_BLOCK_ORDER)

_Static_assert((int64_t)SR_GUARD_BAND_MAX * SR_SUBPIXEL_ONE < ((int64_t)1 << 22) + 1,
               "guard band must keep q8 coordinates below 2^22");

/* floor(a / b) and ceil(a / b) for b > 0, on int64. */
static inline int64_t sr__floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

static inline int64_t sr__ceil_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && a > 0) ? q + 1 : q;
}

/* floor(a / 256) and ceil(a / 256): arithmetic shifts, which GCC and
 * Clang define for negative values (rounding toward minus infinity), in
 * place of two 64-bit divisions per bound in triangle setup. */
static inline int64_t sr__floor_q8(int64_t a)
{
    return a >> SR_SUBPIXEL_BITS;
}

static inline int64_t sr__ceil_q8(int64_t a)
{
    return -((-a) >> SR_SUBPIXEL_BITS);
}

/* floor(n / d) kept incrementally while n grows by a constant dn per step:
 * the quotient-and-remainder DDA (a Bresenham-style update) that scan-line
 * edge walking and line rasterization use to step an exact rational
 * coordinate with integer adds only.  d > 0. */
typedef struct sr_dda {
    int64_t q, r, d;    /* n = q d + r, 0 <= r < d */
    int64_t dq, dr;     /* dn = dq d + dr, 0 <= dr < d */
} sr_dda;

static inline void sr__dda_init(sr_dda *s, int64_t n, int64_t d, int64_t dn)
{
    s->d = d;
    s->q = sr__floor_div(n, d);
    s->r = n - s->q * d;
    s->dq = sr__floor_div(dn, d);
    s->dr = dn - s->dq * d;
}

static inline void sr__dda_step(sr_dda *s)
{
    s->q += s->dq;
    s->r += s->dr;
    if (s->r >= s->d) {
        s->r -= s->d;
        s->q++;
    }
}

/* Pixel centre in q8: (256 px + 128). */
static inline int64_t sr__centre_q8(int p)
{
    return (int64_t)p * SR_SUBPIXEL_ONE + SR_SUBPIXEL_HALF;
}

#endif
