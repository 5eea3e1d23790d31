/* test_draw2d_fill.c - polygon scan conversion against independent
 * references: the edge-table fill against a winding-number test at every
 * pixel centre (exact integers, same half-open conventions), shared-edge
 * subdivisions drawn exactly once, area coverage against polygon∩pixel
 * areas clipped in double, supersampling against per-sample winding, and
 * the argument checks.  Fixed seeds throughout. */
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define WIN 32

static sr_context *new_ctx(void)
{
    sr_context *ctx = NULL;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    return ctx;
}

/* Snap like the library: 1/256 pixel, round to nearest even. */
static int64_t q8(double v) { return (int64_t)nearbyint(v * 256.0); }

/* Winding number at the sample (X, Y) in q8, counting an edge when
 * y_min <= Y < y_max and its crossing is at or left of X. */
static int winding_at(const sr_point2 *pts, const int *counts, int contours, int64_t X, int64_t Y)
{
    int w = 0, start = 0;
    for (int c = 0; c < contours; c++) {
        for (int k = 0; k < counts[c]; k++) {
            const sr_point2 *a = &pts[start + k], *b = &pts[start + (k + 1) % counts[c]];
            int64_t ax = q8(a->x), ay = q8(a->y), bx = q8(b->x), by = q8(b->y);
            if (ay == by) {
                continue;
            }
            int dir = ay < by ? 1 : -1;
            if (ay > by) {
                int64_t t = ax; ax = bx; bx = t;
                t = ay; ay = by; by = t;
            }
            if (!(ay <= Y && Y < by)) {
                continue;
            }
            /* crossing x = ax + (Y - ay)(bx - ax)/(by - ay) <= X */
            if ((ax - X) * (by - ay) + (Y - ay) * (bx - ax) <= 0) {
                w += dir;
            }
        }
        start += counts[c];
    }
    return w;
}

static bool rule_inside(sr_fill_rule rule, int w)
{
    return rule == SR_EVENODD ? (w & 1) : w != 0;
}

/* A random polygon of 1..3 contours, 3..12 vertices each, around the
 * window; a third of the coordinates sit on the half-pixel grid so
 * vertices and edges hit pixel centres exactly. */
static int random_polygon(sr_rng *rng, sr_point2 *pts, int *counts, int *contours)
{
    int n = 0;
    *contours = sr_rng_int(rng, 1, 3);
    for (int c = 0; c < *contours; c++) {
        counts[c] = sr_rng_int(rng, 3, 12);
        for (int k = 0; k < counts[c]; k++) {
            double x = sr_rng_range(rng, -6, WIN + 6), y = sr_rng_range(rng, -6, WIN + 6);
            if (sr_rng_int(rng, 0, 2) == 0) {
                x = floor(x * 2) / 2;
                y = floor(y * 2) / 2;
            }
            pts[n++] = (sr_point2){ x, y };
        }
    }
    return n;
}

SR_TEST(edge_table_fill_equals_winding_test_at_pixel_centres)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_rng rng = { 0x5eed2d01u };
    uint8_t mask[WIN * WIN];
    sr_point2 pts[64];
    int counts[4], contours;
    long mismatches = 0;
    for (int iter = 0; iter < 10000; iter++) {
        int n = random_polygon(&rng, pts, counts, &contours);
        for (int r = 0; r < 2; r++) {
            sr_fill_rule rule = r ? SR_EVENODD : SR_NONZERO;
            sr_polygon2 poly = { pts, n, counts, contours };
            REQUIRE(sr_polygon_coverage(ctx, &poly, &(sr_fill_desc){ .rule = rule }, -2, -3,
                                        WIN, WIN, mask, WIN) == SR_OK);
            for (int y = 0; y < WIN; y++) {
                for (int x = 0; x < WIN; x++) {
                    int64_t X = (int64_t)(x - 2) * 256 + 128, Y = (int64_t)(y - 3) * 256 + 128;
                    bool want = rule_inside(rule, winding_at(pts, counts, contours, X, Y));
                    if ((mask[y * WIN + x] == 255) != want || (mask[y * WIN + x] != 0 && !want)) {
                        mismatches++;
                    }
                }
            }
        }
    }
    CHECK_EQ(mismatches, 0);
    sr_destroy_context(ctx);
}

/* A jittered grid of quads covering more than the window; each quad is one
 * polygon (random orientation), or split into two triangles.  Every pixel
 * must be filled exactly once. */
