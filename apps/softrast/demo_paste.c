/* demo_paste.c - composing a demo's page from panels: a panel copied in
 * as it is, or magnified so that its pixels show.  Everything goes
 * through sr_framebuffer_pixels and sr_write_pixels, so the page's
 * pending clears and clean tiles stay the library's business. */
#include "demo.h"

#include <stdlib.h>
#include <string.h>

sr_result demo_paste(sr_context *ctx, sr_framebuffer *dst, const sr_framebuffer *src, int x,
                     int y)
{
    int sw = sr_framebuffer_width(src), sh = sr_framebuffer_height(src);
    int dw = sr_framebuffer_width(dst), dh = sr_framebuffer_height(dst);
    /* The part of src that lands inside dst. */
    int c0 = x < 0 ? -x : 0, r0 = y < 0 ? -y : 0;
    int c1 = x + sw > dw ? dw - x : sw, r1 = y + sh > dh ? dh - y : sh;
    if (c0 >= c1 || r0 >= r1) {
        return SR_OK;
    }
    const uint8_t *px = sr_framebuffer_pixels(src);
    size_t stride = 4 * (size_t)sw;
    return sr_write_pixels(ctx, dst, x + c0, y + r0, c1 - c0, r1 - r0,
                           px + (size_t)r0 * stride + 4 * (size_t)c0, stride);
}

sr_result demo_magnify(sr_context *ctx, sr_framebuffer *dst, int x, int y,
                       const sr_framebuffer *src, int scale, const uint8_t *grid)
{
    int sw = sr_framebuffer_width(src), sh = sr_framebuffer_height(src);
    int w = sw * scale, h = sh * scale;
    uint32_t *cell = malloc(sizeof *cell * (size_t)w * (size_t)h);
    if (!cell) {
        return SR_OUT_OF_MEMORY;
    }
    const uint32_t *s = (const uint32_t *)sr_framebuffer_pixels(src);
    uint32_t line = 0;
    if (grid) {
        memcpy(&line, grid, sizeof line);
    }
    bool lines = grid && scale >= 4;
    for (int cy = 0; cy < h; cy++) {
        for (int cx = 0; cx < w; cx++) {
            bool edge = lines && (cx % scale == 0 || cy % scale == 0);
            cell[(size_t)cy * (size_t)w + (size_t)cx] =
                edge ? line : s[(size_t)(cy / scale) * (size_t)sw + (size_t)(cx / scale)];
        }
    }
    sr_result r = sr_write_pixels(ctx, dst, x, y, w, h, (const uint8_t *)cell, 4 * (size_t)w);
    free(cell);
    return r;
}
