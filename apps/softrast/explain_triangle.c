/* explain_triangle.c - `softrast explain triangle`: a triangle by its
 * edge functions, as the pipeline's rasterizers cover it.  The vertices
 * are snapped to 1/256 pixel; each edge a->b gives the edge function
 * E(x, y) = (xb - xa)(y - ya) - (yb - ya)(x - xa), evaluated exactly at
 * every pixel centre; a pixel is covered when all three are positive, and
 * a centre exactly on an edge (E = 0, a tie) is covered only when that
 * edge is a top or a left edge: the top-left rule, which draws a pixel
 * shared by two triangles exactly once. */
#include "explain.h"

#include <stdio.h>

typedef ex_tri tri;

int64_t ex_tri_edge(const ex_tri *t, int i, int64_t sx, int64_t sy)
{
    int a = i, b = (i + 1) % 3;
    return (t->x[b] - t->x[a]) * (sy - t->y[a]) - (t->y[b] - t->y[a]) * (sx - t->x[a]);
}

static int64_t edge_at(const tri *t, int i, int px, int py)
{
    return ex_tri_edge(t, i, (int64_t)px * 256 + 128, (int64_t)py * 256 + 128);
}

bool ex_tri_covers(const ex_tri *t, int64_t sx, int64_t sy)
{
    for (int i = 0; i < 3; i++) {
        int64_t e = ex_tri_edge(t, i, sx, sy);
        if (e < 0 || (e == 0 && !t->top_left[i])) {
            return false;
        }
    }
    return true;
}

static bool covered(const tri *t, int px, int py)
{
    return ex_tri_covers(t, (int64_t)px * 256 + 128, (int64_t)py * 256 + 128);
}

bool ex_tri_setup(ex_tri *t, const ex_primitive *prim)
{
    for (int i = 0; i < 3; i++) {
        t->x[i] = ex_snap(prim->pts[i].x);
        t->y[i] = ex_snap(prim->pts[i].y);
    }
    t->area2 = (t->x[1] - t->x[0]) * (t->y[2] - t->y[0]) - (t->y[1] - t->y[0]) * (t->x[2] - t->x[0]);
    bool swapped = t->area2 < 0;
    if (swapped) {   /* the rasterizers take either winding: reorder, not cull */
        int64_t tx = t->x[1], ty = t->y[1];
        t->x[1] = t->x[2]; t->y[1] = t->y[2];
        t->x[2] = tx; t->y[2] = ty;
        t->area2 = -t->area2;
    }
    for (int i = 0; i < 3; i++) {
        int64_t dx = t->x[(i + 1) % 3] - t->x[i], dy = t->y[(i + 1) % 3] - t->y[i];
        t->top_left[i] = dy < 0 || (dy == 0 && dx > 0);
    }
    return swapped;
}

bool ex_tri_setup_at(ex_tri *t, double z[3], const ex_primitive *prim, int first)
{
    ex_primitive one = { .kind = EX_TRIANGLE, .count = 3 };
    for (int i = 0; i < 3; i++) {
        one.pts[i] = prim->pts[first + i];
        z[i] = prim->z[first + i];
    }
    bool swapped = ex_tri_setup(t, &one);
    if (swapped) {
        double z1 = z[1];
        z[1] = z[2];
        z[2] = z1;
    }
    return swapped;
}

void ex_tri_weights(const ex_tri *t, int64_t sx, int64_t sy, double l[3])
{
    /* edge i runs from Vi to Vi+1: edge 1 is opposite V0, and so on */
    for (int k = 0; k < 3; k++) {
        l[k] = (double)ex_tri_edge(t, (k + 1) % 3, sx, sy) / (double)t->area2;
    }
}

void ex_tri_order_by_y(const ex_tri *t, int o[3])
{
    o[0] = 0;
    o[1] = 1;
    o[2] = 2;
    for (int i = 0; i < 3; i++) {
        for (int j = i + 1; j < 3; j++) {
            if (t->y[o[j]] < t->y[o[i]] || (t->y[o[j]] == t->y[o[i]] && t->x[o[j]] < t->x[o[i]])) {
                int k = o[i];
                o[i] = o[j];
                o[j] = k;
            }
        }
    }
}