SR_TEST(shared_edge_subdivision_fills_every_pixel_exactly_once)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    enum { G = 9, W = 64 };
    sr_rng rng = { 0x5eed2d02u };
    for (int iter = 0; iter < 50; iter++) {
        sr_point2 grid[G + 1][G + 1];
        for (int j = 0; j <= G; j++) {
            for (int i = 0; i <= G; i++) {
                double x = -8 + i * 10.0, y = -8 + j * 10.0;
                if (i > 0 && i < G) {
                    x += sr_rng_range(&rng, -3.9, 3.9);
                }
                if (j > 0 && j < G) {
                    y += sr_rng_range(&rng, -3.9, 3.9);
                }
                if (iter % 2) { /* snap half of the runs to pixel centres */
                    x = floor(x) + 0.5;
                    y = floor(y) + 0.5;
                }
                grid[j][i] = (sr_point2){ x, y };
            }
        }
        uint16_t hits[W * W] = { 0 };
        uint8_t mask[W * W];
        for (int j = 0; j < G; j++) {
            for (int i = 0; i < G; i++) {
                sr_point2 q[4] = { grid[j][i], grid[j][i + 1], grid[j + 1][i + 1], grid[j + 1][i] };
                if (sr_rng_int(&rng, 0, 1)) {
                    sr_point2 t = q[1]; q[1] = q[3]; q[3] = t; /* reverse orientation */
                }
                /* Split along the diagonal that lies inside a concave quad. */
                double s1 = (q[2].x - q[0].x) * (q[1].y - q[0].y) - (q[2].y - q[0].y) * (q[1].x - q[0].x);
                double s3 = (q[2].x - q[0].x) * (q[3].y - q[0].y) - (q[2].y - q[0].y) * (q[3].x - q[0].x);
                if ((s1 > 0) == (s3 > 0)) {
                    sr_point2 t = q[0]; q[0] = q[1]; q[1] = q[2]; q[2] = q[3]; q[3] = t;
                }
                sr_point2 tris[2][3] = { { q[0], q[1], q[2] }, { q[0], q[2], q[3] } };
                bool split = (iter / 2) % 2;
                for (int part = 0; part < (split ? 2 : 1); part++) {
                    sr_polygon2 poly = { split ? tris[part] : q, split ? 3 : 4, NULL, 0 };
                    REQUIRE(sr_polygon_coverage(ctx, &poly, NULL, 0, 0, W, W, mask, W) == SR_OK);
                    for (int p = 0; p < W * W; p++) {
                        hits[p] += mask[p] == 255;
                    }
                }
            }
        }
        long bad = 0;
        for (int p = 0; p < W * W; p++) {
            bad += hits[p] != 1;
        }
        CHECK_EQ(bad, 0);
    }
    sr_destroy_context(ctx);
}

/* ---- area reference: clip to the pixel square, shoelace ---------------- */

static int clip_half(const sr_point2 *in, int n, sr_point2 *out, int axis, double v, bool keep_ge)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        sr_point2 a = in[i], b = in[(i + 1) % n];
        double ca = axis ? a.y : a.x, cb = axis ? b.y : b.x;
        bool ia = keep_ge ? ca >= v : ca <= v, ib = keep_ge ? cb >= v : cb <= v;
        if (ia) {
            out[m++] = a;
        }
        if (ia != ib) {
            double t = (v - ca) / (cb - ca);
            out[m++] = (sr_point2){ a.x + t * (b.x - a.x), a.y + t * (b.y - a.y) };
        }
    }
    return m;
}

static double area_in_pixel(const sr_point2 *poly, int n, int px, int py)
{
    sr_point2 a[256], b[256];
    int m = clip_half(poly, n, a, 0, px, true);
    m = clip_half(a, m, b, 0, px + 1, false);
    m = clip_half(b, m, a, 1, py, true);
    m = clip_half(a, m, b, 1, py + 1, false);
    double s = 0;
    for (int i = 0; i < m; i++) {
        s += b[i].x * b[(i + 1) % m].y - b[(i + 1) % m].x * b[i].y;
    }
    return fabs(s) / 2;
}

