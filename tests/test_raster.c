/* test_raster.c - triangle coverage: the top-left fill rule, watertight
 * shared edges, fans, and the three rasterizers (half-space, scanline
 * edge walking, barycentric bounding box) against an independent
 * reference and against each other.  Fixed seeds throughout. */
#include "raster_util.h"
#include "raster/fixed.h"

static const sr_rasterizer all_rasterizers[] = {
    SR_RASTER_HALFSPACE, SR_RASTER_SCANLINE, SR_RASTER_BARYCENTRIC
};

static int count_mask(const uint8_t *m, int n)
{
    int c = 0;
    for (int i = 0; i < n; i++) {
        c += m[i];
    }
    return c;
}

/* Direct3D's worked example: in integer-centre coordinates the triangles
 * (0,0)(5,0)(5,5) and (0,5)(0,0)(5,5) cover 15 and 10 pixels; softrast
 * puts centres at +0.5, so the same triangles are shifted by half a pixel. */
SR_TEST(d3d_worked_example_covers_15_and_10_pixels)
{
    const double a[] = { 0.5, 0.5, 5.5, 0.5, 5.5, 5.5 };
    const double b[] = { 0.5, 5.5, 0.5, 0.5, 5.5, 5.5 };
    uint8_t mask[16 * 16], ma[16 * 16];
    for (int r = 0; r < 3; r++) {
        rt_target t = rt_make(16, 16, 1);
        rt_clear(&t);
        REQUIRE(rt_draw_tris(&t, a, 1, NULL, all_rasterizers[r]) == SR_OK);
        rt_mask(&t, ma);
        CHECK_EQ(count_mask(ma, 256), 15);
        rt_clear(&t);
        REQUIRE(rt_draw_tris(&t, b, 1, NULL, all_rasterizers[r]) == SR_OK);
        rt_mask(&t, mask);
        CHECK_EQ(count_mask(mask, 256), 10);
        for (int i = 0; i < 256; i++) {
            CHECK(!(mask[i] && ma[i]));
        }
        rt_free(&t);
    }
}

/* Draw each triangle alone and add up the masks. */
static void count_cover(rt_target *t, const double *xy, int ntri, sr_rasterizer rast, int *count)
{
    uint8_t *m = malloc((size_t)t->w * t->h);
    memset(count, 0, sizeof(int) * (size_t)t->w * t->h);
    for (int k = 0; k < ntri; k++) {
        rt_clear(t);
        rt_draw_tris(t, xy + k * 6, 1, NULL, rast);
        rt_mask(t, m);
        for (int i = 0; i < t->w * t->h; i++) {
            count[i] += m[i];
        }
    }
    free(m);
}

static double q8(sr_rng *rng, double lo, double hi)
{
    return floor(sr_rng_range(rng, lo, hi) * 256.0) / 256.0;
}

/* A square split along a diagonal, rotated through every direction and
 * shifted by sub-pixel offsets: every pixel is drawn at most once, and
 * exactly the pixels of the reference union are drawn. */
SR_TEST(shared_edge_in_every_orientation_is_drawn_exactly_once)
{
    rt_target t = rt_make(64, 64, 1);
    int count[64 * 64];
    uint8_t r1[64 * 64], r2[64 * 64];
    sr_rng rng = { 0x5eed1 };
    for (int step = 0; step < 72; step++) {
        double ang = step * (M_PI / 36.0);
        double cx = 32 + q8(&rng, -1, 1), cy = 32 + q8(&rng, -1, 1), rad = 20;
        double p[4][2];
        for (int k = 0; k < 4; k++) {
            p[k][0] = floor((cx + rad * cos(ang + k * M_PI / 2)) * 256) / 256;
            p[k][1] = floor((cy + rad * sin(ang + k * M_PI / 2)) * 256) / 256;
        }
        double xy[12] = { p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1],
                          p[0][0], p[0][1], p[2][0], p[2][1], p[3][0], p[3][1] };
        for (int r = 0; r < 3; r++) {
            count_cover(&t, xy, 2, all_rasterizers[r], count);
            ref_cover(xy, 64, 64, r1);
            ref_cover(xy + 6, 64, 64, r2);
            for (int i = 0; i < 64 * 64; i++) {
                CHECK(count[i] <= 1);
                CHECK_EQ(count[i], r1[i] + r2[i]);
            }
        }
    }
    rt_free(&t);
}

