/* test_draw2d_curves.c - midpoint ellipses and circles against the
 * implicit definition evaluated independently at every pixel centre
 * (filled and outline, random centres and radii), octant symmetry, the
 * implicit-region fills, and Bezier / arc flattening against the curves'
 * equations and the tolerance.  Fixed seeds. */
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef __SIZEOF_INT128__
__extension__ typedef __int128 i128;
#else
#include "math/wide.h"   /* 32-bit targets: the library's two-word integers */
#endif

enum { W = 48, H = 40 };

static sr_context *new_ctx(void)
{
    sr_context *ctx = NULL;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    return ctx;
}

static sr_framebuffer *new_fb(sr_context *ctx, int w, int h)
{
    sr_framebuffer *fb = NULL;
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                     .depth_format = SR_DEPTH_NONE }, &fb);
    if (fb) {
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    }
    return fb;
}

static bool lit(const sr_framebuffer *fb, int x, int y)
{
    return sr_framebuffer_pixels(fb)[((size_t)y * sr_framebuffer_width(fb) + x) * 4] != 0;
}

/* The implicit definition, directly: F < 0 at the pixel centre, in q8. */
static bool ellipse_inside(double cx, double cy, double rx, double ry, int64_t i, int64_t j)
{
    int64_t CX = (int64_t)nearbyint(cx * 256), CY = (int64_t)nearbyint(cy * 256);
#ifdef __SIZEOF_INT128__
    i128 RX = (int64_t)nearbyint(rx * 256), RY = (int64_t)nearbyint(ry * 256);
    i128 dx = i * 256 + 128 - CX, dy = j * 256 + 128 - CY;
    return RY * RY * dx * dx + RX * RX * dy * dy - RX * RX * RY * RY < 0;
#else
    int64_t RX = (int64_t)nearbyint(rx * 256), RY = (int64_t)nearbyint(ry * 256);
    int64_t dx = i * 256 + 128 - CX, dy = j * 256 + 128 - CY;
    sr_i128 f = sr__wide_add(sr__wide_mul(RY * RY, dx * dx), sr__wide_mul(RX * RX, dy * dy));
    return sr__wide_negative(sr__wide_sub(f, sr__wide_mul(RX * RX, RY * RY)));
#endif
}

