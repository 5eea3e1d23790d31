/* test_draw2d_alloc.c - every 2D toolkit call survives each allocation
 * failing in turn: it returns SR_OUT_OF_MEMORY (or succeeds when the
 * failed allocation was optional) and leaves no block behind. */
#include "softrast.h"
#include "sr_test.h"
#include "failing_alloc.h"

#include <stdlib.h>
#include <string.h>

typedef sr_result (*op_fn)(sr_context *ctx, sr_framebuffer *fb);

static sr_result op_fill(sr_context *ctx, sr_framebuffer *fb)
{
    sr_point2 p[5] = { { 1, 1 }, { 30, 4 }, { 8, 28 }, { 20, 2 }, { 28, 30 } };
    sr_result r = sr_fill_polygon(ctx, fb, &(sr_polygon2){ p, 5, NULL, 0 }, (sr_rgba){ 1, 1, 1, 1 },
                                  NULL);
    if (r == SR_OK) {
        r = sr_fill_polygon(ctx, fb, &(sr_polygon2){ p, 5, NULL, 0 }, (sr_rgba){ 1, 1, 1, 1 },
                            &(sr_fill_desc){ .antialias = SR_AA_AREA });
    }
    if (r == SR_OK) {
        r = sr_fill_polygon(ctx, fb, &(sr_polygon2){ p, 5, NULL, 0 }, (sr_rgba){ 1, 1, 1, 1 },
                            &(sr_fill_desc){ .antialias = SR_AA_SUPERSAMPLE });
    }
    return r;
}

static sr_result op_flood(sr_context *ctx, sr_framebuffer *fb)
{
    return sr_flood_fill(ctx, fb, 3, 3, (sr_rgba){ 1, 0, 0, 1 },
                         &(sr_region_fill_desc){ .connectivity = SR_CONNECT_8 }, NULL);
}

static sr_result op_clip(sr_context *ctx, sr_framebuffer *fb)
{
    (void)fb;
    sr_point2 p[5] = { { -1, 1 }, { 30, 4 }, { 8, 28 }, { 20, 2 }, { 28, 30 } }, out[32];
    sr_point2 win[3] = { { 0, 0 }, { 20, 0 }, { 0, 20 } };
    int n;
    sr_result r = sr_clip_polygon_rect(ctx, p, 5, 2, 2, 20, 20, NULL, out, 32, &n);
    return r == SR_OK ? sr_clip_polygon_convex(ctx, p, 5, win, 3, NULL, out, 32, &n) : r;
}

static sr_result op_path(sr_context *ctx, sr_framebuffer *fb)
{
    sr_path *path = NULL;
    sr_result r = sr_make_path(ctx, 0.01, &path);
    if (r != SR_OK) {
        return r;
    }
    if (r == SR_OK) r = sr_path_move_to(path, 2, 2);
    if (r == SR_OK) r = sr_path_cubic_to(path, 40, 0, -10, 30, 28, 28);
    if (r == SR_OK) r = sr_path_arc_to(path, 10, 6, 30, true, false, 5, 20);
    if (r == SR_OK) r = sr_path_close(path);
    if (r == SR_OK) r = sr_path_line_to(path, 25, 4);
    if (r == SR_OK) r = sr_fill_path(ctx, fb, path, (sr_rgba){ 1, 1, 1, 1 }, NULL);
    if (r == SR_OK) {
        r = sr_stroke_path(ctx, fb, path, (sr_rgba){ 1, 0, 0, 1 },
                           &(sr_stroke_desc){ .width = 3, .join = SR_STROKE_JOIN_ROUND,
                                              .cap = SR_STROKE_CAP_ROUND });
    }
    sr_destroy_path(ctx, path);
    return r;
}

static sr_result op_gouraud(sr_context *ctx, sr_framebuffer *fb)
{
    sr_point2 p[4] = { { 1, 1 }, { 30, 4 }, { 28, 30 }, { 3, 25 } };
    sr_rgba c[4] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, 1, 1 }, { 1, 1, 1, 1 } };
    sr_result r = sr_fill_triangle_gouraud(ctx, fb, p, c);
    return r == SR_OK ? sr_fill_polygon_gouraud(ctx, fb, &(sr_polygon2){ p, 4, NULL, 0 }, c,
                                                SR_NONZERO)
                      : r;
}

static void check_op(const char *name, op_fn op)
{
    for (long fail_at = 0;; fail_at++) {
        failing f = { .fail_at = -1 };
        sr_context *ctx = NULL;
        sr_framebuffer *fb = NULL;
        sr_allocator a = { fail_alloc, fail_free, &f };
        REQUIRE(sr_make_context(&(sr_context_desc){ .allocator = a, .threads = 1 }, &ctx) == SR_OK);
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 32, .height = 32 }, &fb) == SR_OK);
        f.fail_at = f.count + fail_at; /* count from here */
        sr_result r = op(ctx, fb);
        bool failed_one = f.count > f.fail_at;
        if (r != SR_OK) {
            if (r != SR_OUT_OF_MEMORY) {
                sr_test_fail(__FILE__, __LINE__, "%s: allocation %ld failed: %s", name, fail_at,
                             sr_result_name(r));
            }
        }
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
        CHECK_EQ(f.live, 0);
        if (!failed_one) {
            CHECK_EQ(r, SR_OK); /* no allocation failed: must succeed */
            break;
        }
        if (fail_at > 10000) {
            sr_test_fail(__FILE__, __LINE__, "%s: too many allocations", name);
            break;
        }
    }
}

SR_TEST(fills_survive_every_allocation_failure) { check_op("fill", op_fill); }
SR_TEST(flood_fill_survives_every_allocation_failure) { check_op("flood", op_flood); }
SR_TEST(clipping_survives_every_allocation_failure) { check_op("clip", op_clip); }
SR_TEST(paths_and_strokes_survive_every_allocation_failure) { check_op("path", op_path); }
SR_TEST(gouraud_survives_every_allocation_failure) { check_op("gouraud", op_gouraud); }
