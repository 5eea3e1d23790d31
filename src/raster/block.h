/* block.h - classifying a rectangle of pixels (an 8x8 block, a tile's
 * part) against a set-up triangle (raster stage), shared by the scalar,
 * vector and per-sample half-space loops.  An edge
 * function is linear, so its extremes over the block's sample points are
 * at the corners: the block is outside when some edge is negative at every
 * corner, inside when every edge is non-negative at every corner. */
#ifndef SR_BLOCK_H
#define SR_BLOCK_H

#include "pipeline.h"

/* Each edge function's step from one pixel to the next along a row (sx)
 * and down a column (sy), in q8 units. */
static inline void sr__pixel_steps(const sr_tri *t, int64_t sx[3], int64_t sy[3])
{
    /* From the record, not a copy in sr_edges: the vectorized loads of a
     * copy just stored one field at a time would wait on store
     * forwarding (a tenth of the kernel's time on `small`). */
    for (int i = 0; i < 3; i++) {
        sx[i] = (int64_t)t->a[i] * SR_SUBPIXEL_ONE;
        sy[i] = (int64_t)t->b[i] * SR_SUBPIXEL_ONE;
    }
}

/* The largest and smallest value over a rectangle's corners of an edge
 * function that is e at its first corner and changes by ex across its
 * width and ey down its height. */
static inline int64_t sr__edge_max(int64_t e, int64_t ex, int64_t ey)
{
    return e + (ex > 0 ? ex : 0) + (ey > 0 ? ey : 0);
}

static inline int64_t sr__edge_min(int64_t e, int64_t ex, int64_t ey)
{
    return e + (ex < 0 ? ex : 0) + (ey < 0 ? ey : 0);
}

/* The pixels [x0, x1) x [y0, y1): e[i] = biased edge value at pixel
 * (x0, y0)'s centre; sx, sy = per-pixel steps; slack[i] widens the test to
 * samples up to that far from the centres (multisampling; zero for pixel
 * centres).  Returns false when no sample of the rectangle is covered;
 * *inside tells whether every one is. */
static inline bool sr__rect_classify(const sr_edges *ed, int x0, int y0, int x1, int y1,
                                     const int64_t sx[3], const int64_t sy[3],
                                     const int64_t slack[3], int64_t e[3], bool *inside)
{
    bool in = true;
    for (int i = 0; i < 3; i++) {
        e[i] = sr__edge_at(ed, i, sr__centre_q8(x0), sr__centre_q8(y0)) + ed->bias[i];
        int64_t ex = sx[i] * (x1 - 1 - x0), ey = sy[i] * (y1 - 1 - y0);
        if (sr__edge_max(e[i], ex, ey) + slack[i] < 0) {
            return false;
        }
        in &= sr__edge_min(e[i], ex, ey) - slack[i] >= 0;
    }
    *inside = in;
    return true;
}

static const int64_t sr__no_slack[3] = { 0, 0, 0 };

/* An 8x8 block at (bx, by), pixel centres. */
static inline bool sr__block_classify(const sr_edges *ed, int bx, int by, const int64_t sx[3],
                                      const int64_t sy[3], int64_t e[3], bool *inside)
{
    return sr__rect_classify(ed, bx, by, bx + SR_BLOCK_SIZE, by + SR_BLOCK_SIZE, sx, sy,
                             sr__no_slack, e, inside);
}

/* Whether every pixel centre of [x0, x1) x [y0, y1) is covered: a big
 * triangle over most of its tiles, whose blocks then need no
 * classification. */
static inline bool sr__rect_inside(const sr_edges *ed, int x0, int y0, int x1, int y1,
                                   const int64_t sx[3], const int64_t sy[3])
{
    int64_t e[3];
    bool inside;
    return sr__rect_classify(ed, x0, y0, x1, y1, sx, sy, sr__no_slack, e, &inside) && inside;
}

/* Whether every edge value at the pixel centres of [x0, x1) x [y0, y1)
 * fits in 32 bits (with room for the coverage bias): an edge function is
 * linear, so its extremes over the rectangle are at the corners.  This
 * goes by the values, not by the rectangle's size: a small box can be the
 * corner of a huge triangle, whose values there exceed 32 bits. */
static inline bool sr__rect_fits32(const sr_edges *ed, int x0, int y0, int x1, int y1)
{
    const int64_t lim = INT32_MAX - 1;
    for (int i = 0; i < 3; i++) {
        int64_t e = sr__edge_at(ed, i, sr__centre_q8(x0), sr__centre_q8(y0));
        int64_t ex = ed->a[i] * SR_SUBPIXEL_ONE * (x1 - 1 - x0);
        int64_t ey = ed->b[i] * SR_SUBPIXEL_ONE * (y1 - 1 - y0);
        if (sr__edge_max(e, ex, ey) > lim || sr__edge_min(e, ex, ey) < -lim) {
            return false;
        }
    }
    return true;
}

#endif
