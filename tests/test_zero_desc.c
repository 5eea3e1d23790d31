/* test_zero_desc.c - `{0}` is a valid desc: a zeroed sr_clear_desc clears
 * depth to the far value, so a zeroed sr_state (depth test LESS) draws;
 * the clear actions and the color mask keep their documented defaults
 * and refuse what they would silently ignore. */
#include "sr_test.h"
#include "softrast.h"

#include <string.h>

enum { W = 16, H = 16 };

/* A triangle over the left half of the framebuffer's diagonal, in NDC. */
static const float tri[9] = { -1, 1, 0, -1, -1, 0, 1, 1, 0 };

static sr_result draw_zeroed(sr_context *ctx, sr_framebuffer *fb, const sr_state *st)
{
    return sr_draw(ctx, fb, st, &(sr_draw_desc){ .positions = tri, .vertex_count = 3 });
}

SR_TEST(zeroed_clear_and_state_draw_the_triangle)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){0}, &ctx) == SR_OK);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    REQUIRE(sr_clear(ctx, fb, &(sr_clear_desc){0}) == SR_OK);
    float depth[W * H];
    REQUIRE(sr_read_depth(ctx, fb, 0, 0, W, H, depth, W) == SR_OK);
    CHECK(depth[0] == 1.0f && depth[W * H - 1] == 1.0f);

    const sr_state st = {0};
    REQUIRE(draw_zeroed(ctx, fb, &st) == SR_OK);
    CHECK(sr_last_draw_info(ctx).fragments > 0);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    /* (2, 2) is inside the triangle: the default material's diffuse 0.8,
     * opaque; (13, 13) is outside: the zeroed clear color. */
    const uint8_t *in = px + (2 * W + 2) * 4, *out = px + (13 * W + 13) * 4;
    CHECK_EQ(in[0], 204);
    CHECK_EQ(in[1], 204);
    CHECK_EQ(in[2], 204);
    CHECK_EQ(in[3], 255);
    CHECK(out[0] == 0 && out[1] == 0 && out[2] == 0 && out[3] == 0);
    REQUIRE(sr_read_depth(ctx, fb, 0, 0, W, H, depth, W) == SR_OK);
    CHECK(depth[2 * W + 2] > 0.4999f && depth[2 * W + 2] < 0.5001f); /* z = 0, D24 */
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(clear_actions_clear_keep_and_refuse_ignored_values)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                             .stencil = true }, &fb) == SR_OK);
    REQUIRE(sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 1, 0, 0, 1 },
                                                .depth_action = SR_ACTION_CLEAR, .depth = 0.25f,
                                                .stencil_action = SR_ACTION_CLEAR,
                                                .stencil = 7 }) == SR_OK);
    float depth;
    uint8_t stencil, rgba[4];
    REQUIRE(sr_read_depth(ctx, fb, 3, 3, 1, 1, &depth, 1) == SR_OK);
    REQUIRE(sr_read_stencil(ctx, fb, 3, 3, 1, 1, &stencil, 1) == SR_OK);
    CHECK(depth > 0.2499f && depth < 0.2501f);
    CHECK_EQ(stencil, 7);

    /* KEEP leaves each buffer as it was. */
    REQUIRE(sr_clear(ctx, fb, &(sr_clear_desc){ .color_action = SR_ACTION_KEEP,
                                                .depth_action = SR_ACTION_KEEP,
                                                .stencil_action = SR_ACTION_KEEP }) == SR_OK);
    REQUIRE(sr_read_pixels(ctx, fb, 3, 3, 1, 1, rgba, 4) == SR_OK);
    REQUIRE(sr_read_depth(ctx, fb, 3, 3, 1, 1, &depth, 1) == SR_OK);
    REQUIRE(sr_read_stencil(ctx, fb, 3, 3, 1, 1, &stencil, 1) == SR_OK);
    CHECK(rgba[0] == 255 && rgba[1] == 0 && rgba[3] == 255);
    CHECK(depth > 0.2499f && depth < 0.2501f);
    CHECK_EQ(stencil, 7);

    /* The default actions: depth to 1, stencil to 0. */
    REQUIRE(sr_clear(ctx, fb, &(sr_clear_desc){ .color_action = SR_ACTION_KEEP }) == SR_OK);
    REQUIRE(sr_read_pixels(ctx, fb, 3, 3, 1, 1, rgba, 4) == SR_OK);
    REQUIRE(sr_read_depth(ctx, fb, 3, 3, 1, 1, &depth, 1) == SR_OK);
    REQUIRE(sr_read_stencil(ctx, fb, 3, 3, 1, 1, &stencil, 1) == SR_OK);
    CHECK_EQ(rgba[0], 255);
    CHECK(depth == 1.0f);
    CHECK_EQ(stencil, 0);

    /* A value the default action would drop is refused, by name. */
    CHECK_EQ(sr_clear(ctx, fb, &(sr_clear_desc){ .depth = 0.5f }), SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "sr_clear_desc.depth") != NULL);
    CHECK_EQ(sr_clear(ctx, fb, &(sr_clear_desc){ .stencil = 3 }), SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "sr_clear_desc.stencil") != NULL);
    CHECK_EQ(sr_clear(ctx, fb, &(sr_clear_desc){ .depth_action = (sr_clear_action)9 }),
             SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "sr_clear_desc.depth_action") != NULL);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(color_mask_zero_writes_rgba_and_none_writes_nothing)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    uint8_t rgba[4];
    REQUIRE(sr_clear(ctx, fb, &(sr_clear_desc){0}) == SR_OK);
    REQUIRE(draw_zeroed(ctx, fb, &(sr_state){ .color_mask = SR_COLOR_MASK_NONE,
                                              .depth_write = SR_OFF }) == SR_OK);
    REQUIRE(sr_read_pixels(ctx, fb, 2, 2, 1, 1, rgba, 4) == SR_OK);
    CHECK(rgba[0] == 0 && rgba[1] == 0 && rgba[2] == 0 && rgba[3] == 0);
    REQUIRE(draw_zeroed(ctx, fb, &(sr_state){ .color_mask = SR_COLOR_MASK_G | SR_COLOR_MASK_A })
            == SR_OK);
    REQUIRE(sr_read_pixels(ctx, fb, 2, 2, 1, 1, rgba, 4) == SR_OK);
    CHECK(rgba[0] == 0 && rgba[1] == 204 && rgba[2] == 0 && rgba[3] == 255);
    CHECK_EQ(draw_zeroed(ctx, fb, &(sr_state){ .color_mask = (sr_color_mask)0x13 }),
             SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "sr_state.color_mask") != NULL);
    CHECK_EQ(draw_zeroed(ctx, fb, &(sr_state){ .depth_test = (sr_switch)3 }), SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "sr_state.depth_test") != NULL);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
