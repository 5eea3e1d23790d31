/* test_stencil.c - the 8-bit stencil buffer: every compare function and
 * operation against a model written from the GL rules, the fail /
 * depth-fail / pass choice, read and write masks, separate front and back
 * state, clears, per-sample stencil under MSAA, and a classic use: a
 * stencil mask that limits later drawing to a shape. */
#include "sr_test.h"
#include "softrast.h"

#include <stdlib.h>
#include <string.h>

enum { W = 16, H = 16 };

typedef struct target {
    sr_context *ctx;
    sr_framebuffer *fb;
} target;

static target make(int samples)
{
    target t = { NULL, NULL };
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &t.ctx);
    sr_make_framebuffer(t.ctx, &(sr_framebuffer_desc){ .width = W, .height = H, .stencil = true,
                                                      .samples = samples,
                                                      .depth_format = SR_DEPTH_NONE }, &t.fb);
    return t;
}

static void destroy(target *t)
{
    sr_destroy_framebuffer(t->ctx, t->fb);
    sr_destroy_context(t->ctx);
}

/* A full-screen quad at depth z (NDC), counter-clockwise when ccw. */
static sr_result quad(target *t, const sr_state *st, float z, bool ccw)
{
    float ccw_q[18] = { -1, -1, z, 1, -1, z, 1, 1, z, -1, -1, z, 1, 1, z, -1, 1, z };
    float cw_q[18] = { -1, -1, z, 1, 1, z, 1, -1, z, -1, -1, z, -1, 1, z, 1, 1, z };
    return sr_draw(t->ctx, t->fb, st, &(sr_draw_desc){ .positions = ccw ? ccw_q : cw_q,
                                                       .vertex_count = 6 });
}

static uint8_t stencil_at(target *t, int x, int y)
{
    uint8_t v = 0;
    sr_read_stencil(t->ctx, t->fb, x, y, 1, 1, &v, 1);
    return v;
}

/* The GL rules, written out independently. */
static bool model_func(sr_depth_func f, unsigned ref, unsigned stored)
{
    switch (f) {
    case SR_NEVER:    return false;
    case SR_LESS:     return ref < stored;
    case SR_EQUAL:    return ref == stored;
    case SR_LEQUAL:   return ref <= stored;
    case SR_GREATER:  return ref > stored;
    case SR_NOTEQUAL: return ref != stored;
    case SR_GEQUAL:   return ref >= stored;
    default:          return true;
    }
}

static unsigned model_op(sr_stencil_op op, unsigned v, unsigned ref)
{
    switch (op) {
    case SR_STENCIL_ZERO:      return 0;
    case SR_STENCIL_REPLACE:   return ref;
    case SR_STENCIL_INCR:      return v < 255 ? v + 1 : 255;
    case SR_STENCIL_DECR:      return v > 0 ? v - 1 : 0;
    case SR_STENCIL_INVERT:    return ~v & 0xff;
    case SR_STENCIL_INCR_WRAP: return (v + 1) & 0xff;
    case SR_STENCIL_DECR_WRAP: return (v - 1) & 0xff;
    default:                   return v;
    }
}

SR_TEST(every_function_and_operation_follows_the_rules)
{
    target t = make(0);
    REQUIRE(t.fb);
    static const unsigned stored_values[] = { 0, 1, 7, 128, 254, 255 };
    static const unsigned refs[] = { 0, 7, 255 };
    int checked = 0;
    for (int f = SR_NEVER; f <= SR_ALWAYS; f++) {
        for (int op = SR_STENCIL_KEEP; op <= SR_STENCIL_DECR_WRAP; op++) {
            for (size_t si = 0; si < sizeof stored_values / sizeof *stored_values; si++) {
                for (size_t ri = 0; ri < 3; ri++) {
                    unsigned stored = stored_values[si], ref = refs[ri];
                    sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 },
                                                           .stencil_action = SR_ACTION_CLEAR,
                                                           .stencil = (uint8_t)stored });
                    /* The op under test on pass; the inverse of it on fail,
                     * so both branches are seen. */
                    sr_state st = { .shading = SR_SHADING_UNLIT,
                                    .material = { .diffuse = { 1, 1, 1 } },
                                    .stencil = { .enabled = true,
                                                 .front = { .func = (sr_depth_func)f,
                                                            .ref = (uint8_t)ref,
                                                            .pass = (sr_stencil_op)op,
                                                            .fail = SR_STENCIL_INVERT } } };
                    REQUIRE(quad(&t, &st, 0, true) == SR_OK);
                    bool pass = model_func((sr_depth_func)f, ref, stored);
                    unsigned want = pass ? model_op((sr_stencil_op)op, stored, ref)
                                         : model_op(SR_STENCIL_INVERT, stored, ref);
                    CHECK_EQ(stencil_at(&t, 5, 9), want);
                    /* The color is written exactly where the test passed. */
                    CHECK_EQ(sr_framebuffer_pixels(t.fb)[(9 * W + 5) * 4], pass ? 255 : 0);
                    checked++;
                }
            }
        }
    }
    CHECK_EQ(checked, 8 * 8 * 6 * 3);
    destroy(&t);
}

