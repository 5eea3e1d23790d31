/* test_resample.c - SSAA's resolve, sr_downsample: the box filter is the
 * exact k x k block mean (unweighted area sampling); every filter keeps a
 * flat image flat (weights normalized) and turns a step into a monotonic
 * ramp (Mitchell may overshoot and is clamped); bad sizes are refused. */
#include "sr_test.h"
#include "softrast.h"

#include <stdlib.h>
#include <string.h>

static sr_framebuffer *fb_from(sr_context *ctx, int w, int h, uint8_t (*fn)(int x, int y, int c))
{
    sr_framebuffer *fb = NULL;
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                    .depth_format = SR_DEPTH_NONE }, &fb);
    /* Write through the pixel pointer (clears are resolved by reading it).
     * The API calls it read-only because a later clear to the same color
     * would not see these writes; these sources are never cleared again. */
    uint8_t *px = (uint8_t *)sr_framebuffer_pixels(fb);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            for (int c = 0; c < 4; c++) {
                px[(y * w + x) * 4 + c] = fn(x, y, c);
            }
        }
    }
    return fb;
}

static uint8_t noise(int x, int y, int c) { return (uint8_t)((x * 37 + y * 91 + c * 53) * 2654435761u >> 24); }
static uint8_t flat(int x, int y, int c) { (void)x; (void)y; return (uint8_t)(40 + c * 50); }
static uint8_t step(int x, int y, int c) { (void)y; (void)c; return x < 32 ? 0 : 255; }

SR_TEST(box_filter_is_the_block_mean)
{
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    for (int k = 1; k <= 4; k++) {
        sr_framebuffer *src = fb_from(ctx, 8 * k, 6 * k, noise), *dst = NULL;
        sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 6,
                                                        .depth_format = SR_DEPTH_NONE }, &dst);
        REQUIRE(sr_downsample(ctx, src, dst, SR_RESAMPLE_BOX) == SR_OK);
        const uint8_t *d = sr_framebuffer_pixels(dst), *s = sr_framebuffer_pixels(src);
        for (int y = 0; y < 6; y++) {
            for (int x = 0; x < 8; x++) {
                for (int c = 0; c < 4; c++) {
                    int sum = 0;
                    for (int j = 0; j < k; j++) {
                        for (int i = 0; i < k; i++) {
                            sum += s[((y * k + j) * 8 * k + x * k + i) * 4 + c];
                        }
                    }
                    CHECK_NEAR(d[(y * 8 + x) * 4 + c], (double)sum / (k * k), 0.51);
                }
            }
        }
        sr_destroy_framebuffer(ctx, src);
        sr_destroy_framebuffer(ctx, dst);
    }
    sr_destroy_context(ctx);
}

SR_TEST(every_filter_keeps_flat_images_flat_and_steps_monotonic)
{
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    const sr_resample_filter filters[] = { SR_RESAMPLE_BOX, SR_RESAMPLE_TENT, SR_RESAMPLE_GAUSSIAN,
                                           SR_RESAMPLE_MITCHELL };
    for (int f = 0; f < 4; f++) {
        sr_framebuffer *src = fb_from(ctx, 64, 64, flat), *dst = NULL;
        sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 16, .height = 16,
                                                        .depth_format = SR_DEPTH_NONE }, &dst);
        REQUIRE(sr_downsample(ctx, src, dst, filters[f]) == SR_OK);
        const uint8_t *d = sr_framebuffer_pixels(dst);
        for (int i = 0; i < 16 * 16; i++) {
            for (int c = 0; c < 4; c++) {
                CHECK_NEAR(d[i * 4 + c], 40 + c * 50, 0.51);
            }
        }
        sr_destroy_framebuffer(ctx, src);
        src = fb_from(ctx, 64, 64, step);
        REQUIRE(sr_downsample(ctx, src, dst, filters[f]) == SR_OK);
        d = sr_framebuffer_pixels(dst);
        /* Along a row: dark on the left, light on the right, and for the
         * positive filters never decreasing. */
        CHECK(d[0] < 20 && d[15 * 4] > 235);
        if (filters[f] != SR_RESAMPLE_MITCHELL) {
            for (int x = 1; x < 16; x++) {
                CHECK(d[x * 4] >= d[(x - 1) * 4]);
            }
        }
        sr_destroy_framebuffer(ctx, src);
        sr_destroy_framebuffer(ctx, dst);
    }
    sr_destroy_context(ctx);
}

SR_TEST(downsample_sizes_are_validated)
{
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    sr_framebuffer *a = fb_from(ctx, 30, 20, flat), *b = fb_from(ctx, 8, 5, flat);
    CHECK_EQ(sr_downsample(ctx, a, b, SR_RESAMPLE_BOX), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "k times");
    CHECK_EQ(sr_downsample(ctx, a, NULL, SR_RESAMPLE_BOX), SR_INVALID_ARG);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}
