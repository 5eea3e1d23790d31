/* test_draw_coverage.c - sr_draw_coverage (src/draw2d/coverage.c): a
 * coverage mask computed once by sr_polygon_coverage and blended later
 * gives exactly the pixels sr_fill_polygon gives; masks are clipped to the
 * framebuffer wherever they land; bad arguments are rejected, naming the
 * field, with nothing drawn.  sr_draw_layer: an RGBA8 layer blended
 * through a mask as the coverage blend is, at an opacity, clipped. */
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <string.h>

static const sr_point2 star[] = { { 20.3, 2.1 }, { 26.0, 37.5 }, { 2.2, 14.0 },
                                  { 38.1, 13.2 }, { 13.7, 38.0 } };

static sr_framebuffer *make_fb(sr_context *ctx, int w, int h)
{
    sr_framebuffer *fb = NULL;
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h }, &fb);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.2f, 0.3f, 1.0f }, .depth = 1 });
    return fb;
}

SR_TEST(cached_coverage_draws_the_same_pixels_as_the_fill)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_polygon2 poly = { .points = star, .point_count = 5 };
    sr_fill_desc desc = { .rule = SR_NONZERO, .antialias = SR_AA_AREA };
    sr_rgba color = { 0.9f, 0.8f, 0.2f, 0.75f };
    sr_framebuffer *a = make_fb(ctx, 40, 40), *b = make_fb(ctx, 40, 40);
    REQUIRE(a && b);
    CHECK_EQ(sr_fill_polygon(ctx, a, &poly, color, &desc), SR_OK);
    uint8_t mask[40 * 40];
    CHECK_EQ(sr_polygon_coverage(ctx, &poly, &desc, 0, 0, 40, 40, mask, 40), SR_OK);
    CHECK_EQ(sr_draw_coverage(ctx, b, 0, 0, 40, 40, mask, 40, color), SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), 40 * 40 * 4) == 0);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

/* A 16 x 12 image after 10 x 10 white squares drawn at (-5, -5), (11, 7)
 * and far away: lit in its top-left and bottom-right corners only. */
static void check_two_corners_lit(const sr_framebuffer *fb)
{
    const uint8_t *px = sr_framebuffer_pixels(fb);
    int lit = 0;
    for (int y = 0; y < 12; y++) {
        for (int x = 0; x < 16; x++) {
            bool want = (x < 5 && y < 5) || (x >= 11 && y >= 7);
            bool is = px[(y * 16 + x) * 4] == 255;
            CHECK_EQ(is, want);
            lit += is;
        }
    }
    CHECK_EQ(lit, 25 + 25);
}

SR_TEST(coverage_is_clipped_to_the_framebuffer)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    uint8_t mask[10 * 10];
    memset(mask, 255, sizeof mask);
    sr_rgba white = { 1, 1, 1, 1 };
    sr_framebuffer *fb = make_fb(ctx, 16, 12);
    REQUIRE(fb);
    /* Hanging over the top-left and bottom-right corners, and far away. */
    CHECK_EQ(sr_draw_coverage(ctx, fb, -5, -5, 10, 10, mask, 10, white), SR_OK);
    CHECK_EQ(sr_draw_coverage(ctx, fb, 11, 7, 10, 10, mask, 10, white), SR_OK);
    CHECK_EQ(sr_draw_coverage(ctx, fb, 2000000000, -2000000000, 10, 10, mask, 10, white), SR_OK);
    check_two_corners_lit(fb);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(bad_coverage_arguments_are_rejected)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_fb(ctx, 8, 8);
    REQUIRE(fb);
    uint8_t mask[16] = { 0 };
    sr_rgba c = { 1, 0, 0, 1 };
    CHECK_EQ(sr_draw_coverage(NULL, fb, 0, 0, 4, 4, mask, 4, c), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_coverage(ctx, NULL, 0, 0, 4, 4, mask, 4, c), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "fb");
    CHECK_EQ(sr_draw_coverage(ctx, fb, 0, 0, 4, 4, NULL, 4, c), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "mask");
    CHECK_EQ(sr_draw_coverage(ctx, fb, 0, 0, 4, 4, mask, 3, c), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "stride");
    CHECK_EQ(sr_draw_coverage(ctx, fb, 0, 0, -1, 4, mask, 4, c), SR_INVALID_ARG);
    sr_rgba nan = { NAN, 0, 0, 1 };
    CHECK_EQ(sr_draw_coverage(ctx, fb, 0, 0, 4, 4, mask, 4, nan), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "color");
    CHECK_EQ(sr_draw_coverage(ctx, fb, 0, 0, 0, 0, mask, 0, c), SR_OK);  /* empty: nothing */
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* ---- sr_draw_layer ---------------------------------------------------- */

