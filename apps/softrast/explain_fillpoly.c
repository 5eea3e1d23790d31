/* explain_fillpoly.c - `softrast explain fillpoly`: incremental scan-line
 * interpolation, the notes' FillPoly / FillSpan, as sr_fill_gouraud runs
 * it with SR_GOURAUD_INCREMENTAL.  The triangle's vertices are sorted by y
 * into A (top), B (middle), C (bottom).  Along each edge x steps by
 * dX = 1/m and the intensity by dI per scanline; the long edge AC is walked
 * beside AB above the middle vertex and beside BC below it.  Along each
 * span the intensity steps by (I_R - I_L) / (x_R - x_L) per pixel.  Every
 * walk starts at its first sample (the scanline centre y + 1/2, the pixel
 * centre x + 1/2) and sums in float, as the library does; the spans'
 * pixels are those of the edge-table converter (sr_polygon_coverage). */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* FillPoly's walk down one edge, x by 1/m and the intensity by dI per
 * scanline, from the first scanline centre (y + 1/2) below the top
 * vertex, summed in float as sr_fill_gouraud does. */
typedef struct ex_walk {
    double y0, y1, x0, x1;   /* top and bottom vertex, pixels */
    float i0, i1;
    int row;                 /* the scanline x and I are at; -1: not started */
    double x, dxdy;
    float I, dI;
    const char *name;
} ex_walk;

static ex_walk ex_walk_edge(const ex_tri *t, const double *in, int a, int b, const char *name)
{
    return (ex_walk){ .y0 = t->y[a] / 256.0, .y1 = t->y[b] / 256.0, .x0 = t->x[a] / 256.0,
                      .x1 = t->x[b] / 256.0, .i0 = (float)in[a], .i1 = (float)in[b], .row = -1,
                      .name = name };
}

static void ex_walk_to(ex_walk *w, int y)
{
    if (w->row < 0) {
        double dy = w->y1 - w->y0, pre = y + 0.5 - w->y0;
        w->dxdy = (w->x1 - w->x0) / dy;
        w->x = w->x0 + pre * w->dxdy;
        w->dI = (float)((w->i1 - w->i0) / dy);
        w->I = (float)(w->i0 + pre * w->dI);
        w->row = y;
    }
    while (w->row < y) {
        w->x += w->dxdy;
        w->I += w->dI;
        w->row++;
    }
}

/* B right of AC: AC is the left edge */
static bool ex_tri_long_edge_left(const ex_tri *t, const int o[3])
{
    return (t->x[o[1]] - t->x[o[0]]) * (t->y[o[2]] - t->y[o[0]]) -
           (t->y[o[1]] - t->y[o[0]]) * (t->x[o[2]] - t->x[o[0]]) > 0;
}

static sr_rgba grey(float v)
{
    return (sr_rgba){ v, v, v, 1 };
}

void ex_fillpoly_spans(const ex_tri *t, const double in[3], const uint8_t *mask, int gw, int gh,
                       float *I, ex_interp_row *rows)
{
    for (int i = 0; i < gw * gh; i++) {
        I[i] = NAN;
    }
    int o[3];   /* A, B, C: the vertices by y (then x) */
    ex_tri_order_by_y(t, o);
    ex_walk ac = ex_walk_edge(t, in, o[0], o[2], "AC"), ab = ex_walk_edge(t, in, o[0], o[1], "AB"),
            bc = ex_walk_edge(t, in, o[1], o[2], "BC");
    bool ac_left = ex_tri_long_edge_left(t, o);
    for (int y = 0; y < gh; y++) {
        ex_interp_row *r = &rows[y];
        *r = (ex_interp_row){ 0 };
        int x0 = -1, x1 = -1;
        for (int x = 0; x < gw; x++) {
            bool in_mask = mask ? mask[y * gw + x] != 0
                                : t->area2 != 0 && ex_tri_covers(t, (int64_t)x * 256 + 128,
                                                                  (int64_t)y * 256 + 128);
            if (in_mask) {
                x0 = x0 < 0 ? x : x0;
                x1 = x + 1;
            }
        }
        if (x0 < 0) {
            continue;
        }
        /* a covered centre lies below A and above C, so AC crosses it; the
         * other edge is AB above B, BC from B down (a horizontal AB is
         * never taken: no covered centre is above B then) */
        ex_walk *other = y + 0.5 < ab.y1 ? &ab : &bc;
        ex_walk *l = ac_left ? &ac : other, *rt = ac_left ? other : &ac;
        r->left = l->name;
        r->right = rt->name;
        r->fresh = (l->row < 0) | (rt->row < 0) << 1;
        ex_walk_to(l, y);
        ex_walk_to(rt, y);
        double width = rt->x - l->x;
        float dI = width > 0 ? (float)((rt->I - l->I) / width) : 0.0f;
        /* FillSpan: the first centre's value, then dI per pixel */
        float v = (float)(l->I + (x0 + 0.5 - l->x) * dI);
        for (int x = x0; x < x1; x++) {
            I[y * gw + x] = v;
            v += dI;
        }
        r->x0 = x0;
        r->x1 = x1;
        r->xl = l->x;
        r->xr = rt->x;
        r->il = l->I;
        r->ir = rt->I;
        r->dI = dI;
    }
}

