/* test_draw2d_guard.c - polygons beyond the 2D fixed-point budget
 * (SR_MAX_COORD2D) are cut to a guard band around the window before they
 * are snapped (draw2d/guardclip.c).  On random polygons inside the budget
 * but reaching past the guard band, the cut polygon must give the pixels
 * of the uncut one, byte for byte, with both fill rules, aliased, area
 * and supersampled; polygons beyond the budget are drawn, NaN and
 * infinities still refused, and so are windows reaching past the budget.
 * Fixed seeds. */
#include "context.h"
#include "draw2d/polyfill.h"
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 48
#define H 40

/* 1..3 contours of 3..10 vertices around a W x H window at (ox, oy), some
 * far beyond the guard band (up to the budget), some on pixel centres. */
static int random_polygon(sr_rng *rng, int ox, int oy, sr_point2 *pts, int *counts,
                          int *contours)
{
    int n = 0;
    *contours = sr_rng_int(rng, 1, 3);
    for (int c = 0; c < *contours; c++) {
        counts[c] = sr_rng_int(rng, 3, 10);
        for (int k = 0; k < counts[c]; k++) {
            double x = ox + sr_rng_range(rng, -20, W + 20);
            double y = oy + sr_rng_range(rng, -20, H + 20);
            int kind = sr_rng_int(rng, 0, 9);
            if (kind < 3) {
                x = sr_rng_range(rng, -SR_MAX_COORD2D, SR_MAX_COORD2D);
            } else if (kind == 3) {
                y = sr_rng_range(rng, -SR_MAX_COORD2D, SR_MAX_COORD2D);
            } else if (kind == 4) {
                x = round(x) + 0.5;
                y = round(y) + 0.5;
            }
            pts[n++] = (sr_point2){ x, y };
        }
    }
    return n;
}

SR_TEST(polygons_cut_to_the_guard_band_cover_the_same_pixels)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_rng rng = { 0x9a7d0c5u };
    sr_point2 pts[30];
    int counts[3], contours;
    uint8_t whole[W * H], cut[W * H];
    static const sr_fill_desc descs[] = {
        { .rule = SR_NONZERO }, { .rule = SR_EVENODD },
        { .rule = SR_NONZERO, .antialias = SR_AA_AREA },
        { .rule = SR_EVENODD, .antialias = SR_AA_AREA },
        { .rule = SR_NONZERO, .antialias = SR_AA_SUPERSAMPLE, .samples = 4 },
        { .rule = SR_EVENODD, .antialias = SR_AA_SUPERSAMPLE, .samples = 16 },
    };
    long differ[3] = { 0 }, clipped = 0, lit = 0;
    int worst[3] = { 0 };
    for (int iter = 0; iter < 600; iter++) {
        int ox = sr_rng_int(&rng, -100, 100), oy = sr_rng_int(&rng, -100, 100);
        int n = random_polygon(&rng, ox, oy, pts, counts, &contours);
        sr_polygon2 poly = { pts, n, counts, contours }, g;
        REQUIRE(sr__guard_clip(ctx, "test", &poly, (sr__window){ ox, oy, ox + W, oy + H }, &g) ==
                SR_OK);
        clipped += g.point_count != n;
        for (size_t d = 0; d < sizeof descs / sizeof descs[0]; d++) {
            REQUIRE(sr_polygon_coverage(ctx, &poly, &descs[d], ox, oy, W, H, whole, W) == SR_OK);
            REQUIRE(sr_polygon_coverage(ctx, &g, &descs[d], ox, oy, W, H, cut, W) == SR_OK);
            for (int i = 0; i < W * H; i++) {
                int dd = abs(whole[i] - cut[i]);
                int k = descs[d].antialias == SR_AA_AREA ? 1
                        : descs[d].antialias == SR_AA_SUPERSAMPLE ? 2 : 0;
                worst[k] = dd > worst[k] ? dd : worst[k];
                differ[k] += dd != 0;
            }
            for (int i = 0; i < W * H; i++) {
                lit += whole[i] != 0;
            }
        }
        sr__free(ctx, (void *)g.points);
        sr__free(ctx, (void *)g.contour_counts);
    }
    /* A cut edge ends on the guard line at a point rounded to 1/256 px,
     * which turns it by a hair: in the window it moves by about
     * (distance / 131072) / 512 px.  Aliased samples, 1 px apart, stay on
     * their sides; the area sums round differently by at most one step;
     * of 4 x 4 and 16 x 16 subsamples, 1/4 and 1/16 px apart, a few change
     * sides. */
    CHECK_EQ(differ[0], 0);
    CHECK(worst[1] <= 1);
    CHECK(differ[2] <= 200 && worst[2] <= 64);
    printf("area: %ld pixels differ by 1; supersampled: %ld pixels, by up to %d\n", differ[1],
           differ[2], worst[2]);
    CHECK(clipped > 300); /* the property was tried where it matters */
    CHECK(lit > 100000);
    sr_destroy_context(ctx);
}