SR_TEST(opaque_layer_through_a_mask_is_the_coverage_blend)
{
    /* A layer of one opaque color through a mask blends as that color
     * through the mask does (both source-over at coverage / 255); where
     * the layer is transparent nothing changes. */
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_polygon2 poly = { .points = star, .point_count = 5 };
    sr_fill_desc desc = { .rule = SR_EVENODD, .antialias = SR_AA_AREA };
    uint8_t mask[40 * 40], layer[40 * 40 * 4];
    CHECK_EQ(sr_polygon_coverage(ctx, &poly, &desc, 0, 0, 40, 40, mask, 40), SR_OK);
    for (int i = 0; i < 40 * 40; i++) {
        bool drawn = (i % 40) < 30; /* the layer's right quarter is empty */
        uint8_t px[4] = { 230, 20, 90, drawn ? 255 : 0 };
        memcpy(layer + i * 4, px, 4);
    }
    sr_framebuffer *a = make_fb(ctx, 40, 40), *b = make_fb(ctx, 40, 40);
    REQUIRE(a && b);
    uint8_t cut[40 * 40];
    for (int i = 0; i < 40 * 40; i++) {
        cut[i] = (i % 40) < 30 ? mask[i] : 0;
    }
    CHECK_EQ(sr_draw_coverage(ctx, a, 0, 0, 40, 40, cut, 40,
                              (sr_rgba){ 230 / 255.0f, 20 / 255.0f, 90 / 255.0f, 1 }), SR_OK);
    CHECK_EQ(sr_draw_layer(ctx, b, 0, 0, 40, 40, layer, 160,
                           &(sr_layer_desc){ .mask = mask, .mask_stride = 40 }), SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), 40 * 40 * 4) == 0);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

SR_TEST(layer_opacity_and_alpha_blend_source_over)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 3, .height = 1 }, &fb) ==
            SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 1, 1 }, .depth = 1 });
    /* red at alpha 1 and opacity 0.5 over blue: half each (128 = round
     * 127.5); red at alpha 0.6 (153) through coverage 0 and NULL mask. */
    const uint8_t layer[12] = { 255, 0, 0, 255, 255, 0, 0, 153, 255, 0, 0, 255 };
    const uint8_t mask[3] = { 255, 255, 0 };
    CHECK_EQ(sr_draw_layer(ctx, fb, 0, 0, 3, 1, layer, 12,
                           &(sr_layer_desc){ .mask = mask, .opacity = 0.5f }), SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    CHECK_EQ(px[0], 128);
    CHECK_EQ(px[2], 128);
    CHECK_EQ(px[3], 255);
    CHECK_EQ(px[4], 77);   /* 255 * 0.3 = 76.5 */
    CHECK_EQ(px[6], 179);  /* 255 * 0.7 = 178.5 */
    CHECK(px[8] == 0 && px[10] == 255);  /* coverage 0: as it was */
    /* opacity 0 is 1 (the zero desc); NULL desc likewise: red replaces */
    CHECK_EQ(sr_draw_layer(ctx, fb, 2, 0, 1, 1, layer, 4, NULL), SR_OK);
    CHECK(px[8] == 255 && px[10] == 0);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(layer_is_clipped_to_the_framebuffer)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    uint8_t layer[10 * 10 * 4];
    memset(layer, 255, sizeof layer);
    sr_framebuffer *fb = make_fb(ctx, 16, 12);
    REQUIRE(fb);
    CHECK_EQ(sr_draw_layer(ctx, fb, -5, -5, 10, 10, layer, 40, NULL), SR_OK);
    CHECK_EQ(sr_draw_layer(ctx, fb, 11, 7, 10, 10, layer, 40, NULL), SR_OK);
    CHECK_EQ(sr_draw_layer(ctx, fb, 2000000000, -2000000000, 10, 10, layer, 40, NULL), SR_OK);
    check_two_corners_lit(fb);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(bad_layer_arguments_are_rejected)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_fb(ctx, 8, 8);
    REQUIRE(fb);
    uint8_t layer[64] = { 0 }, mask[16] = { 0 };
    CHECK_EQ(sr_draw_layer(NULL, fb, 0, 0, 4, 4, layer, 16, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_layer(ctx, NULL, 0, 0, 4, 4, layer, 16, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "fb");
    CHECK_EQ(sr_draw_layer(ctx, fb, 0, 0, 4, 4, NULL, 16, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "rgba");
    CHECK_EQ(sr_draw_layer(ctx, fb, 0, 0, 4, 4, layer, 15, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "stride");
    CHECK_EQ(sr_draw_layer(ctx, fb, 0, 0, 4, -1, layer, 16, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_layer(ctx, fb, 0, 0, 4, 4, layer, 16,
                           &(sr_layer_desc){ .mask = mask, .mask_stride = 3 }), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "mask_stride");
    CHECK_EQ(sr_draw_layer(ctx, fb, 0, 0, 4, 4, layer, 16, &(sr_layer_desc){ .opacity = NAN }),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "opacity");
    CHECK_EQ(sr_draw_layer(ctx, fb, 0, 0, 4, 4, layer, 16, &(sr_layer_desc){ .opacity = 1.5f }),
             SR_INVALID_ARG);
    CHECK_EQ(sr_draw_layer(ctx, fb, 0, 0, 0, 0, layer, 0, NULL), SR_OK); /* empty: nothing */
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
