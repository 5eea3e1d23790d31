/* test_draw2d_gouraud_incremental.c - sr_fill_gouraud: the incremental
 * scan-line interpolation (FillPoly / FillSpan, SR_GOURAUD_INCREMENTAL)
 * against the direct one and the flat fill.  Coverage must be the same
 * pixel set exactly; colors within one 8-bit step (the float sums round at
 * every increment).  Fixed seeds. */
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct canvas {
    sr_context *ctx;
    sr_framebuffer *fb[3]; /* direct, incremental, flat */
    int w, h;
} canvas;

static bool canvas_make(canvas *c, int w, int h)
{
    *c = (canvas){ NULL, { NULL, NULL, NULL }, w, h };
    if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &c->ctx) != SR_OK) {
        return false;
    }
    for (int i = 0; i < 3; i++) {
        if (sr_make_framebuffer(c->ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                .depth_format = SR_DEPTH_NONE }, &c->fb[i]) != SR_OK) {
            return false;
        }
    }
    return true;
}

static void canvas_free(canvas *c)
{
    for (int i = 0; i < 3; i++) {
        if (c->fb[i]) {
            sr_destroy_framebuffer(c->ctx, c->fb[i]);
        }
    }
    sr_destroy_context(c->ctx);
}

static void canvas_clear(canvas *c)
{
    for (int i = 0; i < 3; i++) {
        sr_clear(c->ctx, c->fb[i], &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    }
}

typedef struct tally {
    long covered;        /* pixels the flat fill covers */
    long coverage_bad;   /* pixels where the three fills disagree on coverage */
    long color_off;      /* covered pixels whose colors differ at all */
    int max_step;        /* largest channel difference, in 8-bit steps */
} tally;

/* Compare the three framebuffers: opaque colors, so alpha 255 is covered. */
static void compare(const canvas *c, tally *t)
{
    const uint8_t *d = sr_framebuffer_pixels(c->fb[0]);
    const uint8_t *n = sr_framebuffer_pixels(c->fb[1]);
    const uint8_t *f = sr_framebuffer_pixels(c->fb[2]);
    for (size_t i = 0; i < (size_t)c->w * c->h; i++) {
        bool in_f = f[4 * i + 3] != 0;
        t->covered += in_f;
        t->coverage_bad += (d[4 * i + 3] != 0) != in_f || (n[4 * i + 3] != 0) != in_f;
        bool off = false;
        for (int k = 0; k < 3; k++) {
            int step = abs(d[4 * i + k] - n[4 * i + k]);
            t->max_step = step > t->max_step ? step : t->max_step;
            off |= step != 0;
        }
        t->color_off += off;
    }
}

/* The same pixels, colors within one step, and enough pixels to say so;
 * when `few_off`, under 1% of them off at all (rounding moves few values
 * across an 8-bit boundary). */
static void check_tally(const tally *t, long min_covered, bool few_off)
{
    CHECK_EQ(t->coverage_bad, 0);
    CHECK(t->max_step <= 1);
    CHECK(t->covered > min_covered);
    CHECK(!few_off || t->color_off * 100 < t->covered);
}

static sr_rgba random_color(sr_rng *rng)
{
    return (sr_rgba){ (float)sr_rng_unit(rng), (float)sr_rng_unit(rng), (float)sr_rng_unit(rng),
                      1 };
}

/* A coordinate in [lo, hi]: a third of the time on a pixel centre and a
 * third on a pixel corner, where the fill rule decides the ties. */
static double random_coord(sr_rng *rng, double lo, double hi)
{
    double v = sr_rng_range(rng, lo, hi);
    switch (sr_rng_int(rng, 0, 2)) {
    case 0:  return floor(v) + 0.5;
    case 1:  return floor(v);
    default: return v;
    }
}

/* Fill poly on cleared canvases by the three fills and tally them. */
static void fill_and_compare(canvas *c, const sr_polygon2 *poly, const sr_rgba *col,
                             sr_fill_rule rule, tally *t)
{
    canvas_clear(c);
    CHECK_EQ(sr_fill_gouraud(c->ctx, c->fb[0], poly, col,
                             &(sr_gouraud_desc){ .rule = rule, .method = SR_GOURAUD_DIRECT }),
             SR_OK);
    CHECK_EQ(sr_fill_gouraud(c->ctx, c->fb[1], poly, col,
                             &(sr_gouraud_desc){ .rule = rule, .method = SR_GOURAUD_INCREMENTAL }),
             SR_OK);
    CHECK_EQ(sr_fill_polygon(c->ctx, c->fb[2], poly, (sr_rgba){ 1, 1, 1, 1 },
                             &(sr_fill_desc){ .rule = rule }),
             SR_OK);
    compare(c, t);
}

/* One random shape: corners and colors into p/col, contours into counts;
 * returns the corner count, *contours and *rule set. */
typedef int (*shape_fn)(sr_rng *rng, int iter, const canvas *c, sr_point2 *p, sr_rgba *col,
                        int *counts, int *contours, sr_fill_rule *rule);

static int random_triangle(sr_rng *rng, int iter, const canvas *c, sr_point2 *p, sr_rgba *col,
                           int *counts, int *contours, sr_fill_rule *rule)
{
    /* Mostly small triangles, some larger than the canvas. */
    double span = iter % 5 ? 40 : 160;
    double cx = sr_rng_range(rng, 0, c->w), cy = sr_rng_range(rng, 0, c->h);
    for (int k = 0; k < 3; k++) {
        p[k] = (sr_point2){ random_coord(rng, cx - span / 2, cx + span / 2),
                            random_coord(rng, cy - span / 2, cy + span / 2) };
        col[k] = random_color(rng);
    }
    counts[0] = 3;
    *contours = 1;
    *rule = SR_FILL_RULE_DEFAULT;
    return 3;
}

/* One to three contours of 3..8 corners anywhere, either rule. */
static int random_polygon(sr_rng *rng, int iter, const canvas *c, sr_point2 *p, sr_rgba *col,
                          int *counts, int *contours, sr_fill_rule *rule)
{
    int n = 0;
    *contours = sr_rng_int(rng, 1, 3);
    for (int k = 0; k < *contours; k++) {
        counts[k] = sr_rng_int(rng, 3, 8);
        for (int i = 0; i < counts[k]; i++, n++) {
            p[n] = (sr_point2){ random_coord(rng, -6, c->w + 6), random_coord(rng, -6, c->h + 6) };
            col[n] = random_color(rng);
        }
    }
    *rule = iter % 2 ? SR_EVENODD : SR_NONZERO;
    return n;
}

static void property(int w, int h, uint64_t seed, int iters, shape_fn shape, long min_covered)
{
    canvas c;
    REQUIRE(canvas_make(&c, w, h));
    sr_rng rng = { seed };
    tally t = { 0 };
    for (int iter = 0; iter < iters; iter++) {
        sr_point2 p[24];
        sr_rgba col[24];
        int counts[3], contours;
        sr_fill_rule rule;
        int n = shape(&rng, iter, &c, p, col, counts, &contours, &rule);
        fill_and_compare(&c, &(sr_polygon2){ p, n, counts, contours }, col, rule, &t);
    }
    check_tally(&t, min_covered, true);
    canvas_free(&c);
}

SR_TEST(incremental_triangles_cover_the_same_pixels_within_one_step)
{
    property(96, 80, 0x6f11b01bu, 3000, random_triangle, 700000);
}

SR_TEST(incremental_polygons_match_under_both_rules)
{
    property(80, 64, 0x9a11e7u, 1500, random_polygon, 500000);
}

/* Two thousand steps along edges and spans: the rounding the float sums
 * gather still stays within the step the 8-bit output can show. */
SR_TEST(incremental_sums_stay_within_one_step_across_a_large_triangle)
{
    canvas c;
    REQUIRE(canvas_make(&c, 2048, 2048));
    sr_rng rng = { 0xb16u };
    tally t = { 0 };
    for (int iter = 0; iter < 3; iter++) {
        sr_point2 p[3] = { { sr_rng_range(&rng, 0, 30), sr_rng_range(&rng, 0, 30) },
                           { sr_rng_range(&rng, 2000, 2048), sr_rng_range(&rng, 900, 1100) },
                           { sr_rng_range(&rng, 0, 50), sr_rng_range(&rng, 2000, 2048) } };
        sr_rgba col[3] = { random_color(&rng), random_color(&rng), random_color(&rng) };
        fill_and_compare(&c, &(sr_polygon2){ p, 3, NULL, 0 }, col, SR_FILL_RULE_DEFAULT, &t);
    }
    check_tally(&t, 4000000, false);
    canvas_free(&c);
}

SR_TEST(default_method_is_the_direct_fills)
{
    canvas c;
    REQUIRE(canvas_make(&c, 64, 48));
    const size_t bytes = 64 * 48 * 4;
    sr_point2 tri[3] = { { 3.3, 2.1 }, { 60.2, 20.7 }, { 10.9, 45.5 } };
    sr_rgba col[5] = { { 1, 0, 0, 1 }, { 0, 1, 0, 0.5f }, { 0, 0, 1, 1 }, { 1, 1, 0, 1 },
                       { 0, 1, 1, 1 } };
    canvas_clear(&c);
    REQUIRE(sr_fill_gouraud(c.ctx, c.fb[0], &(sr_polygon2){ tri, 3, NULL, 0 }, col, NULL) == SR_OK);
    REQUIRE(sr_fill_triangle_gouraud(c.ctx, c.fb[1], tri, col) == SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(c.fb[0]), sr_framebuffer_pixels(c.fb[1]), bytes) == 0);
    sr_point2 pent[5] = { { 5, 5 }, { 50, 3 }, { 60, 30 }, { 30, 44 }, { 2, 25 } };
    sr_polygon2 poly = { pent, 5, NULL, 0 };
    canvas_clear(&c);
    REQUIRE(sr_fill_gouraud(c.ctx, c.fb[0], &poly, col, &(sr_gouraud_desc){ .rule = SR_EVENODD })
            == SR_OK);
    REQUIRE(sr_fill_polygon_gouraud(c.ctx, c.fb[1], &poly, col, SR_EVENODD) == SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(c.fb[0]), sr_framebuffer_pixels(c.fb[1]), bytes) == 0);
    /* With alpha < 1 blending the incremental colors still lands within a
     * step of the direct ones. */
    REQUIRE(sr_fill_gouraud(c.ctx, c.fb[2], &poly, col,
                            &(sr_gouraud_desc){ .rule = SR_EVENODD,
                                                .method = SR_GOURAUD_INCREMENTAL }) == SR_OK);
    const uint8_t *a = sr_framebuffer_pixels(c.fb[1]), *b = sr_framebuffer_pixels(c.fb[2]);
    int worst = 0;
    for (size_t i = 0; i < bytes; i++) {
        int d = abs(a[i] - b[i]);
        worst = d > worst ? d : worst;
    }
    CHECK(worst <= 1);
    canvas_free(&c);
}

