/* sample_walk.h - walking a triangle's 8x8 blocks for the per-sample
 * and programmable paths (raster stage, tile workers).  A block is
 * classified over the whole squares of its pixels - every sample lies
 * within 128 q8 of its pixel centre on each axis - as outside (skipped),
 * inside (every sample of every pixel covered) or partial.  The callers
 * pass a constant callback and get their own inlined loop. */
#ifndef SR_SAMPLE_WALK_H
#define SR_SAMPLE_WALK_H

#include "fragment/fragment.h"

#include <stdlib.h>

typedef struct sr_block_steps {
    int64_t slack[3];                 /* |a| + |b| times half a pixel, multisampled */
    int64_t sx[3], sy[3];             /* per-pixel steps */
} sr_block_steps;

SR_INLINE void sr__block_steps(const sr_draw_state *ds, const sr_tri *t, sr_block_steps *k)
{
    for (int i = 0; i < 3; i++) {
        k->slack[i] = ds->samples > 1 ? (llabs(t->a[i]) + llabs(t->b[i])) * SR_SUBPIXEL_HALF : 0;
        k->sx[i] = t->a[i] * SR_SUBPIXEL_ONE;
        k->sy[i] = t->b[i] * SR_SUBPIXEL_ONE;
    }
}

/* The unbiased edge values at pixel (px0, py0)'s centre in u[]; false when
 * the pixels [px0, px1) x [py0, py1) hold no covered sample. */
SR_INLINE bool sr__block_open(const sr_tri *t, const sr_block_steps *k, int px0, int py0,
                              int px1, int py1, int64_t u[3], bool *inside)
{
    bool in = true;
    for (int i = 0; i < 3; i++) {
        int64_t e = t->a[i] * sr__centre_q8(px0) + t->b[i] * sr__centre_q8(py0) + t->c[i] +
                    t->bias[i];
        int64_t ex = k->sx[i] * (px1 - 1 - px0), ey = k->sy[i] * (py1 - 1 - py0);
        if (e + (ex > 0 ? ex : 0) + (ey > 0 ? ey : 0) + k->slack[i] < 0) {
            return false;
        }
        in &= e + (ex < 0 ? ex : 0) + (ey < 0 ? ey : 0) - k->slack[i] >= 0;
        u[i] = e - t->bias[i];
    }
    *inside = in;
    return true;
}

/* Every pixel of the open blocks of [rx0, rx1) x [ry0, ry1): `pixel` gets
 * its unbiased centre edge values and whether its block is inside. */
SR_INLINE void sr__sample_walk(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0,
                               int rx1, int ry1, void *arg,
                               void (*pixel)(void *, int, int, const int64_t *, bool))
{
    sr_block_steps k;
    sr__block_steps(ds, t, &k);
    const int last = SR_BLOCK_SIZE - 1;
    for (int by = ry0 & ~last; by < ry1; by += SR_BLOCK_SIZE) {
        for (int bx = rx0 & ~last; bx < rx1; bx += SR_BLOCK_SIZE) {
            int px0 = bx > rx0 ? bx : rx0, px1 = bx + SR_BLOCK_SIZE < rx1 ? bx + SR_BLOCK_SIZE : rx1;
            int py0 = by > ry0 ? by : ry0, py1 = by + SR_BLOCK_SIZE < ry1 ? by + SR_BLOCK_SIZE : ry1;
            int64_t row[3];
            bool inside;
            if (!sr__block_open(t, &k, px0, py0, px1, py1, row, &inside)) {
                continue;
            }
            for (int py = py0; py < py1; py++) {
                int64_t u[3] = { row[0], row[1], row[2] };
                for (int px = px0; px < px1; px++) {
                    pixel(arg, px, py, u, inside);
                    for (int i = 0; i < 3; i++) {
                        u[i] += k.sx[i];
                    }
                }
                for (int i = 0; i < 3; i++) {
                    row[i] += k.sy[i];
                }
            }
        }
    }
}

/* The same by 2x2 quads (for fragment shaders): `quad` gets the quad's
 * top-left pixel (qx, qy), even coordinates, with its unbiased centre edge
 * values, and the part [px0, px1) x [py0, py1) of the block it may cover;
 * its lanes outside that part hold no fragment. */
SR_INLINE void sr__quad_walk(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0,
                             int rx1, int ry1, void *arg,
                             void (*quad)(void *, int, int, const int64_t *, bool,
                                          const int rect[4]))
{
    sr_block_steps k;
    sr__block_steps(ds, t, &k);
    const int last = SR_BLOCK_SIZE - 1;
    for (int by = ry0 & ~last; by < ry1; by += SR_BLOCK_SIZE) {
        for (int bx = rx0 & ~last; bx < rx1; bx += SR_BLOCK_SIZE) {
            int px0 = bx > rx0 ? bx : rx0, px1 = bx + SR_BLOCK_SIZE < rx1 ? bx + SR_BLOCK_SIZE : rx1;
            int py0 = by > ry0 ? by : ry0, py1 = by + SR_BLOCK_SIZE < ry1 ? by + SR_BLOCK_SIZE : ry1;
            int64_t e[3];
            bool inside;
            if (!sr__block_open(t, &k, px0, py0, px1, py1, e, &inside)) {
                continue;
            }
            const int rect[4] = { px0, py0, px1, py1 };
            for (int qy = py0 & ~1; qy < py1; qy += 2) {
                for (int qx = px0 & ~1; qx < px1; qx += 2) {
                    int64_t u[3];
                    for (int i = 0; i < 3; i++) {
                        u[i] = e[i] + k.sx[i] * (qx - px0) + k.sy[i] * (qy - py0);
                    }
                    quad(arg, qx, qy, u, inside, rect);
                }
            }
        }
    }
}

#endif
