/* raster_util.h - helpers for the rasterization tests: draw triangles given
 * in window coordinates (pixels, y down) through the public API with
 * identity matrices, read back a coverage mask, and an independent int64
 * reference of the top-left rule written from docs/raster-rules.md §3.2. */
#ifndef SR_RASTER_UTIL_H
#define SR_RASTER_UTIL_H

#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct rt_target {
    sr_context *ctx;
    sr_framebuffer *fb;
    int w, h;
} rt_target;

static inline rt_target rt_make(int w, int h, int threads)
{
    rt_target t = { NULL, NULL, w, h };
    sr_make_context(&(sr_context_desc){ .threads = threads }, &t.ctx);
    sr_make_framebuffer(t.ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                      .depth_format = SR_DEPTH_NONE }, &t.fb);
    return t;
}

static inline void rt_free(rt_target *t)
{
    sr_destroy_framebuffer(t->ctx, t->fb);
    sr_destroy_context(t->ctx);
}

/* Window x (pixels) to NDC for a full-framebuffer viewport.  With w, h
 * powers of two and x on the 1/256 grid this is exact in float, so the
 * pipeline snaps back to exactly the same q8 value. */
static inline float rt_ndc_x(const rt_target *t, double x) { return (float)(x / (t->w * 0.5) - 1.0); }
static inline float rt_ndc_y(const rt_target *t, double y) { return (float)(1.0 - y / (t->h * 0.5)); }

static inline sr_result rt_draw_tris(rt_target *t, const double *xy, int ntri,
                                     const float *colors, sr_rasterizer rast)
{
    float *pos = malloc(sizeof(float) * 3 * 3 * (size_t)ntri);
    for (int i = 0; i < ntri * 3; i++) {
        pos[i * 3 + 0] = rt_ndc_x(t, xy[i * 2 + 0]);
        pos[i * 3 + 1] = rt_ndc_y(t, xy[i * 2 + 1]);
        pos[i * 3 + 2] = 0.0f;
    }
    sr_state st = { .rasterizer = rast, .shading = SR_SHADING_UNLIT,
                    .material = { .diffuse = { 1, 1, 1 } } };
    sr_result r = sr_draw(t->ctx, t->fb, &st,
                          &(sr_draw_desc){ .positions = pos, .vertex_count = (size_t)ntri * 3,
                                           .colors = colors, .color_size = 4 });
    free(pos);
    return r;
}

static inline void rt_clear(rt_target *t)
{
    sr_clear(t->ctx, t->fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 }, .depth = 1 });
}

/* mask[i] = 1 where the pixel's red channel is non-zero. */
static inline void rt_mask(const rt_target *t, uint8_t *mask)
{
    const uint8_t *px = sr_framebuffer_pixels(t->fb);
    for (int i = 0; i < t->w * t->h; i++) {
        mask[i] = px[i * 4] != 0;
    }
}

/* ---- independent reference (docs/raster-rules.md §3.2) ---- */

static inline int64_t ref_snap(double v) { return (int64_t)nearbyint(v * 256.0); }

static inline int64_t ref_edge(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t px, int64_t py)
{
    return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

/* Coverage of one triangle (window coords) by the top-left rule. */
static inline void ref_cover(const double *xy, int w, int h, uint8_t *mask)
{
    int64_t x[3], y[3];
    for (int i = 0; i < 3; i++) {
        x[i] = ref_snap(xy[i * 2]);
        y[i] = ref_snap(xy[i * 2 + 1]);
    }
    int64_t area2 = ref_edge(x[0], y[0], x[1], y[1], x[2], y[2]);
    memset(mask, 0, (size_t)w * h);
    if (area2 == 0) {
        return;
    }
    if (area2 < 0) {
        int64_t tx = x[1], ty = y[1];
        x[1] = x[2]; y[1] = y[2];
        x[2] = tx; y[2] = ty;
    }
    for (int py = 0; py < h; py++) {
        for (int px = 0; px < w; px++) {
            int64_t sx = px * 256 + 128, sy = py * 256 + 128;
            bool in = true;
            for (int i = 0; i < 3; i++) {
                int a = i, b = (i + 1) % 3;
                int64_t dx = x[b] - x[a], dy = y[b] - y[a];
                bool tl = dy < 0 || (dy == 0 && dx > 0);
                in &= ref_edge(x[a], y[a], x[b], y[b], sx, sy) + (tl ? 1 : 0) > 0;
            }
            mask[py * w + px] = in;
        }
    }
}

#endif
