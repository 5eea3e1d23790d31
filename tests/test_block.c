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
#include <string.h>

/* Edge i's value at pixel (x, y)'s centre, unbiased. */
static int64_t edge_at(const sr_tri *t, int i, int x, int y)
{
    return t->a[i] * sr__centre_q8(x) + t->b[i] * sr__centre_q8(y) + t->c[i];
}

static void random_edges(sr_rng *rng, sr_tri *t, int64_t cmax)
{
    memset(t, 0, sizeof *t);
    int32_t amax = sr_rng_int(rng, 0, 3) == 0 ? (1 << 22) : 4096;
    for (int i = 0; i < 3; i++) {
        t->a[i] = sr_rng_int(rng, -amax, amax);
        t->b[i] = sr_rng_int(rng, -amax, amax);
        t->c[i] = (int64_t)sr_rng_range(rng, -(double)cmax, (double)cmax);
        t->bias[i] = sr_rng_int(rng, -1, 0);
    }
}

SR_TEST(fits32_goes_by_the_corner_values_up_to_the_limit)
{
    const int64_t lim = INT32_MAX - 1;
    sr_tri t;
    memset(&t, 0, sizeof t);
    /* Constant edges (a = b = 0): the value everywhere is c. */
    const struct { int64_t c; bool fits; } cases[] = {
        { 0, true }, { lim, true }, { -lim, true }, { lim + 1, false }, { -lim - 1, false },
        { (int64_t)1 << 40, false }, { -((int64_t)1 << 40), false },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        for (int i = 0; i < 3; i++) {
            t.c[0] = t.c[1] = t.c[2] = 0;
            t.c[i] = cases[k].c;
            if (sr__rect_fits32(&t, 10, 20, 14, 23) != cases[k].fits) {
                sr_test_fail(__FILE__, __LINE__, "edge %d = %lld everywhere: fits32 says %d", i,
                             (long long)cases[k].c, !cases[k].fits);
            }
        }
    }
    /* A slope along x, then along y: only the rectangle's last column
     * (row) crosses the limit, below and above. */
    for (int axis = 0; axis < 2; axis++) {
        for (int sign = -1; sign <= 1; sign += 2) {
            memset(&t, 0, sizeof t);
            int32_t *slope = axis ? &t.b[1] : &t.a[1];
            *slope = sign * 1000;
            t.c[1] = sign * (lim + 1) - *slope * sr__centre_q8(99); /* lim + 1 at 99 */
            int x1 = axis ? 5 : 100, y1 = axis ? 100 : 5;
            CHECK(!sr__rect_fits32(&t, axis ? 0 : 90, axis ? 90 : 0, x1, y1));
            CHECK(sr__rect_fits32(&t, axis ? 0 : 90, axis ? 90 : 0, x1 - !axis, y1 - axis));
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
        random_edges(&rng, &t, (int64_t)1 << 31);
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
        if (sr__rect_fits32(&t, x0, y0, x1, y1) != all) {
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
        /* Edges through the block's neighbourhood: offsets of a few
         * blocks, so all three outcomes occur. */
        random_edges(&rng, &t, 0);
        int bx = sr_rng_int(&rng, 0, 200) * SR_BLOCK_SIZE, by = sr_rng_int(&rng, 0, 200) * SR_BLOCK_SIZE;
        for (int i = 0; i < 3; i++) {
            int px = bx + sr_rng_int(&rng, -12, 20), py = by + sr_rng_int(&rng, -12, 20);
            t.c[i] = -(t.a[i] * sr__centre_q8(px) + t.b[i] * sr__centre_q8(py)) +
                     sr_rng_int(&rng, -300, 300);
        }
        int64_t sx[3], sy[3], e[3];
        for (int i = 0; i < 3; i++) {
            sx[i] = (int64_t)t.a[i] * SR_SUBPIXEL_ONE;
            sy[i] = (int64_t)t.b[i] * SR_SUBPIXEL_ONE;
        }
        bool inside = false;
        bool any = sr__block_classify(&t, bx, by, sx, sy, e, &inside);
        int covered = 0;
        for (int y = by; y < by + SR_BLOCK_SIZE; y++) {
            for (int x = bx; x < bx + SR_BLOCK_SIZE; x++) {
                bool in = true;
                for (int i = 0; i < 3; i++) {
                    in &= edge_at(&t, i, x, y) + t.bias[i] >= 0;
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
                CHECK_EQ(e[i], edge_at(&t, i, bx, by) + t.bias[i]);
            }
        }
        rejected += !any;
        accepted += any && inside;
        partial += any && !inside;
    }
    CHECK(rejected > 100 && accepted > 100 && partial > 100);
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
            if (!sr__rect_fits32(&t, t.h.x0, t.h.y0, t.h.x1, t.h.y1)) {
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
        if (!sr__rect_fits32(&t, t.h.x0, t.h.y0, t.h.x1, t.h.y1)) {
            sr_test_fail(__FILE__, __LINE__, "fits32 set for a %d x %d q8 right triangle whose "
                         "box does not fit", wq, hq);
            return;
        }
    }
    CHECK(near_yes > 500);  /* the limit is reached from both sides */
}
