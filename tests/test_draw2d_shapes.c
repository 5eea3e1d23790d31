/* test_draw2d_shapes.c - Gouraud-shaded 2D triangles and polygons (same
 * pixels as the flat fill; linear color fields reproduced exactly), paths
 * (Bezier and arc circles against their area) and strokes (widths, caps,
 * joins and the miter limit against the geometry they must cover).
 * Fixed seeds. */
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 64, H = 48 };

static sr_context *new_ctx(void)
{
    sr_context *ctx = NULL;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    return ctx;
}

static sr_framebuffer *new_fb(sr_context *ctx)
{
    sr_framebuffer *fb = NULL;
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                     .depth_format = SR_DEPTH_NONE }, &fb);
    if (fb) {
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    }
    return fb;
}

static const uint8_t *px_at(const sr_framebuffer *fb, int x, int y)
{
    return sr_framebuffer_pixels(fb) + ((size_t)y * W + x) * 4;
}

/* A color field linear in x and y, inside [0, 1] over the framebuffer. */
static sr_rgba field(double x, double y)
{
    return (sr_rgba){ (float)(0.1 + 0.8 * x / W), (float)(0.1 + 0.8 * y / H),
                      (float)(0.5 + 0.3 * (x - y) / (W + H)), 1 };
}

static void random_convex(sr_rng *rng, sr_point2 *p, int n)
{
    double cx = sr_rng_range(rng, 10, W - 10), cy = sr_rng_range(rng, 10, H - 10);
    double r = sr_rng_range(rng, 3, 30), a0 = sr_rng_range(rng, 0, 6.3);
    bool rev = sr_rng_int(rng, 0, 1);
    for (int k = 0; k < n; k++) {
        double a = a0 + (rev ? -1 : 1) * 2 * M_PI * k / n;
        p[k] = (sr_point2){ nearbyint((cx + r * cos(a)) * 256) / 256,
                            nearbyint((cy + r * 0.8 * sin(a)) * 256) / 256 };
    }
}

SR_TEST(gouraud_fills_the_flat_fill_pixels_with_linear_fields_exact)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *g = new_fb(ctx), *f = new_fb(ctx);
    REQUIRE(g && f);
    sr_rng rng = { 0x5eed2d40u };
    long coverage_bad = 0, color_bad = 0, pixels = 0;
    for (int iter = 0; iter < 600; iter++) {
        int n = iter % 2 ? 3 : sr_rng_int(&rng, 3, 9);
        sr_point2 p[16];
        sr_rgba c[16];
        if (iter % 4 == 1) { /* arbitrary triangles, any shape */
            for (int k = 0; k < 3; k++) {
                p[k] = (sr_point2){ sr_rng_range(&rng, -5, W + 5), sr_rng_range(&rng, -5, H + 5) };
            }
        } else {
            random_convex(&rng, p, n);
        }
        for (int k = 0; k < n; k++) {
            c[k] = field(p[k].x, p[k].y);
        }
        sr_clear(ctx, g, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
        sr_clear(ctx, f, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
        sr_polygon2 poly = { p, n, NULL, 0 };
        if (n == 3 && iter % 4 != 3) {
            REQUIRE(sr_fill_triangle_gouraud(ctx, g, p, c) == SR_OK);
        } else {
            REQUIRE(sr_fill_polygon_gouraud(ctx, g, &poly, c, SR_FILL_RULE_DEFAULT) == SR_OK);
        }
        sr_fill_polygon(ctx, f, &poly, (sr_rgba){ 1, 1, 1, 1 }, NULL);
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                bool in_f = px_at(f, x, y)[3] != 0, in_g = px_at(g, x, y)[3] != 0;
                coverage_bad += in_f != in_g;
                if (in_g) {
                    sr_rgba want = field(x + 0.5, y + 0.5);
                    const uint8_t *q = px_at(g, x, y);
                    color_bad += fabs(q[0] - want.r * 255) > 1.01 || fabs(q[1] - want.g * 255) > 1.01 ||
                                 fabs(q[2] - want.b * 255) > 1.01;
                    pixels++;
                }
            }
        }
    }
    CHECK_EQ(coverage_bad, 0);
    CHECK_EQ(color_bad, 0);
    CHECK(pixels > 50000);
    sr_destroy_framebuffer(ctx, g);
    sr_destroy_framebuffer(ctx, f);
    sr_destroy_context(ctx);
}

