/* scanline.c - scan-line edge walking, a reference rasterizer (raster
 * stage).  The classic triangle scan conversion: split the triangle at its
 * middle vertex into two regions and, scanline by scanline, step x along
 * the left and the right edges, filling the span between them.
 *
 * Exactness: each edge's span limit on scanline y is the exact rational
 * solution of E_i(x, y_c) + bias_i >= 0, kept as a quotient and remainder
 * and stepped by a DDA (an integer Bresenham-style update), so the spans are
 * bit-identical to the half-space rasterizer's coverage.  Edges with a > 0
 * bound the span on the left, edges with a < 0 on the right; which edges
 * those are changes at the middle vertex - the split into two regions -
 * and taking the tightest of them on every row handles it without
 * special cases.  Runs on a tile worker thread. */
#include "fragment/fragment.h"

void sr__raster_scanline(const sr_draw_state *ds, const sr_tri *t,
                         int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st)
{
    /* Per edge, on the first scanline y_c = centre(ry0), with
     * R = b y_c + c + bias the edge value at x = 0:
     *   a > 0 (left):  a X + R >= 0  <=>  X >= -R/a
     *       first pixel = ceil((-R - 128 a) / 256 a) = floor((-R - 128 a - 1) / 256 a) + 1
     *   a < 0 (right): X <= R/|a|
     *       last pixel  = floor((R - 128 |a|) / 256 |a|)
     *   a = 0 (horizontal): the whole row is in iff R >= 0.
     * R grows by 256 b per scanline. */
    sr_dda dda[3];
    int kind[3]; /* +1 left, -1 right, 0 horizontal */
    sr_edges ed;
    sr__tri_edges(t, &ed);
    int64_t yc0 = sr__centre_q8(ry0);
    for (int i = 0; i < 3; i++) {
        int64_t a = t->a[i];
        int64_t R = ed.b[i] * yc0 + ed.c[i] + ed.bias[i];
        int64_t dR = (int64_t)t->b[i] * SR_SUBPIXEL_ONE;
        if (a > 0) {
            kind[i] = 1;
            sr__dda_init(&dda[i], -R - SR_SUBPIXEL_HALF * a - 1, SR_SUBPIXEL_ONE * a, -dR);
        } else if (a < 0) {
            kind[i] = -1;
            sr__dda_init(&dda[i], R + SR_SUBPIXEL_HALF * a, -SR_SUBPIXEL_ONE * a, dR);
        } else {
            kind[i] = 0;
            /* Reuse q as the row value R itself, stepped by dR. */
            dda[i].q = R;
            dda[i].dq = dR;
        }
    }

    for (int py = ry0; py < ry1; py++) {
        int left = rx0, right = rx1 - 1; /* inclusive */
        bool empty = false;
        for (int i = 0; i < 3; i++) {
            if (kind[i] > 0) {
                int64_t first = dda[i].q + 1;
                left = first > left ? (int)(first < rx1 ? first : rx1) : left;
            } else if (kind[i] < 0) {
                int64_t lastp = dda[i].q;
                right = lastp < right ? (int)(lastp > rx0 - 1 ? lastp : rx0 - 1) : right;
            } else {
                empty |= dda[i].q < 0;
            }
        }
        if (!empty && left <= right) {
            int64_t yc = sr__centre_q8(py);
            int64_t xc = sr__centre_q8(left);
            int64_t e0 = sr__edge_at(&ed, 0, xc, yc);
            int64_t e1 = sr__edge_at(&ed, 1, xc, yc);
            int64_t e2 = sr__edge_at(&ed, 2, xc, yc);
            for (int px = left; px <= right; px++) {
                sr__fragment(ds, t, px, py, e0, e1, e2, st);
                e0 += (int64_t)t->a[0] * SR_SUBPIXEL_ONE;
                e1 += (int64_t)t->a[1] * SR_SUBPIXEL_ONE;
                e2 += (int64_t)t->a[2] * SR_SUBPIXEL_ONE;
            }
        }
        for (int i = 0; i < 3; i++) {
            if (kind[i] != 0) {
                sr__dda_step(&dda[i]);
            } else {
                dda[i].q += dda[i].dq;
            }
        }
    }
}