SR_TEST(ellipses_match_the_implicit_definition_filled_and_outlined)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = new_fb(ctx, W, H);
    REQUIRE(fb);
    sr_rng rng = { 0x5eed2d30u };
    long bad = 0, drawn = 0;
    for (int iter = 0; iter < 3000; iter++) {
        double cx = sr_rng_range(&rng, -10, W + 10), cy = sr_rng_range(&rng, -10, H + 10);
        double rx = sr_rng_range(&rng, 0, 30), ry = iter % 3 ? sr_rng_range(&rng, 0, 30) : rx;
        if (iter % 4 == 0) { /* centres and radii on the half-pixel grid: ties */
            cx = floor(cx * 2) / 2;
            cy = floor(cy * 2) / 2;
            rx = floor(rx * 2) / 2;
            ry = floor(ry * 2) / 2;
        }
        bool filled = iter % 2;
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        REQUIRE(sr_draw_ellipse(ctx, fb, cx, cy, rx, ry, (sr_rgba){ 1, 1, 1, 1 }, filled) == SR_OK);
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                bool in = ellipse_inside(cx, cy, rx, ry, x, y);
                bool want = in;
                if (!filled && in) {
                    want = !ellipse_inside(cx, cy, rx, ry, x - 1, y) ||
                           !ellipse_inside(cx, cy, rx, ry, x + 1, y) ||
                           !ellipse_inside(cx, cy, rx, ry, x, y - 1) ||
                           !ellipse_inside(cx, cy, rx, ry, x, y + 1);
                }
                bad += lit(fb, x, y) != want;
                drawn += want;
            }
        }
    }
    CHECK_EQ(bad, 0);
    CHECK(drawn > 100000);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(circle_outline_has_eightfold_symmetry_so_octants_join_exactly)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    enum { S = 41 };
    sr_framebuffer *fb = new_fb(ctx, S, S);
    REQUIRE(fb);
    for (int k = 1; k <= 76; k++) {
        double r = k * 0.25;
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        sr_draw_circle(ctx, fb, 20.5, 20.5, r, (sr_rgba){ 1, 1, 1, 1 }, false);
        long asym = 0, count = 0;
        for (int y = 0; y < S; y++) {
            for (int x = 0; x < S; x++) {
                bool v = lit(fb, x, y);
                count += v;
                asym += v != lit(fb, y, x);               /* the diagonal: octant joins */
                asym += v != lit(fb, S - 1 - x, y);
                asym += v != lit(fb, x, S - 1 - y);
            }
        }
        CHECK_EQ(asym, 0);
        /* 8-connected ring: every lit pixel has 2..3 lit 8-neighbours... at
         * least 2 (no loose ends), for radii with a real ring */
        if (r >= 2) {
            long loose = 0;
            for (int y = 1; y < S - 1; y++) {
                for (int x = 1; x < S - 1; x++) {
                    if (!lit(fb, x, y)) {
                        continue;
                    }
                    int nb = 0;
                    for (int dy = -1; dy <= 1; dy++) {
                        for (int dx = -1; dx <= 1; dx++) {
                            nb += (dx || dy) && lit(fb, x + dx, y + dy);
                        }
                    }
                    loose += nb < 2;
                }
            }
            CHECK_EQ(loose, 0);
        }
        CHECK(count > 0);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(huge_and_degenerate_ellipses_are_handled)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = new_fb(ctx, W, H);
    REQUIRE(fb);
    sr_rgba white = { 1, 1, 1, 1 };
    CHECK_EQ(sr_draw_ellipse(ctx, fb, 20, 20, 0, 0, white, true), SR_OK);
    CHECK_EQ(sr_draw_ellipse(ctx, fb, 20, 20, 100000, 3, white, false), SR_OK);
    CHECK_EQ(sr_draw_circle(ctx, fb, 100000, 20, 99990, white, true), SR_OK);
    CHECK(lit(fb, 20, 20));
    CHECK_EQ(sr_draw_circle(ctx, fb, 20, 20, -1, white, true), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_circle(ctx, fb, NAN, 20, 1, white, true), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_circle(ctx, fb, 1e9, 20, 1, white, true), SR_TOO_LARGE);
    CHECK_EQ(sr_draw_circle(ctx, NULL, 1, 20, 1, white, true), SR_INVALID_ARG);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

typedef struct circle_fn { double cx, cy, r; } circle_fn;

static double circle_f(void *user, double x, double y, double grad[2])
{
    const circle_fn *c = user;
    if (grad) {
        grad[0] = 2 * (x - c->cx);
        grad[1] = 2 * (y - c->cy);
    }
    return (x - c->cx) * (x - c->cx) + (y - c->cy) * (y - c->cy) - c->r * c->r;
}

static double halfplane_f(void *user, double x, double y, double grad[2])
{
    (void)user;
    (void)grad; /* no gradient: central differences */
    return x - 10.3 + 0 * y;
}

SR_TEST(aliased_implicit_circle_equals_the_midpoint_circle)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *a = new_fb(ctx, W, H), *b = new_fb(ctx, W, H);
    REQUIRE(a && b);
    circle_fn c = { 20.25, 17.5, 12.375 }; /* on the 1/256 grid */
    CHECK_EQ(sr_fill_implicit(ctx, a, &(sr_implicit_desc){ .f = circle_f, .user = &c },
                              (sr_rgba){ 1, 1, 1, 1 }), SR_OK);
    sr_draw_circle(ctx, b, c.cx, c.cy, c.r, (sr_rgba){ 1, 1, 1, 1 }, true);
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), (size_t)W * H * 4) == 0);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

SR_TEST(antialiased_implicit_half_plane_gives_exact_areas)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = new_fb(ctx, W, H);
    REQUIRE(fb);
    CHECK_EQ(sr_fill_implicit(ctx, fb, &(sr_implicit_desc){ .f = halfplane_f, .antialias = true },
                              (sr_rgba){ 1, 1, 1, 1 }), SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int x = 0; x < W; x++) {
        double area = fmin(fmax(10.3 - x, 0), 1);
        CHECK_NEAR(px[(5 * W + x) * 4] / 255.0, area, 1.0 / 255.0);
    }
    circle_fn c = { 20, 20, 8 };
    CHECK_EQ(sr_fill_implicit(ctx, fb, &(sr_implicit_desc){ .f = circle_f, .user = &c,
                                                            .antialias = true, .x0 = 10, .y0 = 10,
                                                            .x1 = 30, .y1 = 30 },
                              (sr_rgba){ 1, 1, 1, 1 }), SR_OK);
    CHECK_EQ(sr_fill_implicit(ctx, fb, NULL, (sr_rgba){ 1, 1, 1, 1 }), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_implicit(ctx, fb, &(sr_implicit_desc){ 0 }, (sr_rgba){ 1, 1, 1, 1 }),
             SR_INVALID_ARG);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

static sr_point2 cubic_at(const sr_point2 p[4], double t)
{
    double u = 1 - t;
    return (sr_point2){ u * u * u * p[0].x + 3 * u * u * t * p[1].x + 3 * u * t * t * p[2].x + t * t * t * p[3].x,
                        u * u * u * p[0].y + 3 * u * u * t * p[1].y + 3 * u * t * t * p[2].y + t * t * t * p[3].y };
}