/* A simple (star-shaped) polygon with vertices on the 1/256 grid. */
static int star_polygon(sr_rng *rng, sr_point2 *pts, double cx, double cy, double rmax)
{
    int n = sr_rng_int(rng, 3, 24);
    double ang[32];
    for (int k = 0; k < n; k++) {
        ang[k] = sr_rng_range(rng, 0, 2 * M_PI);
    }
    for (int i = 1; i < n; i++) { /* sort angles */
        double v = ang[i];
        int j = i - 1;
        while (j >= 0 && ang[j] > v) {
            ang[j + 1] = ang[j];
            j--;
        }
        ang[j + 1] = v;
    }
    for (int k = 0; k < n; k++) {
        double r = sr_rng_range(rng, 0.2, 1.0) * rmax;
        pts[k] = (sr_point2){ nearbyint((cx + r * cos(ang[k])) * 256) / 256,
                              nearbyint((cy + r * sin(ang[k])) * 256) / 256 };
    }
    return n;
}

SR_TEST(area_coverage_is_within_one_level_of_exact_pixel_areas)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_rng rng = { 0x5eed2d03u };
    uint8_t mask[WIN * WIN];
    double worst = 0;
    for (int iter = 0; iter < 400; iter++) {
        sr_point2 pts[64];
        int counts[2];
        counts[0] = star_polygon(&rng, pts, 16 + sr_rng_range(&rng, -3, 3),
                                 16 + sr_rng_range(&rng, -3, 3), sr_rng_range(&rng, 3, 20));
        int contours = 1;
        bool hole = iter % 3 == 0;
        if (hole) { /* a small hole well inside: same polygon shrunk, reversed */
            counts[1] = 4;
            double cx = 0, cy = 0;
            for (int k = 0; k < counts[0]; k++) {
                cx += pts[k].x / counts[0];
                cy += pts[k].y / counts[0];
            }
            double r = 0.7;
            sr_point2 *h = pts + counts[0];
            h[0] = (sr_point2){ cx - r, cy - r };
            h[1] = (sr_point2){ cx - r, cy + r };
            h[2] = (sr_point2){ cx + r + 0.3, cy + r };
            h[3] = (sr_point2){ cx + r, cy - r };
            for (int k = 0; k < 4; k++) {
                h[k].x = nearbyint(h[k].x * 256) / 256;
                h[k].y = nearbyint(h[k].y * 256) / 256;
            }
            /* keep the hole inside a polygon that contains its box */
            bool ok = true;
            for (int k = 0; k < 4; k++) {
                int64_t X = q8(h[k].x), Y = q8(h[k].y);
                ok = ok && winding_at(pts, counts, 1, X, Y) != 0;
            }
            if (ok) {
                contours = 2;
            }
        }
        for (int r = 0; r < 2; r++) {
            sr_fill_rule rule = r ? SR_EVENODD : SR_NONZERO;
            if (contours == 2 && rule == SR_NONZERO) {
                continue; /* the reversed hole only matters for nonzero: tested below */
            }
            sr_polygon2 poly = { pts, counts[0] + (contours == 2 ? 4 : 0),
                                 counts, contours };
            REQUIRE(sr_polygon_coverage(ctx, &poly,
                                        &(sr_fill_desc){ .rule = rule, .antialias = SR_AA_AREA },
                                        0, 0, WIN, WIN, mask, WIN) == SR_OK);
            for (int y = 0; y < WIN; y++) {
                for (int x = 0; x < WIN; x++) {
                    double a = area_in_pixel(pts, counts[0], x, y);
                    if (contours == 2) {
                        a -= area_in_pixel(pts + counts[0], 4, x, y);
                    }
                    double err = fabs(mask[y * WIN + x] / 255.0 - a);
                    if (err > worst) {
                        worst = err;
                    }
                }
            }
        }
    }
    CHECK(worst <= 1.0 / 255.0);
    sr_destroy_context(ctx);
}

SR_TEST(area_coverage_with_a_reversed_hole_under_nonzero)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    /* outer clockwise (in y-down), inner counter-clockwise: a hole under
     * both rules; same-direction inner: a hole only under even-odd. */
    sr_point2 pts[8] = { { 2.3, 2.1 }, { 28.7, 2.1 }, { 28.7, 29.9 }, { 2.3, 29.9 },
                         { 10.25, 10.5 }, { 10.25, 20.75 }, { 20.5, 20.75 }, { 20.5, 10.5 } };
    int counts[2] = { 4, 4 };
    uint8_t a[WIN * WIN], b[WIN * WIN];
    sr_polygon2 poly = { pts, 8, counts, 2 };
    sr_polygon_coverage(ctx, &poly, &(sr_fill_desc){ .rule = SR_NONZERO, .antialias = SR_AA_AREA },
                        0, 0, WIN, WIN, a, WIN);
    sr_polygon_coverage(ctx, &poly, &(sr_fill_desc){ .rule = SR_EVENODD, .antialias = SR_AA_AREA },
                        0, 0, WIN, WIN, b, WIN);
    CHECK(memcmp(a, b, sizeof a) == 0);
    for (int y = 0; y < WIN; y++) {
        for (int x = 0; x < WIN; x++) {
            double e = area_in_pixel(pts, 4, x, y) - area_in_pixel(pts + 4, 4, x, y);
            CHECK_NEAR(a[y * WIN + x] / 255.0, e, 1.0 / 255.0);
        }
    }
    /* the hole's pixels are empty, the ring's full */
    CHECK_EQ(a[15 * WIN + 15], 0);
    CHECK_EQ(a[5 * WIN + 5], 255);
    sr_destroy_context(ctx);
}