/* Whether no edge function is negative at the centre of (px, py);
 * *strict: whether all are positive. */
static bool on_or_inside(const tri *t, int px, int py, bool *strict)
{
    int64_t e[3] = { edge_at(t, 0, px, py), edge_at(t, 1, px, py), edge_at(t, 2, px, py) };
    *strict = e[0] > 0 && e[1] > 0 && e[2] > 0;
    return e[0] >= 0 && e[1] >= 0 && e[2] >= 0;
}

static const char *edge_kind(const tri *t, int i)
{
    int64_t dx = t->x[(i + 1) % 3] - t->x[i], dy = t->y[(i + 1) % 3] - t->y[i];
    if (dy == 0) {
        return dx > 0 ? "a top edge" : "a bottom edge";
    }
    return dy < 0 ? "a left edge" : "a right edge";
}

static sr_point2 vertex(const ex_tri *t, int i)
{
    return (sr_point2){ t->x[i] / 256.0, t->y[i] / 256.0 };
}

void ex_tri_draw(ex_canvas *c, const ex_tri *t, int hilite)
{
    sr_point2 v[3] = { vertex(t, 0), vertex(t, 1), vertex(t, 2) };
    ex_outline(c, v, 3, true, EX_EDGE, 1.5);
    if (hilite >= 0) {
        ex_segment(c, v[hilite], v[(hilite + 1) % 3], EX_HILITE, 4);
    }
    for (int i = 0; i < 3; i++) {
        char name[8];
        snprintf(name, sizeof name, "V%d", i);
        ex_dot(c, v[i], c->zoom >= 20 ? 4 : c->zoom * 0.2, EX_EDGE);
        ex_label(c, v[i], name, EX_EDGE);
    }
}

void ex_tri_samples(ex_canvas *c)
{
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            ex_sample(c, x, y, EX_EDGE);
        }
    }
}

/* E in square pixels, short enough for a cell. */
static void edge_text(char *buf, size_t size, int64_t e)
{
    double v = (double)e / 65536.0;
    if (v == (double)(int64_t)v) {
        snprintf(buf, size, "%lld", (long long)v);
    } else {
        snprintf(buf, size, "%.1f", v);
    }
}

static void fmt_q8(char *buf, size_t size, int64_t q)
{
    snprintf(buf, size, "%g", (double)q / 256.0);
}

/* Frames 2-6 of the half-space rasterizer: each edge function's sign,
 * their intersection, the top-left rule on the ties. */
static void halfspace_steps(ex_canvas *c, const tri *t)
{
    char cap[512];
    /* 2-4: each edge function's sign at every centre */
    for (int i = 0; i < 3; i++) {
        int b = (i + 1) % 3;
        ex_begin(c);
        int pos = 0, zero = 0;
        for (int y = 0; y < c->grid_h; y++) {
            for (int x = 0; x < c->grid_w; x++) {
                int64_t e = edge_at(t, i, x, y);
                ex_cell(c, x, y, e > 0 ? EX_CELL_IN : e == 0 ? EX_TIE : EX_CELL_OUT);
                pos += e > 0;
                zero += e == 0;
                char v[24];
                edge_text(v, sizeof v, e);
                ex_cell_text(c, x, y, v, EX_TEXT);
            }
        }
        ex_tri_samples(c);
        ex_tri_draw(c, t, i);
        snprintf(cap, sizeof cap,
                 "%d. Edge function E%d of V%d->V%d: E%d(x,y) = (x%d-x%d)(y-y%d) - (y%d-y%d)(x-x%d), "
                 "exact in integers. Green: E%d > 0 (inside this edge, %d pixels); "
                 "yellow: E%d = 0 (%d ties). It is %s.",
                 2 + i, i, i, b, i, b, i, i, b, i, i, i, pos, i, zero, edge_kind(t, i));
        ex_end(c, cap);
    }

    /* 5: the intersection, ties still open */
    ex_begin(c);
    int inside = 0, ties = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            bool strict, nonneg = on_or_inside(t, x, y, &strict);
            if (nonneg) {
                ex_cell(c, x, y, strict ? EX_CELL_IN : EX_TIE);
            }
            inside += strict;
            ties += nonneg && !strict;
        }
    }
    ex_tri_samples(c);
    ex_tri_draw(c, t, -1);
    snprintf(cap, sizeof cap,
             "5. The edge equations together: %d centres have E0, E1 and E2 all > 0 (green) and "
             "are covered. %d centres lie exactly on an edge (yellow, some E = 0): "
             "the next step decides them.",
             inside, ties);
    ex_end(c, cap);

    /* 6: the top-left rule on the ties */
    ex_begin(c);
    int taken = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            bool strict, nonneg = on_or_inside(t, x, y, &strict);
            if (strict) {
                ex_cell(c, x, y, EX_CELL_IN);
            } else if (nonneg) {
                bool in = covered(t, x, y);
                ex_cell(c, x, y, in ? EX_CELL_IN : EX_CELL_OUT);
                if (in) {
                    ex_ring(c, x, y, EX_INK);
                } else {
                    ex_cross(c, x, y, EX_BAD);
                }
                taken += in;
            }
        }
    }
    ex_tri_samples(c);
    ex_tri_draw(c, t, -1);
    snprintf(cap, sizeof cap,
             "6. Top-left rule: a tie on a top edge (horizontal, inside below) or a left edge "
             "is covered (ringed: %d), one on a right or bottom edge is not (crossed: %d), so "
             "triangles sharing an edge draw it once. E0: %s, E1: %s, E2: %s.",
             taken, ties - taken, edge_kind(t, 0), edge_kind(t, 1), edge_kind(t, 2));
    ex_end(c, cap);
}

