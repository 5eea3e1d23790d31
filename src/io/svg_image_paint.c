/* svg_image_paint.c - an RGBA8 image as the SVG reader's paint (src/io):
 * a pattern's tile or an <image>, sampled bilinearly a row at a time,
 * repeated or its edge texels extended.  Used by svg_fill.c on the thread
 * that renders the document. */
#include "io/svg.h"

#include <math.h>
#include <string.h>

/* Texel (i, j)'s index: repeated, or the nearest edge texel outside. */
static size_t texel_index(const svg_image *im, long i, long j)
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
    return (size_t)j * (size_t)im->w + (size_t)i;
}

/* Texel (i, j) premultiplied, in [0, 1]. */
static void texel(const svg_image *im, long i, long j, float out[4])
{
    const uint8_t *p = im->rgba + texel_index(im, i, j) * 4;
    float a = p[3] * (1.0f / 255.0f);
    for (int k = 0; k < 3; k++) {
        out[k] = p[k] * (1.0f / 255.0f) * a;
    }
    out[3] = a;
}

/* The image at texel coordinates (u, v) of a texel's corner, bilinear
 * and premultiplied (a transparent texel adds no color), straight RGBA8. */
static uint32_t sample(const svg_image *im, double u, double v)
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
    uint8_t b[4] = { svg_unorm8(o[0] / o[3]), svg_unorm8(o[1] / o[3]), svg_unorm8(o[2] / o[3]),
                     svg_unorm8(o[3]) };
    uint32_t w;
    memcpy(&w, b, sizeof w);
    return w;
}

bool svg_image_span(void *image, int x, int y, int n, uint32_t *out)
{
    const svg_image *im = image;
    const double *m = im->inv;
    double px = x + 0.5, py = y + 0.5;
    double u0 = m[0] * px + m[2] * py + m[4] - 0.5, v0 = m[1] * px + m[3] * py + m[5] - 0.5;
    /* One texel a pixel along the row, texel centres on pixel centres
     * (a tile drawn at the device's scale, an image at its size): the
     * weights are 0 and each pixel is its texel, bytes copied. */
    if (m[0] == 1 && m[1] == 0 && u0 == floor(u0) && v0 == floor(v0) && fabs(u0) < 1e15 &&
        fabs(v0) < 1e15) {
        long i = (long)u0, w = im->w;
        const uint8_t *row = im->rgba + texel_index(im, 0, (long)v0) * 4;
        if (im->repeat) {
            i %= w;
            i += i < 0 ? w : 0;
        }
        for (int k = 0; k < n; k++) {
            long c = im->repeat ? i : i < 0 ? 0 : i >= w ? w - 1 : i;
            const uint8_t *t = row + (size_t)c * 4;
            if (t[3] == 0) {
                out[k] = 0;
            } else {
                memcpy(&out[k], t, sizeof out[k]);
            }
            i = im->repeat && i + 1 == w ? 0 : i + 1;
        }
        return false;
    }
    for (int k = 0; k < n; k++) {
        out[k] = sample(im, u0 + m[0] * k, v0 + m[1] * k);
    }
    return false;
}
