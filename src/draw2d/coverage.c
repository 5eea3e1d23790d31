/* coverage.c - draw2d stage: a color blended into the framebuffer through
 * a coverage mask the caller keeps (from sr_polygon_coverage), so shapes
 * drawn again and again (an overlay's glyphs) are rasterized once; and an
 * RGBA8 layer blended through one (a clip's).  Consumes the mask,
 * produces pixels blended source-over like every fill; any thread that
 * owns the framebuffer may call it. */
#include "context.h"
#include "draw2d/paint.h"
#include "draw2d/paint_fill.h"
#include "rows.h"

#include <math.h>

/* The checks both calls make of a w x h image of `what` (a mask, a
 * layer) with `bpp` bytes a pixel and stride bytes a row. */
static sr_result check_image(sr_context *ctx, const char *fn, const sr_framebuffer *fb,
                             const void *pixels, const char *what, int w, int h, size_t stride,
                             size_t bpp)
{
    if (!fb || !pixels) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn, fb ? what : "fb");
    }
    if (w < 0 || h < 0 || w > SR_MAX_FRAMEBUFFER_SIZE || h > SR_MAX_FRAMEBUFFER_SIZE) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s %d x %d must be 0..%d on each side", fn,
                        what, w, h, SR_MAX_FRAMEBUFFER_SIZE);
    }
    if (stride < (size_t)w * bpp) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: stride %zu < %s width %d", fn, stride,
                        bpp == 4 ? "4 *" : "the", w);
    }
    if (!sr__rows_fit(pixels, (size_t)h, stride, (size_t)w * bpp)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %d rows of stride %zu run past the end of memory",
                        fn, h, stride);
    }
    return SR_OK;
}

/* The part [r[0], r[2]) x [r[1], r[3]) of the w x h rectangle at (x, y)
 * inside fb, in 64 bits: x + w may not fit an int. */
static void inside_fb(const sr_framebuffer *fb, int x, int y, int w, int h, long long r[4])
{
    r[0] = x < 0 ? 0 : x;
    r[1] = y < 0 ? 0 : y;
    r[2] = (long long)x + w > fb->width ? fb->width : (long long)x + w;
    r[3] = (long long)y + h > fb->height ? fb->height : (long long)y + h;
}

sr_result sr_draw_coverage(sr_context *ctx, sr_framebuffer *fb, int x, int y, int w, int h,
                           const uint8_t *mask, size_t stride, sr_rgba color)
{
    static const char fn[] = "sr_draw_coverage";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_draw_coverage: ctx is NULL");
    }
    sr_result r = check_image(ctx, fn, fb, mask, "mask", w, h, stride, 1);
    if (r != SR_OK) {
        return r;
    }
    sr__paint paint;
    if (!sr__paint_init(&paint, color, false)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: color is not finite", fn);
    }
    paint.wide = fb->wide_stores;
    r = sr__fb_begin_2d(ctx, fn, fb);
    if (r != SR_OK) {
        return r;
    }
    long long in[4];
    inside_fb(fb, x, y, w, h, in);
    for (long long py = in[1]; py < in[3]; py++) {
        const uint8_t *m = mask + (size_t)(py - y) * stride;
        uint32_t *row = fb->color + (size_t)py * (size_t)fb->width;
        if (in[2] > in[0]) {
            sr__paint_row(&paint, row + in[0], m + (in[0] - x), (int)(in[2] - in[0]));
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
        return sr__fail(NULL, SR_INVALID_ARG, "sr_draw_layer: ctx is NULL");
    }
    sr_result r = check_image(ctx, fn, fb, rgba, "rgba", w, h, stride, 4);
    if (r != SR_OK) {
        return r;
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
    r = sr__fb_begin_2d(ctx, fn, fb);
    if (r != SR_OK) {
        return r;
    }
    long long in[4];
    inside_fb(fb, x, y, w, h, in);
    for (long long py = in[1]; py < in[3]; py++) {
        const uint8_t *src = rgba + (size_t)(py - y) * stride;
        const uint8_t *m = d.mask ? d.mask + (size_t)(py - y) * d.mask_stride : NULL;
        uint8_t *row = (uint8_t *)(fb->color + (size_t)py * (size_t)fb->width);
        for (long long px = in[0]; px < in[2]; px++) {
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
