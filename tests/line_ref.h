/* line_ref.h - the pieces of the diamond-exit closed form
 * (docs/raster-rules.md §7.1) that the 3D line tests' independent references share, written
 * from the rules rather than from line.c: exact ceil division, a column's
 * pixel, and which pixel's diamond owns a q8 point (Direct3D's boundary ownership: the
 * lower edges and bottom corner, and for a y-major line the right
 * corner). */
#ifndef SR_LINE_REF_H
#define SR_LINE_REF_H
#include <stdbool.h>
#include <stdint.h>

static inline int64_t lr_cdiv(int64_t a, int64_t b) /* ceil, b > 0 */
{
    return a >= 0 ? (a + b - 1) / b : -((-a) / b);
}

static inline bool lr_diamond_owns(int64_t x, int64_t y, int64_t qx, int64_t qy, bool xmaj)
{
    int64_t dx = x - (qx * 256 + 128), dy = y - (qy * 256 + 128);
    int64_t d = (dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy);
    return d < 128 || (d == 128 && (dy > 0 || (!xmaj && dx == 128 && dy == 0)));
}

/* The minor index of the pixel holding the segment's point at major
 * coordinate c (q8; u major, v minor): ceil(num / 256 den) - 1, a point on
 * a pixel boundary going to the smaller index. */
static inline int64_t lr_column_pixel(int64_t au, int64_t av, int64_t bu, int64_t bv, int64_t c)
{
    int64_t num = av * (bu - au) + (c - au) * (bv - av), den = bu - au;
    if (den < 0) {
        num = -num;
        den = -den;
    }
    return lr_cdiv(num, den * 256) - 1;
}

#endif