void ex_cell_value(ex_canvas *c, int x, int y, float v)
{
    char s[16];
    snprintf(s, sizeof s, "%.2f", v);
    ex_cell_text(c, x, y, s + (v >= 0 && v < 1), v < 0.55f ? (sr_rgba){ 1, 1, 1, 1 } : EX_TEXT);
}

static void draw_tri(ex_canvas *c, const ex_tri *t, const int *order, const double *in)
{
    sr_point2 v[3];
    for (int i = 0; i < 3; i++) {
        v[i] = (sr_point2){ t->x[i] / 256.0, t->y[i] / 256.0 };
    }
    ex_outline(c, v, 3, true, EX_EDGE, 1.5);
    for (int k = 0; k < 3; k++) {
        char label[32];
        snprintf(label, sizeof label, "%c I=%g", "ABC"[k], in[order[k]]);
        ex_dot(c, v[order[k]], c->zoom >= 20 ? 4 : c->zoom * 0.2, EX_HILITE);
        ex_label(c, v[order[k]], label, EX_EDGE);
    }
}

sr_result explain_fillpoly(ex_canvas *c, const ex_primitive *prim)
{
    ex_tri t;
    double in[3];
    ex_tri_setup_at(&t, in, prim, 0);
    int o[3];   /* A, B, C: the vertices by y (then x) */
    ex_tri_order_by_y(&t, o);
    /* the edges' walks, for their increments */
    ex_walk ac = ex_walk_edge(&t, in, o[0], o[2], "AC"),
            ab = ex_walk_edge(&t, in, o[0], o[1], "AB"),
            bc = ex_walk_edge(&t, in, o[1], o[2], "BC");
    int gw = c->grid_w, gh = c->grid_h;
    uint8_t *mask = calloc((size_t)gw * (size_t)gh, 1);
    float *shade = calloc((size_t)gw * (size_t)gh, sizeof *shade);
    ex_interp_row *rows = calloc((size_t)gh, sizeof *rows);
    if (!mask || !shade || !rows) {
        free(mask);
        free(shade);
        free(rows);
        return SR_OUT_OF_MEMORY;
    }
    sr_point2 pts[3] = { prim->pts[0], prim->pts[1], prim->pts[2] };
    sr_result r = sr_polygon_coverage(c->ctx, &(sr_polygon2){ pts, 3, NULL, 0 },
                                      &(sr_fill_desc){ .rule = SR_NONZERO }, 0, 0, gw, gh, mask,
                                      (size_t)gw);
    if (r != SR_OK) {
        free(mask);
        free(shade);
        free(rows);
        return r;
    }
    ex_fillpoly_spans(&t, in, mask, gw, gh, shade, rows);
    char cap[900];

    ex_begin(c);
    draw_tri(c, &t, o, in);
    double yab = ab.y1 - ab.y0, ybc = bc.y1 - bc.y0, yac = ac.y1 - ac.y0;
    /* a horizontal edge has no increments (AC too, when all three
     * vertices lie on one row) */
    char dx[6][24];
    snprintf(dx[0], 24, yab > 0 ? "%.3f" : "-", yab > 0 ? (ab.x1 - ab.x0) / yab : 0);
    snprintf(dx[1], 24, yab > 0 ? "%.3f" : "-", yab > 0 ? (ab.i1 - ab.i0) / yab : 0);
    snprintf(dx[2], 24, ybc > 0 ? "%.3f" : "-", ybc > 0 ? (bc.x1 - bc.x0) / ybc : 0);
    snprintf(dx[3], 24, ybc > 0 ? "%.3f" : "-", ybc > 0 ? (bc.i1 - bc.i0) / ybc : 0);
    snprintf(dx[4], 24, yac > 0 ? "%.3f" : "-", yac > 0 ? (ac.x1 - ac.x0) / yac : 0);
    snprintf(dx[5], 24, yac > 0 ? "%.3f" : "-", yac > 0 ? (ac.i1 - ac.i0) / yac : 0);
    snprintf(cap, sizeof cap,
             "1. FillPoly: A, B, C sorted by y, an intensity I at each. Per scanline along "
             "each edge: dX_AC = %s, dI_AC = %s; dX_AB = %s, dI_AB = %s; dX_BC = %s, "
             "dI_BC = %s (1/m and dI/dy; a horizontal edge crosses no scanline). Above B, AC "
             "runs beside AB; below B, beside BC.",
             dx[4], dx[5], dx[0], dx[1], dx[2], dx[3]);
    ex_end(c, cap);

    for (int y = 0; y < gh; y++) {
        const ex_interp_row *row = &rows[y];
        if (row->x0 == row->x1) {
            continue;
        }
        ex_begin(c);
        for (int yy = 0; yy < y; yy++) {
            for (int x = 0; x < gw; x++) {
                if (mask[yy * gw + x]) {
                    ex_cell(c, x, yy, grey(shade[yy * gw + x]));
                }
            }
        }
        for (int x = row->x0; x < row->x1; x++) {
            ex_cell(c, x, y, grey(shade[y * gw + x]));
            ex_cell_value(c, x, y, shade[y * gw + x]);
        }
        draw_tri(c, &t, o, in);
        ex_segment(c, (sr_point2){ 0, y + 0.5 }, (sr_point2){ gw, y + 0.5 }, EX_HILITE, 1);
        ex_dot(c, (sr_point2){ row->xl, y + 0.5 }, 4, EX_INK);
        ex_dot(c, (sr_point2){ row->xr, y + 0.5 }, 4, EX_INK);
        snprintf(cap, sizeof cap,
                 "%d. Scanline %d (centre y = %d.5). Left %s: x = %.3f, I = %.3f (%s). Right "
                 "%s: x = %.3f, I = %.3f (%s). FillSpan: dI = (I_R - I_L) / (x_R - x_L) = "
                 "%.4f per pixel, I = %.3f at the first centre x = %d.5, pixels %d..%d.",
                 c->frame_count + 1, y, y, row->left, row->xl, row->il,
                 row->fresh & 1 ? "starts: first sample" : "stepped by dX, dI", row->right,
                 row->xr, row->ir, row->fresh & 2 ? "starts: first sample" : "stepped by dX, dI",
                 row->dI, shade[y * gw + row->x0], row->x0, row->x0, row->x1 - 1);
        ex_end(c, cap);
    }

    ex_begin(c);
    for (int y = 0; y < gh; y++) {
        for (int x = 0; x < gw; x++) {
            if (mask[y * gw + x]) {
                ex_cell(c, x, y, grey(shade[y * gw + x]));
            }
        }
    }
    snprintf(cap, sizeof cap,
             "%d. The result (no outline: the cells alone): the pixels of sr_fill_polygon, each with the intensity the "
             "increments reached (over a triangle I is a plane, so every span steps by the same "
             "dI), what sr_fill_gouraud draws with SR_GOURAUD_INCREMENTAL "
             "(within one 8-bit step of interpolating each pixel directly: the float sums "
             "accumulate rounding).",
             c->frame_count + 1);
    ex_end(c, cap);
    free(mask);
    free(shade);
    free(rows);
    return c->error;
}
