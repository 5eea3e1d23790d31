/* test_block.c - raster/block.h, the rectangle tests the half-space
 * kernels rely on, against every pixel of the rectangle: a rejected block
 * has no covered pixel and an accepted one has every pixel covered
 * (sr__rect_classify), and sr__rect_fits32 says yes exactly when every
 * edge value in the rectangle fits the 32-bit lanes of the AVX-512 kernel,
 * at the limit too. */
#include "sr_test.h"
#include "pipeline.h"
#include "raster/block.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Edge i's value at pixel (x, y)'s centre, unbiased. */
static int64_t edge_at(const sr_tri *t, int i, int x, int y)
{
    return t->a[i] * sr__centre_q8(x) + t->b[i] * sr__centre_q8(y) + sr__tri_c(t, i);
}

/* sr__rect_fits32 of a record's edge functions. */
static bool rect_fits32(const sr_tri *t, int x0, int y0, int x1, int y1)
{
    sr_edges ed;
    sr__tri_edges(t, &ed);
    return sr__rect_fits32(&ed, x0, y0, x1, y1);
}

/* The edges setup makes of vertices (x[k], y[k]) in q8, in that order
 * (either orientation; the rectangle tests do not care). */
static void edges_from(sr_tri *t, const int64_t x[3], const int64_t y[3])
{
    memset(t, 0, sizeof *t);
    for (int i = 0; i < 3; i++) {
        int a = (i + 1) % 3, b = (i + 2) % 3;
        t->a[i] = (int32_t)-(y[b] - y[a]);
        t->b[i] = (int32_t)(x[b] - x[a]);
    }
    t->x0_q8 = (int32_t)x[0];
    t->y0_q8 = (int32_t)y[0];
}

/* A triangle with vertices within `reach` q8 units of (cx, cy), its edges
 * at most `amax` long each way. */
static void random_tri(sr_rng *rng, sr_tri *t, int64_t cx, int64_t cy, int64_t reach,
                       int32_t amax)
{
    int64_t x[3], y[3];
    x[0] = cx + (int64_t)sr_rng_range(rng, -(double)reach, (double)reach);
    y[0] = cy + (int64_t)sr_rng_range(rng, -(double)reach, (double)reach);
    for (int k = 1; k < 3; k++) {
        x[k] = x[0] + sr_rng_int(rng, -amax / 2, amax / 2);
        y[k] = y[0] + sr_rng_int(rng, -amax / 2, amax / 2);
    }
    edges_from(t, x, y);
}

SR_TEST(edge_constants_rebuilt_from_vertex_0_match_setup)
{
    /* sr__tri_c and sr__tri_bias against the vertex form setup used to
     * store: c_i = dy x_a - dx y_a, bias 0 on a top or left edge. */
    sr_rng rng = { 0xc0 };
    for (int k = 0; k < 20000 && !sr_test_failed_now(); k++) {
        int64_t x[3], y[3];
        int32_t span = k % 3 == 0 ? 8 : (1 << 22) - 1;   /* axis-aligned edges often */
        for (int v = 0; v < 3; v++) {
            x[v] = sr_rng_int(&rng, -(1 << 22), 1 << 22);
            y[v] = sr_rng_int(&rng, -(1 << 22), 1 << 22);
            if (v > 0) {
                x[v] = x[0] + sr_rng_int(&rng, -span / 2, span / 2);
                y[v] = y[0] + sr_rng_int(&rng, -span / 2, span / 2);
            }
        }
        sr_tri t;
        edges_from(&t, x, y);
        for (int i = 0; i < 3; i++) {
            int a = (i + 1) % 3, b = (i + 2) % 3;
            int64_t dx = x[b] - x[a], dy = y[b] - y[a];
            CHECK_EQ(sr__tri_c(&t, i), dy * x[a] - dx * y[a]);
            bool top_left = dy < 0 || (dy == 0 && dx > 0);
            CHECK_EQ(sr__tri_bias(&t, i), top_left ? 0 : -1);
        }
    }
}

SR_TEST(fits32_goes_by_the_corner_values_up_to_the_limit)
{
    const int64_t lim = INT32_MAX - 1;
    sr_tri t;
    /* A slope of one q8 unit along x, then along y, through a vertex so
     * far off that only the rectangle's last column (row), 99, crosses
     * the limit: edge 1 (vertices 2 and 0) is sign (X - x0) or
     * sign (Y - y0), edge 0 its negation, edge 2 degenerate (0). */
    for (int axis = 0; axis < 2; axis++) {
        for (int sign = -1; sign <= 1; sign += 2) {
            int64_t far = sr__centre_q8(99) - (lim + 1);
            int64_t x[3] = { axis ? 0 : far, axis ? 0 : far, axis ? sign : far };
            int64_t y[3] = { axis ? far : 0, axis ? far : 0, axis ? far : -sign };
            edges_from(&t, x, y);
            CHECK_EQ(llabs(edge_at(&t, 1, axis ? 0 : 99, axis ? 99 : 0)), lim + 1);
            CHECK_EQ(llabs(edge_at(&t, 0, axis ? 0 : 99, axis ? 99 : 0)), lim + 1);
            int x1 = axis ? 5 : 100, y1 = axis ? 100 : 5;
            CHECK(!rect_fits32(&t, axis ? 0 : 90, axis ? 90 : 0, x1, y1));
            CHECK(rect_fits32(&t, axis ? 0 : 90, axis ? 90 : 0, x1 - !axis, y1 - axis));
        }
    }
}

