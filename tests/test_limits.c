/* test_limits.c - documented limits are refused with SR_TOO_LARGE and a
 * message naming the field, before anything is allocated from the
 * oversized value: the calls below go through a counting allocator that
 * must see no allocation at all.  (The readers' limits, checked against
 * the file size before allocating, are tested in test_ply.c, test_stl.c
 * and test_png.c.) */
#include "sr_test.h"
#include "softrast.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

typedef struct counting {
    long calls;
    size_t largest;
} counting;

static void *counting_alloc(size_t n, void *user)
{
    counting *c = user;
    c->calls++;
    c->largest = n > c->largest ? n : c->largest;
    return malloc(n);
}

static void counting_free(void *p, void *user)
{
    (void)user;
    free(p);
}

static sr_context *counted_context(counting *c)
{
    sr_context *ctx = NULL;
    sr_make_context(&(sr_context_desc){ .allocator = { counting_alloc, counting_free, c },
                                        .threads = 2 }, &ctx);
    return ctx;
}

SR_TEST(vertex_count_over_the_limit_is_refused_before_any_allocation)
{
    counting c = { 0 };
    sr_context *ctx = counted_context(&c);
    REQUIRE(ctx);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) == SR_OK);
    static const float one[4] = { 0, 0, 0, 1 };
    const size_t counts[] = { ((size_t)1 << 28) + 1, (size_t)1 << 40, SIZE_MAX };
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        c.calls = 0;
        /* positions points at one vertex: nothing may be read either. */
        sr_result r = sr_draw(ctx, fb, &(sr_state){ 0 },
                              &(sr_draw_desc){ .positions = one, .vertex_count = counts[i] });
        CHECK_EQ(r, SR_TOO_LARGE);
        CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_draw_desc.vertex_count");
        CHECK_EQ(c.calls, 0);
    }
    /* The context still draws afterwards. */
    static const float tri[9] = { -1, -1, 0, 1, -1, 0, 0, 1, 0 };
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ 0 }, &(sr_draw_desc){ .positions = tri,
                                                                 .vertex_count = 3 }), SR_OK);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(framebuffer_over_the_limit_is_refused_before_any_allocation)
{
    counting c = { 0 };
    sr_context *ctx = counted_context(&c);
    REQUIRE(ctx);
    const int sizes[][2] = {
        { SR_MAX_FRAMEBUFFER_SIZE + 1, 1 }, { 1, SR_MAX_FRAMEBUFFER_SIZE + 1 },
        { INT_MAX, INT_MAX }, { 65536, 65536 }, /* w * h overflows 32 bits */
    };
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        c.calls = 0;
        sr_framebuffer *fb = (sr_framebuffer *)&c; /* must come back NULL */
        sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
            .width = sizes[i][0], .height = sizes[i][1] }, &fb);
        CHECK_EQ(r, SR_TOO_LARGE);
        CHECK(fb == NULL);
        CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_framebuffer_desc");
        CHECK_EQ(c.calls, 0);
    }
    /* The largest allowed size is allocated in one piece per buffer. */
    c.calls = 0;
    c.largest = 0;
    sr_framebuffer *fb = NULL;
    sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
        .width = SR_MAX_FRAMEBUFFER_SIZE, .height = 1, .depth_format = SR_DEPTH_D32 }, &fb);
    CHECK_EQ(r, SR_OK);
    CHECK(c.largest <= (size_t)SR_MAX_FRAMEBUFFER_SIZE * 4 + 4096);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(viewport_outside_the_guard_band_is_refused)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) == SR_OK);
    static const float tri[9] = { -1, -1, 0, 1, -1, 0, 0, 1, 0 };
    const sr_viewport bad[] = {
        { -16385, 0, 8, 8 }, { 0, -16385, 8, 8 }, { 16380, 0, 8, 8 }, { 0, 16380, 8, 8 },
        { 0, 0, SR_MAX_FRAMEBUFFER_SIZE + 1, 8 }, { INT_MAX, 0, 8, 8 }, { 0, INT_MIN, 8, 8 },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sr_result r = sr_draw(ctx, fb, &(sr_state){ .viewport = bad[i] },
                              &(sr_draw_desc){ .positions = tri, .vertex_count = 3 });
        CHECK_EQ(r, SR_INVALID_ARG);
        CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_state.viewport");
    }
    /* The extremes that are allowed draw (nothing visible) without error. */
    const sr_viewport edge[] = { { -16384, -16384, 8, 8 }, { 16384 - 8192, 16384 - 8192, 8192, 8192 } };
    for (size_t i = 0; i < 2; i++) {
        CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ .viewport = edge[i] },
                         &(sr_draw_desc){ .positions = tri, .vertex_count = 3 }), SR_OK);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
