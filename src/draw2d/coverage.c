/* coverage.c - draw2d stage: a color blended into the framebuffer through
 * a coverage mask the caller keeps (from sr_polygon_coverage), so shapes
 * drawn again and again (an overlay's glyphs) are rasterized once.
 * Consumes the mask, produces pixels blended source-over like every fill;
 * any thread that owns the framebuffer may call it. */
#include "context.h"
#include "draw2d/paint.h"
#include "rows.h"

sr_result sr_draw_coverage(sr_context *ctx, sr_framebuffer *fb, int x, int y, int w, int h,
                           const uint8_t *mask, size_t stride, sr_rgba color)
{
    static const char fn[] = "sr_draw_coverage";
    if (!ctx) {
        return SR_INVALID_ARG;
    }
    if (!fb || !mask) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn, fb ? "mask" : "fb");
    }
    if (w < 0 || h < 0 || w > SR_MAX_FRAMEBUFFER_SIZE || h > SR_MAX_FRAMEBUFFER_SIZE) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: mask %d x %d must be 0..%d on each side", fn,
                        w, h, SR_MAX_FRAMEBUFFER_SIZE);
    }
    if (stride < (size_t)w) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: stride %zu < width %d", fn, stride, w);
    }
    if (!sr__rows_fit(mask, (size_t)h, stride, (size_t)w)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %d rows of stride %zu run past the end of memory",
                        fn, h, stride);
    }
    sr__paint paint;
    if (!sr__paint_init(&paint, color, false)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: color is not finite", fn);
    }
    paint.wide = fb->wide_stores;
    sr_result r = sr__fb_begin_2d(ctx, fn, fb);
    if (r != SR_OK) {
        return r;
    }
    /* Clip the mask rectangle to the framebuffer in 64 bits: x + w may not
     * fit an int. */
    long long x0 = x < 0 ? 0 : x, y0 = y < 0 ? 0 : y;
    long long x1 = (long long)x + w, y1 = (long long)y + h;
    x1 = x1 > fb->width ? fb->width : x1;
    y1 = y1 > fb->height ? fb->height : y1;
    for (long long py = y0; py < y1; py++) {
        const uint8_t *m = mask + (size_t)(py - y) * stride;
        uint32_t *row = fb->color + (size_t)py * (size_t)fb->width;
        if (x1 > x0) {
            sr__paint_row(&paint, row + x0, m + (x0 - x), (int)(x1 - x0));
        }
    }
    sr__ok(ctx);
    return SR_OK;
}
