/* test_draw2d_clip.c - Sutherland-Hodgman polygon clipping against
 * independent point-in-region tests: on random convex and concave
 * polygons, every sample point away from the edges is inside the clipped
 * polygon exactly when it is inside both the polygon and the window;
 * plus the stage callback, a worked example and the argument
 * checks.  Fixed seeds. */
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static sr_context *new_ctx(void)
{
    sr_context *ctx = NULL;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    return ctx;
}

/* Winding number of a closed polygon around p (ray to +x). */
static int winding(const sr_point2 *poly, int n, sr_point2 p)
{
    int w = 0;
    for (int i = 0; i < n; i++) {
        sr_point2 a = poly[i], b = poly[(i + 1) % n];
        if ((a.y <= p.y) != (b.y <= p.y)) {
            double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (x > p.x) {
                w += a.y <= p.y ? 1 : -1;
            }
        }
    }
    return w;
}

static double seg_dist(sr_point2 p, sr_point2 a, sr_point2 b)
{
    double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

static bool near_any_edge(const sr_point2 *poly, int n, sr_point2 p, double eps)
{
    for (int i = 0; i < n; i++) {
        if (seg_dist(p, poly[i], poly[(i + 1) % n]) < eps) {
            return true;
        }
    }
    return false;
}

/* A star-shaped (possibly concave) simple polygon, or its convex hull-ish
 * version with equal radii. */
static int random_star(sr_rng *rng, sr_point2 *pts, bool convex)
{
    int n = sr_rng_int(rng, 3, 20);
    double ang[32], cx = sr_rng_range(rng, -5, 15), cy = sr_rng_range(rng, -5, 15);
    double r0 = sr_rng_range(rng, 2, 14);
    for (int k = 0; k < n; k++) {
        ang[k] = sr_rng_range(rng, 0, 2 * M_PI);
    }
    for (int i = 1; i < n; i++) {
        double v = ang[i];
        int j = i - 1;
        while (j >= 0 && ang[j] > v) {
            ang[j + 1] = ang[j];
            j--;
        }
        ang[j + 1] = v;
    }
    bool reverse = sr_rng_int(rng, 0, 1);
    for (int k = 0; k < n; k++) {
        double r = convex ? r0 : r0 * sr_rng_range(rng, 0.2, 1.0);
        pts[reverse ? n - 1 - k : k] = (sr_point2){ cx + r * cos(ang[k]), cy + r * sin(ang[k]) };
    }
    return n;
}

typedef struct stage_log { int calls, last_edge, counts[16]; } stage_log;

static void log_stage(void *user, int edge, const sr_point2 *poly, int count)
{
    (void)poly;
    stage_log *l = user;
    l->counts[l->calls % 16] = count;
    l->calls++;
    l->last_edge = edge;
}

static void check_clip(sr_context *ctx, sr_rng *rng, const sr_point2 *subj, int n,
                       const sr_point2 *win, int wn, bool rect, long *bad, long *samples)
{
    sr_point2 out[512];
    int m = -1;
    stage_log log = { 0 };
    sr_polygon_clip_desc d = { log_stage, &log };
    sr_result r = rect ? sr_clip_polygon_rect(ctx, subj, n, win[0].x, win[0].y, win[2].x, win[2].y,
                                              &d, out, 512, &m)
                       : sr_clip_polygon_convex(ctx, subj, n, win, wn, &d, out, 512, &m);
    CHECK_EQ(r, SR_OK);
    CHECK_EQ(log.calls, wn);
    CHECK_EQ(log.last_edge, wn - 1);
    CHECK_EQ(log.counts[(wn - 1) % 16], m);
    if (r != SR_OK) {
        return;
    }
    for (int s = 0; s < 400; s++) {
        sr_point2 p = { sr_rng_range(rng, -12, 32), sr_rng_range(rng, -12, 32) };
        if (near_any_edge(subj, n, p, 1e-7) || near_any_edge(win, wn, p, 1e-7)) {
            continue;
        }
        bool want = winding(subj, n, p) != 0 && winding(win, wn, p) != 0;
        bool got = m >= 3 && winding(out, m, p) != 0;
        *bad += want != got;
        (*samples)++;
    }
}

SR_TEST(clipped_polygon_is_exactly_polygon_and_window)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_rng rng = { 0x5eed2d20u };
    long bad = 0, samples = 0;
    for (int iter = 0; iter < 3000; iter++) {
        sr_point2 subj[32], win[32];
        int n = random_star(&rng, subj, iter % 2 == 0);
        int wn;
        bool rect = iter % 3 == 0;
        if (rect) {
            double x0 = sr_rng_range(&rng, -4, 10), y0 = sr_rng_range(&rng, -4, 10);
            double x1 = x0 + sr_rng_range(&rng, 0.5, 16), y1 = y0 + sr_rng_range(&rng, 0.5, 16);
            win[0] = (sr_point2){ x0, y0 };
            win[1] = (sr_point2){ x1, y0 };
            win[2] = (sr_point2){ x1, y1 };
            win[3] = (sr_point2){ x0, y1 };
            wn = 4;
        } else {
            wn = random_star(&rng, win, true);
        }
        check_clip(ctx, &rng, subj, n, win, wn, rect, &bad, &samples);
    }
    CHECK_EQ(bad, 0);
    CHECK(samples > 500000);
    sr_destroy_context(ctx);
}