SR_TEST(depth_fail_and_pass_choose_their_ops)
{
    target t = make(0);
    sr_context *ctx = t.ctx;
    sr_framebuffer *fb = NULL;
    /* A depth buffer as well: the default framebuffer format. */
    sr_destroy_framebuffer(ctx, t.fb);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                            .stencil = true }, &fb) == SR_OK);
    t.fb = fb;
    sr_clear(ctx, fb, &(sr_clear_desc){ .stencil_action = SR_ACTION_CLEAR, .stencil = 10 });
    sr_state occluder = { .shading = SR_SHADING_UNLIT };
    float half[18] = { -1, -1, 0, 0, -1, 0, 0, 1, 0, -1, -1, 0, 0, 1, 0, -1, 1, 0 };
    REQUIRE(sr_draw(ctx, fb, &occluder, &(sr_draw_desc){ .positions = half, .vertex_count = 6 })
            == SR_OK);
    sr_state st = { .shading = SR_SHADING_UNLIT,
                    .stencil = { .enabled = true,
                                 .front = { .func = SR_ALWAYS, .pass = SR_STENCIL_INCR,
                                            .depth_fail = SR_STENCIL_DECR,
                                            .fail = SR_STENCIL_ZERO } } };
    REQUIRE(quad(&t, &st, 0.5f, true) == SR_OK);
    /* Left half: behind the occluder (depth fails): 9.  Right: 11. */
    CHECK_EQ(stencil_at(&t, 2, 8), 9);
    CHECK_EQ(stencil_at(&t, 12, 8), 11);
    /* With the depth test off every fragment takes the pass op. */
    st.depth_test = SR_OFF;
    REQUIRE(quad(&t, &st, 0.5f, true) == SR_OK);
    CHECK_EQ(stencil_at(&t, 2, 8), 10);
    CHECK_EQ(stencil_at(&t, 12, 8), 12);
    destroy(&t);
}

SR_TEST(masks_limit_what_is_compared_and_written)
{
    target t = make(0);
    REQUIRE(t.fb);
    sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .stencil_action = SR_ACTION_CLEAR, .stencil = 0xa5 });
    /* Compare only the low nibble: ref 0x35 & 0x0f == 0xa5 & 0x0f. */
    sr_state st = { .shading = SR_SHADING_UNLIT,
                    .stencil = { .enabled = true,
                                 .front = { .func = SR_EQUAL, .ref = 0x35, .masked = true,
                                            .read_mask = 0x0f, .write_mask = 0xf0,
                                            .pass = SR_STENCIL_INVERT } } };
    REQUIRE(quad(&t, &st, 0, true) == SR_OK);
    /* Inverted, but only the high nibble written: 0x5a & 0xf0 | 0xa5 & 0x0f. */
    CHECK_EQ(stencil_at(&t, 3, 3), 0x55);
    destroy(&t);
}

SR_TEST(front_and_back_faces_use_their_own_state)
{
    target t = make(0);
    REQUIRE(t.fb);
    sr_stencil_face front = { .func = SR_ALWAYS, .ref = 1, .pass = SR_STENCIL_REPLACE };
    sr_stencil_face back = { .func = SR_ALWAYS, .ref = 2, .pass = SR_STENCIL_REPLACE };
    sr_state st = { .shading = SR_SHADING_UNLIT,
                    .stencil = { .enabled = true, .front = front, .back = back, .separate = true } };
    sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .stencil = 0 });
    REQUIRE(quad(&t, &st, 0, true) == SR_OK);
    CHECK_EQ(stencil_at(&t, 7, 7), 1);
    REQUIRE(quad(&t, &st, 0, false) == SR_OK);
    CHECK_EQ(stencil_at(&t, 7, 7), 2);
    /* Without `separate` the back faces use the front state. */
    st.stencil.separate = false;
    REQUIRE(quad(&t, &st, 0, false) == SR_OK);
    CHECK_EQ(stencil_at(&t, 7, 7), 1);
    destroy(&t);
}

