/* fuzz_fill2d.c - libFuzzer target for the 2D raster toolkit: a polygon of
 * up to 64 points decoded from the bytes (hostile doubles, several
 * contours), filled with every rule and antialiasing mode, its coverage
 * mask, Sutherland-Hodgman clipping against a rectangle, and flood and
 * boundary fills from a seed.  Checked: valid results with messages, and
 * the aliased fill lights exactly the pixels of the aliased coverage mask.
 * scripts/fuzz.sh fuzz_fill2d SECONDS. */
#include "softrast.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct reader {
    const uint8_t *p;
    size_t n;
} reader;

static unsigned byte(reader *r)
{
    if (!r->n) {
        return 0;
    }
    r->n--;
    return *r->p++;
}

static double coord(reader *r, int extent)
{
    static const double hostile[] = { 0.0, -0.0, NAN, INFINITY, -INFINITY, DBL_MAX, -DBL_MAX,
                                      1e-300, 262144.0, 262145.0, -262145.0, 0.5, 1.0 / 256 };
    unsigned k = byte(r);
    if (k < 16) {
        return hostile[k % (sizeof hostile / sizeof hostile[0])];
    }
    /* On the 1/16 grid around the target. */
    int v = (int)(byte(r) | byte(r) << 8) - 32768;
    return (double)v / 16.0 * (extent + 8) / 2048.0 + extent / 2.0;
}

static void check(sr_context *ctx, sr_result r)
{
    if (r != SR_OK && (r >= SR_RESULT_COUNT || !sr_context_error(ctx)[0])) {
        abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reader rd = { data, size };
    int w = 1 + (int)(byte(&rd) % 48), h = 1 + (int)(byte(&rd) % 48);
    int n = (int)(byte(&rd) % 65);
    sr_point2 pts[64];
    for (int i = 0; i < n; i++) {
        pts[i].x = coord(&rd, w);
        pts[i].y = coord(&rd, h);
    }
    int contours[4], ncont = 1 + (int)(byte(&rd) % 4), left = n;
    for (int c = 0; c < ncont; c++) {
        contours[c] = c + 1 < ncont ? (int)(byte(&rd) % (unsigned)(left + 1)) : left;
        left -= contours[c];
    }
    sr_polygon2 poly = { pts, n, contours, ncont };

    sr_context *ctx;
    if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) != SR_OK) {
        return 0;
    }
    sr_framebuffer *fb;
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                        .depth_format = SR_DEPTH_NONE },
                            &fb) != SR_OK) {
        sr_destroy_context(ctx);
        return 0;
    }
    const sr_rgba white = { 1, 1, 1, 1 }, red = { 1, 0, 0, 1 };
    for (int rule = SR_NONZERO; rule <= SR_EVENODD; rule++) {
        /* Aliased fill and aliased coverage: the same pixels. */
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        sr_fill_desc desc = { .rule = (sr_fill_rule)rule, .antialias = SR_AA_NONE };
        sr_result a = sr_fill_polygon(ctx, fb, &poly, white, &desc);
        check(ctx, a);
        uint8_t *mask = malloc((size_t)w * h);
        sr_result b = mask ? sr_polygon_coverage(ctx, &poly, &desc, 0, 0, w, h, mask, (size_t)w)
                           : SR_OUT_OF_MEMORY;
        check(ctx, b);
        if (a != b) {
            abort();
        }
        if (a == SR_OK && b == SR_OK) {
            const uint8_t *px = sr_framebuffer_pixels(fb);
            for (int i = 0; i < w * h; i++) {
                if ((px[i * 4] == 255) != (mask[i] == 255)) {
                    abort();
                }
            }
        }
        free(mask);
        /* The antialiased fills. */
        desc.antialias = SR_AA_AREA;
        check(ctx, sr_fill_polygon(ctx, fb, &poly, red, &desc));
        desc.antialias = SR_AA_SUPERSAMPLE;
        desc.samples = 1 + (int)(byte(&rd) % 6);
        desc.linear_light = byte(&rd) & 1;
        check(ctx, sr_fill_polygon(ctx, fb, &poly, (sr_rgba){ 0, 1, 0, 0.5f }, &desc));
    }
    /* Clipping against a rectangle (capacity always enough: n + 4 per edge). */
    sr_point2 out[64 + 8];
    int out_n = 0;
    if (n > 0) {
        check(ctx, sr_clip_polygon_rect(ctx, pts, n, coord(&rd, w), coord(&rd, h), coord(&rd, w),
                                        coord(&rd, h), NULL, out, 64 + 8, &out_n));
    }
    /* Region fills from a seed anywhere (also outside the target). */
    int sx = (int)(byte(&rd) % (unsigned)(w + 4)) - 2, sy = (int)(byte(&rd) % (unsigned)(h + 4)) - 2;
    sr_region_fill_desc rf = { .connectivity = (byte(&rd) & 1) ? SR_CONNECT_8 : SR_CONNECT_4,
                               .tolerance = (int)(byte(&rd) % 8) };
    size_t filled = 0;
    check(ctx, sr_flood_fill(ctx, fb, sx, sy, (sr_rgba){ 0, 0, 1, 1 }, &rf, &filled));
    if (filled > (size_t)w * h) {
        abort();
    }
    check(ctx, sr_boundary_fill(ctx, fb, sx, sy, (sr_rgba){ 1, 1, 0, 1 }, white, &rf, &filled));
    if (filled > (size_t)w * h) {
        abort();
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    return 0;
}