SR_TEST(gouraud_rejects_bad_arguments)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = new_fb(ctx);
    REQUIRE(fb);
    sr_point2 p[3] = { { 0, 0 }, { 9, 0 }, { 0, 9 } };
    sr_rgba c[3] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, NAN, 1 } };
    CHECK_EQ(sr_fill_triangle_gouraud(ctx, fb, p, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_triangle_gouraud(ctx, fb, p, c), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_polygon_gouraud(ctx, fb, &(sr_polygon2){ p, 3, NULL, 0 }, c, SR_EVENODD),
             SR_INVALID_ARG);
    CHECK_EQ(sr_fill_polygon_gouraud(ctx, fb, &(sr_polygon2){ p, 3, NULL, 0 }, c, (sr_fill_rule)5),
             SR_INVALID_ARG);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* Pixels whose centre satisfies inside(). */
static long count_mismatch(const sr_framebuffer *fb, bool (*inside)(double, double))
{
    long bad = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            bad += (px_at(fb, x, y)[0] != 0) != inside(x + 0.5, y + 0.5);
        }
    }
    return bad;
}

static bool butt_box(double x, double y) { return x >= 10 && x < 50 && y >= 18 && y < 22; }
static bool square_box(double x, double y) { return x >= 8 && x < 52 && y >= 18 && y < 22; }

static sr_path *line_path(sr_context *ctx, const sr_point2 *p, int n, bool closed)
{
    sr_path *path = NULL;
    if (sr_make_path(ctx, 0.01, &path) != SR_OK) {
        return NULL;
    }
    sr_path_move_to(path, p[0].x, p[0].y);
    for (int i = 1; i < n; i++) {
        sr_path_line_to(path, p[i].x, p[i].y);
    }
    if (closed) {
        sr_path_close(path);
    }
    return path;
}

SR_TEST(strokes_cover_their_width_and_caps)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = new_fb(ctx);
    REQUIRE(fb);
    sr_point2 seg[2] = { { 10, 20 }, { 50, 20 } };
    sr_path *path = line_path(ctx, seg, 2, false);
    REQUIRE(path);
    sr_rgba white = { 1, 1, 1, 1 };
    CHECK_EQ(sr_stroke_path(ctx, fb, path, white, &(sr_stroke_desc){ .width = 4 }), SR_OK);
    CHECK_EQ(count_mismatch(fb, butt_box), 0);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_stroke_path(ctx, fb, path, white, &(sr_stroke_desc){ .width = 4, .cap = SR_STROKE_CAP_SQUARE });
    CHECK_EQ(count_mismatch(fb, square_box), 0);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_stroke_path(ctx, fb, path, white, &(sr_stroke_desc){ .width = 9, .cap = SR_STROKE_CAP_ROUND });
    long bad = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            double cx = x + 0.5, cy = y + 0.5;
            double t = fmin(fmax(cx, 10), 50);
            double dist = hypot(cx - t, cy - 20);
            bool lit = px_at(fb, x, y)[0] != 0;
            if (dist < 4.5 - 0.02 || dist > 4.5 + 0.02) {
                bad += lit != (dist < 4.5);
            }
        }
    }
    CHECK_EQ(bad, 0);
    sr_destroy_path(ctx, path);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* An L: (10,10) -> (40,10) -> (40,40), width 6: the outer corner square
 * [40,43] x [7,10] is in with a miter join, only its half below the
 * diagonal with a bevel, and a disc of radius 3 with a round join. */
