/* test_line_area_pixels.c - sr_line_area_pixels: the pixels of an
 * SR_LINE_AREA line (what `softrast explain area` shows) are the pixels
 * sr_draw_line writes, each with the covered area it blends, and each
 * area is A(x + 1) - A(x) of its row's strip. */
#include "sr_test.h"
#include "softrast.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 48
#define H 40

typedef struct cells {
    int n, cap;
    sr_line_area_info *c;
    int bad_strips;           /* strips that are not within their row */
} cells;

static void collect(void *user, const sr_line_area_info *p)
{
    cells *cs = user;
    if (cs->n == cs->cap) {
        cs->cap = cs->cap ? 2 * cs->cap : 64;
        cs->c = realloc(cs->c, (size_t)cs->cap * sizeof *cs->c);
        REQUIRE(cs->c);
    }
    bool ok = p->strip && p->strip_count >= 3;
    for (int i = 0; ok && i < p->strip_count; i++) {
        ok = p->strip[i].y >= p->y && p->strip[i].y <= p->y + 1;
    }
    cs->bad_strips += !ok;
    cs->c[cs->n] = *p;
    cs->c[cs->n++].strip = NULL;
}

/* Random lines of random widths and caps in every direction, ends at
 * 1/64 px and anywhere, some far outside, some of no length: the pixels'
 * coverage is exactly the opacity sr_draw_line writes (white over
 * transparent black: the alpha is the 8-bit coverage; every other pixel
 * stays transparent), each pixel once, row by row, and each area the
 * difference of its strip's areas left of its sides. */
SR_TEST(area_pixels_are_what_sr_draw_line_writes)
{
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    sr_rng rng = { 0xa4ea5u };
    cells cs = { 0 };
    static int cov8[H][W];
    int caps[3] = { 0 }, total = 0, partial = 0, dots = 0, bad_lines = 0;
    for (int n = 0; n < 3000; n++) {
        sr_point2 a, b;
        if (n % 10 == 9) {   /* far ends: only the rows on the framebuffer */
            a = (sr_point2){ sr_rng_range(&rng, -4000, 4000), sr_rng_range(&rng, -4000, 4000) };
            b = (sr_point2){ sr_rng_range(&rng, -4000, 4000), sr_rng_range(&rng, -4000, 4000) };
        } else if (n % 10 == 7) {   /* a dot: only square and round caps draw it */
            a = b = (sr_point2){ sr_rng_range(&rng, -3, W + 3), sr_rng_range(&rng, -3, H + 3) };
        } else if (n % 2) {
            a = (sr_point2){ sr_rng_int(&rng, -256, 56 * 64) / 64.0,
                             sr_rng_int(&rng, -256, 48 * 64) / 64.0 };
            b = (sr_point2){ sr_rng_int(&rng, -256, 56 * 64) / 64.0,
                             sr_rng_int(&rng, -256, 48 * 64) / 64.0 };
        } else {
            a = (sr_point2){ sr_rng_range(&rng, -3, W + 3), sr_rng_range(&rng, -3, H + 3) };
            b = (sr_point2){ a.x + sr_rng_range(&rng, -12, 12), a.y + sr_rng_range(&rng, -12, 12) };
        }
        /* thinner than a pixel to a few pixels, and now and then wide */
        double width = n % 7 == 0 ? sr_rng_range(&rng, 4, 24) : sr_rng_range(&rng, 0.05, 4);
        int cap = sr_rng_int(&rng, 0, 2);
        caps[cap]++;
        const sr_line_desc desc = { .algorithm = SR_LINE_AREA, .width = width,
                                    .cap = (sr_line_cap)(SR_LINE_CAP_BUTT + cap) };
        cs.n = 0;
        REQUIRE(sr_line_area_pixels(ctx, W, H, a, b, &desc, collect, &cs) == SR_OK);
        memset(cov8, 0xff, sizeof cov8);   /* -1: not visited */
        int bad = 0;
        for (int i = 0; i < cs.n; i++) {
            const sr_line_area_info *p = &cs.c[i];
            if (p->x < 0 || p->x >= W || p->y < 0 || p->y >= H || cov8[p->y][p->x] != -1) {
                bad++;   /* off the framebuffer, or twice */
                continue;
            }
            if (i && (p->y < cs.c[i - 1].y || (p->y == cs.c[i - 1].y && p->x <= cs.c[i - 1].x))) {
                bad++;   /* out of order */
            }
            float want = p->area > 1e-9 ? (float)(p->area > 1.0 ? 1.0 : p->area) : 0.0f;
            bad += p->area != p->right - p->left || p->drawn != (p->area > 1e-9) ||
                   p->coverage != want || p->left < -1e-9 || p->area > 1.0 + 1e-9;
            float c = p->coverage;
            cov8[p->y][p->x] = !p->drawn ? 0 : c >= 1.0f ? 255 : (int)(c * 255.0f + 0.5f);
            total += p->drawn;
            partial += p->drawn && c < 1.0f;
        }
        dots += a.x == b.x && a.y == b.y && cs.n > 0;
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
        REQUIRE(sr_draw_line(ctx, fb, a, b, (sr_rgba){ 1, 1, 1, 1 }, &desc) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(fb);
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                int want = cov8[y][x] < 0 ? 0 : cov8[y][x];
                bad += px[4 * (y * W + x) + 3] != want;
            }
        }
        if (bad) {
            printf("line (%.17g, %.17g) -> (%.17g, %.17g) width %.17g cap %d: %d pixels "
                   "differ\n", a.x, a.y, b.x, b.y, width, cap, bad);
            bad_lines++;
        }
    }
    CHECK_EQ(bad_lines, 0);
    CHECK_EQ(cs.bad_strips, 0);
    for (int i = 0; i < 3; i++) {
        CHECK(caps[i] > 800);
    }
    CHECK(total > 100000);
    CHECK(partial > 20000);
    CHECK(dots > 100);
    printf("%d pixels (%d partly covered) over 3000 lines, %d dots\n", total, partial, dots);
    free(cs.c);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* Unweighted area sampling keeps the area: the pixels' areas of a butt
 * line inside the framebuffer sum to w |ab|, whatever its slope. */
