/* paint_api.c - draw2d stage: sr_fill_polygon_paint and sr_fill_path_paint.
 * Checks a public sr_paint field by field and resolves it to a paint
 * server of paint_fill.h (a gradient with the map from pixels into its
 * space, or an image): the code the SVG reader paints with. */
#include "draw2d/paint_fill.h"

#include "context.h"
#include "draw2d/polyfill.h"
#include "math/affine2.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* The inverse of m as a b c d e f, or false when it is singular or not
 * finite. */
static bool invert_affine(const sr_affine2 *m, double inv[6])
{
    const double f[6] = { m->a, m->b, m->c, m->d, m->e, m->f };
    for (int i = 0; i < 6; i++) {
        if (!isfinite(f[i])) {
            return false;
        }
    }
    return sr__affine2_invert(f, 1e-300, inv);
}

static bool finite_rgba(sr_rgba c)
{
    return isfinite(c.r) && isfinite(c.g) && isfinite(c.b) && isfinite(c.a);
}

/* Check the stops and copy them into g.  Its color table depends on the
 * stops alone, so g keeps the table when they are the ones it holds: a
 * drawing's shapes that share a gradient fill it once, not once a shape
 * (a radial gradient's shape asks for most of the table's cells). */
static sr_result gradient_stops(sr_context *ctx, const char *fn, const sr_paint *p,
                                sr__gradient *g)
{
    bool same = g->n_stops == p->stop_count;
    if (p->stop_count < 1 || p->stop_count > SR_MAX_GRADIENT_STOPS) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.stop_count %d is outside 1..%d", fn,
                        p->stop_count, SR_MAX_GRADIENT_STOPS);
    }
    if (!p->stops) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.stops is NULL", fn);
    }
    for (int i = 0; i < p->stop_count; i++) {
        double o = p->stops[i].offset;
        if (!(o >= 0 && o <= 1) || (i > 0 && o < p->stops[i - 1].offset)) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "%s: sr_paint.stops[%d].offset %g is outside [0, 1] or below the "
                            "offset before it", fn, i, o);
        }
        if (!finite_rgba(p->stops[i].color)) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.stops[%d].color is not finite",
                            fn, i);
        }
        sr_rgba c = p->stops[i].color;
        same = same && g->offset[i] == o && g->color[i].r == c.r && g->color[i].g == c.g &&
               g->color[i].b == c.b && g->color[i].a == c.a;
    }
    if (!same) {
        for (int i = 0; i < p->stop_count; i++) {
            g->offset[i] = p->stops[i].offset;
            g->color[i] = p->stops[i].color;
        }
        g->n_stops = p->stop_count;
        memset(g->lut_state, 0, sizeof g->lut_state);
    }
    return SR_OK;
}

/* The gradient's geometry, checked.  A focal point outside the end circle
 * is moved just inside it (SVG 1.1), so the cone stays a cone. */
static sr_result gradient_geometry(sr_context *ctx, const char *fn, const sr_paint *p,
                                   sr__gradient *g)
{
    g->radial = p->kind == SR_PAINT_RADIAL_GRADIENT;
    if (!g->radial) {
        if (!(isfinite(p->x1) && isfinite(p->y1) && isfinite(p->x2) && isfinite(p->y2))) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.x1, y1, x2, y2 not finite", fn);
        }
        g->x1 = p->x1;
        g->y1 = p->y1;
        g->x2 = p->x2;
        g->y2 = p->y2;
        return SR_OK;
    }
    g->cx = p->cx;
    g->cy = p->cy;
    g->fx = p->focal ? p->focal->x : p->cx;
    g->fy = p->focal ? p->focal->y : p->cy;
    if (!(isfinite(g->cx) && isfinite(g->cy) && isfinite(g->fx) && isfinite(g->fy))) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.cx, cy or focal not finite", fn);
    }
    if (!(p->r > 0) || !isfinite(p->r)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.r %g is not > 0 and finite", fn, p->r);
    }
    if (!(p->fr >= 0) || !isfinite(p->fr)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.fr %g is not >= 0 and finite", fn,
                        p->fr);
    }
    g->r = p->r;
    g->fr = p->fr;
    double dx = g->fx - g->cx, dy = g->fy - g->cy, d = sqrt(dx * dx + dy * dy);
    if (d > g->r * 0.999) {
        g->fx = g->cx + dx * g->r * 0.999 / d;
        g->fy = g->cy + dy * g->r * 0.999 / d;
    }
    return SR_OK;
}