SR_TEST(fits32_agrees_with_every_pixel_of_random_rectangles)
{
    const int64_t lim = INT32_MAX - 1;
    sr_rng rng = { 0xb10c };
    int yes = 0, no = 0;
    for (int k = 0; k < 4000 && !sr_test_failed_now(); k++) {
        sr_tri t;
        int32_t amax = sr_rng_int(&rng, 0, 3) == 0 ? (1 << 22) : 4096;
        int64_t reach = (int64_t)1 << sr_rng_int(&rng, 10, 24);
        random_tri(&rng, &t, 200 * 256, 200 * 256, reach, amax);
        int x0 = sr_rng_int(&rng, -50, 400), y0 = sr_rng_int(&rng, -50, 400);
        int x1 = x0 + sr_rng_int(&rng, 1, 20), y1 = y0 + sr_rng_int(&rng, 1, 20);
        bool all = true;
        for (int y = y0; y < y1; y++) {
            for (int x = x0; x < x1; x++) {
                for (int i = 0; i < 3; i++) {
                    int64_t v = edge_at(&t, i, x, y);
                    all &= v <= lim && v >= -lim;
                }
            }
        }
        if (rect_fits32(&t, x0, y0, x1, y1) != all) {
            sr_test_fail(__FILE__, __LINE__, "case %d: fits32 %d, every pixel %d", k, !all, all);
        }
        yes += all;
        no += !all;
    }
    if (!(yes > 100 && no > 100)) { /* both answers were reached */
        sr_test_fail(__FILE__, __LINE__, "yes %d, no %d", yes, no);
    }
}

SR_TEST(rect_classify_agrees_with_every_pixel_of_random_blocks)
{
    sr_rng rng = { 0xc1a5 };
    int rejected = 0, accepted = 0, partial = 0;
    for (int k = 0; k < 20000 && !sr_test_failed_now(); k++) {
        sr_tri t;
        /* Vertices in the block's neighbourhood, a few blocks either way,
         * in coverage order, so all three outcomes occur. */
        int bx = sr_rng_int(&rng, 0, 200) * SR_BLOCK_SIZE, by = sr_rng_int(&rng, 0, 200) * SR_BLOCK_SIZE;
        int64_t x[3], y[3];
        for (int v = 0; v < 3; v++) {
            x[v] = sr__centre_q8(bx) + sr_rng_int(&rng, -24 * 256, 32 * 256);
            y[v] = sr__centre_q8(by) + sr_rng_int(&rng, -24 * 256, 32 * 256);
        }
        if ((x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]) < 0) {
            int64_t tx = x[1], ty = y[1];
            x[1] = x[2], y[1] = y[2];
            x[2] = tx, y[2] = ty;
        }
        edges_from(&t, x, y);
        int64_t sx[3], sy[3], e[3];
        for (int i = 0; i < 3; i++) {
            sx[i] = (int64_t)t.a[i] * SR_SUBPIXEL_ONE;
            sy[i] = (int64_t)t.b[i] * SR_SUBPIXEL_ONE;
        }
        bool inside = false;
        sr_edges ed;
        sr__tri_edges(&t, &ed);
        bool any = sr__block_classify(&ed, bx, by, sx, sy, e, &inside);
        int covered = 0;
        for (int py = by; py < by + SR_BLOCK_SIZE; py++) {
            for (int px = bx; px < bx + SR_BLOCK_SIZE; px++) {
                bool in = true;
                for (int i = 0; i < 3; i++) {
                    in &= edge_at(&t, i, px, py) + sr__tri_bias(&t, i) >= 0;
                }
                covered += in;
            }
        }
        if (!any && covered) {
            sr_test_fail(__FILE__, __LINE__, "case %d: rejected with %d pixels covered", k, covered);
        }
        if (any && inside && covered != SR_BLOCK_SIZE * SR_BLOCK_SIZE) {
            sr_test_fail(__FILE__, __LINE__, "case %d: inside with %d pixels covered", k, covered);
        }
        if (any) {
            for (int i = 0; i < 3; i++) {
                CHECK_EQ(e[i], edge_at(&t, i, bx, by) + sr__tri_bias(&t, i));
            }
        }
        rejected += !any;
        accepted += any && inside;
        partial += any && !inside;
    }
    if (!(rejected > 100 && accepted > 100 && partial > 100)) {
        sr_test_fail(__FILE__, __LINE__, "rejected %d, accepted %d, partial %d", rejected,
                     accepted, partial);
    }
}

