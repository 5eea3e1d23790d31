/* sample.c - the per-sample triangle path (raster stage): multisampled
 * coverage, and the stencil test, for every triangle rasterizer choice.
 * Runs on tile workers.
 *
 * Coverage (RASTER_RULES 8.2): sample s of pixel (x, y) lies at the pixel
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
#include "fragment/sample.h"

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
    unsigned pass = 0;
    for (unsigned m = mask; m; m &= m - 1) {
        int s = __builtin_ctz(m);
        uint32_t q = 0;
        if (ds->depth_mode != SR_DEPTH_MODE_OFF) {
            double z = sr__tri_depth(t, u[1] + so[s][1], u[2] + so[s][2]);
            q = sr__quantize_depth(ds, &z);
        }
        if (sr__sample_test(ds, base + (size_t)s, q, t->front, true)) {
            pass |= 1u << s;
        }
    }
    if (!pass) {
        return;
    }
    if (!shaded) {
        shade_centre(ds, t, u, c);
    }
    sr__write_samples(ds, base, pass, c, &ds->blend);
    st->fragments += (uint64_t)__builtin_popcount(pass);
}

void sr__raster_sample(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0, int rx1,
                       int ry1, sr_frag_stats *st)
{
    int n = ds->samples;
    unsigned all = n >= 32 ? ~0u : (1u << n) - 1u;
    int64_t so[16][3];
    /* A block is classified over the whole squares of its pixels: every
     * sample lies within 128 q8 of its pixel centre on each axis. */
    int64_t slack[3], sx[3], sy[3];
    for (int i = 0; i < 3; i++) {
        for (int s = 0; s < n; s++) {
            so[s][i] = t->a[i] * ds->sample_off[s][0] + t->b[i] * ds->sample_off[s][1];
        }
        slack[i] = n > 1 ? (llabs(t->a[i]) + llabs(t->b[i])) * SR_SUBPIXEL_HALF : 0;
        sx[i] = t->a[i] * SR_SUBPIXEL_ONE;
        sy[i] = t->b[i] * SR_SUBPIXEL_ONE;
    }
    const int last = SR_BLOCK_SIZE - 1;
    for (int by = ry0 & ~last; by < ry1; by += SR_BLOCK_SIZE) {
        for (int bx = rx0 & ~last; bx < rx1; bx += SR_BLOCK_SIZE) {
            int px0 = bx > rx0 ? bx : rx0, px1 = bx + SR_BLOCK_SIZE < rx1 ? bx + SR_BLOCK_SIZE : rx1;
            int py0 = by > ry0 ? by : ry0, py1 = by + SR_BLOCK_SIZE < ry1 ? by + SR_BLOCK_SIZE : ry1;
            /* Biased edge values at the first pixel centre; the extremes
             * over the block are at its corners, widened by the slack. */
            int64_t e[3];
            bool outside = false, inside = true;
            for (int i = 0; i < 3; i++) {
                e[i] = t->a[i] * sr__centre_q8(px0) + t->b[i] * sr__centre_q8(py0) + t->c[i] +
                       t->bias[i];
                int64_t ex = sx[i] * (px1 - 1 - px0), ey = sy[i] * (py1 - 1 - py0);
                int64_t hi = e[i] + (ex > 0 ? ex : 0) + (ey > 0 ? ey : 0) + slack[i];
                int64_t lo = e[i] + (ex < 0 ? ex : 0) + (ey < 0 ? ey : 0) - slack[i];
                outside |= hi < 0;
                inside &= lo >= 0;
            }
            if (outside) {
                continue;
            }
            for (int py = py0; py < py1; py++) {
                for (int px = px0; px < px1; px++) {
                    int64_t dx = px - px0, dy = py - py0;
                    /* Unbiased values at this pixel's centre. */
                    int64_t u[3];
                    for (int i = 0; i < 3; i++) {
                        u[i] = e[i] - t->bias[i] + sx[i] * dx + sy[i] * dy;
                    }
                    unsigned mask = all;
                    if (!inside) {
                        mask = 0;
                        for (int s = 0; s < n; s++) {
                            if (((u[0] + so[s][0] + t->bias[0]) | (u[1] + so[s][1] + t->bias[1]) |
                                 (u[2] + so[s][2] + t->bias[2])) >= 0) {
                                mask |= 1u << s;
                            }
                        }
                    }
                    if (mask) {
                        fragment_samples(ds, t, px, py, u, (const int64_t(*)[3])so, mask, st);
                    }
                }
            }
        }
    }
}
