/* svg_fill.c - the SVG reader's painted fills (src/io): a polygon's
 * coverage from the 2D filler, then a paint evaluated at each covered
 * pixel's centre (a gradient, a pattern tile, an image) and blended
 * source-over in straight alpha, as the 2D fills blend.  Used by svg.c. */
#include "io/svg.h"

#include <math.h>
#include <stdlib.h>

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

sr_result svg_fill_paint(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                         const sr_fill_desc *desc, svg_paint_fn at, const void *paint,
                         float opacity)
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
                sr_rgba c = at(paint, bx0 + x + 0.5, by0 + y + 0.5);
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

/* Texel (i, j) of the image premultiplied: repeated, or the nearest edge
 * texel outside. */
static void texel(const svg_image *im, long i, long j, float out[4])
{
    if (im->repeat) {
        i %= im->w;
        j %= im->h;
        i += i < 0 ? im->w : 0;
        j += j < 0 ? im->h : 0;
    } else {
        i = i < 0 ? 0 : i >= im->w ? im->w - 1 : i;
        j = j < 0 ? 0 : j >= im->h ? im->h - 1 : j;
    }
    const uint8_t *p = im->rgba + ((size_t)j * (size_t)im->w + (size_t)i) * 4;
    float a = p[3] * (1.0f / 255.0f);
    for (int k = 0; k < 3; k++) {
        out[k] = p[k] * (1.0f / 255.0f) * a;
    }
    out[3] = a;
}

sr_rgba svg_image_at(const void *image, double x, double y)
{
    const svg_image *im = image;
    const double *m = im->inv;
    double u = m[0] * x + m[2] * y + m[4] - 0.5, v = m[1] * x + m[3] * y + m[5] - 0.5;
    if (!(fabs(u) < 1e15 && fabs(v) < 1e15)) {
        return (sr_rgba){ 0, 0, 0, 0 };
    }
    double fu = floor(u), fv = floor(v);
    float tu = (float)(u - fu), tv = (float)(v - fv), c[4][4], o[4];
    long i = (long)fu, j = (long)fv;
    /* bilinear, premultiplied: a transparent texel adds no color */
    texel(im, i, j, c[0]);
    texel(im, i + 1, j, c[1]);
    texel(im, i, j + 1, c[2]);
    texel(im, i + 1, j + 1, c[3]);
    for (int k = 0; k < 4; k++) {
        float top = c[0][k] + (c[1][k] - c[0][k]) * tu, bot = c[2][k] + (c[3][k] - c[2][k]) * tu;
        o[k] = top + (bot - top) * tv;
    }
    if (!(o[3] > 0)) {
        return (sr_rgba){ 0, 0, 0, 0 };
    }
    return (sr_rgba){ o[0] / o[3], o[1] / o[3], o[2] / o[3], o[3] };
}