/* Setup's fits32 (the whole box of the triangle, from its vertex spans)
 * may only say yes where sr__rect_fits32 says yes over that box, and it
 * must say yes for the small triangles the kernels meet most.  Triangles
 * from a pixel to past the guard band, anywhere in it; multisampled
 * boxes (a pixel wider) too. */
SR_TEST(setup_fits32_implies_the_box_fits)
{
    sr_draw_state ds;
    memset(&ds, 0, sizeof ds);
    ds.depth_scale = 1.0;
    ds.zq_max = 1.0;
    ds.rect_x0 = SR_GUARD_BAND_MIN;
    ds.rect_y0 = SR_GUARD_BAND_MIN;
    ds.rect_x1 = SR_GUARD_BAND_MAX;
    ds.rect_y1 = SR_GUARD_BAND_MAX;
    sr_rng rng = { 0xf1757eedull };
    sr_tri t;
    int yes = 0, small_no = 0;
    for (int n = 0; n < 40000; n++) {
        ds.samples = n % 4 == 0 ? 4 : 1;
        double size = ldexp(1.0, sr_rng_int(&rng, 0, 16));   /* 1 .. 65536 px */
        double cx = sr_rng_range(&rng, SR_GUARD_BAND_MIN / 2, SR_GUARD_BAND_MAX / 2);
        double cy = sr_rng_range(&rng, SR_GUARD_BAND_MIN / 2, SR_GUARD_BAND_MAX / 2);
        sr_window_vertex w[3];
        memset(w, 0, sizeof w);
        for (int k = 0; k < 3; k++) {
            double x = cx + sr_rng_range(&rng, -size, size), y = cy + sr_rng_range(&rng, -size, size);
            x = x < SR_GUARD_BAND_MIN ? SR_GUARD_BAND_MIN : x > SR_GUARD_BAND_MAX ? SR_GUARD_BAND_MAX : x;
            y = y < SR_GUARD_BAND_MIN ? SR_GUARD_BAND_MIN : y > SR_GUARD_BAND_MAX ? SR_GUARD_BAND_MAX : y;
            w[k].x_q8 = (int32_t)(x * SR_SUBPIXEL_ONE);
            w[k].y_q8 = (int32_t)(y * SR_SUBPIXEL_ONE);
        }
        memset(&t, 0, sizeof t);
        if (sr__area2(&w[0], &w[1], &w[2]) == 0 ||
            !sr__setup_triangle(&ds, &w[0], &w[1], &w[2], true, 0, NULL, &t)) {
            continue;
        }
        if (t.fits32) {
            yes++;
            if (!rect_fits32(&t, t.h.x0, t.h.y0, t.h.x1, t.h.y1)) {
                sr_test_fail(__FILE__, __LINE__, "fits32 set, but the box [%d, %d) x [%d, %d) "
                             "does not fit", t.h.x0, t.h.x1, t.h.y0, t.h.y1);
                return;
            }
        } else if (size <= 64) {
            small_no++;
        }
    }
    CHECK(yes > 10000);     /* the flag is not trivially false */
    CHECK_EQ(small_no, 0);  /* nor false for triangles of up to 128 px a side */

    /* At the limit: right triangles filling half their box, whose long
     * edge reaches the box's area at the far corner, with spans around
     * sqrt(2^31) (181 px), both ways round and multisampled. */
    int near_yes = 0;
    for (int n = 0; n < 4000; n++) {
        ds.samples = n % 2 ? 4 : 1;
        int32_t wq = 46000 + sr_rng_int(&rng, -600, 600), hq = 46000 + sr_rng_int(&rng, -600, 600);
        int32_t ox = sr_rng_int(&rng, 0, 1 << 20), oy = sr_rng_int(&rng, 0, 1 << 20);
        sr_window_vertex w[3];
        memset(w, 0, sizeof w);
        w[0].x_q8 = ox, w[0].y_q8 = oy;
        w[1].x_q8 = ox + wq, w[1].y_q8 = oy;
        w[2].x_q8 = ox, w[2].y_q8 = oy + hq;
        if (n % 4 >= 2) {   /* the right angle at the other corner */
            w[0].x_q8 = ox + wq, w[0].y_q8 = oy + hq;
        }
        memset(&t, 0, sizeof t);
        if (!sr__setup_triangle(&ds, &w[0], &w[1], &w[2], true, 0, NULL, &t) || !t.fits32) {
            continue;
        }
        near_yes++;
        if (!rect_fits32(&t, t.h.x0, t.h.y0, t.h.x1, t.h.y1)) {
            sr_test_fail(__FILE__, __LINE__, "fits32 set for a %d x %d q8 right triangle whose "
                         "box does not fit", wq, hq);
            return;
        }
    }
    CHECK(near_yes > 500);  /* the limit is reached from both sides */
}