SR_TEST(worked_example_gains_and_loses_vertices_per_edge)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    /* A pentagon sticking out of the left and bottom of the window. */
    sr_point2 in[5] = { { 2, 2 }, { 8, 1 }, { 9, 7 }, { 3, 12 }, { -3, 6 } };
    sr_point2 out[32];
    int m = 0;
    stage_log log = { 0 };
    CHECK_EQ(sr_clip_polygon_rect(ctx, in, 5, 0, 0, 10, 10, &(sr_polygon_clip_desc){ log_stage, &log },
                                  out, 32, &m), SR_OK);
    CHECK_EQ(log.counts[0], 6); /* left: one vertex replaced by two intersections */
    CHECK_EQ(log.counts[1], 7); /* bottom (y = 10): likewise */
    CHECK_EQ(log.counts[2], 7); /* right, top: nothing to clip */
    CHECK_EQ(m, 7);
    for (int i = 0; i < m; i++) {
        CHECK(out[i].x >= 0 && out[i].x <= 10 && out[i].y >= 0 && out[i].y <= 10);
    }
    /* clipped coordinates land exactly on the rectangle */
    int on_left = 0, on_bottom = 0;
    for (int i = 0; i < m; i++) {
        on_left += out[i].x == 0;
        on_bottom += out[i].y == 10;
    }
    CHECK_EQ(on_left, 2);
    CHECK_EQ(on_bottom, 2);
    /* capacity too small: SR_TOO_LARGE and the size needed */
    CHECK_EQ(sr_clip_polygon_rect(ctx, in, 5, 0, 0, 10, 10, NULL, out, 3, &m), SR_TOO_LARGE);
    CHECK_EQ(m, 7);
    /* wholly outside: empty */
    CHECK_EQ(sr_clip_polygon_rect(ctx, in, 5, 20, 20, 30, 30, NULL, out, 32, &m), SR_OK);
    CHECK_EQ(m, 0);
    sr_destroy_context(ctx);
}

SR_TEST(bad_clip_arguments_are_rejected)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_point2 tri[3] = { { 0, 0 }, { 4, 0 }, { 0, 4 } }, out[16];
    int m;
    CHECK_EQ(sr_clip_polygon_rect(NULL, tri, 3, 0, 0, 1, 1, NULL, out, 16, &m), SR_INVALID_ARG);
    CHECK_EQ(sr_clip_polygon_rect(ctx, NULL, 3, 0, 0, 1, 1, NULL, out, 16, &m), SR_INVALID_ARG);
    CHECK_EQ(sr_clip_polygon_rect(ctx, tri, 3, 0, 0, 1, 1, NULL, out, 16, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_clip_polygon_rect(ctx, tri, 3, 2, 0, 1, 1, NULL, out, 16, &m), SR_INVALID_ARG);
    CHECK_EQ(sr_clip_polygon_rect(ctx, tri, 3, 0, 0, NAN, 1, NULL, out, 16, &m), SR_INVALID_ARG);
    sr_point2 concave[4] = { { 0, 0 }, { 4, 0 }, { 1, 1 }, { 0, 4 } };
    CHECK_EQ(sr_clip_polygon_convex(ctx, tri, 3, concave, 4, NULL, out, 16, &m), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "convex");
    sr_point2 line[3] = { { 0, 0 }, { 1, 1 }, { 2, 2 } };
    CHECK_EQ(sr_clip_polygon_convex(ctx, tri, 3, line, 3, NULL, out, 16, &m), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "zero area");
    CHECK_EQ(sr_clip_polygon_convex(ctx, tri, 3, tri, 2, NULL, out, 16, &m), SR_INVALID_ARG);
    sr_point2 nan_pt[3] = { { 0, 0 }, { NAN, 0 }, { 0, 4 } };
    CHECK_EQ(sr_clip_polygon_convex(ctx, nan_pt, 3, tri, 3, NULL, out, 16, &m), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "in[1]");
    sr_destroy_context(ctx);
}
