/* gouraud.c - draw2d stage: Gouraud-shaded 2D triangles and polygons.
 * Consumes vertices with colors, produces the edge-table fill's pixels
 * colored by barycentric (triangles) or bilinear (polygons: along edges,
 * then along spans) interpolation, blended source-over.  Caller's thread. */
#include "draw2d/polyfill.h"

#include "context.h"
#include "draw2d/paint.h"

#include <math.h>
#include <string.h>

bool sr__colors_finite(const sr_rgba *c, int n)
{
    for (int i = 0; i < n; i++) {
        if (!isfinite(c[i].r) || !isfinite(c[i].g) || !isfinite(c[i].b) || !isfinite(c[i].a)) {
            return false;
        }
    }
    return true;
}

/* ---- triangles: barycentric ------------------------------------------------ */

typedef struct tri_shade {
    sr_framebuffer *fb;
    double x[3], y[3];   /* snapped vertices, pixels */
    double inv_area2;
    const sr_rgba *c;
} tri_shade;

static void tri_span(void *user, const sr__span *sp)
{
    tri_shade *t = user;
    uint32_t *row = t->fb->color + (size_t)sp->y * (size_t)t->fb->width;
    double py = sp->y + 0.5;
    for (int x = sp->x0; x < sp->x1; x++) {
        double px = x + 0.5;
        /* alpha, beta, gamma: the sub-triangle areas opposite each vertex. */
        double w[3];
        for (int k = 0; k < 3; k++) {
            int a = (k + 1) % 3, b = (k + 2) % 3;
            w[k] = ((t->x[b] - t->x[a]) * (py - t->y[a]) - (t->y[b] - t->y[a]) * (px - t->x[a])) *
                   t->inv_area2;
            w[k] = w[k] < 0 ? 0 : w[k] > 1 ? 1 : w[k];
        }
        float c[4] = {
            (float)(w[0] * t->c[0].r + w[1] * t->c[1].r + w[2] * t->c[2].r),
            (float)(w[0] * t->c[0].g + w[1] * t->c[1].g + w[2] * t->c[2].g),
            (float)(w[0] * t->c[0].b + w[1] * t->c[1].b + w[2] * t->c[2].b),
            (float)(w[0] * t->c[0].a + w[1] * t->c[1].a + w[2] * t->c[2].a),
        };
        sr__blend_rgba(&row[x], c);
    }
}

sr_result sr_fill_triangle_gouraud(sr_context *ctx, sr_framebuffer *fb, const sr_point2 v[3],
                                   const sr_rgba colors[3])
{
    static const char fn[] = "sr_fill_triangle_gouraud";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_fill_triangle_gouraud: ctx is NULL");
    }
    if (!fb || !v || !colors) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn,
                        !fb ? "fb" : !v ? "v" : "colors");
    }
    if (!sr__colors_finite(colors, 3)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: a color is not finite", fn);
    }
    sr__edge2 *edges;
    int count;
    sr_polygon2 poly = { v, 3, NULL, 0 };
    sr_result r = sr__edges_from_polygon(ctx, fn, &poly, 1, &edges, &count);
    if (r != SR_OK) {
        return r;
    }
    tri_shade t = { .fb = fb, .c = colors };
    for (int k = 0; k < 3; k++) {
        t.x[k] = nearbyint(v[k].x * 256) / 256;
        t.y[k] = nearbyint(v[k].y * 256) / 256;
    }
    double area2 = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
    if (area2 != 0) {
        t.inv_area2 = 1.0 / area2;
        r = sr__fb_begin_2d(ctx, fn, fb);
        if (r == SR_OK) {
            r = sr__scan_edge_table(ctx, edges, count, SR_NONZERO,
                                    (sr__window){ 0, 0, fb->width, fb->height }, tri_span, &t);
        }
    }
    sr__free(ctx, edges);
    if (r == SR_OK) {
        sr__ok(ctx);
    }
    return r;
}

/* ---- polygons: along edges, then along spans -------------------------------- */

typedef struct poly_shade {
    sr_framebuffer *fb;
    const sr__edge2 *edges;
    const sr_rgba *c;
} poly_shade;

/* Where edge e crosses the scanline yc, and the color there. */
static double edge_at(const poly_shade *s, int e, double yc, float out[4])
{
    const sr__edge2 *d = &s->edges[e];
    double y0 = d->y0 / 256.0, y1 = d->y1 / 256.0;
    double t = (yc - y0) / (y1 - y0);
    const sr_rgba *a = &s->c[d->v0], *b = &s->c[d->v1];
    out[0] = (float)(a->r + t * (b->r - a->r));
    out[1] = (float)(a->g + t * (b->g - a->g));
    out[2] = (float)(a->b + t * (b->b - a->b));
    out[3] = (float)(a->a + t * (b->a - a->a));
    return d->x0 / 256.0 + t * (d->x1 - d->x0) / 256.0;
}

static void poly_span(void *user, const sr__span *sp)
{
    poly_shade *s = user;
    float cl[4], cr[4];
    double xl = edge_at(s, sp->edge_l, sp->yc, cl);
    double xr = edge_at(s, sp->edge_r, sp->yc, cr);
    uint32_t *row = s->fb->color + (size_t)sp->y * (size_t)s->fb->width;
    double inv = xr > xl ? 1.0 / (xr - xl) : 0.0;
    for (int x = sp->x0; x < sp->x1; x++) {
        double u = (x + 0.5 - xl) * inv;
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        float c[4];
        for (int k = 0; k < 4; k++) {
            c[k] = (float)(cl[k] + u * (cr[k] - cl[k]));
        }
        sr__blend_rgba(&row[x], c);
    }
}

sr_result sr_fill_polygon_gouraud(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                                  const sr_rgba *colors, sr_fill_rule rule)
{
    static const char fn[] = "sr_fill_polygon_gouraud";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_fill_polygon_gouraud: ctx is NULL");
    }
    if (!fb || !poly || (!colors && poly->point_count > 0)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn,
                        !fb ? "fb" : !poly ? "poly" : "colors");
    }
    sr_fill_desc d;
    sr_result r = sr__fill_desc_defaults(ctx, fn, &(sr_fill_desc){ .rule = rule }, &d);
    if (r != SR_OK) {
        return r;
    }
    sr__edge2 *edges;
    int count;
    r = sr__edges_from_polygon(ctx, fn, poly, 1, &edges, &count);
    if (r != SR_OK) {
        return r;
    }
    if (!sr__colors_finite(colors, poly->point_count)) {
        sr__free(ctx, edges);
        return sr__fail(ctx, SR_INVALID_ARG, "%s: a color is not finite", fn);
    }
    poly_shade s = { fb, edges, colors };
    r = sr__fb_begin_2d(ctx, fn, fb);
    if (r == SR_OK) {
        r = sr__scan_edge_table(ctx, edges, count, d.rule,
                                (sr__window){ 0, 0, fb->width, fb->height }, poly_span, &s);
    }
    sr__free(ctx, edges);
    if (r == SR_OK) {
        sr__ok(ctx);
    }
    return r;
}