SR_TEST(polygons_beyond_the_budget_are_drawn_where_they_are_seen)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    uint8_t mask[W * H], ref[W * H];
    /* A triangle reaching 1e12 px to the right, nearly horizontal edges,
     * against the same shape cut by hand at x = 2e5 (the edge moves by
     * less than 1e-6 px in the window): aliased, the same pixels. */
    for (int r = 0; r < 2; r++) {
        sr_fill_desc d = { .rule = r ? SR_EVENODD : SR_NONZERO };
        sr_point2 far[3] = { { 3.25, 2.5 }, { 1e12, 1e12 * 0.3 }, { 5.5, 37.75 } };
        double t = (2e5 - 3.25) / (1e12 - 3.25);
        sr_point2 near[4] = { { 3.25, 2.5 }, { 2e5, 2.5 + t * (1e12 * 0.3 - 2.5) },
                              { 2e5, 37.75 }, { 5.5, 37.75 } };
        near[2].y = 37.75 + (2e5 - 5.5) / (1e12 - 5.5) * (1e12 * 0.3 - 37.75);
        REQUIRE(sr_polygon_coverage(ctx, &(sr_polygon2){ far, 3, NULL, 0 }, &d, 0, 0, W, H, mask,
                                    W) == SR_OK);
        REQUIRE(sr_polygon_coverage(ctx, &(sr_polygon2){ near, 4, NULL, 0 }, &d, 0, 0, W, H, ref,
                                    W) == SR_OK);
        CHECK(memcmp(mask, ref, sizeof mask) == 0);
        CHECK_EQ(mask[20 * W + 30], 255);
    }
    /* A square 1e300 px a side around the window covers it, both rules. */
    sr_point2 vast[4] = { { -1e300, -1e300 }, { 1e300, -1e300 }, { 1e300, 1e300 },
                          { -1e300, 1e300 } };
    for (int a = 0; a < 3; a++) {
        sr_fill_desc d = { .antialias = a == 0 ? SR_AA_NONE : a == 1 ? SR_AA_AREA
                                                                     : SR_AA_SUPERSAMPLE };
        REQUIRE(sr_polygon_coverage(ctx, &(sr_polygon2){ vast, 4, NULL, 0 }, &d, -7, 5, W, H,
                                    mask, W) == SR_OK);
        int full = 0;
        for (int i = 0; i < W * H; i++) {
            full += mask[i] == 255;
        }
        CHECK_EQ(full, W * H);
    }
    /* A window on the budget's edge: the guard line held there lies on
     * the window's edge, and its chord covers no pixel of it.  One
     * reaching past the budget, where no edge can be snapped, is refused
     * (its pixels there would stay empty). */
    const int edge = (int)SR_MAX_COORD2D;
    for (int a = 0; a < 3; a++) {
        sr_fill_desc d = { .antialias = a == 0 ? SR_AA_NONE : a == 1 ? SR_AA_AREA
                                                                     : SR_AA_SUPERSAMPLE };
        REQUIRE(sr_polygon_coverage(ctx, &(sr_polygon2){ vast, 4, NULL, 0 }, &d, edge - W,
                                    -edge, W, H, mask, W) == SR_OK);
        int full = 0;
        for (int i = 0; i < W * H; i++) {
            full += mask[i] == 255;
        }
        CHECK_EQ(full, W * H);
    }
    CHECK_EQ(sr_polygon_coverage(ctx, &(sr_polygon2){ vast, 4, NULL, 0 }, NULL, edge - W / 2, 0,
                                 W, H, mask, W), SR_TOO_LARGE);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "reaches beyond");
    CHECK_EQ(sr_polygon_coverage(ctx, &(sr_polygon2){ vast, 4, NULL, 0 }, NULL, 0, -edge - 1, W,
                                 H, mask, W), SR_TOO_LARGE);
    /* Wholly beyond the budget and away from the window: nothing. */
    sr_point2 away[3] = { { 1e7, 0 }, { 2e7, 0 }, { 1e7, 40 } };
    REQUIRE(sr_polygon_coverage(ctx, &(sr_polygon2){ away, 3, NULL, 0 }, NULL, 0, 0, W, H, mask,
                                W) == SR_OK);
    int any = 0;
    for (int i = 0; i < W * H; i++) {
        any |= mask[i];
    }
    CHECK_EQ(any, 0);
    /* NaN and infinities stay refused. */
    sr_point2 inf[3] = { { 0, 0 }, { INFINITY, 0 }, { 0, 4 } };
    CHECK_EQ(sr_polygon_coverage(ctx, &(sr_polygon2){ inf, 3, NULL, 0 }, NULL, 0, 0, W, H, mask,
                                 W), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "points[1] is not finite");
    /* The Gouraud fill interpolates by vertex: it still refuses. */
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    sr_rgba c3[3] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, 1, 1 } };
    CHECK_EQ(sr_fill_gouraud(ctx, fb, &(sr_polygon2){ away, 3, NULL, 0 }, c3, NULL),
             SR_TOO_LARGE);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
