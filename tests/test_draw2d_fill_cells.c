/* test_draw2d_fill_cells.c - the fast aliased fill (winding cells and a
 * prefix sum) against the sorted-AET scan-line fill it replaces in the
 * public calls: on random polygons (self-intersecting, several contours,
 * vertices on pixel centres, far outside the window), both fill rules and
 * many window sizes and origins, the two converters must cover the same
 * pixels, byte for byte, each pixel at most once.  Fixed seeds. */
#include "context.h"
#include "draw2d/polyfill.h"
#include "softrast.h"
#include "span_mask.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_W 300
#define MAX_H 200

/* A random polygon for a w x h window at (x0, y0): 1..4 contours of
 * 3..n_max vertices, mostly around the window, some on the half-pixel
 * grid (vertices and edges through pixel centres), some far away. */
static int random_polygon(sr_rng *rng, sr__window win, int n_max, sr_point2 *pts, int *counts,
                          int *contours)
{
    int n = 0;
    double w = win.x1 - win.x0, h = win.y1 - win.y0;
    *contours = sr_rng_int(rng, 1, 4);
    for (int c = 0; c < *contours; c++) {
        counts[c] = sr_rng_int(rng, 3, n_max);
        for (int k = 0; k < counts[c]; k++) {
            double x = win.x0 + sr_rng_range(rng, -0.2 * w - 3, 1.2 * w + 3);
            double y = win.y0 + sr_rng_range(rng, -0.2 * h - 3, 1.2 * h + 3);
            int kind = sr_rng_int(rng, 0, 9);
            if (kind < 3) {
                x = floor(x * 2) / 2;
                y = floor(y * 2) / 2;
            } else if (kind == 3) {
                x = sr_rng_range(rng, -SR_MAX_COORD2D, SR_MAX_COORD2D);
            } else if (kind == 4) {
                x = round(x);
                y = round(y) + 0.5;
            }
            pts[n++] = (sr_point2){ x, y };
        }
    }
    return n;
}

SR_TEST(winding_cells_fill_the_pixels_of_the_sorted_active_edge_table)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_rng rng = { 0x5eed2d0cu };
    enum { N_MAX = 200 };
    sr_point2 pts[4 * N_MAX];
    int counts[4], contours;
    uint8_t *ref = malloc(MAX_W * MAX_H), *fast = malloc(MAX_W * MAX_H);
    REQUIRE(ref && fast);
    long differ = 0, overlaps = 0, outside = 0, filled = 0, empty = 0;
    for (int iter = 0; iter < 3000; iter++) {
        int w = sr_rng_int(&rng, 1, iter % 10 == 0 ? MAX_W : 40);
        int h = sr_rng_int(&rng, 1, iter % 10 == 0 ? MAX_H : 40);
        int ox = sr_rng_int(&rng, -50, 50), oy = sr_rng_int(&rng, -50, 50);
        sr__window win = { ox, oy, ox + w, oy + h };
        int n_max = iter % 7 == 0 ? N_MAX : 12;
        int n = random_polygon(&rng, win, n_max, pts, counts, &contours);
        sr__edge2 *edges;
        int count;
        REQUIRE(sr__edges_from_polygon(ctx, "test", &(sr_polygon2){ pts, n, counts, contours },
                                       1, &edges, &count) == SR_OK);
        for (int r = 0; r < 2; r++) {
            sr_fill_rule rule = r ? SR_EVENODD : SR_NONZERO;
            memset(ref, 0, (size_t)w * h);
            memset(fast, 0, (size_t)w * h);
            mask_out mr = { ref, win, 0, 0, 0 }, mf = { fast, win, 0, 0, 0 };
            REQUIRE(sr__scan_edge_table(ctx, edges, count, rule, win, mark_span, &mr) == SR_OK);
            REQUIRE(sr__scan_winding_cells(ctx, edges, count, rule, win, mark_span, &mf) ==
                    SR_OK);
            differ += memcmp(ref, fast, (size_t)w * h) != 0;
            overlaps += mr.overlaps + mf.overlaps;
            outside += mr.outside + mf.outside + mr.with_cov + mf.with_cov; /* aliased */
            long on = 0;
            for (int i = 0; i < w * h; i++) {
                on += ref[i] != 0;
            }
            filled += on > 0;
            empty += on < (long)w * h;
        }
        sr__free(ctx, edges);
    }
    CHECK_EQ(differ, 0);
    CHECK_EQ(overlaps, 0);
    CHECK_EQ(outside, 0);
    /* The cases are not degenerate: most fill something and leave something. */
    CHECK(filled > 4000);
    CHECK(empty > 4000);
    free(ref);
    free(fast);
    sr_destroy_context(ctx);
}

/* The public calls go through the winding cells: sr_polygon_coverage's
 * aliased mask equals the sorted-AET reference on the same windows. */
SR_TEST(aliased_polygon_coverage_equals_the_sorted_active_edge_table)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_rng rng = { 0x5eed2d0du };
    sr_point2 pts[4 * 40];
    int counts[4], contours;
    uint8_t ref[64 * 48], mask[64 * 48];
    long differ = 0;
    for (int iter = 0; iter < 500; iter++) {
        int w = sr_rng_int(&rng, 1, 64), h = sr_rng_int(&rng, 1, 48);
        int ox = sr_rng_int(&rng, -20, 20), oy = sr_rng_int(&rng, -20, 20);
        sr__window win = { ox, oy, ox + w, oy + h };
        int n = random_polygon(&rng, win, 40, pts, counts, &contours);
        sr_polygon2 poly = { pts, n, counts, contours };
        sr__edge2 *edges;
        int count;
        REQUIRE(sr__edges_from_polygon(ctx, "test", &poly, 1, &edges, &count) == SR_OK);
        sr_fill_rule rule = iter % 2 ? SR_EVENODD : SR_NONZERO;
        memset(ref, 0, sizeof ref);
        mask_out mr = { ref, win, 0, 0, 0 };
        REQUIRE(sr__scan_edge_table(ctx, edges, count, rule, win, mark_span, &mr) == SR_OK);
        sr__free(ctx, edges);
        REQUIRE(sr_polygon_coverage(ctx, &poly, &(sr_fill_desc){ .rule = rule }, ox, oy, w, h,
                                    mask, (size_t)w) == SR_OK);
        differ += memcmp(ref, mask, (size_t)w * h) != 0;
    }
    CHECK_EQ(differ, 0);
    sr_destroy_context(ctx);
}