static double seg_dist(sr_point2 p, sr_point2 a, sr_point2 b)
{
    double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

SR_TEST(forward_differenced_beziers_stay_on_the_curve_within_tolerance)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_rng rng = { 0x5eed2d31u };
    static sr_point2 out[1 << 16];
    for (int iter = 0; iter < 500; iter++) {
        sr_point2 p[4];
        for (int k = 0; k < 4; k++) {
            p[k] = (sr_point2){ sr_rng_range(&rng, -200, 200), sr_rng_range(&rng, -200, 200) };
        }
        double tol = sr_rng_range(&rng, 0.01, 2);
        bool quad = iter % 2;
        int n = 0;
        if (quad) {
            /* a quadratic is the cubic with p1' = p0 + 2/3 (p1 - p0), ... */
            REQUIRE(sr_flatten_quadratic(ctx, p[0], p[1], p[2], tol, out, 1 << 16, &n) == SR_OK);
            sr_point2 q1 = p[1];
            p[1] = (sr_point2){ p[0].x + 2.0 / 3 * (q1.x - p[0].x), p[0].y + 2.0 / 3 * (q1.y - p[0].y) };
            p[3] = p[2];
            p[2] = (sr_point2){ p[3].x + 2.0 / 3 * (q1.x - p[3].x), p[3].y + 2.0 / 3 * (q1.y - p[3].y) };
        } else {
            REQUIRE(sr_flatten_cubic(ctx, p[0], p[1], p[2], p[3], tol, out, 1 << 16, &n) == SR_OK);
        }
        REQUIRE(n >= 1);
        CHECK(out[n - 1].x == p[3].x && out[n - 1].y == p[3].y);
        sr_point2 prev = p[0];
        double worst_on = 0, worst_chord = 0;
        for (int i = 0; i < n; i++) {
            sr_point2 c = cubic_at(p, (double)(i + 1) / n);
            worst_on = fmax(worst_on, hypot(c.x - out[i].x, c.y - out[i].y));
            for (int s = 1; s < 8; s++) { /* the curve between samples vs the chord */
                sr_point2 m = cubic_at(p, (i + s / 8.0) / n);
                worst_chord = fmax(worst_chord, seg_dist(m, prev, out[i]));
            }
            prev = out[i];
        }
        CHECK(worst_on < 1e-6);
        CHECK(worst_chord <= tol * 1.0001);
    }
    int n = 0;
    sr_point2 a = { 0, 0 }, b = { 50, 100 }, c = { 100, 0 };
    CHECK_EQ(sr_flatten_quadratic(ctx, a, b, c, 0.1, out, 0, &n), SR_TOO_LARGE);
    CHECK(n > 1);
    CHECK_EQ(sr_flatten_quadratic(ctx, a, b, c, 0, out, 100, &n), SR_INVALID_ARG);
    sr_destroy_context(ctx);
}

SR_TEST(svg_arcs_pick_the_flagged_arc_and_stay_on_the_ellipse)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_point2 out[4096];
    int n = 0;
    /* Half circle from (0,0) to (10,0): sweep = 1 runs through y = -5 (y down). */
    REQUIRE(sr_flatten_arc(ctx, (sr_point2){ 0, 0 }, 5, 5, 0, false, true, (sr_point2){ 10, 0 },
                           0.01, out, 4096, &n) == SR_OK);
    double miny = 0, maxy = 0;
    for (int i = 0; i < n; i++) {
        CHECK_NEAR(hypot(out[i].x - 5, out[i].y), 5, 1e-9);
        miny = fmin(miny, out[i].y);
        maxy = fmax(maxy, out[i].y);
    }
    CHECK_NEAR(miny, -5, 0.02);
    CHECK(maxy <= 1e-9);
    CHECK(out[n - 1].x == 10 && out[n - 1].y == 0);
    /* radii too small are scaled up: same half circle */
    int m = 0;
    REQUIRE(sr_flatten_arc(ctx, (sr_point2){ 0, 0 }, 1, 1, 0, false, false, (sr_point2){ 10, 0 },
                           0.01, out, 4096, &m) == SR_OK);
    for (int i = 0; i < m; i++) {
        CHECK_NEAR(hypot(out[i].x - 5, out[i].y), 5, 1e-9);
        CHECK(out[i].y >= -1e-9);
    }
    /* a large rotated elliptical arc: every point on the ellipse */
    sr_point2 from = { 10, 20 }, to = { 30, 25 };
    REQUIRE(sr_flatten_arc(ctx, from, 20, 10, 30, true, false, to, 0.05, out, 4096, &n) == SR_OK);
    /* recover the centre from two end conditions is involved; check instead
     * that consecutive chords are short and the arc ends exactly at `to` */
    CHECK(out[n - 1].x == to.x && out[n - 1].y == to.y);
    sr_point2 prev = from;
    for (int i = 0; i < n; i++) {
        CHECK(hypot(out[i].x - prev.x, out[i].y - prev.y) < 5);
        prev = out[i];
    }
    CHECK(n > 10);
    /* zero radius: a straight line */
    REQUIRE(sr_flatten_arc(ctx, from, 0, 10, 0, false, false, to, 0.05, out, 4096, &n) == SR_OK);
    CHECK_EQ(n, 1);
    sr_destroy_context(ctx);
}