/* Fans of 3..200 triangles around a centre at a random sub-pixel position,
 * closing the ring: no pixel twice, and no hole strictly inside the ring. */
SR_TEST(fans_around_a_vertex_have_no_overlap_and_no_holes)
{
    rt_target t = rt_make(64, 64, 1);
    static int count[64 * 64];
    sr_rng rng = { 0xfa45 };
    int sizes[] = { 3, 4, 5, 7, 12, 31, 64, 97, 150, 200 };
    for (unsigned s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        int n = sizes[s];
        double cx = q8(&rng, 28, 36), cy = q8(&rng, 28, 36);
        double *xy = malloc(sizeof(double) * 6 * (size_t)n);
        double (*ring)[2] = malloc(sizeof(double) * 2 * (size_t)n);
        double phase = sr_rng_unit(&rng);
        for (int k = 0; k < n; k++) {
            double ang = (k + phase) * 2 * M_PI / n;
            double rad = q8(&rng, 18, 26);
            ring[k][0] = floor((cx + rad * cos(ang)) * 256) / 256;
            ring[k][1] = floor((cy + rad * sin(ang)) * 256) / 256;
        }
        for (int k = 0; k < n; k++) {
            double tri[6] = { cx, cy, ring[k][0], ring[k][1], ring[(k + 1) % n][0], ring[(k + 1) % n][1] };
            memcpy(xy + k * 6, tri, sizeof tri);
        }
        count_cover(&t, xy, n, SR_RASTER_HALFSPACE, count);
        /* Strictly inside the ring polygon (star-shaped about the centre):
         * inside some fan triangle with every edge value > 0 by a margin. */
        for (int py = 0; py < 64; py++) {
            for (int px = 0; px < 64; px++) {
                int i = py * 64 + px;
                CHECK(count[i] <= 1);
                int64_t sx = px * 256 + 128, sy = py * 256 + 128;
                bool strictly_inside_ring = true;
                for (int k = 0; k < n; k++) {
                    int64_t ax = ref_snap(ring[k][0]), ay = ref_snap(ring[k][1]);
                    int64_t bx = ref_snap(ring[(k + 1) % n][0]), by = ref_snap(ring[(k + 1) % n][1]);
                    int64_t e = ref_edge(ax, ay, bx, by, sx, sy);
                    /* Ring runs with increasing angle (clockwise on a
                     * y-down screen): inside is e > 0. */
                    strictly_inside_ring &= e > 0;
                }
                if (strictly_inside_ring) {
                    CHECK_EQ(count[i], 1);
                }
            }
        }
        free(xy);
        free(ring);
    }
    rt_free(&t);
}

/* 10,000 random pairs of triangles sharing an edge, drawn together: the
 * shared edge's pixels go to exactly one of them. */
SR_TEST(random_triangle_pairs_share_edges_exactly)
{
    rt_target t = rt_make(32, 32, 1);
    int count[32 * 32];
    uint8_t r1[32 * 32], r2[32 * 32];
    sr_rng rng = { 0xbeef };
    long bad = 0;
    for (int it = 0; it < 10000; it++) {
        double a[2] = { q8(&rng, 0, 32), q8(&rng, 0, 32) };
        double b[2] = { q8(&rng, 0, 32), q8(&rng, 0, 32) };
        double c[2] = { q8(&rng, -4, 36), q8(&rng, -4, 36) };
        /* d on the other side of ab: reflect c across the midpoint and jitter. */
        double d[2] = { a[0] + b[0] - c[0] + q8(&rng, -2, 2), a[1] + b[1] - c[1] + q8(&rng, -2, 2) };
        int64_t sc = ref_edge(ref_snap(a[0]), ref_snap(a[1]), ref_snap(b[0]), ref_snap(b[1]),
                              ref_snap(c[0]), ref_snap(c[1]));
        int64_t sd = ref_edge(ref_snap(a[0]), ref_snap(a[1]), ref_snap(b[0]), ref_snap(b[1]),
                              ref_snap(d[0]), ref_snap(d[1]));
        if (!((sc > 0 && sd < 0) || (sc < 0 && sd > 0))) {
            it--; /* not a pair across ab: draw another */
            continue;
        }
        double xy[12] = { a[0], a[1], b[0], b[1], c[0], c[1], b[0], b[1], a[0], a[1], d[0], d[1] };
        int rast = it % 3;
        count_cover(&t, xy, 2, all_rasterizers[rast], count);
        ref_cover(xy, 32, 32, r1);
        ref_cover(xy + 6, 32, 32, r2);
        for (int i = 0; i < 32 * 32; i++) {
            bad += count[i] != r1[i] + r2[i];
            /* Opposite sides of ab: the two triangles cannot both own a pixel. */
            bad += count[i] > 1;
        }
    }
    CHECK_EQ(bad, 0);
    rt_free(&t);
}

