/* gouraud_incremental.c - draw2d stage: Gouraud-shaded 2D polygons by
 * incremental scan-line interpolation, the notes' FillPoly / FillSpan, and
 * sr_fill_gouraud, which selects it or the direct interpolation of
 * gouraud.c.  Consumes vertices with colors; produces the edge-table
 * fill's pixels (the same converter, so the same pixels), blended
 * source-over.  Caller's thread.
 *
 * FillPoly: along each edge, x steps by 1/m = dx/dy and the color by
 * dI/dy from one scanline to the next.  For a triangle A, B, C sorted by y
 * the active edge table holds the long edge AC and AB above the middle
 * vertex B, AC and BC below it: the notes' two loops, split at B.  Polygons
 * work the same way with more edges active.  FillSpan: between the left and
 * right crossings x_L, x_R the color steps by (I_R - I_L) / (x_R - x_L) per
 * pixel.  Each walk starts at the first sample it meets (scanline centre
 * y + 1/2, pixel centre x + 1/2), not at the vertex: starting at the vertex
 * would shift every color by up to one increment.  The colors are summed in
 * float, so every step adds a rounding; see docs/draw2d.md for the bound.
 */
#include "draw2d/polyfill.h"

#include "context.h"
#include "draw2d/paint.h"

#include <limits.h>
#include <math.h>

/* One edge's walk, started on the first scanline that asks for it. */
typedef struct edge_walk {
    int row;            /* scanline x and I are at; INT_MIN: not started */
    double x, dxdy;     /* crossing at the row's centre, and 1/m */
    float I[4], dI[4];  /* color there, and its step per scanline */
} edge_walk;

typedef struct incremental {
    sr_framebuffer *fb;
    const sr__edge2 *edges;
    const sr_rgba *c;
    edge_walk *walk;
} incremental;

static void rgba4(const sr_rgba *c, float out[4])
{
    out[0] = c->r;
    out[1] = c->g;
    out[2] = c->b;
    out[3] = c->a;
}

/* Edge e's walk brought to scanline y: set up at its first row, then
 * stepped one scanline at a time (FillPoly's x += dX, I += dI). */
static const edge_walk *walk_to(incremental *s, int e, int y)
{
    edge_walk *w = &s->walk[e];
    if (w->row == INT_MIN) {
        const sr__edge2 *d = &s->edges[e];
        double y0 = d->y0 / 256.0, dy = (d->y1 - d->y0) / 256.0;
        double pre = y + 0.5 - y0; /* from the vertex down to the first sample */
        float a[4], b[4];
        rgba4(&s->c[d->v0], a);
        rgba4(&s->c[d->v1], b);
        w->dxdy = (d->x1 - d->x0) / 256.0 / dy;
        w->x = d->x0 / 256.0 + pre * w->dxdy;
        for (int k = 0; k < 4; k++) {
            w->dI[k] = (float)((b[k] - a[k]) / dy);
            w->I[k] = (float)(a[k] + pre * w->dI[k]);
        }
        w->row = y;
    }
    while (w->row < y) {
        w->x += w->dxdy;
        for (int k = 0; k < 4; k++) {
            w->I[k] += w->dI[k];
        }
        w->row++;
    }
    return w;
}

/* FillSpan(y, x_L, I_L, x_R, I_R) over the pixels the converter covers. */
static void fill_span(void *user, const sr__span *sp)
{
    incremental *s = user;
    const edge_walk *l = walk_to(s, sp->edge_l, sp->y);
    const edge_walk *r = walk_to(s, sp->edge_r, sp->y);
    double width = r->x - l->x;
    float I[4], dI[4];
    for (int k = 0; k < 4; k++) {
        dI[k] = width > 0 ? (float)((r->I[k] - l->I[k]) / width) : 0.0f;
        I[k] = (float)(l->I[k] + (sp->x0 + 0.5 - l->x) * dI[k]);
    }
    uint32_t *row = s->fb->color + (size_t)sp->y * (size_t)s->fb->width;
    for (int x = sp->x0; x < sp->x1; x++) {
        sr__blend_rgba(&row[x], I);
        for (int k = 0; k < 4; k++) {
            I[k] += dI[k];
        }
    }
}

static sr_result fill_incremental(sr_context *ctx, const char *fn, sr_framebuffer *fb,
                                  const sr_polygon2 *poly, const sr_rgba *colors,
                                  sr_fill_rule rule)
{
    sr__edge2 *edges;
    int count;
    sr_result r = sr__edges_from_polygon(ctx, fn, poly, 1, &edges, &count);
    if (r != SR_OK) {
        return r;
    }
    edge_walk *walk = count ? sr__alloc(ctx, (size_t)count * sizeof *walk) : NULL;
    if (count && !walk) {
        sr__free(ctx, edges);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory for %d edge walks", fn, count);
    }
    for (int i = 0; i < count; i++) {
        walk[i].row = INT_MIN;
    }
    incremental s = { fb, edges, colors, walk };
    r = sr__fb_begin_2d(ctx, fn, fb);
    if (r == SR_OK) {
        r = sr__scan_edge_table(ctx, edges, count, rule,
                                (sr__window){ 0, 0, fb->width, fb->height }, fill_span, &s);
    }
    sr__free(ctx, walk);
    sr__free(ctx, edges);
    return r;
}

sr_result sr_fill_gouraud(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                          const sr_rgba *colors, const sr_gouraud_desc *desc)
{
    static const char fn[] = "sr_fill_gouraud";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_fill_gouraud: ctx is NULL");
    }
    sr_gouraud_desc d = desc ? *desc : (sr_gouraud_desc){ 0 };
    if (d.method < SR_GOURAUD_DEFAULT || d.method > SR_GOURAUD_INCREMENTAL) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_gouraud_desc.method %d is not a method", fn,
                        (int)d.method);
    }
    if (d.method != SR_GOURAUD_INCREMENTAL) {
        if (poly && poly->point_count == 3 &&
            (!poly->contour_counts || (poly->contour_count == 1 && poly->contour_counts[0] == 3))) {
            /* One triangle: either rule covers the same pixels. */
            sr_fill_desc fd;
            sr_result r = sr__fill_desc_defaults(ctx, fn, &(sr_fill_desc){ .rule = d.rule }, &fd);
            return r != SR_OK ? r : sr_fill_triangle_gouraud(ctx, fb, poly->points, colors);
        }
        return sr_fill_polygon_gouraud(ctx, fb, poly, colors, d.rule);
    }
    if (!fb || !poly || (!colors && poly->point_count > 0)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn,
                        !fb ? "fb" : !poly ? "poly" : "colors");
    }
    sr_fill_desc fd;
    sr_result r = sr__fill_desc_defaults(ctx, fn, &(sr_fill_desc){ .rule = d.rule }, &fd);
    if (r != SR_OK) {
        return r;
    }
    if (poly->point_count > 0 && !sr__colors_finite(colors, poly->point_count)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: a color is not finite", fn);
    }
    r = fill_incremental(ctx, fn, fb, poly, colors, fd.rule);
    if (r == SR_OK) {
        sr__ok(ctx);
    }
    return r;
}