SR_TEST(supersampling_counts_exact_per_sample_winding)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_rng rng = { 0x5eed2d04u };
    uint8_t mask[WIN * WIN];
    sr_point2 pts[64];
    int counts[4], contours;
    long bad = 0;
    for (int iter = 0; iter < 300; iter++) {
        int n = random_polygon(&rng, pts, counts, &contours);
        int s = 1 + iter % 5;
        sr_fill_rule rule = iter % 2 ? SR_EVENODD : SR_NONZERO;
        sr_polygon2 poly = { pts, n, counts, contours };
        REQUIRE(sr_polygon_coverage(ctx, &poly,
                                    &(sr_fill_desc){ .rule = rule, .antialias = SR_AA_SUPERSAMPLE,
                                                     .samples = s },
                                    0, 0, WIN, WIN, mask, WIN) == SR_OK);
        for (int y = 0; y < WIN; y++) {
            for (int x = 0; x < WIN; x++) {
                int hit = 0;
                for (int j = 0; j < s; j++) {
                    for (int i = 0; i < s; i++) {
                        /* sample (x + (i+1/2)/s, y + (j+1/2)/s): scale by s */
                        int64_t X = ((int64_t)x * s + i) * 256 + 128;
                        int64_t Y = ((int64_t)y * s + j) * 256 + 128;
                        sr_point2 sp[64];
                        for (int k = 0; k < n; k++) {
                            /* the library snaps first, then scales */
                            sp[k] = (sr_point2){ q8(pts[k].x) / 256.0 * s, q8(pts[k].y) / 256.0 * s };
                        }
                        hit += rule_inside(rule, winding_at(sp, counts, contours, X, Y));
                    }
                }
                int want = (hit * 255 + s * s / 2) / (s * s);
                bad += mask[y * WIN + x] != want;
            }
        }
    }
    CHECK_EQ(bad, 0);
    sr_destroy_context(ctx);
}

/* Clipping to the window must not change any pixel: a window is exactly
 * the same-sized slice of a larger window, for every converter. */
SR_TEST(coverage_window_is_a_slice_of_a_larger_window)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_rng rng = { 0x5eed2d05u };
    enum { BIG = 56, SUB = 17 };
    static uint8_t big[BIG * BIG], sub[SUB * SUB];
    sr_point2 pts[64];
    int counts[4], contours;
    long bad = 0;
    for (int iter = 0; iter < 600; iter++) {
        int n = random_polygon(&rng, pts, counts, &contours);
        sr_fill_desc d = { .rule = iter % 2 ? SR_EVENODD : SR_NONZERO,
                           .antialias = (sr_antialias)(SR_AA_NONE + iter % 3), .samples = 3 };
        sr_polygon2 poly = { pts, n, counts, contours };
        REQUIRE(sr_polygon_coverage(ctx, &poly, &d, -12, -12, BIG, BIG, big, BIG) == SR_OK);
        int ox = sr_rng_int(&rng, -12, BIG - 12 - SUB), oy = sr_rng_int(&rng, -12, BIG - 12 - SUB);
        REQUIRE(sr_polygon_coverage(ctx, &poly, &d, ox, oy, SUB, SUB, sub, SUB) == SR_OK);
        for (int y = 0; y < SUB; y++) {
            for (int x = 0; x < SUB; x++) {
                int want = big[(y + oy + 12) * BIG + (x + ox + 12)];
                /* area sums may round differently by one level */
                bad += abs(sub[y * SUB + x] - want) > (d.antialias == SR_AA_AREA ? 1 : 0);
            }
        }
    }
    CHECK_EQ(bad, 0);
    sr_destroy_context(ctx);
}

