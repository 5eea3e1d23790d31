/* test_draw2d_fill_rect.c - the area converter's shortcuts (columns
 * narrowed to the edges', a row with only vertical edges reused for the
 * rows below it, columns no deposit reached taken from their left
 * neighbour) against the plain walk over every row and column
 * (sr__scan_area_each_row): on random axis-aligned rectangles (sub-pixel,
 * ordinary, huge, off the window; alone, overlapping, nested) and on random
 * rectilinear and general polygons, both fill rules, the coverage bytes
 * must be the same.  The aliased winding cells, narrowed the same way, are
 * held to the sorted-AET fill on the same rectangles.  Fixed seeds. */
#include "context.h"
#include "draw2d/polyfill.h"
#include "softrast.h"
#include "span_mask.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_W 160
#define MAX_H 120
#define MAX_PTS 64

/* A coordinate for a window [lo, lo + len): mostly near it, on the q8
 * grid, on pixel edges or centres, or far away. */
static double random_coord(sr_rng *rng, int lo, int len)
{
    double v = lo + sr_rng_range(rng, -0.3 * len - 4, 1.3 * len + 4);
    switch (sr_rng_int(rng, 0, 9)) {
    case 0:
        return round(v);
    case 1:
        return floor(v) + 0.5;
    case 2:
        return sr_rng_range(rng, -SR_MAX_COORD2D, SR_MAX_COORD2D);
    case 3:
        return floor(v * 256) / 256;
    default:
        return v;
    }
}

/* Append an axis-aligned rectangle contour from (x, y) of size (w, h),
 * w and h may be negative: its corners in either direction. */
static int add_rect(sr_point2 *pts, int n, double x, double y, double w, double h, bool ccw)
{
    sr_point2 c[4] = { { x, y }, { x + w, y }, { x + w, y + h }, { x, y + h } };
    for (int k = 0; k < 4; k++) {
        pts[n + k] = c[ccw ? 3 - k : k];
    }
    return n + 4;
}

/* 1..3 rectangles: sub-pixel, ordinary or huge, clamped to the
 * coordinate range. */
static int random_rects(sr_rng *rng, sr__window win, sr_point2 *pts, int *counts, int *contours)
{
    int n = 0, ww = win.x1 - win.x0, wh = win.y1 - win.y0;
    *contours = sr_rng_int(rng, 1, 3);
    for (int c = 0; c < *contours; c++) {
        double x = random_coord(rng, win.x0, ww), y = random_coord(rng, win.y0, wh);
        double w, h;
        switch (sr_rng_int(rng, 0, 3)) {
        case 0: /* sub-pixel */
            w = sr_rng_range(rng, -1.5, 1.5);
            h = sr_rng_range(rng, -1.5, 1.5);
            break;
        case 1: /* huge */
            w = sr_rng_range(rng, -2 * SR_MAX_COORD2D, 2 * SR_MAX_COORD2D);
            h = sr_rng_range(rng, -2 * SR_MAX_COORD2D, 2 * SR_MAX_COORD2D);
            break;
        default:
            w = sr_rng_range(rng, -1.2 * ww, 1.2 * ww);
            h = sr_rng_range(rng, -1.2 * wh, 1.2 * wh);
            break;
        }
        w = fmin(fmax(x + w, -SR_MAX_COORD2D), SR_MAX_COORD2D) - x;
        h = fmin(fmax(y + h, -SR_MAX_COORD2D), SR_MAX_COORD2D) - y;
        n = add_rect(pts, n, x, y, w, h, sr_rng_int(rng, 0, 1));
        counts[c] = 4;
    }
    return n;
}

/* A rectilinear contour (horizontal and vertical sides in turn, the last
 * one back to the start) or a general one of random vertices. */
static int random_polygon(sr_rng *rng, sr__window win, sr_point2 *pts, int *counts)
{
    int ww = win.x1 - win.x0, wh = win.y1 - win.y0;
    int n = 2 * sr_rng_int(rng, 2, MAX_PTS / 2);
    double x = random_coord(rng, win.x0, ww), y = random_coord(rng, win.y0, wh);
    bool rectilinear = sr_rng_int(rng, 0, 1);
    for (int k = 0; k < n; k++) {
        if (!rectilinear) {
            pts[k] = (sr_point2){ random_coord(rng, win.x0, ww), random_coord(rng, win.y0, wh) };
        } else if (k % 2 == 0) {
            pts[k] = (sr_point2){ x, y };
            x = k == n - 2 ? pts[0].x : random_coord(rng, win.x0, ww);
        } else {
            pts[k] = (sr_point2){ x, y };
            y = random_coord(rng, win.y0, wh);
        }
    }
    counts[0] = n;
    return n;
}

