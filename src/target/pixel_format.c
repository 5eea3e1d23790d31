/* pixel_format.c - RGBA8 pixels packed into the small formats of
 * sr_pixel_format (target stage), for the bands sr_render_bands hands
 * over.  Any thread. */
#include "target/pixel_format.h"

/* The nearest n-bit value to c / 255: (c * max + 127) / 255 with max =
 * 2^n - 1.  c * max / 255 is never halfway between two integers (255 is
 * odd), so there are no ties to break. */
static inline unsigned to_bits(unsigned c, unsigned max)
{
    return (c * max + 127u) / 255u;
}

size_t sr__pixel_size(sr_pixel_format format)
{
    switch (format) {
    case SR_PIXEL_RGB565: return 2;
    case SR_PIXEL_RGB332: return 1;
    default:              return 4;
    }
}

void sr__pack_pixels(uint8_t *dst, const uint8_t *rgba, size_t n, sr_pixel_format format)
{
    /* Front to back: pixel i is read at 4i before 2i or i is written, so
     * dst may be rgba itself. */
    for (size_t i = 0; i < n; i++) {
        const uint8_t *p = rgba + 4 * i;
        if (format == SR_PIXEL_RGB565) {
            unsigned v = to_bits(p[0], 31) << 11 | to_bits(p[1], 63) << 5 | to_bits(p[2], 31);
            dst[2 * i] = (uint8_t)(v >> 8);
            dst[2 * i + 1] = (uint8_t)v;
        } else if (format == SR_PIXEL_RGB332) {
            dst[i] = (uint8_t)(to_bits(p[0], 7) << 5 | to_bits(p[1], 7) << 2 | to_bits(p[2], 3));
        }
    }
}
