/* explain_triangle_walk.c - `softrast explain triangle --rasterizer
 * scanline|barycentric`: the coverage of explain_triangle.c reached the two
 * other ways the pipeline can (SR_RASTER_SCANLINE, SR_RASTER_BARYCENTRIC).
 * The scan-line rasterizer sorts the vertices by y, walks the long edge
 * on one side and the two short edges, split at the middle vertex, on the
 * other, and fills each scanline between the crossings of its centre line
 * y + 1/2; the barycentric one tests every pixel centre of the bounding
 * box by its weights.  Both decide ties by the same top-left rule, so the
 * pixels are the half-space rasterizer's. */
#include "explain.h"

#include <math.h>
#include <stdio.h>

#define MAX_WALK_FRAMES 12  /* scanlines are grouped beyond this many */

static double px(int64_t q)
{
    return (double)q / 256.0;
}

/* Where edge a -> b crosses the horizontal line at y (pixels). */
static double cross_x(const ex_tri *t, int a, int b, double y)
{
    double ya = px(t->y[a]), yb = px(t->y[b]);
    return px(t->x[a]) + (y - ya) * (px(t->x[b]) - px(t->x[a])) / (yb - ya);
}

static double slope(const ex_tri *t, int a, int b)
{
    return t->y[a] == t->y[b] ? 0 : (double)(t->x[b] - t->x[a]) / (double)(t->y[b] - t->y[a]);
}

/* Whether the centre of (x, y) lies on an edge (some E = 0) with the
 * others not negative: a tie the top-left rule decides. */
static bool tie(const ex_tri *t, int x, int y)
{
    int64_t sx = (int64_t)x * 256 + 128, sy = (int64_t)y * 256 + 128;
    bool zero = false;
    for (int i = 0; i < 3; i++) {
        int64_t e = ex_tri_edge(t, i, sx, sy);
        if (e < 0) {
            return false;
        }
        zero |= e == 0;
    }
    return zero;
}

static bool covers(const ex_tri *t, int x, int y)
{
    return ex_tri_covers(t, (int64_t)x * 256 + 128, (int64_t)y * 256 + 128);
}

/* A covered cell in `fill`, a tie ringed (taken) or crossed (not). */
static void mark(ex_canvas *c, const ex_tri *t, int x, int y, sr_rgba fill)
{
    bool in = covers(t, x, y);
    if (in) {
        ex_cell(c, x, y, fill);
    }
    if (tie(t, x, y)) {
        if (in) {
            ex_ring(c, x, y, EX_INK);
        } else {
            ex_cross(c, x, y, EX_BAD);
        }
    }
}

void ex_tri_scanline_steps(ex_canvas *c, const ex_tri *t)
{
    int o[3];   /* by y, then x */
    ex_tri_order_by_y(t, o);
    int top = o[0], mid = o[1], bot = o[2];
    double y_top = px(t->y[top]), y_mid = px(t->y[mid]), y_bot = px(t->y[bot]);
    bool long_left = cross_x(t, top, bot, y_mid) < px(t->x[mid]);
    /* the scanlines whose centre line meets the triangle, within the grid */
    int first = (int)fmax(0, ceil(y_top - 0.5));
    int last = (int)fmin(c->grid_h - 1, ceil(y_bot - 0.5) - 1);
    char cap[640];

    ex_begin(c);
    ex_tri_samples(c);
    ex_tri_draw(c, t, -1);
    sr_point2 a = { px(t->x[top]), y_top }, b = { px(t->x[bot]), y_bot };
    ex_segment(c, a, b, EX_HILITE, 4);
    for (int y = first; y <= last; y++) {
        double yc = y + 0.5;
        int s0 = yc < y_mid ? top : mid, s1 = yc < y_mid ? mid : bot;
        ex_dot(c, (sr_point2){ cross_x(t, top, bot, yc), yc }, 3, EX_HILITE);
        ex_dot(c, (sr_point2){ cross_x(t, s0, s1, yc), yc }, 3, EX_EDGE);
    }
    snprintf(cap, sizeof cap,
             "2. Edge walking: V%d top, V%d middle, V%d bottom by y. The long edge V%d->V%d "
             "(pink) bounds the spans on the %s, the short edges, split at V%d, on the %s. Down "
             "the centre lines y+1/2 the crossings (dots) step by dx/dy: %.3g long, %.3g and "
             "%.3g short.",
             top, mid, bot, top, bot, long_left ? "left" : "right", mid,
             long_left ? "right" : "left", slope(t, top, bot), slope(t, top, mid),
             slope(t, mid, bot));
    ex_end(c, cap);

    int rows = last - first + 1;
    int per = rows <= MAX_WALK_FRAMES ? 1 : (rows + MAX_WALK_FRAMES - 1) / MAX_WALK_FRAMES;
    for (int g = first; g <= last; g += per) {
        int g_end = g + per - 1 < last ? g + per - 1 : last;
        ex_begin(c);
        for (int y = first; y <= g_end; y++) {
            for (int x = 0; x < c->grid_w; x++) {
                if (y < g) {
                    if (covers(t, x, y)) {
                        ex_cell(c, x, y, EX_CELL_IN);
                    }
                } else {
                    mark(c, t, x, y, EX_CELL_IN);
                }
            }
        }
        ex_tri_samples(c);
        ex_tri_draw(c, t, -1);
        int n = 0, lo = -1, hi = -1;
        double xl = 0, xr = 0;
        for (int y = g; y <= g_end; y++) {
            double yc = y + 0.5;
            int s0 = yc < y_mid ? top : mid, s1 = yc < y_mid ? mid : bot;
            double xa = cross_x(t, top, bot, yc), xb = cross_x(t, s0, s1, yc);
            xl = long_left ? xa : xb;
            xr = long_left ? xb : xa;
            ex_segment(c, (sr_point2){ xl, yc }, (sr_point2){ xr, yc }, EX_HILITE, 2);
            ex_dot(c, (sr_point2){ xl, yc }, 3, EX_HILITE);
            ex_dot(c, (sr_point2){ xr, yc }, 3, EX_HILITE);
            for (int x = 0; x < c->grid_w; x++) {
                if (covers(t, x, y)) {
                    lo = lo < 0 ? x : lo;
                    hi = y == g ? x : hi;
                    n++;
                }
            }
        }
        if (g == g_end) {
            char span[96] = "no pixel centre lies between them";
            if (n) {
                snprintf(span, sizeof span, "pixels %d..%d (%d) have their centres between them",
                         lo, hi, n);
            }
            snprintf(cap, sizeof cap,
                     "%d. Scanline %d: its centre line y = %g crosses the left edge at x = %.3f "
                     "and the right edge at x = %.3f; %s. A centre exactly on an edge is taken "
                     "on a left edge (ringed), not on a right one (crossed).",
                     c->frame_count + 1, g, g + 0.5, xl, xr, span);
        } else {
            snprintf(cap, sizeof cap,
                     "%d. Scanlines %d to %d: each one's span runs from the left edge's crossing "
                     "of its centre line to the right edge's (pink), %d pixels in all. A centre "
                     "exactly on an edge is taken on a left edge (ringed), not on a right one "
                     "(crossed).",
                     c->frame_count + 1, g, g_end, n);
        }
        ex_end(c, cap);
    }
}

