/* paint_fill.c - draw2d stage: painted fills.  A polygon's coverage from
 * the 2D filler, then a paint evaluated along each row's covered span (a
 * gradient, a pattern tile, an image) and blended source-over in straight
 * alpha, as the 2D fills blend.  Used by paint_api.c. */
#include "draw2d/paint_fill.h"

#include "context.h"
#include "draw2d/polyfill.h"

#include <math.h>
#include <string.h>

/* The part of a row of coverage from its first covered pixel to its last:
 * [*a, *b), empty when *a == *b.  Eight bytes at a time: a coverage row
 * is mostly zeros around the shape. */
static void covered_part(const uint8_t *cov, int w, int *a, int *b)
{
    int i = 0, j = w;
    uint64_t v;
    while (i + 8 <= w && (memcpy(&v, cov + i, 8), v == 0)) {
        i += 8;
    }
    while (i < w && cov[i] == 0) {
        i++;
    }
    while (j - 8 >= i && (memcpy(&v, cov + j - 8, 8), v == 0)) {
        j -= 8;
    }
    while (j > i && cov[j - 1] == 0) {
        j--;
    }
    *a = i;
    *b = j;
}

/* Whether every pixel of paint[a, b) is opaque: the alpha byte of the
 * AND of them all. */
static bool opaque_paint(const uint32_t *paint, int a, int b)
{
    uint32_t all = ~0u;
    for (int i = a; i < b; i++) {
        all &= paint[i];
    }
    uint8_t s[4];
    memcpy(s, &all, sizeof s);
    return s[3] == 255;
}

/* The end of the run of full coverage from i (before b). */
static int full_run(const uint8_t *cov, int i, int b)
{
    uint64_t v;
    while (i + 8 <= b && (memcpy(&v, cov + i, 8), v == ~(uint64_t)0)) {
        i += 8;
    }
    while (i < b && cov[i] == 255) {
        i++;
    }
    return i;
}

/* Row `out` = row `dst` with the paint over it.  Where the coverage is
 * full and the paint opaque the blend gives the paint's bytes: with an
 * opaque paint (`opaque`, opacity 1) such runs are copied whole.  The
 * paint may be `out` itself (each pixel is read before it is written). */
static void blend_row(uint32_t *out, const uint32_t *dst, const uint32_t *paint,
                      const uint8_t *cov, int a, int b, float opacity, bool opaque)
{
    for (int i = a; i < b; i++) {
        unsigned c = cov[i];
        if (opaque && c == 255) {
            int e = full_run(cov, i, b);
            if (out != paint) {
                memcpy(out + i, paint + i, (size_t)(e - i) * 4);
            }
            i = e - 1;
            continue;
        }
        uint8_t s[4];
        memcpy(s, &paint[i], sizeof s);
        if (c == 255 && s[3] == 255 && opacity >= 1.0f) {
            out[i] = paint[i];
            continue;
        }
        out[i] = dst[i];
        if (s[3] == 255 && opacity >= 1.0f && c > 0) {
            uint8_t d[4];
            memcpy(d, &out[i], sizeof d);
            if (d[3] == 255) {
                /* Both opaque: the blend's alpha is c / 255, and its
                 * result round(n / 255) for n = s c + d (255 - c), in
                 * integers (n / 255 is never within the float blend's
                 * error of a half: the same bytes, checked for every
                 * s, d and c). */
                for (int k = 0; k < 3; k++) {
                    d[k] = (uint8_t)((s[k] * c + d[k] * (255 - c) + 127) / 255);
                }
                memcpy(&out[i], d, sizeof d);
                continue;
            }
        }
        float alpha = s[3] * (1.0f / 255.0f) * opacity;
        alpha = (alpha > 1.0f ? 1.0f : alpha) * ((float)c * (1.0f / 255.0f));
        if (alpha > 0.0f) {
            sr__blend_rgba8((uint8_t *)&out[i], s, alpha);
        }
    }
}

sr_result sr__fill_paint(sr_context *ctx, const char *fn, sr_framebuffer *fb,
                         const sr_polygon2 *poly, const sr_fill_desc *desc,
                         sr__paint_span_fn span, void *paint, float opacity)
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
    /* One block: the result, a row of paint, the coverage. */
    uint32_t *px = sr__alloc_large(ctx, (size_t)w * ((size_t)h + 1) * 5), *row = px ? px + (size_t)w * h : NULL;
    uint8_t *mask = px ? (uint8_t *)(row + w) : NULL;
    sr_result r = px ? SR_OK : SR_OUT_OF_MEMORY;
    if (r == SR_OK) {
        r = sr__polygon_coverage(ctx, fn, poly, desc, bx0, by0, w, h, mask, (size_t)w);
    }
    /* The destination is read where it is, when the framebuffer lends its
     * pixels, and the result composed in px: one copy, not two. */
    const uint32_t *dst = (const uint32_t *)(const void *)sr_framebuffer_pixels(fb);
    size_t dst_stride = (size_t)fw;
    if (r == SR_OK && dst) {
        dst += (size_t)by0 * dst_stride + (size_t)bx0;
    } else if (r == SR_OK) {
        r = sr_read_pixels(ctx, fb, bx0, by0, w, h, (uint8_t *)px, (size_t)w * 4);
        dst = px;
        dst_stride = (size_t)w;
    }
    bool painted = false; /* row holds the paint of every x of a paint of x alone */
    bool opaque = false;  /* the paint in row[a, b) is opaque and the opacity 1 */
    for (int y = 0; r == SR_OK && y < h; y++) {
        const uint8_t *cov = mask + (size_t)y * w;
        const uint32_t *d = dst + (size_t)y * dst_stride;
        uint32_t *out = px + (size_t)y * w;
        int a, b;
        covered_part(cov, w, &a, &b);
        if (d != out) {
            memcpy(out, d, (size_t)a * 4);
            memcpy(out + b, d + b, (size_t)(w - b) * 4);
        }
        if (a == b) {
            continue;
        }
        /* A paint of x alone is evaluated once, over the whole width; one
         * that changes from row to row goes straight into the result when
         * that is not where the destination is read (the blend reads each
         * pixel of the paint before it writes it there). */
        uint32_t *paint_row = y > 0 && !painted && d != out ? out : row;
        if (!painted) {
            painted = span(paint, bx0 + a, by0 + y, b - a, paint_row + a);
            if (painted && paint_row != row) {
                memcpy(row + a, paint_row + a, (size_t)(b - a) * 4);
                paint_row = row;
            }
            if (painted && (a > 0 || b < w)) {
                span(paint, bx0, by0 + y, w, row);
            }
            opaque = opacity >= 1.0f &&
                     opaque_paint(paint_row, painted ? 0 : a, painted ? w : b);
        }
        blend_row(out, d, paint_row, cov, a, b, opacity, opaque);
    }
    if (r == SR_OK) {
        r = sr_write_pixels(ctx, fb, bx0, by0, w, h, (const uint8_t *)px, (size_t)w * 4);
    }
    sr__free(ctx, px);
    return r;
}

