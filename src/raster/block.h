/* block.h - classifying an 8x8 block against a set-up triangle (raster
 * stage), shared by the scalar and the vector half-space loops.  An edge
 * function is linear, so its extremes over the block's sample points are
 * at the corners: the block is outside when some edge is negative at every
 * corner, inside when every edge is non-negative at every corner. */
#ifndef SR_BLOCK_H
#define SR_BLOCK_H

#include "pipeline.h"

/* e[i] = biased edge value at the block's first pixel centre (bx, by);
 * sx, sy = per-pixel steps.  Returns false when the block is outside. */
static inline bool sr__block_classify(const sr_tri *t, int bx, int by, const int64_t sx[3],
                                      const int64_t sy[3], int64_t e[3], bool *inside)
{
    const int last = SR_BLOCK_SIZE - 1;
    bool in = true;
    for (int i = 0; i < 3; i++) {
        e[i] = t->a[i] * sr__centre_q8(bx) + t->b[i] * sr__centre_q8(by) + t->c[i] + t->bias[i];
        int64_t ex = sx[i] * last, ey = sy[i] * last;
        if (e[i] + (ex > 0 ? ex : 0) + (ey > 0 ? ey : 0) < 0) {
            return false;
        }
        in &= e[i] + (ex < 0 ? ex : 0) + (ey < 0 ? ey : 0) >= 0;
    }
    *inside = in;
    return true;
}

/* Whether every pixel centre of [x0, x1) x [y0, y1) is covered: a big
 * triangle over most of its tiles, whose blocks then need no
 * classification. */
static inline bool sr__rect_inside(const sr_tri *t, int x0, int y0, int x1, int y1,
                                   const int64_t sx[3], const int64_t sy[3])
{
    for (int i = 0; i < 3; i++) {
        int64_t e = t->a[i] * sr__centre_q8(x0) + t->b[i] * sr__centre_q8(y0) + t->c[i] +
                    t->bias[i];
        int64_t ex = sx[i] * (x1 - 1 - x0), ey = sy[i] * (y1 - 1 - y0);
        if (e + (ex < 0 ? ex : 0) + (ey < 0 ? ey : 0) < 0) {
            return false;
        }
    }
    return true;
}

#endif