SR_TEST(sr_fill_gouraud_rejects_bad_arguments)
{
    canvas c;
    REQUIRE(canvas_make(&c, 16, 16));
    sr_point2 p[3] = { { 0, 0 }, { 9, 0 }, { 0, 9 } };
    sr_rgba ok[3] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, 1, 1 } };
    sr_rgba bad[3] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, NAN, 1 } };
    sr_polygon2 poly = { p, 3, NULL, 0 };
    const sr_gouraud_desc inc = { .method = SR_GOURAUD_INCREMENTAL };
    CHECK_EQ(sr_fill_gouraud(NULL, c.fb[0], &poly, ok, &inc), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_gouraud(c.ctx, NULL, &poly, ok, &inc), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(c.ctx), "fb");
    CHECK_EQ(sr_fill_gouraud(c.ctx, c.fb[0], NULL, ok, &inc), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_gouraud(c.ctx, c.fb[0], &poly, NULL, &inc), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(c.ctx), "colors");
    CHECK_EQ(sr_fill_gouraud(c.ctx, c.fb[0], &poly, bad, &inc), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(c.ctx), "not finite");
    CHECK_EQ(sr_fill_gouraud(c.ctx, c.fb[0], &poly, ok,
                             &(sr_gouraud_desc){ .method = (sr_gouraud_method)7 }),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(c.ctx), "sr_gouraud_desc.method");
    for (int m = SR_GOURAUD_DEFAULT; m <= SR_GOURAUD_INCREMENTAL; m++) {
        CHECK_EQ(sr_fill_gouraud(c.ctx, c.fb[0], &poly, ok,
                                 &(sr_gouraud_desc){ .rule = (sr_fill_rule)9,
                                                     .method = (sr_gouraud_method)m }),
                 SR_INVALID_ARG);
    }
    sr_point2 far[3] = { { 0, 0 }, { 1e9, 0 }, { 0, 9 } };
    CHECK_EQ(sr_fill_gouraud(c.ctx, c.fb[0], &(sr_polygon2){ far, 3, NULL, 0 }, ok, &inc),
             SR_TOO_LARGE);
    /* An empty polygon draws nothing and succeeds. */
    CHECK_EQ(sr_fill_gouraud(c.ctx, c.fb[0], &(sr_polygon2){ NULL, 0, NULL, 0 }, NULL, &inc),
             SR_OK);
    canvas_free(&c);
}

/* 2D drawing needs a single-sampled target: every path refuses a
 * multisampled one, after building its edges (the sanitizer build checks
 * that they are freed). */
SR_TEST(gouraud_fills_refuse_a_multisampled_framebuffer)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 16, .height = 16,
                                .samples = 4 }, &fb) == SR_OK);
    sr_point2 p[4] = { { 1, 1 }, { 14, 2 }, { 12, 13 }, { 2, 12 } };
    sr_rgba col[4] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, 1, 1 }, { 1, 1, 1, 1 } };
    for (int n = 3; n <= 4; n++) {
        for (int m = SR_GOURAUD_DEFAULT; m <= SR_GOURAUD_INCREMENTAL; m++) {
            CHECK_EQ(sr_fill_gouraud(ctx, fb, &(sr_polygon2){ p, n, NULL, 0 }, col,
                                     &(sr_gouraud_desc){ .method = (sr_gouraud_method)m }),
                     SR_INVALID_ARG);
            CHECK_STR_CONTAINS(sr_context_error(ctx), "multisampled");
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
