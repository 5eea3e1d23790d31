/* pixel_format.h - RGBA8 pixels packed into sr_pixel_format's small
 * formats (target stage).  Any thread.  Internal to the library. */
#ifndef SR_PIXEL_FORMAT_H
#define SR_PIXEL_FORMAT_H

#include "softrast.h"

#include <stddef.h>
#include <stdint.h>

/* Bytes per pixel of a resolved format. */
size_t sr__pixel_size(sr_pixel_format format);
/* n RGBA8 pixels into `format` (SR_PIXEL_RGB565 or SR_PIXEL_RGB332);
 * dst may be rgba (packing in place). */
void sr__pack_pixels(uint8_t *dst, const uint8_t *rgba, size_t n, sr_pixel_format format);

#endif