/* Every rasterizer equals the independent reference on random triangles,
 * including needles, tiny and degenerate ones. */
SR_TEST(rasterizers_match_the_reference_on_random_triangles)
{
    rt_target t = rt_make(64, 64, 1);
    uint8_t got[64 * 64], want[64 * 64];
    sr_rng rng = { 0x1234 };
    long mismatches = 0;
    for (int it = 0; it < 3000; it++) {
        double xy[6];
        int kind = it % 4;
        for (int k = 0; k < 3; k++) {
            if (kind == 0) {          /* anywhere, partly off screen */
                xy[k * 2] = q8(&rng, -20, 84);
                xy[k * 2 + 1] = q8(&rng, -20, 84);
            } else if (kind == 1) {   /* small */
                xy[k * 2] = 30 + q8(&rng, 0, 3);
                xy[k * 2 + 1] = 30 + q8(&rng, 0, 3);
            } else if (kind == 2) {   /* on the pixel-centre grid: ties */
                xy[k * 2] = sr_rng_int(&rng, 0, 63) + 0.5;
                xy[k * 2 + 1] = sr_rng_int(&rng, 0, 63) + 0.5;
            } else {                  /* needles */
                double base = q8(&rng, 0, 64);
                xy[k * 2] = k == 2 ? q8(&rng, 0, 64) : base + k / 256.0;
                xy[k * 2 + 1] = q8(&rng, 0, 64);
            }
        }
        ref_cover(xy, 64, 64, want);
        for (int r = 0; r < 3; r++) {
            rt_clear(&t);
            rt_draw_tris(&t, xy, 1, NULL, all_rasterizers[r]);
            rt_mask(&t, got);
            mismatches += memcmp(got, want, sizeof got) != 0;
        }
    }
    CHECK_EQ(mismatches, 0);
    rt_free(&t);
}

/* The three rasterizers give byte-identical images with interpolated
 * colors too (same samples, same barycentrics), and so do 1 and 3 threads. */
SR_TEST(rasterizers_and_thread_counts_give_identical_bytes)
{
    enum { N = 400, W = 4 * SR_TILE_SIZE, H = 2 * SR_TILE_SIZE }; /* 4 x 2 tiles */
    double *xy = malloc(sizeof(double) * 6 * N);
    float *col = malloc(sizeof(float) * 12 * N);
    sr_rng rng = { 0xc0102 };
    for (int i = 0; i < N * 3; i++) {
        xy[i * 2] = q8(&rng, -10, W + 10);
        xy[i * 2 + 1] = q8(&rng, -10, H + 10);
        for (int c = 0; c < 3; c++) {
            col[i * 4 + c] = (float)sr_rng_unit(&rng);
        }
        col[i * 4 + 3] = 1;
    }
    uint8_t *first = NULL;
    int variants = 0;
    for (int r = 0; r < 3; r++) {
        for (int threads = 1; threads <= 3; threads += 2) {
            rt_target t = rt_make(W, H, threads);
            rt_clear(&t);
            REQUIRE(rt_draw_tris(&t, xy, N, col, all_rasterizers[r]) == SR_OK);
            const uint8_t *px = sr_framebuffer_pixels(t.fb);
            if (!first) {
                first = malloc(W * H * 4);
                memcpy(first, px, W * H * 4);
            } else {
                CHECK(memcmp(first, px, W * H * 4) == 0);
            }
            variants++;
            rt_free(&t);
        }
    }
    CHECK_EQ(variants, 6);
    free(first);
    free(xy);
    free(col);
}