SR_TEST(area_pixels_sum_to_the_rectangles_area)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK);
    sr_rng rng = { 0xa4ea6u };
    cells cs = { 0 };
    for (int n = 0; n < 200; n++) {
        double width = sr_rng_range(&rng, 0.1, 6);
        double m = width / 2 + 0.01;
        sr_point2 a = { sr_rng_range(&rng, m, W - m), sr_rng_range(&rng, m, H - m) };
        sr_point2 b = { sr_rng_range(&rng, m, W - m), sr_rng_range(&rng, m, H - m) };
        cs.n = 0;
        REQUIRE(sr_line_area_pixels(ctx, W, H, a, b,
                                    &(sr_line_desc){ .algorithm = SR_LINE_AREA, .width = width },
                                    collect, &cs) == SR_OK);
        double sum = 0;
        for (int i = 0; i < cs.n; i++) {
            sum += cs.c[i].area;
        }
        CHECK_NEAR(sum, width * hypot(b.x - a.x, b.y - a.y), 1e-9 * W * H);
    }
    free(cs.c);
    sr_destroy_context(ctx);
}

static void count_cells(void *user, const sr_line_area_info *p)
{
    (void)p;
    (*(int *)user)++;
}

SR_TEST(area_pixels_refuses_bad_input)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK);
    int n = 0;
    const sr_line_desc area = { .algorithm = SR_LINE_AREA };
    sr_point2 a = { 1.5, 1.5 }, b = { 9.5, 1.5 };
    CHECK_EQ(sr_line_area_pixels(NULL, W, H, a, b, &area, count_cells, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, a, b, &area, NULL, &n), SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "fn is NULL") != NULL);
    CHECK_EQ(sr_line_area_pixels(ctx, 0, H, a, b, &area, count_cells, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_area_pixels(ctx, W, -1, a, b, &area, count_cells, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, (sr_point2){ NAN, 1 }, b, &area, count_cells, &n),
             SR_INVALID_ARG);
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, a, (sr_point2){ 1, 2e12 }, &area, count_cells, &n),
             SR_TOO_LARGE);
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, a, b,
                                 &(sr_line_desc){ .algorithm = SR_LINE_AREA, .width = -1 },
                                 count_cells, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, a, b,
                                 &(sr_line_desc){ .algorithm = SR_LINE_AREA, .width = 5000 },
                                 count_cells, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, a, b,
                                 &(sr_line_desc){ .algorithm = SR_LINE_AREA, .cap = 7 },
                                 count_cells, &n), SR_INVALID_ARG);
    /* Only the area-sampled line has areas: NULL is Bresenham's. */
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, a, b, NULL, count_cells, &n), SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "SR_LINE_AREA") != NULL);
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, a, b, &(sr_line_desc){ .algorithm = SR_LINE_WU },
                                 count_cells, &n), SR_INVALID_ARG);
    CHECK_EQ(n, 0);
    /* width 1 along the row centre y = 1.5: pixels 1 to 9 of row 1 */
    CHECK_EQ(sr_line_area_pixels(ctx, W, H, a, b, &area, count_cells, &n), SR_OK);
    CHECK_EQ(n, 9);
    sr_destroy_context(ctx);
}