static sr_result image_paint(sr_context *ctx, const char *fn, const sr_paint *p, sr__image *im)
{
    if (!p->image) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.image is NULL", fn);
    }
    if (p->image_width < 1 || p->image_width > SR_MAX_FRAMEBUFFER_SIZE ||
        p->image_height < 1 || p->image_height > SR_MAX_FRAMEBUFFER_SIZE) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: sr_paint.image_width x image_height %d x %d is outside 1..%d", fn,
                        p->image_width, p->image_height, SR_MAX_FRAMEBUFFER_SIZE);
    }
    size_t row = (size_t)p->image_width * 4;
    size_t stride = p->image_stride ? p->image_stride : row;
    /* The last row's end must be addressable: (h - 1) strides and a row
     * within PTRDIFF_MAX (a 32-bit size_t meets that bound first). */
    size_t h1 = (size_t)p->image_height - 1;
    if (stride < row || stride > (size_t)SR_MAX_FRAMEBUFFER_SIZE * 64 ||
        (h1 > 0 && stride > ((size_t)PTRDIFF_MAX - row) / h1)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: sr_paint.image_stride %zu is below 4 * image_width or absurd", fn,
                        p->image_stride);
    }
    if (p->image_wrap != SR_WRAP_DEFAULT && p->image_wrap != SR_WRAP_REPEAT &&
        p->image_wrap != SR_WRAP_CLAMP) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.image_wrap %d is not REPEAT or CLAMP",
                        fn, (int)p->image_wrap);
    }
    *im = (sr__image){ .rgba = p->image, .w = p->image_width, .h = p->image_height,
                       .stride = stride, .repeat = p->image_wrap != SR_WRAP_CLAMP };
    return SR_OK;
}

sr_result sr_fill_polygon_paint(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                                const sr_paint *paint, const sr_fill_desc *desc)
{
    static const char fn[] = "sr_fill_polygon_paint";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_fill_polygon_paint: ctx is NULL");
    }
    if (!paint) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: paint is NULL", fn);
    }
    float opacity = paint->opacity == 0 ? 1 : paint->opacity;
    if (!(opacity >= 0 && opacity <= 1)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.opacity %g is outside [0, 1]", fn,
                        (double)paint->opacity);
    }
    if (paint->kind == SR_PAINT_COLOR) {
        sr_rgba c = paint->color;
        c.a *= opacity;
        return sr_fill_polygon(ctx, fb, poly, c, desc);
    }
    if (!fb) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: fb is NULL", fn);
    }
    if (!poly) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: poly is NULL", fn);
    }
    /* sr__fill_paint bounds the points before the coverage checks the rest */
    if (poly->point_count < 0 || (poly->point_count > 0 && !poly->points)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: sr_polygon2.points is NULL or point_count < 0", fn);
    }
    if (paint->kind != SR_PAINT_LINEAR_GRADIENT && paint->kind != SR_PAINT_RADIAL_GRADIENT &&
        paint->kind != SR_PAINT_PATTERN) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.kind %d is not a paint kind", fn,
                        (int)paint->kind);
    }
    sr_fill_desc d;
    sr_result r = sr__fill_desc_defaults(ctx, fn, desc, &d);
    if (r != SR_OK) {
        return r;
    }
    if (d.linear_light) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: desc->linear_light is for SR_PAINT_COLOR only", fn);
    }
    if (paint->spread != SR_SPREAD_PAD && paint->spread != SR_SPREAD_REFLECT &&
        paint->spread != SR_SPREAD_REPEAT) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_paint.spread %d is not a spread method",
                        fn, (int)paint->spread);
    }
    double inv[6] = { 1, 0, 0, 1, 0, 0 };
    if (paint->transform && !invert_affine(paint->transform, inv)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: sr_paint.transform is singular or not finite", fn);
    }
    if (paint->kind == SR_PAINT_PATTERN) {
        sr__image im;
        r = image_paint(ctx, fn, paint, &im);
        if (r != SR_OK) {
            return r;
        }
        memcpy(im.inv, inv, sizeof im.inv);
        r = sr__fill_paint(ctx, fn, fb, poly, &d, sr__image_span, &im, opacity);
    } else {
        if (!ctx->gradient && (ctx->gradient = sr__alloc(ctx, sizeof *ctx->gradient))) {
            ctx->gradient->n_stops = 0;
        }
        sr__gradient *g = ctx->gradient;
        if (!g) {
            return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: out of memory", fn);
        }
        r = gradient_geometry(ctx, fn, paint, g);
        if (r == SR_OK) {
            r = gradient_stops(ctx, fn, paint, g);
        }
        if (r == SR_OK) {
            g->spread = paint->spread;
            memcpy(g->inv, inv, sizeof g->inv);
            r = sr__fill_paint(ctx, fn, fb, poly, &d, sr__gradient_span, g, opacity);
        }
    }
    if (r == SR_OK) {
        sr__ok(ctx);
    }
    return r;
}

sr_result sr_fill_path_paint(sr_context *ctx, sr_framebuffer *fb, const sr_path *path,
                             const sr_paint *paint, const sr_fill_desc *desc)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_fill_path_paint: ctx is NULL");
    }
    if (!path) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_fill_path_paint: path is NULL");
    }
    sr_polygon2 poly = sr_path_polygon(path);
    return sr_fill_polygon_paint(ctx, fb, &poly, paint, desc);
}