SR_TEST(joins_fill_the_outer_corner_as_specified)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = new_fb(ctx);
    REQUIRE(fb);
    sr_point2 l[3] = { { 10, 10 }, { 40, 10 }, { 40, 40 } };
    sr_path *path = line_path(ctx, l, 3, false);
    REQUIRE(path);
    for (int j = SR_STROKE_JOIN_MITER; j <= SR_STROKE_JOIN_BEVEL; j++) {
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        REQUIRE(sr_stroke_path(ctx, fb, path, (sr_rgba){ 1, 1, 1, 1 },
                               &(sr_stroke_desc){ .width = 6, .join = (sr_stroke_join)j }) == SR_OK);
        long bad = 0;
        for (int y = 7; y < 10; y++) {
            for (int x = 40; x < 43; x++) {
                double cx = x + 0.5 - 40, cy = 10 - (y + 0.5); /* into the corner square */
                bool want = j == SR_STROKE_JOIN_MITER ? true
                          : j == SR_STROKE_JOIN_BEVEL ? cx + cy < 3
                                                      : hypot(cx, cy) < 3;
                bad += (px_at(fb, x, y)[0] != 0) != want;
            }
        }
        CHECK_EQ(bad, 0);
        /* the stroke body: both legs */
        CHECK(px_at(fb, 25, 10)[0] && px_at(fb, 40, 25)[0] && !px_at(fb, 25, 20)[0]);
    }
    /* miter limit 1.2 < sqrt(2): the right-angle miter becomes a bevel */
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_stroke_path(ctx, fb, path, (sr_rgba){ 1, 1, 1, 1 },
                   &(sr_stroke_desc){ .width = 6, .miter_limit = 1.2 });
    CHECK(!px_at(fb, 42, 7)[0]);
    CHECK(px_at(fb, 40, 9)[0]);
    sr_destroy_path(ctx, path);
    /* a round join before a segment shorter than half the width: nothing
     * past that segment's butt end (a whole disc there would reach y 45) */
    sr_point2 s[3] = { { 10, 40 }, { 40, 40 }, { 40, 41 } };
    path = line_path(ctx, s, 3, false);
    REQUIRE(path);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_stroke_path(ctx, fb, path, (sr_rgba){ 1, 1, 1, 1 },
                   &(sr_stroke_desc){ .width = 10, .join = SR_STROKE_JOIN_ROUND });
    CHECK(!px_at(fb, 41, 43)[0] && !px_at(fb, 43, 42)[0]);
    CHECK(px_at(fb, 43, 40)[0] && px_at(fb, 40, 36)[0]);
    /* the outer sector: round, inside the corner square's circle */
    CHECK(px_at(fb, 42, 37)[0] && !px_at(fb, 44, 35)[0]);
    sr_destroy_path(ctx, path);
    REQUIRE(sr_path_subpath_closed(path = line_path(ctx, l, 3, true), 0));
    CHECK(!sr_path_subpath_closed(path, 1) && !sr_path_subpath_closed(NULL, 0));
    sr_destroy_path(ctx, path);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(closed_stroke_is_a_ring_and_overlaps_merge)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *a = new_fb(ctx), *b = new_fb(ctx);
    REQUIRE(a && b);
    sr_point2 r[4] = { { 10, 8 }, { 50, 8 }, { 50, 40 }, { 10, 40 } };
    sr_path *path = line_path(ctx, r, 4, true);
    REQUIRE(path);
    sr_stroke_path(ctx, a, path, (sr_rgba){ 1, 1, 1, 0.5f }, &(sr_stroke_desc){ .width = 4 });
    /* reference: the ring between two rectangles, even-odd */
    sr_point2 ring[8] = { { 8, 6 }, { 52, 6 }, { 52, 42 }, { 8, 42 },
                          { 12, 10 }, { 48, 10 }, { 48, 38 }, { 12, 38 } };
    int counts[2] = { 4, 4 };
    sr_fill_polygon(ctx, b, &(sr_polygon2){ ring, 8, counts, 2 }, (sr_rgba){ 1, 1, 1, 0.5f },
                    &(sr_fill_desc){ .rule = SR_EVENODD });
    /* half-transparent: any doubly covered pixel would be brighter */
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), (size_t)W * H * 4) == 0);
    sr_destroy_path(ctx, path);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

static double covered(const sr_framebuffer *fb)
{
    double s = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            s += px_at(fb, x, y)[0] / 255.0;
        }
    }
    return s;
}