void ex_tri_coverage(ex_canvas *c, const ex_tri *t, const char *lead)
{
    ex_begin(c);
    int total = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            if (covered(t, x, y)) {
                ex_cell(c, x, y, EX_INK);
                total++;
            }
        }
    }
    ex_tri_draw(c, t, -1);
    char cap[512];
    snprintf(cap, sizeof cap,
             "%d. %s: %d pixels, exactly those sr_draw fills for this triangle with any of "
             "its rasterizers (half-space, scan-line, barycentric).",
             c->frame_count + 1, lead, total);
    ex_end(c, cap);
}

sr_result explain_triangle(ex_canvas *c, const ex_primitive *prim)
{
    tri t;
    bool swapped = ex_tri_setup(&t, prim);
    char cap[512], a[3][2][24];
    for (int i = 0; i < 3; i++) {
        fmt_q8(a[i][0], sizeof a[i][0], t.x[i]);
        fmt_q8(a[i][1], sizeof a[i][1], t.y[i]);
    }

    /* 1: the triangle over the sample points */
    ex_begin(c);
    ex_tri_samples(c);
    ex_tri_draw(c, &t, -1);
    snprintf(cap, sizeof cap,
             "1. The triangle V0 (%s, %s), V1 (%s, %s), V2 (%s, %s), snapped to 1/256 pixel "
             "(8 sub-pixel bits). A pixel is a point sample at its centre (x+1/2, y+1/2): it is "
             "covered when its centre is inside.%s",
             a[0][0], a[0][1], a[1][0], a[1][1], a[2][0], a[2][1],
             swapped ? " (Given the other way round: V1 and V2 swapped so inside is E > 0.)" : "");
    ex_end(c, cap);
    if (t.area2 == 0) {
        ex_begin(c);
        ex_tri_samples(c);
        ex_tri_draw(c, &t, -1);
        ex_end(c, "2. The triangle has no area (its vertices are on one line after snapping): "
                  "it covers no pixel.");
        return c->error;
    }

    if (prim->rasterizer == SR_RASTER_SCANLINE) {
        ex_tri_scanline_steps(c, &t);
    } else if (prim->rasterizer == SR_RASTER_BARYCENTRIC) {
        ex_tri_barycentric_steps(c, &t);
    } else {
        halfspace_steps(c, &t);
    }
    ex_tri_coverage(c, &t, prim->rasterizer == SR_RASTER_SCANLINE ? "Spans filled"
                         : prim->rasterizer == SR_RASTER_BARYCENTRIC ? "Bounding box tested"
                                                                    : "Coverage");
    return c->error;
}
