/* triangle.c - the half-space rasterizer (raster stage): within one tile,
 * walk 8x8 blocks; classify each block from the edge values at its corner
 * samples as outside (skip), inside (every pixel, no tests) or partial
 * (test each pixel).  Only integer adds and sign tests; the fill rule was
 * folded into the bias by setup.  Runs on a tile worker thread. */
#include "fragment/fragment.h"

void sr__raster_halfspace(const sr_draw_state *ds, const sr_tri *t,
                          int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st)
{
    /* Per-pixel steps of each edge function (q8 coordinates). */
    int64_t sx[3], sy[3];
    for (int i = 0; i < 3; i++) {
        sx[i] = t->a[i] * SR_SUBPIXEL_ONE;
        sy[i] = t->b[i] * SR_SUBPIXEL_ONE;
    }
    int bx_start = rx0 & ~(SR_BLOCK_SIZE - 1);
    int by_start = ry0 & ~(SR_BLOCK_SIZE - 1);
    const int last = SR_BLOCK_SIZE - 1;

    for (int by = by_start; by < ry1; by += SR_BLOCK_SIZE) {
        for (int bx = bx_start; bx < rx1; bx += SR_BLOCK_SIZE) {
            /* Edge values (biased) at the block's first pixel centre. */
            int64_t e[3], lo[3], hi[3];
            bool outside = false, inside = true;
            for (int i = 0; i < 3; i++) {
                e[i] = t->a[i] * sr__centre_q8(bx) + t->b[i] * sr__centre_q8(by) + t->c[i] +
                       t->bias[i];
                /* E is linear: its extremes over the block are at corners. */
                int64_t ex = sx[i] * last, ey = sy[i] * last;
                lo[i] = e[i] + (ex < 0 ? ex : 0) + (ey < 0 ? ey : 0);
                hi[i] = e[i] + (ex > 0 ? ex : 0) + (ey > 0 ? ey : 0);
                outside |= hi[i] < 0;
                inside &= lo[i] >= 0;
            }
            if (outside) {
                continue;
            }
            int px0 = bx > rx0 ? bx : rx0, px1 = bx + SR_BLOCK_SIZE < rx1 ? bx + SR_BLOCK_SIZE : rx1;
            int py0 = by > ry0 ? by : ry0, py1 = by + SR_BLOCK_SIZE < ry1 ? by + SR_BLOCK_SIZE : ry1;
            for (int py = py0; py < py1; py++) {
                int64_t r0 = e[0] + sy[0] * (py - by) + sx[0] * (px0 - bx);
                int64_t r1 = e[1] + sy[1] * (py - by) + sx[1] * (px0 - bx);
                int64_t r2 = e[2] + sy[2] * (py - by) + sx[2] * (px0 - bx);
                for (int px = px0; px < px1; px++) {
                    if (inside || (r0 | r1 | r2) >= 0) {
                        /* Barycentrics use the unbiased values. */
                        sr__fragment(ds, t, px, py, r0 - t->bias[0], r1 - t->bias[1],
                                     r2 - t->bias[2], st);
                    }
                    r0 += sx[0];
                    r1 += sx[1];
                    r2 += sx[2];
                }
            }
        }
    }
}
