/* explain_circle.c - `softrast explain circle`: the midpoint circle as
 * sr_draw_circle runs it.  The decision variable is the circle's implicit
 * function F(x, y) = (x - cx)^2 + (y - cy)^2 - r^2 at pixel centres, exact
 * in integers (centre and radius snapped to 1/256 pixel); a pixel is
 * inside when F < 0.  Row by row, the walk starts from the previous row's
 * ends and steps left or right while the sign says so, each step by a
 * forward difference, F(x + 1) - F(x) = 2 (x - cx) + 1, so the whole
 * circle costs steps in proportion to its perimeter.  The outline is the
 * set of inside pixels with an outside 4-neighbour: no gaps, no pixel
 * twice, for any centre and radius. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define Q8 256
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const sr_rgba INTERIOR = { 0.80f, 0.90f, 0.80f, 1 };
static const sr_rgba OUTSIDE = { 1.0f, 0.85f, 0.82f, 1 };   /* tested, F >= 0 */

typedef struct circle {
    int64_t cx, cy, r;   /* q8 */
} circle;

/* F at the centre of pixel (i, j), in q8 squared (1/65536 pixel^2). */
static int64_t decide(const circle *k, int64_t i, int64_t j)
{
    int64_t dx = i * Q8 + Q8 / 2 - k->cx, dy = j * Q8 + Q8 / 2 - k->cy;
    return dx * dx + dy * dy - k->r * k->r;
}

/* F(i + 1) - F(i) on one row: the forward difference 2 dx + 1 (q8). */
static int64_t step(const circle *k, int64_t i)
{
    int64_t dx = i * Q8 + Q8 / 2 - k->cx;
    return 2 * Q8 * dx + Q8 * Q8;
}

static void f_text(ex_canvas *c, int x, int y, int64_t f)
{
    char s[32];
    double v = f / 65536.0;
    snprintf(s, sizeof s, "%.1f", v);
    if (!ex_cell_text(c, x, y, s, f < 0 ? EX_TEXT : EX_BAD)) {
        snprintf(s, sizeof s, "%.0f", v);
        ex_cell_text(c, x, y, s, f < 0 ? EX_TEXT : EX_BAD);
    }
}

static void note(int64_t *seen, int *n, int max, int64_t i)
{
    if (*n < max) {
        seen[(*n)++] = i;
    }
}

/* One end of row j's span: from pixel i, step outward (dir) while the
 * next pixel is inside, or inward while this one is outside.  The first
 * `max` pixels tested go to seen[]. */
static int64_t walk_end(const circle *k, int64_t i, int64_t j, int dir, int64_t *seen, int *n,
                        int max)
{
    int64_t f = decide(k, i, j);
    note(seen, n, max, i);
    if (f < 0) {
        for (;;) {
            int64_t g = dir > 0 ? f + step(k, i) : f - step(k, i - 1);
            note(seen, n, max, i + dir);
            if (g >= 0) {
                return i;
            }
            f = g;
            i += dir;
        }
    }
    while (f >= 0) {
        f = dir > 0 ? f - step(k, i - 1) : f + step(k, i);
        i -= dir;
        note(seen, n, max, i);
    }
    return i;
}

/* Row j's inside pixels lo..hi (lo > hi: none), from the hint's ends. */
static void row_span(const circle *k, int64_t j, int64_t ic, const int64_t hint[2],
                     int64_t span[2], int64_t *seen, int *n, int max)
{
    span[0] = 1;
    span[1] = 0;
    if (decide(k, ic, j) >= 0) {
        return;
    }
    int nl = 0, nr = 0;
    span[0] = walk_end(k, hint[0] < ic ? hint[0] : ic, j, -1, seen, &nl, max / 2);
    span[1] = walk_end(k, hint[1] > ic ? hint[1] : ic, j, +1, seen + nl, &nr, max / 2);
    *n = nl + nr;
}

static void draw_circle(ex_canvas *c, const circle *k)
{
    sr_point2 pts[96];
    double r = k->r / 256.0;
    for (int i = 0; i < 96; i++) {
        double a = i * 2 * M_PI / 96;
        pts[i] = (sr_point2){ k->cx / 256.0 + r * cos(a), k->cy / 256.0 + r * sin(a) };
    }
    ex_outline(c, pts, 96, true, EX_HILITE, 1.5);
    ex_dot(c, (sr_point2){ k->cx / 256.0, k->cy / 256.0 }, 3, EX_HILITE);
}

/* Rows whose span and tested centres are all off the grid, shown as one
 * frame: the first and the last row and their spans. */
typedef struct off_rows {
    int first, last, rows;
    int64_t first_span[2], last_span[2];
} off_rows;

static void off_rows_frame(ex_canvas *c, const circle *k, off_rows *o)
{
    if (o->rows == 0) {
        return;
    }
    char cap[400];
    ex_begin(c);
    draw_circle(c, k);
    if (o->first == o->last) {
        snprintf(cap, sizeof cap,
                 "%d. Row %d: inside %lld..%lld, off the grid, not shown.",
                 c->frame_count + 1, o->first, (long long)o->first_span[0],
                 (long long)o->first_span[1]);
    } else {
        snprintf(cap, sizeof cap,
                 "%d. Rows %d to %d: inside %lld..%lld to %lld..%lld, off the grid, "
                 "not shown.", c->frame_count + 1, o->first, o->last,
                 (long long)o->first_span[0], (long long)o->first_span[1],
                 (long long)o->last_span[0], (long long)o->last_span[1]);
    }
    ex_end(c, cap);
    o->rows = 0;
}