/* The classic use: draw a shape into the stencil only (color masked),
 * then draw a full-screen quad only where the stencil is set. */
SR_TEST(a_stencil_mask_limits_drawing_to_a_shape)
{
    enum { N = 4 };
    for (int samples = 1; samples <= N; samples *= N) {
        target t = make(samples);
        REQUIRE(t.fb);
        sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .stencil = 0 });
        float tri[9] = { -1, -1, 0, 1, -1, 0, -1, 1, 0 };  /* lower-left half */
        sr_state mark = { .shading = SR_SHADING_UNLIT,
                          .color_mask = SR_COLOR_MASK_NONE,
                          .stencil = { .enabled = true,
                                       .front = { .ref = 1, .pass = SR_STENCIL_REPLACE } } };
        REQUIRE(sr_draw(t.ctx, t.fb, &mark, &(sr_draw_desc){ .positions = tri, .vertex_count = 3 })
                == SR_OK);
        sr_state fill = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                          .stencil = { .enabled = true,
                                       .front = { .func = SR_EQUAL, .ref = 1 } } };
        REQUIRE(quad(&t, &fill, 0, true) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                /* The triangle is x < y on screen (y down): pixels off
                 * the diagonal are in or out; on it, partly covered when
                 * multisampled. */
                int v = px[(y * W + x) * 4];
                if (x > y) {
                    CHECK_EQ(v, 0);
                } else if (x < y) {
                    CHECK_EQ(v, 255);
                } else if (samples > 1) {
                    CHECK(v > 0 && v < 255);
                }
            }
        }
        destroy(&t);
    }
}

SR_TEST(lines_and_points_are_stencil_tested)
{
    target t = make(0);
    REQUIRE(t.fb);
    sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 },
                                            .stencil_action = SR_ACTION_CLEAR, .stencil = 3 });
    float line[6] = { -1, 0.0625f, 0, 1, 0.0625f, 0 };
    sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                    .stencil = { .enabled = true,
                                 .front = { .func = SR_EQUAL, .ref = 3, .pass = SR_STENCIL_INCR } } };
    REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                       .positions = line, .vertex_count = 2 })
            == SR_OK);
    /* The line runs along row 7; each of its pixels went 3 -> 4. */
    CHECK_EQ(stencil_at(&t, 4, 7), 4);
    CHECK_EQ(stencil_at(&t, 4, 6), 3);
    /* Drawn again, EQUAL 3 now fails on the line. */
    sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .stencil_action = SR_ACTION_KEEP });
    REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                       .positions = line, .vertex_count = 2 })
            == SR_OK);
    CHECK_EQ(sr_framebuffer_pixels(t.fb)[(7 * W + 4) * 4], 0);
    CHECK_EQ(stencil_at(&t, 4, 7), 4);
    destroy(&t);
}

SR_TEST(stencil_state_is_validated)
{
    target t = make(0);
    REQUIRE(t.fb);
    sr_state st = { .stencil = { .enabled = true, .front = { .pass = (sr_stencil_op)99 } } };
    CHECK_EQ(quad(&t, &st, 0, true), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(t.ctx), "stencil.front");
    st = (sr_state){ .stencil = { .back = { .func = (sr_depth_func)42 } } };
    CHECK_EQ(quad(&t, &st, 0, true), SR_INVALID_ARG);
    uint8_t v;
    sr_framebuffer *plain = NULL;
    REQUIRE(sr_make_framebuffer(t.ctx, &(sr_framebuffer_desc){ .width = 4, .height = 4 }, &plain)
            == SR_OK);
    CHECK(!sr_framebuffer_has_stencil(plain));
    CHECK_EQ(sr_read_stencil(t.ctx, plain, 0, 0, 1, 1, &v, 1), SR_INVALID_ARG);
    sr_destroy_framebuffer(t.ctx, plain);
    destroy(&t);
}