void ex_tri_barycentric_steps(ex_canvas *c, const ex_tri *t)
{
    int64_t x0 = t->x[0], x1 = t->x[0], y0 = t->y[0], y1 = t->y[0];
    for (int i = 1; i < 3; i++) {
        x0 = t->x[i] < x0 ? t->x[i] : x0;
        x1 = t->x[i] > x1 ? t->x[i] : x1;
        y0 = t->y[i] < y0 ? t->y[i] : y0;
        y1 = t->y[i] > y1 ? t->y[i] : y1;
    }
    /* the pixels whose centres lie in the box */
    int bx0 = (int)ceil(px(x0) - 0.5), bx1 = (int)floor(px(x1) - 0.5);
    int by0 = (int)ceil(px(y0) - 0.5), by1 = (int)floor(px(y1) - 0.5);
    sr_point2 box[4] = { { px(x0), px(y0) }, { px(x1), px(y0) }, { px(x1), px(y1) },
                         { px(x0), px(y1) } };
    bool in_box[2] = { false, true };
    char cap[640];
    int tested = 0, inside = 0, ties = 0;
    for (int step = 0; step < 2; step++) {
        ex_begin(c);
        for (int y = 0; y < c->grid_h; y++) {
            for (int x = 0; x < c->grid_w; x++) {
                if (x < bx0 || x > bx1 || y < by0 || y > by1) {
                    continue;
                }
                if (!in_box[step]) {
                    ex_cell(c, x, y, EX_TIE);
                    tested++;
                    continue;
                }
                double l[3];
                ex_tri_weights(t, (int64_t)x * 256 + 128, (int64_t)y * 256 + 128, l);
                double m = fmin(l[0], fmin(l[1], l[2]));
                char s[16];
                snprintf(s, sizeof s, "%.2f", m);
                mark(c, t, x, y, EX_CELL_IN);
                if (m >= 0) {
                    ex_cell_text(c, x, y, s, EX_TEXT);
                }
                inside += m > 0;
                ties += tie(t, x, y);
            }
        }
        ex_tri_samples(c);
        ex_outline(c, box, 4, true, EX_HILITE, 2);
        ex_tri_draw(c, t, -1);
        if (step == 0) {
            snprintf(cap, sizeof cap,
                     "2. The bounding box of the snapped vertices (pink), x %g..%g, y %g..%g: "
                     "the %d pixels whose centres lie in it (yellow) are each tested; no other "
                     "pixel is looked at.",
                     px(x0), px(x1), px(y0), px(y1), tested);
        } else {
            snprintf(cap, sizeof cap,
                     "3. Each centre's barycentric weights l0, l1, l2 (edge functions over "
                     "twice the area, summing to 1; printed: the smallest, if not negative). "
                     "Inside when all are > 0 (green, %d); %d centres have a weight of 0: the "
                     "top-left rule decides (ringed taken, crossed not).",
                     inside, ties);
        }
        ex_end(c, cap);
    }
}
