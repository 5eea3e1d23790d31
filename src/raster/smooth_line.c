/* smooth_line.c - sr_smooth_line_pixels: the pixels and coverage of an
 * antialiased 3D line (smooth_line.h's walk, the one the rasterizer
 * shades) for a program to show, e.g. `softrast explain aaline`.  Runs
 * on the caller's thread. */
#include "context.h"
#include "raster/smooth_line.h"

#include <math.h>

sr_result sr_smooth_line_pixels(sr_context *ctx, int width, int height, sr_point2 a,
                                sr_point2 b, double line_width, sr_line_pixel_fn fn, void *user)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_smooth_line_pixels: ctx is NULL");
    }
    if (!fn) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_smooth_line_pixels: fn is NULL");
    }
    if (width <= 0 || height <= 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_smooth_line_pixels: width and height must be "
                        "> 0 (got %d x %d)", width, height);
    }
    const double coords[4] = { a.x, a.y, b.x, b.y };
    for (int i = 0; i < 4; i++) {
        if (!(fabs(coords[i]) <= 1048576.0)) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_smooth_line_pixels: the ends must be "
                            "finite and within +-2^20 px");
        }
    }
    if (!(line_width >= 0.0 && line_width <= 64.0)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_smooth_line_pixels: line_width must be in "
                        "[0, 64] (got %g)", line_width);
    }
    /* As sr_draw: ends snapped to 1/256 px, half the width as a float,
     * a = b draws nothing. */
    int64_t q[4];
    for (int i = 0; i < 4; i++) {
        q[i] = (int64_t)nearbyint(coords[i] * 256.0);
    }
    if (q[0] != q[2] || q[1] != q[3]) {
        float lw = (float)line_width;   /* sr_state.line_width is a float */
        float half = (float)((lw == 0.0f ? 1.0 : (double)lw) * 0.5);
        sr__smooth_line_walk(q[0], q[1], q[2], q[3], half, 0, 0, width, height, fn, user);
    }
    sr__ok(ctx);
    return SR_OK;
}
