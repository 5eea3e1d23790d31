/* explain_clip.c - `softrast explain clip`: Sutherland-Hodgman polygon
 * clipping against a rectangular window, one clip edge at a time, in the
 * library's order (left, bottom, right, top).  The polygons after each
 * stage are the library's own (sr_clip_polygon_rect's stage callback);
 * the captions classify each polygon edge S -> P against the clip edge by
 * the four cases: in-in outputs P, in-out the intersection I, out-in I
 * then P, out-out nothing.  The last frame fills the clipped polygon as
 * sr_fill_polygon does. */
#include "explain.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_OUT (4 * EX_MAX_POINTS + 8)   /* each stage adds at most one point per edge */

typedef struct stages {
    sr_point2 poly[5][MAX_OUT];   /* 0: the input, k + 1: after clip edge k */
    int count[5];
} stages;

static void on_stage(void *user, int edge, const sr_point2 *poly, int count)
{
    stages *s = user;
    int n = count < MAX_OUT ? count : MAX_OUT;
    memcpy(s->poly[edge + 1], poly, (size_t)n * sizeof *poly);
    s->count[edge + 1] = n;
}

static const char *const edge_names[4] = { "left", "bottom", "right", "top" };

/* Inside clip edge k of window w (xmin, ymin, xmax, ymax), as the
 * library decides it (on the edge is inside). */
static bool inside(const double *w, int k, sr_point2 p)
{
    switch (k) {
    case 0: return p.x >= w[0];
    case 1: return p.y <= w[3];
    case 2: return p.x <= w[2];
    default: return p.y >= w[1];
    }
}

static void draw_window(ex_canvas *c, const double *w, int hilite)
{
    sr_point2 r[4] = { { w[0], w[1] }, { w[2], w[1] }, { w[2], w[3] }, { w[0], w[3] } };
    ex_outline(c, r, 4, true, (sr_rgba){ 0.92f, 0.50f, 0.08f, 1 }, 2.5);
    if (hilite >= 0) {
        /* the clip edge as the whole line it lies on */
        double gw = c->grid_w, gh = c->grid_h;
        sr_point2 a, b;
        switch (hilite) {
        case 0: a = (sr_point2){ w[0], 0 }; b = (sr_point2){ w[0], gh }; break;
        case 1: a = (sr_point2){ 0, w[3] }; b = (sr_point2){ gw, w[3] }; break;
        case 2: a = (sr_point2){ w[2], 0 }; b = (sr_point2){ w[2], gh }; break;
        default: a = (sr_point2){ 0, w[1] }; b = (sr_point2){ gw, w[1] }; break;
        }
        ex_segment(c, a, b, EX_HILITE, 3);
    }
}

static void draw_poly(ex_canvas *c, const sr_point2 *p, int n, sr_rgba color, double width,
                      bool dots)
{
    ex_outline(c, p, n, true, color, width);
    for (int i = 0; i < n && dots; i++) {
        ex_dot(c, p[i], c->zoom >= 20 ? 3.5 : c->zoom * 0.18, color);
    }
}

/* Shade the cells whose centres are outside clip edge k. */
static void shade_outside(ex_canvas *c, const double *w, int k)
{
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            if (!inside(w, k, (sr_point2){ x + 0.5, y + 0.5 })) {
                ex_cell(c, x, y, (sr_rgba){ 0.88f, 0.88f, 0.90f, 1 });
            }
        }
    }
}

