/* coverage.c - draw2d stage: a color blended into the framebuffer through
 * a coverage mask the caller keeps (from sr_polygon_coverage), so shapes
 * drawn again and again (an overlay's glyphs) are rasterized once; and an
 * RGBA8 layer blended through one (a clip's).  Consumes the mask,
 * produces pixels blended source-over like every fill; any thread that
 * owns the framebuffer may call it. */
#include "context.h"
#include "draw2d/paint.h"
#include "draw2d/paint_fill.h"

#include <math.h>

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

sr_result sr_draw_layer(sr_context *ctx, sr_framebuffer *fb, int x, int y, int w, int h,
                        const uint8_t *rgba, size_t stride, const sr_layer_desc *desc)
{
    static const char fn[] = "sr_draw_layer";
    if (!ctx) {
        return SR_INVALID_ARG;
    }
    if (!fb || !rgba) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn, fb ? "rgba" : "fb");
    }
    if (w < 0 || h < 0 || w > SR_MAX_FRAMEBUFFER_SIZE || h > SR_MAX_FRAMEBUFFER_SIZE) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: layer %d x %d must be 0..%d on each side", fn,
                        w, h, SR_MAX_FRAMEBUFFER_SIZE);
    }
    if (stride < (size_t)w * 4) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: stride %zu < 4 * width %d", fn, stride, w);
    }
    sr_layer_desc d = desc ? *desc : (sr_layer_desc){ 0 };
    if (d.mask_stride == 0) {
        d.mask_stride = (size_t)w;
    }
    if (d.mask && d.mask_stride < (size_t)w) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_layer_desc.mask_stride %zu < width %d", fn,
                        d.mask_stride, w);
    }
    if (!(d.opacity >= 0.0f && d.opacity <= 1.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_layer_desc.opacity %g is not in [0, 1]", fn,
                        (double)d.opacity);
    }
    double opacity = d.opacity > 0.0f ? d.opacity : 1.0;
    sr_result r = sr__fb_begin_2d(ctx, fn, fb);
    if (r != SR_OK) {
        return r;
    }
    long long x0 = x < 0 ? 0 : x, y0 = y < 0 ? 0 : y;
    long long x1 = (long long)x + w, y1 = (long long)y + h;
    x1 = x1 > fb->width ? fb->width : x1;
    y1 = y1 > fb->height ? fb->height : y1;
    for (long long py = y0; py < y1; py++) {
        const uint8_t *src = rgba + (size_t)(py - y) * stride;
        const uint8_t *m = d.mask ? d.mask + (size_t)(py - y) * d.mask_stride : NULL;
        uint8_t *row = (uint8_t *)(fb->color + (size_t)py * (size_t)fb->width);
        for (long long px = x0; px < x1; px++) {
            const uint8_t *s = src + (size_t)(px - x) * 4;
            unsigned c = m ? m[px - x] : 255;
            if (s[3] == 0 || c == 0) {
                continue;
            }
            /* The alpha in float as the layer's pixel times the opacity
             * in double, then the coverage: the SVG reader's layers blend
             * so, and a canvas draw clipped here must give their bytes. */
            float a = (float)(s[3] / 255.0 * opacity);
            a = (a > 1.0f ? 1.0f : a) * ((float)c / 255.0f);
            if (a > 0.0f) {
                sr__blend_rgba8(row + (size_t)px * 4, s, a);
            }
        }
    }
    sr__ok(ctx);
    return SR_OK;
}
