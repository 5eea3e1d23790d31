/* test_draw2d_region.c - flood and boundary fill against a breadth-first
 * search reference on random images (4- and 8-connected, with and without
 * tolerance), the argument checks, and a fill of every pixel of an
 * 8192 x 8192 framebuffer.  Fixed seeds. */
#include "softrast.h"
#include "sr_test.h"
#include "target/framebuffer.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static sr_context *new_ctx(void)
{
    sr_context *ctx = NULL;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    return ctx;
}

static uint32_t pack(uint8_t r, uint8_t g, uint8_t b, uint8_t a)
{
    uint8_t c[4] = { r, g, b, a };
    uint32_t v;
    memcpy(&v, c, 4);
    return v;
}

static bool near(uint32_t a, uint32_t b, int tol)
{
    uint8_t x[4], y[4];
    memcpy(x, &a, 4);
    memcpy(y, &b, 4);
    for (int i = 0; i < 4; i++) {
        if (abs(x[i] - y[i]) > tol) {
            return false;
        }
    }
    return true;
}

/* Breadth-first reference: the connected set of pixels where
 * near(pixel, ref) == want, starting at the seed. */
static long bfs(const uint32_t *img, int w, int h, int sx, int sy, uint32_t ref, bool want,
                int tol, bool conn8, uint8_t *in)
{
    memset(in, 0, (size_t)w * h);
    if (near(img[sy * w + sx], ref, tol) != want) {
        return 0;
    }
    int *queue = malloc(sizeof(int) * (size_t)w * h);
    long head = 0, tail = 0, count = 0;
    queue[tail++] = sy * w + sx;
    in[sy * w + sx] = 1;
    while (head < tail) {
        int p = queue[head++], x = p % w, y = p / w;
        count++;
        for (int dy = -1; dy <= 1; dy++) {
            for (int dx = -1; dx <= 1; dx++) {
                if ((dx == 0 && dy == 0) || (!conn8 && dx && dy)) {
                    continue;
                }
                int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= w || ny >= h || in[ny * w + nx]) {
                    continue;
                }
                if (near(img[ny * w + nx], ref, tol) == want) {
                    in[ny * w + nx] = 1;
                    queue[tail++] = ny * w + nx;
                }
            }
        }
    }
    free(queue);
    return count;
}