SR_TEST(even_odd_and_nonzero_differ_on_a_pentagram)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_point2 star[5];
    for (int k = 0; k < 5; k++) {
        double a = -M_PI / 2 + k * 4 * M_PI / 5;
        star[k] = (sr_point2){ 16 + 14 * cos(a), 16 + 14 * sin(a) };
    }
    sr_polygon2 poly = { star, 5, NULL, 0 };
    uint8_t nz[WIN * WIN], eo[WIN * WIN];
    sr_polygon_coverage(ctx, &poly, &(sr_fill_desc){ .rule = SR_NONZERO }, 0, 0, WIN, WIN, nz, WIN);
    sr_polygon_coverage(ctx, &poly, &(sr_fill_desc){ .rule = SR_EVENODD }, 0, 0, WIN, WIN, eo, WIN);
    CHECK_EQ(nz[16 * WIN + 16], 255); /* centre: winding 2 */
    CHECK_EQ(eo[16 * WIN + 16], 0);
    long only_nz = 0;
    for (int p = 0; p < WIN * WIN; p++) {
        CHECK(!(eo[p] && !nz[p]));
        only_nz += nz[p] && !eo[p];
    }
    CHECK(only_nz > 50);
    sr_destroy_context(ctx);
}

SR_TEST(fill_polygon_blends_and_clips_to_the_framebuffer)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 16, .height = 16 }, &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 1, 1 } });
    sr_point2 big[4] = { { -1000, -1000 }, { 1000, -1000 }, { 1000, 1000 }, { -1000, 1000 } };
    sr_polygon2 poly = { big, 4, NULL, 0 };
    for (int aa = SR_AA_NONE; aa <= SR_AA_SUPERSAMPLE; aa++) {
        CHECK_EQ(sr_fill_polygon(ctx, fb, &poly, (sr_rgba){ 1, 0, 0, 0.5f },
                                 &(sr_fill_desc){ .antialias = (sr_antialias)aa }), SR_OK);
    }
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int p = 0; p < 16 * 16; p++) {
        /* three layers of half red over blue: red 1 - 1/8, blue 1/8 */
        CHECK_NEAR(px[p * 4 + 0], 223, 2);
        CHECK_NEAR(px[p * 4 + 2], 32, 2);
        CHECK_EQ(px[p * 4 + 3], 255);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(partial_coverage_over_transparent_pixels_keeps_the_color)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 3, .height = 1 }, &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    /* pixel 0: a quarter of it in orange over transparent: the color
     * stays orange (straight alpha), only alpha is 1/4; pixel 1: then
     * half of it in blue over that: alpha 1/4 + 1/2 (3/4) = 5/8, color
     * (blue 1/2 + orange 1/8) / (5/8); pixel 2: opaque, as before */
    sr_point2 a[4] = { { 0, 0 }, { 0.25, 0 }, { 0.25, 1 }, { 0, 1 } };
    sr_point2 b[4] = { { 1, 0 }, { 1.25, 0 }, { 1.25, 1 }, { 1, 1 } };
    sr_point2 c[4] = { { 1, 0 }, { 1.5, 0 }, { 1.5, 1 }, { 1, 1 } };
    sr_fill_desc aa = { .antialias = SR_AA_AREA };
    sr_fill_polygon(ctx, fb, &(sr_polygon2){ a, 4, NULL, 0 }, (sr_rgba){ 1, 0.5f, 0, 1 }, &aa);
    sr_fill_polygon(ctx, fb, &(sr_polygon2){ b, 4, NULL, 0 }, (sr_rgba){ 1, 0.5f, 0, 1 }, &aa);
    sr_fill_polygon(ctx, fb, &(sr_polygon2){ c, 4, NULL, 0 }, (sr_rgba){ 0, 0, 1, 1 }, &aa);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    CHECK_NEAR(px[0], 255, 1);
    CHECK_NEAR(px[1], 128, 1);
    CHECK_NEAR(px[3], 64, 1);
    CHECK_NEAR(px[4], 51, 1);  /* 255 * (1/8) / (5/8) */
    CHECK_NEAR(px[6], 204, 1); /* 255 * (1/2) / (5/8) */
    CHECK_NEAR(px[7], 159, 1);
    CHECK_EQ(px[11], 0);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(partial_coverage_blends_in_linear_light_on_request)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 2, .height = 1 }, &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    /* half of pixel 0 (sRGB: 50% of 255), half of pixel 1 in linear light:
     * linear 0.5 is sRGB 0.7354 -> 188 */
    sr_point2 a[4] = { { 0, 0 }, { 0.5, 0 }, { 0.5, 1 }, { 0, 1 } };
    sr_point2 b[4] = { { 1, 0 }, { 1.5, 0 }, { 1.5, 1 }, { 1, 1 } };
    sr_fill_polygon(ctx, fb, &(sr_polygon2){ a, 4, NULL, 0 }, (sr_rgba){ 1, 1, 1, 1 },
                    &(sr_fill_desc){ .antialias = SR_AA_AREA });
    sr_fill_polygon(ctx, fb, &(sr_polygon2){ b, 4, NULL, 0 }, (sr_rgba){ 1, 1, 1, 1 },
                    &(sr_fill_desc){ .antialias = SR_AA_AREA, .linear_light = true });
    const uint8_t *px = sr_framebuffer_pixels(fb);
    CHECK_NEAR(px[0], 128, 1);
    CHECK_NEAR(px[4], 188, 1);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(bad_polygons_and_descs_are_rejected)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    uint8_t mask[16];
    sr_point2 tri[3] = { { 0, 0 }, { 4, 0 }, { 0, 4 } };
    sr_polygon2 ok = { tri, 3, NULL, 0 };
    CHECK_EQ(sr_polygon_coverage(NULL, &ok, NULL, 0, 0, 4, 4, mask, 4), SR_INVALID_ARG);
    CHECK_EQ(sr_polygon_coverage(ctx, NULL, NULL, 0, 0, 4, 4, mask, 4), SR_INVALID_ARG);
    CHECK_EQ(sr_polygon_coverage(ctx, &ok, NULL, 0, 0, 4, 4, NULL, 4), SR_INVALID_ARG);
    CHECK_EQ(sr_polygon_coverage(ctx, &ok, NULL, 0, 0, 0, 4, mask, 4), SR_INVALID_ARG);
    CHECK_EQ(sr_polygon_coverage(ctx, &ok, NULL, 0, 0, 4, 4, mask, 3), SR_INVALID_ARG);
    CHECK_EQ(sr_polygon_coverage(ctx, &ok, &(sr_fill_desc){ .rule = (sr_fill_rule)7 }, 0, 0, 4, 4,
                                 mask, 4), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "rule");
    CHECK_EQ(sr_polygon_coverage(ctx, &ok, &(sr_fill_desc){ .antialias = SR_AA_SUPERSAMPLE,
                                                            .samples = 17 }, 0, 0, 4, 4, mask, 4),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "samples");
    sr_point2 nan_pt[3] = { { 0, 0 }, { NAN, 0 }, { 0, 4 } };
    CHECK_EQ(sr_polygon_coverage(ctx, &(sr_polygon2){ nan_pt, 3, NULL, 0 }, NULL, 0, 0, 4, 4, mask, 4),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "points[1]");
    /* beyond the fixed-point budget: drawn, cut to a guard band */
    sr_point2 far_pt[3] = { { 0, 0 }, { 1e7, 0 }, { 0, 4 } };
    CHECK_EQ(sr_polygon_coverage(ctx, &(sr_polygon2){ far_pt, 3, NULL, 0 }, NULL, 0, 0, 4, 4, mask, 4),
             SR_OK);
    for (int i = 0; i < 16; i++) {
        CHECK_EQ(mask[i], 255);
    }
    int counts[2] = { 2, 2 };
    CHECK_EQ(sr_polygon_coverage(ctx, &(sr_polygon2){ tri, 3, counts, 2 }, NULL, 0, 0, 4, 4, mask, 4),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "contour_counts");
    /* empty and degenerate polygons draw nothing and succeed */
    CHECK_EQ(sr_polygon_coverage(ctx, &(sr_polygon2){ NULL, 0, NULL, 0 }, NULL, 0, 0, 4, 4, mask, 4),
             SR_OK);
    sr_point2 flat[3] = { { 0, 1 }, { 4, 1 }, { 2, 1 } };
    CHECK_EQ(sr_polygon_coverage(ctx, &(sr_polygon2){ flat, 3, NULL, 0 },
                                 &(sr_fill_desc){ .antialias = SR_AA_AREA }, 0, 0, 4, 4, mask, 4), SR_OK);
    for (int i = 0; i < 16; i++) {
        CHECK_EQ(mask[i], 0);
    }
    sr_destroy_context(ctx);
}