sr_result explain_clip(ex_canvas *c, const ex_primitive *prim)
{
    stages *s = calloc(1, sizeof *s);
    if (!s) {
        return c->error = SR_OUT_OF_MEMORY;
    }
    const double *w = prim->window;
    memcpy(s->poly[0], prim->pts, (size_t)prim->count * sizeof *prim->pts);
    s->count[0] = prim->count;
    sr_point2 out[MAX_OUT];
    int n_out = 0;
    sr_result r = sr_clip_polygon_rect(c->ctx, prim->pts, prim->count, w[0], w[1], w[2], w[3],
                                       &(sr_polygon_clip_desc){ on_stage, s }, out, MAX_OUT,
                                       &n_out);
    if (r != SR_OK) {
        free(s);
        return c->error = r;
    }
    char cap[2048];
    ex_begin(c);
    draw_window(c, w, -1);
    draw_poly(c, s->poly[0], s->count[0], EX_EDGE, 1.5, true);
    snprintf(cap, sizeof cap,
             "1. Sutherland-Hodgman: the polygon (%d vertices) is clipped against the window "
             "%g <= x <= %g, %g <= y <= %g (orange) one clip edge at a time: left, bottom, right, "
             "top. Each stage walks the polygon's edges S -> P and outputs by four cases.",
             prim->count, w[0], w[2], w[1], w[3]);
    ex_end(c, cap);

    for (int k = 0; k < 4 && c->error == SR_OK; k++) {
        const sr_point2 *in = s->poly[k];
        int n = s->count[k];
        int cases[4] = { 0 };   /* in-in, in-out, out-in, out-out */
        for (int i = 0; i < n; i++) {
            bool s_in = inside(w, k, in[(i + n - 1) % n]), p_in = inside(w, k, in[i]);
            cases[s_in ? (p_in ? 0 : 1) : (p_in ? 2 : 3)]++;
        }
        ex_begin(c);
        shade_outside(c, w, k);
        draw_window(c, w, k);
        draw_poly(c, in, n, (sr_rgba){ 0.6f, 0.6f, 0.64f, 1 }, 1.0, false);
        draw_poly(c, s->poly[k + 1], s->count[k + 1], EX_EDGE, 2.0, true);
        for (int i = 0; i < s->count[k + 1]; i++) {
            /* the intersections this stage made lie on its clip edge */
            sr_point2 p = s->poly[k + 1][i];
            double coord = k == 0 ? w[0] : k == 1 ? w[3] : k == 2 ? w[2] : w[1];
            if ((k % 2 == 0 ? p.x : p.y) == coord) {
                ex_dot(c, p, c->zoom >= 20 ? 4.5 : c->zoom * 0.22, EX_HILITE);
            }
        }
        snprintf(cap, sizeof cap,
                 "%d. Clip edge %d, %s (%s %s %g; grey: outside): %d vertices in, %d out. "
                 "in-in %d (output P), in-out %d (output I), out-in %d (output I, P), out-out %d "
                 "(nothing). Intersections on the clip edge in pink.",
                 k + 2, k + 1, edge_names[k], k % 2 == 0 ? "x" : "y",
                 k == 0 || k == 3 ? ">=" : "<=", k == 0 ? w[0] : k == 1 ? w[3] : k == 2 ? w[2] : w[1],
                 n, s->count[k + 1], cases[0], cases[1], cases[2], cases[3]);
        ex_end(c, cap);
    }

    /* the clipped polygon filled as sr_fill_polygon fills it */
    ex_begin(c);
    uint8_t *mask = calloc((size_t)c->grid_w * c->grid_h, 1);
    int filled = 0;
    if (!mask) {
        c->error = SR_OUT_OF_MEMORY;
    } else if (n_out > 0) {
        r = sr_polygon_coverage(c->ctx, &(sr_polygon2){ out, n_out, NULL, 0 },
                                &(sr_fill_desc){ .rule = prim->rule }, 0, 0, c->grid_w,
                                c->grid_h, mask, (size_t)c->grid_w);
        if (r != SR_OK && c->error == SR_OK) {
            c->error = r;
        }
    }
    for (int y = 0; y < c->grid_h && mask; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            if (mask[y * c->grid_w + x]) {
                ex_cell(c, x, y, EX_INK);
                filled++;
            }
        }
    }
    free(mask);
    draw_window(c, w, -1);
    draw_poly(c, out, n_out, EX_EDGE, 1.5, true);
    snprintf(cap, sizeof cap,
             "6. The clipped polygon, %d vertices (sr_clip_polygon_rect), filled: %d pixels, "
             "exactly those sr_fill_polygon draws for it (%s). A concave polygon may keep "
             "zero-area bridges along the window border; they fill nothing.",
             n_out, filled, prim->rule == SR_EVENODD ? "even-odd" : "nonzero");
    ex_end(c, cap);
    free(s);
    return c->error;
}