SR_TEST(span_fills_equal_breadth_first_search_on_random_images)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    enum { W = 41, H = 29 };
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                             .depth_format = SR_DEPTH_NONE }, &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    (void)sr_framebuffer_pixels(fb); /* resolve the clear */
    sr_rng rng = { 0x5eed2d10u };
    static uint32_t img[W * H];
    static uint8_t in[W * H];
    const sr_rgba fill = { 1, 0, 1, 1 };
    const uint32_t fill_px = pack(255, 0, 255, 255);
    long mismatches = 0, runs = 0;
    for (int iter = 0; iter < 2000; iter++) {
        /* Two or three colors; with tolerance, nearby shades of them. */
        int tol = iter % 4 == 3 ? 8 : 0;
        double density = sr_rng_range(&rng, 0.2, 0.6);
        for (int p = 0; p < W * H; p++) {
            uint8_t v = sr_rng_unit(&rng) < density ? 200 : 40;
            if (iter % 3 == 2 && sr_rng_int(&rng, 0, 9) == 0) {
                v = 120;
            }
            if (tol) {
                v = (uint8_t)(v + sr_rng_int(&rng, -6, 6));
            }
            img[p] = pack(v, v, (uint8_t)(v / 2), 255);
        }
        int sx = sr_rng_int(&rng, 0, W - 1), sy = sr_rng_int(&rng, 0, H - 1);
        bool conn8 = iter % 2;
        bool boundary = (iter / 2) % 2;
        sr_region_fill_desc d = { conn8 ? SR_CONNECT_8 : SR_CONNECT_4, tol };
        memcpy(fb->color, img, sizeof img);
        size_t filled = 0;
        long want;
        if (boundary) {
            want = bfs(img, W, H, sx, sy, pack(200, 200, 100, 255), false, tol, conn8, in);
            REQUIRE(sr_boundary_fill(ctx, fb, sx, sy, fill, (sr_rgba){ 200 / 255.0f, 200 / 255.0f,
                                     100 / 255.0f, 1 }, &d, &filled) == SR_OK);
        } else {
            want = bfs(img, W, H, sx, sy, img[sy * W + sx], true, tol, conn8, in);
            REQUIRE(sr_flood_fill(ctx, fb, sx, sy, fill, &d, &filled) == SR_OK);
        }
        CHECK_EQ((long)filled, want);
        for (int p = 0; p < W * H; p++) {
            uint32_t expect = in[p] ? fill_px : img[p];
            mismatches += fb->color[p] != expect;
        }
        runs += want > 1;
    }
    CHECK_EQ(mismatches, 0);
    CHECK(runs > 500); /* most cases fill more than the seed */
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(diagonal_gap_leaks_only_when_8_connected)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) == SR_OK);
    for (int conn = SR_CONNECT_4; conn <= SR_CONNECT_8; conn++) {
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        /* a diagonal wall of white from (0,7) to (7,0): 4-connected regions
         * on either side touch only diagonally through it */
        sr_point2 wall[4] = { { 0, 8 }, { 8, 0 }, { 9, 0 }, { 1, 8 } };
        sr_fill_polygon(ctx, fb, &(sr_polygon2){ wall, 4, NULL, 0 }, (sr_rgba){ 1, 1, 1, 1 }, NULL);
        size_t n = 0;
        CHECK_EQ(sr_flood_fill(ctx, fb, 0, 0, (sr_rgba){ 1, 0, 0, 1 },
                               &(sr_region_fill_desc){ (sr_connectivity)conn, 0 }, &n), SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(fb);
        bool far_side = px[(7 * 8 + 7) * 4] == 255 && px[(7 * 8 + 7) * 4 + 1] == 0;
        CHECK_EQ(far_side, conn == SR_CONNECT_8);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(bad_region_fill_arguments_are_rejected)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) == SR_OK);
    sr_rgba red = { 1, 0, 0, 1 };
    CHECK_EQ(sr_flood_fill(NULL, fb, 0, 0, red, NULL, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_flood_fill(ctx, NULL, 0, 0, red, NULL, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_flood_fill(ctx, fb, 8, 0, red, NULL, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "outside");
    CHECK_EQ(sr_flood_fill(ctx, fb, 0, -1, red, NULL, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_flood_fill(ctx, fb, 0, 0, red, &(sr_region_fill_desc){ .tolerance = 256 }, NULL),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "tolerance");
    CHECK_EQ(sr_flood_fill(ctx, fb, 0, 0, red, &(sr_region_fill_desc){ .connectivity = 9 }, NULL),
             SR_INVALID_ARG);
    CHECK_EQ(sr_boundary_fill(ctx, fb, 0, 0, red, (sr_rgba){ NAN, 0, 0, 1 }, NULL, NULL),
             SR_INVALID_ARG);
    size_t n = 99;
    CHECK_EQ(sr_flood_fill(ctx, fb, 3, 3, red, NULL, &n), SR_OK);
    CHECK_EQ(n, 64);
    /* boundary fill started on the boundary color fills nothing */
    CHECK_EQ(sr_boundary_fill(ctx, fb, 3, 3, (sr_rgba){ 0, 1, 0, 1 }, red, NULL, &n), SR_OK);
    CHECK_EQ(n, 0);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(fill_of_a_whole_8192_square_framebuffer_completes)
{
    sr_context *ctx = new_ctx();
    REQUIRE(ctx);
    enum { S = SR_MAX_FRAMEBUFFER_SIZE };
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = S, .height = S,
                                                             .depth_format = SR_DEPTH_NONE }, &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    /* A serpentine of walls, so the region is one long winding corridor
     * (the worst case for a recursive fill), then the whole rest. */
    for (int k = 0; k < 64; k++) {
        double x = 64 + k * 128;
        double y0 = k % 2 ? 64 : 0, y1 = k % 2 ? S : S - 64;
        sr_point2 wall[4] = { { x, y0 }, { x + 8, y0 }, { x + 8, y1 }, { x, y1 } };
        sr_fill_polygon(ctx, fb, &(sr_polygon2){ wall, 4, NULL, 0 }, (sr_rgba){ 1, 1, 1, 1 }, NULL);
    }
    size_t n = 0;
    CHECK_EQ(sr_flood_fill(ctx, fb, 0, 0, (sr_rgba){ 0, 0, 1, 1 }, NULL, &n), SR_OK);
    CHECK_EQ((long long)n, (long long)S * S - 64LL * 8 * (S - 64));
    const uint8_t *px = sr_framebuffer_pixels(fb);
    CHECK_EQ(px[((size_t)(S - 1) * S + (S - 1)) * 4 + 2], 255);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