sr_result explain_circle(ex_canvas *c, const ex_primitive *prim)
{
    circle k = { ex_snap(prim->pts[0].x), ex_snap(prim->pts[0].y), ex_snap(prim->z[0]) };
    int gw = c->grid_w, gh = c->grid_h;
    int64_t *span = malloc(sizeof *span * 2 * (size_t)(gh + 2)),
            *seen = malloc(sizeof *seen * (size_t)(4 * gw + 8));
    if (!span || !seen) {
        free(span);
        free(seen);
        return SR_OUT_OF_MEMORY;
    }
    char cap[700];
    ex_begin(c);
    for (int y = 0; y < gh; y++) {
        for (int x = 0; x < gw; x++) {
            ex_sample(c, x, y, EX_EDGE);
        }
    }
    draw_circle(c, &k);
    snprintf(cap, sizeof cap,
             "1. A circle, centre (%g, %g), radius %g (snapped to 1/256). Decision variable: "
             "F(x, y) = (x - cx)^2 + (y - cy)^2 - r^2 at each pixel centre, exact in integers; "
             "inside where F < 0. Along a row it changes by the forward difference "
             "F(x+1) - F(x) = 2(x - cx) + 1. Each row starts from the ends of the row above.",
             prim->pts[0].x, prim->pts[0].y, prim->z[0]);
    ex_end(c, cap);

    /* rows -1 .. gh: the ones beside the grid decide its edge rows' outline */
    int64_t ic = (int64_t)floor(k.cx / 256.0);   /* the column nearest the centre */
    int64_t hint[2] = { ic, ic };
    int max = 4 * gw + 8;
    off_rows off = { 0 };
    for (int y = -1; y <= gh; y++) {
        int64_t *sp = span + 2 * (y + 1);
        int n = 0;
        row_span(&k, y, ic, hint, sp, seen, &n, max);
        if (sp[0] > sp[1]) {
            continue;
        }
        int64_t from[2] = { hint[0] < ic ? hint[0] : ic, hint[1] > ic ? hint[1] : ic };
        hint[0] = sp[0];
        hint[1] = sp[1];
        if (y < 0 || y == gh) {
            continue;
        }
        bool shown = sp[0] < gw && sp[1] >= 0;
        for (int s = 0; s < n; s++) {
            shown = shown || (seen[s] >= 0 && seen[s] < gw);
        }
        if (!shown) {
            if (off.rows == 0) {
                off.first = y;
                off.first_span[0] = sp[0];
                off.first_span[1] = sp[1];
            }
            off.last = y;
            off.last_span[0] = sp[0];
            off.last_span[1] = sp[1];
            off.rows++;
            continue;
        }
        off_rows_frame(c, &k, &off);
        ex_begin(c);
        for (int yy = 0; yy <= y; yy++) {
            const int64_t *q = span + 2 * (yy + 1);
            for (int64_t x = q[0] > 0 ? q[0] : 0; x <= q[1] && x < gw; x++) {
                ex_cell(c, (int)x, yy, yy == y ? EX_CELL_IN : INTERIOR);
            }
        }
        for (int s = 0; s < n; s++) {
            if (seen[s] >= 0 && seen[s] < gw) {
                int64_t f = decide(&k, seen[s], y);
                if (f >= 0) {
                    ex_cell(c, (int)seen[s], y, OUTSIDE);
                }
                f_text(c, (int)seen[s], y, f);
            }
        }
        draw_circle(c, &k);
        snprintf(cap, sizeof cap,
                 "%d. Row %d (F < 0 at the centre column %lld): from x = %lld step left while the "
                 "next F < 0 (right while this F >= 0), from x = %lld the other way; each F is "
                 "its neighbour's plus one forward difference. %d centres tested (F in "
                 "pixels^2; pink: outside). Inside: %lld..%lld.",
                 c->frame_count + 1, y, (long long)ic, (long long)from[0], (long long)from[1], n,
                 (long long)sp[0], (long long)sp[1]);
        ex_end(c, cap);
    }

    off_rows_frame(c, &k, &off);

    /* the outline: inside pixels with an outside 4-neighbour */
    ex_begin(c);
    int outline = 0;
    for (int y = 0; y < gh; y++) {
        const int64_t *up = span + 2 * y, *cur = up + 2, *down = up + 4;
        for (int64_t x = cur[0] > 0 ? cur[0] : 0; x <= cur[1] && x < gw; x++) {
            bool edge = x < up[0] || x > up[1] || x < down[0] || x > down[1] || x == cur[0] ||
                        x == cur[1];
            ex_cell(c, (int)x, y, edge ? EX_INK : INTERIOR);
            outline += edge;
        }
    }
    draw_circle(c, &k);
    snprintf(cap, sizeof cap,
             "%d. The outline: the %d inside pixels with an outside 4-neighbour (blue), so "
             "the octants meet with no gap and no pixel twice: what sr_draw_circle draws (filled, "
             "it draws the green interior too).",
             c->frame_count + 1, outline);
    ex_end(c, cap);
    free(span);
    free(seen);
    return c->error;
}
