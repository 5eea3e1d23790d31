/* test_draw2d_text.c - sr_draw_text / sr_text_width: glyph placement,
 * scaling, clipping at every border, blending and argument checks, and a
 * reference image of the whole printable ASCII set. */
#include "image_compare.h"
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const sr_rgba WHITE = { 1, 1, 1, 1 };

static sr_framebuffer *make_fb(sr_context *ctx, int w, int h)
{
    sr_framebuffer *fb = NULL;
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                         .depth_format = SR_DEPTH_NONE }, &fb) != SR_OK) {
        return NULL;
    }
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    return fb;
}

static int red_at(const sr_framebuffer *fb, int x, int y)
{
    return sr_framebuffer_pixels(fb)[((size_t)y * sr_framebuffer_width(fb) + x) * 4];
}

static long count_lit(const sr_framebuffer *fb)
{
    const uint8_t *px = sr_framebuffer_pixels(fb);
    long n = 0;
    for (int i = 0; i < sr_framebuffer_width(fb) * sr_framebuffer_height(fb); i++) {
        n += px[i * 4] != 0;
    }
    return n;
}

SR_TEST(text_width_is_six_pixels_per_char_times_scale)
{
    CHECK_EQ(sr_text_width("", 1), 0);
    CHECK_EQ(sr_text_width("abc", 1), 18);
    CHECK_EQ(sr_text_width("abc", 3), 54);
    CHECK_EQ(sr_text_width("ab\nabcd\nx", 2), 48);  /* widest line */
    CHECK_EQ(sr_text_width(NULL, 1), 0);
    CHECK_EQ(sr_text_width("abc", 0), 0);
}

SR_TEST(glyph_l_has_the_designed_bitmap)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_fb(ctx, 8, 8);
    REQUIRE(fb);
    CHECK_EQ(sr_draw_text(ctx, fb, 1, 0, 1, "L", WHITE), SR_OK);
    for (int y = 0; y < 8; y++) {
        for (int x = 0; x < 8; x++) {
            /* 'L': column 0 of the glyph for rows 0..6, plus the bottom row. */
            int want = (y < 7 && x == 1) || (y == 6 && x >= 1 && x <= 5);
            CHECK_EQ(red_at(fb, x, y) != 0, want);
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(scale_multiplies_every_font_pixel)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *a = make_fb(ctx, 64, 64), *b = make_fb(ctx, 64, 64);
    REQUIRE(a && b);
    sr_draw_text(ctx, a, 0, 0, 1, "Q7", WHITE);
    sr_draw_text(ctx, b, 0, 0, 3, "Q7", WHITE);
    CHECK_EQ(count_lit(b), 9 * count_lit(a));
    for (int y = 0; y < 24; y++) {
        for (int x = 0; x < 36; x++) {
            CHECK_EQ(red_at(b, x, y), red_at(a, x / 3, y / 3));
        }
    }
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

SR_TEST(text_is_clipped_at_every_border)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *big = make_fb(ctx, 40, 40), *small = make_fb(ctx, 10, 10);
    REQUIRE(big && small);
    /* Text straddling all four borders of a 10x10 target draws exactly the
     * pixels a larger target has in that window. */
    sr_draw_text(ctx, big, 15 - 4, 15 - 5, 2, "#@W\n8M", WHITE);
    CHECK_EQ(sr_draw_text(ctx, small, -4, -5, 2, "#@W\n8M", WHITE), SR_OK);
    for (int y = 0; y < 10; y++) {
        for (int x = 0; x < 10; x++) {
            CHECK_EQ(red_at(small, x, y), red_at(big, x + 15, y + 15));
        }
    }
    CHECK_EQ(sr_draw_text(ctx, small, -100000, 2000000000, 64, "far away", WHITE), SR_OK);
    CHECK_EQ(sr_draw_text(ctx, small, 2000000000, -2000000000, 64, "far away", WHITE), SR_OK);
    sr_destroy_framebuffer(ctx, big);
    sr_destroy_framebuffer(ctx, small);
    sr_destroy_context(ctx);
}

SR_TEST(text_blends_source_over)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_fb(ctx, 8, 8);
    REQUIRE(fb);
    sr_draw_text(ctx, fb, 0, 0, 1, "|", (sr_rgba){ 1, 0.5f, 0, 0.5f });
    const uint8_t *px = sr_framebuffer_pixels(fb) + (0 * 8 + 2) * 4;
    CHECK_NEAR(px[0], 128, 1);
    CHECK_NEAR(px[1], 64, 1);
    CHECK_EQ(px[2], 0);
    CHECK_EQ(px[3], 255);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(bad_text_arguments_are_rejected)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_fb(ctx, 8, 8);
    REQUIRE(fb);
    CHECK_EQ(sr_draw_text(NULL, fb, 0, 0, 1, "x", WHITE), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_text(ctx, NULL, 0, 0, 1, "x", WHITE), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "fb");
    CHECK_EQ(sr_draw_text(ctx, fb, 0, 0, 1, NULL, WHITE), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "text");
    CHECK_EQ(sr_draw_text(ctx, fb, 0, 0, 0, "x", WHITE), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "scale");
    CHECK_EQ(sr_draw_text(ctx, fb, 0, 0, 65, "x", WHITE), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_text(ctx, fb, 0, 0, 1, "x", (sr_rgba){ 0, NAN, 0, 1 }), SR_INVALID_ARG);
    CHECK_EQ(count_lit(fb), 0);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(printable_ascii_matches_reference)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_fb(ctx, 16 * 6 * 2 + 8, 6 * 8 * 2 + 8);
    REQUIRE(fb);
    char line[17];
    for (int row = 0; row < 6; row++) {
        for (int i = 0; i < 16; i++) {
            int c = 32 + row * 16 + i;
            line[i] = (char)(c < 127 ? c : 1); /* 127 shows the box glyph */
        }
        line[16] = 0;
        sr_draw_text(ctx, fb, 4, 4 + row * 16, 2, line, (sr_rgba){ 1, 1, 0.6f, 1 });
    }
    sr_test_check_image("text_ascii", sr_framebuffer_pixels(fb), sr_framebuffer_width(fb),
                        sr_framebuffer_height(fb), 0, 0);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
