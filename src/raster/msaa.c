/* msaa.c - the per-sample triangle path (raster stage): multisampled
 * coverage, and the stencil test, for every triangle rasterizer choice.
 * Runs on tile workers.
 *
 * Coverage (docs/raster-rules.md §9.2): sample s of pixel (x, y) lies at the pixel
 * centre plus the standard offset (16 x the D3D position, so an integer
 * in q8) and is covered iff every biased edge function is >= 0 there: the
 * same top-left rule as single sampling, decided in the same exact
 * integers.  A sample's edge value is the centre's plus a per-triangle
 * constant a dx + b dy, so a pixel costs one add and one sign test per
 * edge and sample.
 *
 * Depth is evaluated at each sample from the exact edge values; shading
 * runs once per pixel at its centre (extrapolated when the centre itself
 * is outside, as GPUs without centroid sampling do) and its color goes to
 * the samples that passed.  With one sample this is exactly the
 * single-sample rule, which is how the stencil test reuses it. */
#include "fragment/msaa_ops.h"
#include "raster/depth_lanes.h"
#include "raster/msaa_walk.h"

#include <stdlib.h>

/* Shade at the pixel centre from its unbiased edge values u[]. */
static void shade_centre(const sr_draw_state *ds, const sr_tri *t, const int64_t u[3], float c[4])
{
    double z = 0.0;
    if (ds->shading == SR_SHADING_DEPTH) {
        z = sr__tri_depth(t, u[1], u[2]);
        (void)sr__quantize_depth(ds, &z);
    }
    sr__shade(ds, t, z, u[0], u[1], u[2], c);
}

/* The pixel (px, py) with covered samples `mask`; so[s][i] is the offset
 * of sample s's edge value i from the centre's. */
static void fragment_samples(const sr_draw_state *ds, const sr_tri *t, int px, int py,
                             const int64_t u[3], const int64_t (*so)[3], unsigned mask,
                             sr_frag_stats *st)
{
    size_t n = (size_t)ds->samples;
    size_t base = ((size_t)py * (size_t)ds->fb->width + (size_t)px) * n;
    float c[4];
    bool shaded = false;
    if (ds->alpha_to_coverage) {
        shade_centre(ds, t, u, c);
        shaded = true;
        mask &= sr__alpha_coverage(c[3], ds->samples);
    }
    unsigned pass = sr__test_tri_samples(ds, t, base, u, so, mask, NULL);
    if (!pass) {
        return;
    }
    if (!shaded) {
        shade_centre(ds, t, u, c);
    }
    sr__write_samples(ds, base, pass, c, &ds->blend);
    st->fragments += (uint64_t)__builtin_popcount(pass);
}

typedef struct generic_pixel {
    const sr_draw_state *ds;
    const sr_tri *t;
    sr_frag_stats *st;
    unsigned all;
    int64_t so[16][3];
    int64_t bias[3];
} generic_pixel;

SR_INLINE void generic_pixel_fn(void *arg, int px, int py, const int64_t *u, bool inside)
{
    const generic_pixel *g = arg;
    const sr_tri *t = g->t;
    unsigned mask = g->all;
    if (!inside) {
        mask = 0;
        for (int s = 0; s < g->ds->samples; s++) {
            if (((u[0] + g->so[s][0] + g->bias[0]) | (u[1] + g->so[s][1] + g->bias[1]) |
                 (u[2] + g->so[s][2] + g->bias[2])) >= 0) {
                mask |= 1u << s;
            }
        }
    }
    if (mask) {
        fragment_samples(g->ds, t, px, py, u, (const int64_t(*)[3])g->so, mask, g->st);
    }
}

void sr__raster_msaa(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0, int rx1,
                     int ry1, sr_frag_stats *st)
{
    generic_pixel g = { ds, t, st, ds->samples >= 32 ? ~0u : (1u << ds->samples) - 1u, { { 0 } },
                        { 0 } };
    for (int i = 0; i < 3; i++) {
        g.bias[i] = sr__tri_bias(t, i);
    }
    for (int s = 0; s < ds->samples; s++) {
        for (int i = 0; i < 3; i++) {
            g.so[s][i] = (int64_t)t->a[i] * ds->sample_off[s][0] + (int64_t)t->b[i] * ds->sample_off[s][1];
        }
    }
    sr__msaa_walk(ds, t, rx0, ry0, rx1, ry1, &g, generic_pixel_fn);
}

/* ---- the four-sample vector path ---------------------------------------- */

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && \
    (defined(__x86_64__) || defined(__i386__))
#define SR_HAVE_SAMPLE_KERNEL 1
#include <immintrin.h>

#define SR_SIMD_FN(name) name##_avx2
#define SR_SIMD_TARGET __attribute__((target("avx2")))
#include "raster/msaa_kernel.h"
#undef SR_SIMD_FN
#undef SR_SIMD_TARGET

#define SR_SIMD_FN(name) name##_base
#define SR_SIMD_TARGET
#include "raster/msaa_kernel.h"
#undef SR_SIMD_FN
#undef SR_SIMD_TARGET

#include "raster/rows_avx512.h"
#include "raster/msaa_wide.h"

#elif defined(__aarch64__) && defined(__ARM_NEON)
/* NEON, the AArch64 baseline: the four-sample kernel is vector extensions
 * only, so it needs no intrinsics of its own. */
#define SR_HAVE_SAMPLE_KERNEL 1
#define SR_SIMD_FN(name) name##_neon
#define SR_SIMD_TARGET
#include "raster/msaa_kernel.h"
#undef SR_SIMD_FN
#undef SR_SIMD_TARGET
#endif

sr_raster_fn sr__raster_msaa_select(const sr_draw_state *ds)
{
#ifdef SR_HAVE_SAMPLE_KERNEL
    bool common = ds->samples == 4 && !ds->program && !ds->stencil_test && !ds->alpha_to_coverage &&
                  !ds->blending && !ds->blend.enabled && ds->depth_mode == SR_DEPTH_MODE_LESS &&
                  ds->depth_bits >= 1 && ds->depth_bits <= 24;
    if (!common) {
        return NULL;
    }
    /* Four pixels at a time where the shading is the interpolated color
     * or flat (as in the half-space kernels' select). */
    bool color = !ds->texture && (sr__color_varying_shading(ds->shading) ||
                                  ds->shading == SR_SHADING_FLAT);
#if defined(__aarch64__)
    (void)color;
    return ds->simd == SR_SIMD_BASE ? raster_ms4_neon : NULL;
#else
    switch (ds->simd) {
    case SR_SIMD_AVX512: return color ? raster_ms16 : raster_ms4_avx2;
    case SR_SIMD_AVX2: return raster_ms4_avx2;
    case SR_SIMD_BASE: return raster_ms4_base;
    default:           return NULL;
    }
#endif
#else
    (void)ds;
    return NULL;
#endif
}
