/* msaa_walk.h - walking a triangle's 8x8 blocks for the per-sample
 * and programmable paths (raster stage, tile workers).  A block is
 * classified over the whole squares of its pixels - every sample lies
 * within 128 q8 of its pixel centre on each axis - as outside (skipped),
 * inside (every sample of every pixel covered) or partial.  The callers
 * pass a constant callback and get their own inlined loop. */
#ifndef SR_SAMPLE_WALK_H
#define SR_SAMPLE_WALK_H

#include "fragment/fragment.h"
#include "raster/block.h"

#include <stdlib.h>

typedef struct sr_block_steps {
    sr_edges ed;                      /* the triangle's edge functions */
    int64_t slack[3];                 /* |a| + |b| times half a pixel, multisampled */
    int64_t sx[3], sy[3];             /* per-pixel steps */
} sr_block_steps;

SR_INLINE void sr__block_steps(const sr_draw_state *ds, const sr_tri *t, sr_block_steps *k)
{
    sr__tri_edges(t, &k->ed);
    for (int i = 0; i < 3; i++) {
        k->slack[i] = ds->samples > 1 ? (llabs(t->a[i]) + llabs(t->b[i])) * SR_SUBPIXEL_HALF : 0;
        k->sx[i] = (int64_t)t->a[i] * SR_SUBPIXEL_ONE;
        k->sy[i] = (int64_t)t->b[i] * SR_SUBPIXEL_ONE;
    }
}

/* The unbiased edge values at pixel (px0, py0)'s centre in u[]; false when
 * the pixels [px0, px1) x [py0, py1) hold no covered sample. */
SR_INLINE bool sr__block_open(const sr_block_steps *k, int px0, int py0, int px1, int py1,
                              int64_t u[3], bool *inside)
{
    if (!sr__rect_classify(&k->ed, px0, py0, px1, py1, k->sx, k->sy, k->slack, u, inside)) {
        return false;
    }
    for (int i = 0; i < 3; i++) {
        u[i] -= k->ed.bias[i];
    }
    return true;
}

/* Every open block of [rx0, rx1) x [ry0, ry1): `block` gets the block's
 * part rect = { px0, py0, px1, py1 }, the unbiased edge values at
 * (px0, py0)'s centre and whether the block is inside.  The two walkers
 * below visit a block's pixels one by one or by 2x2 quads. */
SR_INLINE void sr__block_walk(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0, int rx1,
                              int ry1, void *arg,
                              void (*block)(void *, const sr_block_steps *, const int[4],
                                            const int64_t *, bool))
{
    sr_block_steps k;
    sr__block_steps(ds, t, &k);
    const int last = SR_BLOCK_SIZE - 1;
    for (int by = ry0 & ~last; by < ry1; by += SR_BLOCK_SIZE) {
        for (int bx = rx0 & ~last; bx < rx1; bx += SR_BLOCK_SIZE) {
            const int rect[4] = { bx > rx0 ? bx : rx0, by > ry0 ? by : ry0,
                                  bx + SR_BLOCK_SIZE < rx1 ? bx + SR_BLOCK_SIZE : rx1,
                                  by + SR_BLOCK_SIZE < ry1 ? by + SR_BLOCK_SIZE : ry1 };
            int64_t u[3];
            bool inside;
            if (sr__block_open(&k, rect[0], rect[1], rect[2], rect[3], u, &inside)) {
                block(arg, &k, rect, u, inside);
            }
        }
    }
}

typedef void (*sr_pixel_fn)(void *, int, int, const int64_t *, bool);
typedef void (*sr_quad_fn)(void *, int, int, const int64_t *, bool, const int[4]);

typedef struct sr_walk {
    void *arg;
    sr_pixel_fn pixel;
    sr_quad_fn quad;
} sr_walk;

SR_INLINE void sr__walk_pixels(void *arg, const sr_block_steps *k, const int rect[4],
                               const int64_t *u0, bool inside)
{
    const sr_walk *w = arg;
    int64_t row[3] = { u0[0], u0[1], u0[2] };
    for (int py = rect[1]; py < rect[3]; py++) {
        int64_t u[3] = { row[0], row[1], row[2] };
        for (int px = rect[0]; px < rect[2]; px++) {
            w->pixel(w->arg, px, py, u, inside);
            for (int i = 0; i < 3; i++) {
                u[i] += k->sx[i];
            }
        }
        for (int i = 0; i < 3; i++) {
            row[i] += k->sy[i];
        }
    }
}

SR_INLINE void sr__walk_quads(void *arg, const sr_block_steps *k, const int rect[4],
                              const int64_t *u0, bool inside)
{
    const sr_walk *w = arg;
    for (int qy = rect[1] & ~1; qy < rect[3]; qy += 2) {
        for (int qx = rect[0] & ~1; qx < rect[2]; qx += 2) {
            int64_t u[3];
            for (int i = 0; i < 3; i++) {
                u[i] = u0[i] + k->sx[i] * (qx - rect[0]) + k->sy[i] * (qy - rect[1]);
            }
            w->quad(w->arg, qx, qy, u, inside, rect);
        }
    }
}

/* Every pixel of the open blocks: `pixel` gets its unbiased centre edge
 * values and whether its block is inside. */
SR_INLINE void sr__msaa_walk(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0,
                             int rx1, int ry1, void *arg, sr_pixel_fn pixel)
{
    sr_walk w = { arg, pixel, NULL };
    sr__block_walk(ds, t, rx0, ry0, rx1, ry1, &w, sr__walk_pixels);
}

/* The same by 2x2 quads (for fragment shaders): `quad` gets the quad's
 * top-left pixel (qx, qy), even coordinates, with its unbiased centre edge
 * values, and the part of the block it may cover; its lanes outside that
 * part hold no fragment. */
SR_INLINE void sr__quad_walk(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0,
                             int rx1, int ry1, void *arg, sr_quad_fn quad)
{
    sr_walk w = { arg, NULL, quad };
    sr__block_walk(ds, t, rx0, ry0, rx1, ry1, &w, sr__walk_quads);
}

#endif