SR_TEST(path_circles_from_cubics_and_arcs_have_the_circle_area)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = new_fb(ctx);
    REQUIRE(fb);
    sr_path *path = NULL;
    REQUIRE(sr_make_path(ctx, 0.01, &path) == SR_OK);
    /* four cubic quarter circles, k = 0.5523 (the usual approximation) */
    double cx = 30, cy = 24, r = 15, k = 0.5522847498 * r;
    sr_path_move_to(path, cx + r, cy);
    sr_path_cubic_to(path, cx + r, cy + k, cx + k, cy + r, cx, cy + r);
    sr_path_cubic_to(path, cx - k, cy + r, cx - r, cy + k, cx - r, cy);
    sr_path_cubic_to(path, cx - r, cy - k, cx - k, cy - r, cx, cy - r);
    sr_path_cubic_to(path, cx + k, cy - r, cx + r, cy - k, cx + r, cy);
    sr_path_close(path);
    CHECK_EQ(sr_fill_path(ctx, fb, path, (sr_rgba){ 1, 1, 1, 1 },
                          &(sr_fill_desc){ .antialias = SR_AA_AREA }), SR_OK);
    CHECK_NEAR(covered(fb), M_PI * r * r, 0.01 * M_PI * r * r);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_path_clear(path);
    sr_path_move_to(path, cx - r, cy);
    sr_path_arc_to(path, r, r, 0, false, true, cx + r, cy);
    sr_path_arc_to(path, r, r, 0, false, true, cx - r, cy);
    sr_path_close(path);
    sr_fill_path(ctx, fb, path, (sr_rgba){ 1, 1, 1, 1 }, &(sr_fill_desc){ .antialias = SR_AA_AREA });
    CHECK_NEAR(covered(fb), M_PI * r * r, 0.002 * M_PI * r * r);
    /* quadratic: the parabola segment's area is 2/3 of its bounding box part */
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_path_clear(path);
    sr_path_move_to(path, 10, 40);
    sr_path_quad_to(path, 30, 0, 50, 40); /* apex at y = 20 */
    sr_path_close(path);
    sr_fill_path(ctx, fb, path, (sr_rgba){ 1, 1, 1, 1 }, &(sr_fill_desc){ .antialias = SR_AA_AREA });
    CHECK_NEAR(covered(fb), 2.0 / 3 * 40 * 20, 0.5);
    sr_polygon2 poly = sr_path_polygon(path);
    CHECK_EQ(poly.contour_count, 1);
    CHECK(poly.point_count > 10);
    sr_destroy_path(ctx, path);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(bad_stroke_arguments_are_rejected)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = new_fb(ctx);
    REQUIRE(fb);
    sr_path *path = NULL;
    CHECK_EQ(sr_make_path(ctx, -1, &path), SR_INVALID_ARG);
    REQUIRE(sr_make_path(ctx, 0, &path) == SR_OK);
    sr_path_move_to(path, 1, 1);
    sr_path_line_to(path, 10, 10);
    sr_rgba w = { 1, 1, 1, 1 };
    CHECK_EQ(sr_stroke_path(ctx, fb, path, w, &(sr_stroke_desc){ .width = -1 }), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "width");
    CHECK_EQ(sr_stroke_path(ctx, fb, path, w, &(sr_stroke_desc){ .join = (sr_stroke_join)9 }), SR_INVALID_ARG);
    CHECK_EQ(sr_stroke_path(ctx, fb, path, w, &(sr_stroke_desc){ .cap = (sr_stroke_cap)9 }), SR_INVALID_ARG);
    CHECK_EQ(sr_stroke_path(ctx, fb, path, w, &(sr_stroke_desc){ .miter_limit = 0.5 }), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "miter_limit");
    CHECK_EQ(sr_stroke_path(ctx, fb, NULL, w, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_path_line_to(path, NAN, 1), SR_INVALID_ARG);
    CHECK_EQ(sr_stroke_path(ctx, fb, path, w, NULL), SR_OK);
    /* a lone point with round caps draws a dot; with butt caps nothing */
    sr_path_clear(path);
    sr_path_move_to(path, 30, 30);
    sr_path_line_to(path, 30, 30);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_stroke_path(ctx, fb, path, w, &(sr_stroke_desc){ .width = 6 });
    CHECK(!px_at(fb, 30, 30)[0]);
    sr_stroke_path(ctx, fb, path, w, &(sr_stroke_desc){ .width = 6, .cap = SR_STROKE_CAP_ROUND });
    CHECK(px_at(fb, 30, 30)[0] && px_at(fb, 32, 30)[0] && !px_at(fb, 34, 30)[0]);
    sr_destroy_path(ctx, path);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
