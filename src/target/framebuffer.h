/* framebuffer.h - render target storage (target stage).  Color is RGBA8 in
 * memory order r, g, b, a, row-major from the top row.  Depth of every
 * format is kept as a uint32 per pixel holding the *quantized* value, so one
 * unsigned compare serves all formats: D16/D24/D32 store k for k/(2^n - 1),
 * D32F stores the bits of a non-negative float, which order like integers. */
#ifndef SR_FRAMEBUFFER_H
#define SR_FRAMEBUFFER_H

#include "softrast.h"

struct sr_framebuffer {
    int width, height;
    sr_depth_format depth_format;   /* resolved: never SR_DEPTH_DEFAULT */
    int depth_bits;                 /* 16, 24, 32; 0 for D32F */
    uint32_t *color;
    uint32_t *depth;                /* NULL with SR_DEPTH_NONE */
};

#endif
