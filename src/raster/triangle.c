/* triangle.c - the half-space rasterizer (raster stage): within one tile,
 * walk 8x8 blocks; classify each block from the edge values at its corner
 * samples as outside (skip), inside (every pixel, no tests) or partial
 * (test each pixel).  Only integer adds and sign tests; the fill rule was
 * folded into the bias by setup.  Runs on a tile worker thread.
 *
 * This is the fast path: the loop is instantiated once per shading model
 * and depth mode (raster_as with constant arguments), so the per-fragment
 * switches vanish.  scanline.c and barycentric.c call the generic
 * fragment stage and are the reference these instances are tested
 * against. */
#include "fragment/fragment.h"
#include "raster/block.h"

SR_INLINE void raster_as(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0, int rx1,
                         int ry1, sr_frag_stats *st, sr_shading shading, sr_depth_mode dmode)
{
    /* The edge functions, and their per-pixel steps (q8 coordinates). */
    sr_edges ed;
    sr__tri_edges(t, &ed);
    int64_t sx[3], sy[3];
    sr__pixel_steps(t, sx, sy);
    int bx_start = rx0 & ~(SR_BLOCK_SIZE - 1);
    int by_start = ry0 & ~(SR_BLOCK_SIZE - 1);

    for (int by = by_start; by < ry1; by += SR_BLOCK_SIZE) {
        for (int bx = bx_start; bx < rx1; bx += SR_BLOCK_SIZE) {
            /* Edge values (biased) at the block's first pixel centre. */
            int64_t e[3];
            bool inside;
            if (!sr__block_classify(&ed, bx, by, sx, sy, e, &inside)) {
                continue;
            }
            int px0 = bx > rx0 ? bx : rx0, px1 = bx + SR_BLOCK_SIZE < rx1 ? bx + SR_BLOCK_SIZE : rx1;
            int py0 = by > ry0 ? by : ry0, py1 = by + SR_BLOCK_SIZE < ry1 ? by + SR_BLOCK_SIZE : ry1;
            /* Barycentrics use the unbiased values: fold -bias in once. */
            int64_t u0 = e[0] - ed.bias[0] + sy[0] * (py0 - by) + sx[0] * (px0 - bx);
            int64_t u1 = e[1] - ed.bias[1] + sy[1] * (py0 - by) + sx[1] * (px0 - bx);
            int64_t u2 = e[2] - ed.bias[2] + sy[2] * (py0 - by) + sx[2] * (px0 - bx);
            for (int py = py0; py < py1; py++) {
                int64_t r0 = u0, r1 = u1, r2 = u2;
                for (int px = px0; px < px1; px++) {
                    /* Covered iff every biased value r + bias >= 0. */
                    if (inside || ((r0 + ed.bias[0]) | (r1 + ed.bias[1]) | (r2 + ed.bias[2])) >= 0) {
                        sr__fragment_as(ds, t, px, py, r0, r1, r2, st, shading, dmode);
                    }
                    r0 += sx[0];
                    r1 += sx[1];
                    r2 += sx[2];
                }
                u0 += sy[0];
                u1 += sy[1];
                u2 += sy[2];
            }
        }
    }
}

/* One instance per shading model and depth mode, named
 * raster_<shading>_<depth> (raster_unlit_less, raster_phong_generic). */
#define SR_RASTER_SHADINGS(X, dname, dmode)                                                  \
    X(unlit, SR_SHADING_UNLIT, dname, dmode) X(flat, SR_SHADING_FLAT, dname, dmode)          \
    X(gouraud, SR_SHADING_GOURAUD, dname, dmode) X(phong, SR_SHADING_PHONG, dname, dmode)    \
    X(normals, SR_SHADING_NORMALS, dname, dmode) X(depth, SR_SHADING_DEPTH, dname, dmode)    \
    X(attribute, SR_SHADING_ATTRIBUTE, dname, dmode)

#define SR_RASTER_INSTANCE(name, shading, dname, dmode)                                      \
    static void raster_##name##_##dname(const sr_draw_state *ds, const sr_tri *t, int rx0,   \
                                        int ry0, int rx1, int ry1, sr_frag_stats *st)        \
    {                                                                                        \
        raster_as(ds, t, rx0, ry0, rx1, ry1, st, shading, dmode);                            \
    }
SR_RASTER_SHADINGS(SR_RASTER_INSTANCE, off, SR_DEPTH_MODE_OFF)
SR_RASTER_SHADINGS(SR_RASTER_INSTANCE, less, SR_DEPTH_MODE_LESS)
SR_RASTER_SHADINGS(SR_RASTER_INSTANCE, generic, SR_DEPTH_MODE_GENERIC)

#define SR_RASTER_ENTRY(name, shading, dname, dmode) [dmode][shading] = raster_##name##_##dname,
static const sr_raster_fn raster_table[3][SR_SHADING_ATTRIBUTE + 1] = {
    SR_RASTER_SHADINGS(SR_RASTER_ENTRY, off, SR_DEPTH_MODE_OFF)
    SR_RASTER_SHADINGS(SR_RASTER_ENTRY, less, SR_DEPTH_MODE_LESS)
    SR_RASTER_SHADINGS(SR_RASTER_ENTRY, generic, SR_DEPTH_MODE_GENERIC)
};

sr_raster_fn sr__raster_halfspace_select(const sr_draw_state *ds)
{
    return raster_table[ds->depth_mode][ds->shading];
}