static sr__window random_window(sr_rng *rng, int iter)
{
    int w = sr_rng_int(rng, 1, iter % 8 == 0 ? MAX_W : 40);
    int h = sr_rng_int(rng, 1, iter % 8 == 0 ? MAX_H : 40);
    int ox = sr_rng_int(rng, -60, 60), oy = sr_rng_int(rng, -60, 60);
    return (sr__window){ ox, oy, ox + w, oy + h };
}

typedef enum shape_set { RECTANGLES, POLYGONS } shape_set;

/* `iters` random shapes of the set, each drawn by the converter and by its
 * reference under both fill rules (aliased: the winding cells and the
 * sorted AET; else the area converter and its plain walk): the masks must
 * be equal, no span may overlap another or leave the window, and more
 * than min_filled of the masks must cover something. */
static void compare_converters(uint64_t seed, int iters, shape_set set, bool aliased,
                               long min_filled)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_rng rng = { seed };
    sr_point2 pts[MAX_PTS];
    int counts[3], contours = 1;
    uint8_t *ref = malloc(MAX_W * MAX_H), *fast = malloc(MAX_W * MAX_H);
    REQUIRE(ref && fast);
    long differ = 0, bad = 0, filled = 0;
    for (int iter = 0; iter < iters; iter++) {
        sr__window win = random_window(&rng, iter);
        int n = set == RECTANGLES ? random_rects(&rng, win, pts, counts, &contours)
                                  : random_polygon(&rng, win, pts, counts);
        sr__edge2 *edges;
        int count;
        REQUIRE(sr__edges_from_polygon(ctx, "test", &(sr_polygon2){ pts, n, counts, contours },
                                       1, &edges, &count) == SR_OK);
        size_t size = (size_t)(win.x1 - win.x0) * (size_t)(win.y1 - win.y0);
        for (int r = 0; r < 2; r++) {
            sr_fill_rule rule = r ? SR_EVENODD : SR_NONZERO;
            memset(ref, 0, size);
            memset(fast, 0, size);
            mask_out mr = { ref, win, 0, 0, 0 }, mf = { fast, win, 0, 0, 0 };
            if (aliased) {
                REQUIRE(sr__scan_edge_table(ctx, edges, count, rule, win, mark_span, &mr) ==
                        SR_OK);
                REQUIRE(sr__scan_winding_cells(ctx, edges, count, rule, win, mark_span, &mf) ==
                        SR_OK);
            } else {
                REQUIRE(sr__scan_area_each_row(ctx, edges, count, rule, win, mark_span, &mr) ==
                        SR_OK);
                REQUIRE(sr__scan_area(ctx, edges, count, rule, win, mark_span, &mf) == SR_OK);
            }
            differ += memcmp(ref, fast, size) != 0;
            bad += mr.overlaps + mf.overlaps + mr.outside + mf.outside;
            bool any = false;
            for (size_t i = 0; i < size && !any; i++) {
                any = ref[i] != 0;
            }
            filled += any;
        }
        sr__free(ctx, edges);
    }
    CHECK_EQ(differ, 0);
    CHECK_EQ(bad, 0);
    CHECK(filled > min_filled);
    free(ref);
    free(fast);
    sr_destroy_context(ctx);
}

SR_TEST(area_coverage_of_rectangles_equals_the_plain_walk)
{
    compare_converters(0x5eed7ec7u, 4000, RECTANGLES, false, 3000); /* of 8,000 masks */
}

SR_TEST(area_coverage_of_polygons_equals_the_plain_walk)
{
    compare_converters(0x5eed7ec8u, 2000, POLYGONS, false, 3000); /* of 4,000 */
}

/* The aliased converter the fills use, narrowed to the edges' columns,
 * covers the pixels of the sorted-AET reference on the same rectangles. */
SR_TEST(aliased_rectangles_equal_the_sorted_active_edge_table)
{
    compare_converters(0x5eed7ec9u, 4000, RECTANGLES, true, 3000);
}
