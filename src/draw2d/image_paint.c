/* image_paint.c - draw2d stage: an RGBA8 image as a paint (a pattern's
 * tile, the SVG reader's <image>), sampled bilinearly a row at a time,
 * repeated or its edge texels extended.  Used by paint_fill.c on the
 * caller's thread. */
#include "draw2d/paint_fill.h"

#include <math.h>
#include <string.h>

/* Texel (i, j)'s byte offset: repeated, or the nearest edge texel outside. */
static size_t texel_offset(const sr__image *im, long i, long j)
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
    return (size_t)j * im->stride + (size_t)i * 4;
}

/* Texel (i, j) premultiplied, in [0, 1]. */
static void texel(const sr__image *im, long i, long j, float out[4])
{
    const uint8_t *p = im->rgba + texel_offset(im, i, j);
    float a = p[3] * (1.0f / 255.0f);
    for (int k = 0; k < 3; k++) {
        out[k] = p[k] * (1.0f / 255.0f) * a;
    }
    out[3] = a;
}

/* out[0..n) = the texels t[0..n), a transparent texel as 0 (a sample
 * with alpha 0 is 0 whatever its color). */
static void copy_texels(uint32_t *out, const uint8_t *t, int n)
{
    static const uint8_t alpha_byte[4] = { 0, 0, 0, 255 };
    uint32_t alpha;
    memcpy(&alpha, alpha_byte, sizeof alpha);
    for (int k = 0; k < n; k++) {
        uint32_t v;
        memcpy(&v, t + (size_t)k * 4, sizeof v);
        out[k] = v & alpha ? v : 0;
    }
}

/* The image at texel coordinates (u, v) of a texel's corner, bilinear
 * and premultiplied (a transparent texel adds no color), straight RGBA8. */
static uint32_t sample(const sr__image *im, double u, double v)
{
    if (!(fabs(u) < 1e15 && fabs(v) < 1e15)) {
        return 0;
    }
    double fu = floor(u), fv = floor(v);
    float tu = (float)(u - fu), tv = (float)(v - fv), c[4][4], o[4];
    long i = (long)fu, j = (long)fv;
    texel(im, i, j, c[0]);
    texel(im, i + 1, j, c[1]);
    texel(im, i, j + 1, c[2]);
    texel(im, i + 1, j + 1, c[3]);
    for (int k = 0; k < 4; k++) {
        float top = c[0][k] + (c[1][k] - c[0][k]) * tu, bot = c[2][k] + (c[3][k] - c[2][k]) * tu;
        o[k] = top + (bot - top) * tv;
    }
    if (!(o[3] > 0)) {
        return 0;
    }
    uint8_t b[4] = { sr__paint_unorm8(o[0] / o[3]), sr__paint_unorm8(o[1] / o[3]), sr__paint_unorm8(o[2] / o[3]),
                     sr__paint_unorm8(o[3]) };
    uint32_t w;
    memcpy(&w, b, sizeof w);
    return w;
}

bool sr__image_span(void *image, int x, int y, int n, uint32_t *out)
{
    const sr__image *im = image;
    const double *m = im->inv;
    double px = x + 0.5, py = y + 0.5;
    double u0 = m[0] * px + m[2] * py + m[4] - 0.5, v0 = m[1] * px + m[3] * py + m[5] - 0.5;
    /* One texel a pixel along the row, texel centres on pixel centres
     * (a tile drawn at the device's scale, an image at its size): the
     * weights are 0 and each pixel is its texel, bytes copied. */
    if (m[0] == 1 && m[1] == 0 && u0 == floor(u0) && v0 == floor(v0) && fabs(u0) < 1e15 &&
        fabs(v0) < 1e15) {
        long i = (long)u0, w = im->w;
        const uint8_t *row = im->rgba + texel_offset(im, 0, (long)v0);
        if (im->repeat) {
            i %= w;
            i += i < 0 ? w : 0;
            /* One period of the row (the tile's row from i to its end,
             * then from its start), then the pixels already made, doubled
             * until the span is full: the row repeats every w pixels. */
            int have = w - i < n ? (int)(w - i) : n;
            copy_texels(out, row + (size_t)i * 4, have);
            int rest = (int)i < n - have ? (int)i : n - have;
            copy_texels(out + have, row, rest);
            for (have += rest; have < n; have *= 2) {
                memcpy(out + have, out, (size_t)(have < n - have ? have : n - have) * 4);
            }
            return false;
        }
        /* Left of the image its first texel, right of it its last. */
        int k = 0;
        for (; k < n && i < 0; k++, i++) {
            copy_texels(out + k, row, 1);
        }
        if (k < n && i < w) {
            int run = w - i < n - k ? (int)(w - i) : n - k;
            copy_texels(out + k, row + (size_t)i * 4, run);
            k += run;
        }
        for (; k < n; k++) {
            copy_texels(out + k, row + (size_t)(w - 1) * 4, 1);
        }
        return false;
    }
    for (int k = 0; k < n; k++) {
        out[k] = sample(im, u0 + m[0] * k, v0 + m[1] * k);
    }
    return false;
}
