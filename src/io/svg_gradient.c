/* svg_gradient.c - the SVG reader's paint servers (src/io): linear and
 * radial gradients evaluated per pixel (spread pad, reflect, repeat; a
 * radial gradient's focal circle as the two-circle cone of SVG 2), and a
 * polygon filled with one: coverage from the 2D filler, then the paint.
 * Pure functions of their arguments; used by svg.c. */
#include "io/svg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The gradient parameter t of a point in gradient space; false where a
 * radial gradient's cone does not reach (the pixel is left unpainted). */
static bool parameter(const svg_gradient *g, double x, double y, double *t)
{
    if (!g->radial) {
        double dx = g->x2 - g->x1, dy = g->y2 - g->y1, len2 = dx * dx + dy * dy;
        *t = len2 > 0 ? ((x - g->x1) * dx + (y - g->y1) * dy) / len2 : 0;
        return true;
    }
    /* Circles (f + t (c - f), fr + t (r - fr)); the largest t with a
     * circle through the point and a radius >= 0. */
    double cdx = g->cx - g->fx, cdy = g->cy - g->fy, dr = g->r - g->fr;
    double pdx = x - g->fx, pdy = y - g->fy;
    double a = cdx * cdx + cdy * cdy - dr * dr;
    double b = pdx * cdx + pdy * cdy + g->fr * dr;
    double c = pdx * pdx + pdy * pdy - g->fr * g->fr;
    if (fabs(a) < 1e-12) {
        if (fabs(b) < 1e-12) {
            return false;
        }
        *t = c / (2 * b);
        return g->fr + *t * dr >= 0;
    }
    double disc = b * b - a * c;
    if (disc < 0) {
        return false;
    }
    double sq = sqrt(disc), t0 = (b + sq) / a, t1 = (b - sq) / a;
    if (t0 < t1) {
        double s = t0;
        t0 = t1;
        t1 = s;
    }
    if (g->fr + t0 * dr >= 0) {
        *t = t0;
        return true;
    }
    if (g->fr + t1 * dr >= 0) {
        *t = t1;
        return true;
    }
    return false;
}

static double spread(svg_spread s, double t)
{
    switch (s) {
    case SVG_SPREAD_REPEAT:
        return t - floor(t);
    case SVG_SPREAD_REFLECT: {
        double u = fmod(fabs(t), 2);
        return u > 1 ? 2 - u : u;
    }
    default:
        return t < 0 ? 0 : t > 1 ? 1 : t;
    }
}

static sr_rgba color_at(const svg_gradient *g, double t)
{
    if (t <= g->offset[0]) {
        return g->color[0];
    }
    for (int i = 1; i < g->n_stops; i++) {
        if (t < g->offset[i]) {
            double span = g->offset[i] - g->offset[i - 1];
            float u = span > 0 ? (float)((t - g->offset[i - 1]) / span) : 1.0f;
            sr_rgba a = g->color[i - 1], b = g->color[i];
            return (sr_rgba){ a.r + (b.r - a.r) * u, a.g + (b.g - a.g) * u, a.b + (b.b - a.b) * u,
                              a.a + (b.a - a.a) * u };
        }
    }
    return g->color[g->n_stops - 1];
}

sr_rgba svg_gradient_at(const svg_gradient *g, double x, double y)
{
    const double *m = g->inv;
    double gx = m[0] * x + m[2] * y + m[4], gy = m[1] * x + m[3] * y + m[5], t;
    if (!parameter(g, gx, gy, &t) || !isfinite(t)) {
        return (sr_rgba){ 0, 0, 0, 0 };
    }
    return color_at(g, spread(g->spread, t));
}

static uint8_t unorm8(float v)
{
    return !(v > 0.0f) ? 0 : v >= 1.0f ? 255 : (uint8_t)(v * 255.0f + 0.5f);
}

void svg_blend(uint8_t *d, sr_rgba c, float cov)
{
    uint8_t s[4] = { unorm8(c.r), unorm8(c.g), unorm8(c.b), 0 };
    float a = (c.a < 0 ? 0 : c.a > 1 ? 1 : c.a) * cov;
    if (a <= 0.0f) {
        return;
    }
    /* Straight alpha: the destination's color counts by its alpha. */
    float da = d[3] * (1.0f / 255.0f), keep = 1.0f - a, oa = a + da * keep;
    if (d[3] < 255) {
        keep = oa > 0.0f ? da * keep / oa : 0.0f;
        a = oa > 0.0f ? a / oa : 0.0f;
    }
    for (int i = 0; i < 3; i++) {
        d[i] = unorm8((s[i] * a + d[i] * keep) * (1.0f / 255.0f));
    }
    d[3] = unorm8(oa);
}

sr_result svg_fill_gradient(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                            const sr_fill_desc *desc, const svg_gradient *g, float opacity)
{
    int fw = sr_framebuffer_width(fb), fh = sr_framebuffer_height(fb);
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int i = 0; i < poly->point_count; i++) {
        x0 = fmin(x0, poly->points[i].x);
        x1 = fmax(x1, poly->points[i].x);
        y0 = fmin(y0, poly->points[i].y);
        y1 = fmax(y1, poly->points[i].y);
    }
    int bx0 = x0 > 0 ? (int)fmin(floor(x0), fw) : 0, by0 = y0 > 0 ? (int)fmin(floor(y0), fh) : 0;
    int bx1 = x1 < fw ? (int)fmax(ceil(x1) + 1, 0) : fw, by1 = y1 < fh ? (int)fmax(ceil(y1) + 1, 0) : fh;
    bx1 = bx1 > fw ? fw : bx1;
    by1 = by1 > fh ? fh : by1;
    int w = bx1 - bx0, h = by1 - by0;
    if (w <= 0 || h <= 0) {
        return SR_OK;
    }
    uint8_t *mask = malloc((size_t)w * (size_t)h);
    uint8_t *px = malloc((size_t)w * (size_t)h * 4);
    sr_result r = mask && px ? SR_OK : SR_OUT_OF_MEMORY;
    if (r == SR_OK) {
        r = sr_polygon_coverage(ctx, poly, desc, bx0, by0, w, h, mask, (size_t)w);
    }
    if (r == SR_OK) {
        r = sr_read_pixels(ctx, fb, bx0, by0, w, h, px, (size_t)w * 4);
    }
    if (r == SR_OK) {
        for (int y = 0; y < h; y++) {
            for (int x = 0; x < w; x++) {
                unsigned cov = mask[(size_t)y * w + x];
                if (cov == 0) {
                    continue;
                }
                sr_rgba c = svg_gradient_at(g, bx0 + x + 0.5, by0 + y + 0.5);
                c.a *= opacity;
                svg_blend(px + ((size_t)y * w + x) * 4, c, (float)cov * (1.0f / 255.0f));
            }
        }
        r = sr_write_pixels(ctx, fb, bx0, by0, w, h, px, (size_t)w * 4);
    }
    free(mask);
    free(px);
    return r;
}
