/* test_line_steps.c - sr_line_steps: the steps of an SR_LINE_WU line (what
 * `softrast explain wu` shows) are the pixels sr_draw_line writes, with
 * the weights it blends them with, and each step is Wu's: two pixels
 * straddling the intersection, weighted 1 - f and f times the column's
 * weight. */
#include "sr_test.h"
#include "softrast.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 48
#define H 40

typedef struct steps {
    int n, cap;
    sr_line_step_info *s;
} steps;

static void collect(void *user, const sr_line_step_info *step)
{
    steps *st = user;
    if (st->n == st->cap) {
        st->cap = st->cap ? 2 * st->cap : 64;
        st->s = realloc(st->s, (size_t)st->cap * sizeof *st->s);
        REQUIRE(st->s);
    }
    st->s[st->n++] = *step;
}

/* One step against Wu's rule; the pixels it draws added to cov8 (the
 * 8-bit coverage sr_draw_line blends with), 0 elsewhere. */
static void check_step(const sr_line_step_info *s, const sr_line_step_info *prev, bool y_major,
                       int cov8[H][W], int *drawn)
{
    CHECK_EQ(s->y_major, y_major);
    CHECK(fabs(s->gradient) <= 1.0);
    CHECK(s->weight >= 0.0 && s->weight <= 1.0 + 1e-12);
    if (prev) {
        /* In order; the columns that cannot reach the framebuffer are
         * skipped, except the ends. */
        CHECK(s->major > prev->major);
        CHECK(!prev->last_end && !s->first_end);
    }
    for (int i = 0; i < 2; i++) {
        int major = y_major ? s->y[i] : s->x[i], minor = y_major ? s->x[i] : s->y[i];
        CHECK_EQ(major, s->major);
        CHECK_EQ(minor, (y_major ? s->x[0] : s->y[0]) + i);
    }
    /* The pixels straddle the intersection: centres at +1/2. */
    double first_centre = (y_major ? s->x[0] : s->y[0]) + 0.5;
    CHECK(s->intersection >= first_centre && s->intersection < first_centre + 1.0);
    double f = s->intersection - first_centre;
    CHECK_NEAR(s->coverage[0], (1.0 - f) * s->weight, 1e-6);
    CHECK_NEAR(s->coverage[1], f * s->weight, 1e-6);
    for (int i = 0; i < 2; i++) {
        bool inside = s->x[i] >= 0 && s->x[i] < W && s->y[i] >= 0 && s->y[i] < H;
        CHECK_EQ(s->drawn[i], inside && s->coverage[i] > 0.0f);
        if (s->drawn[i]) {
            CHECK_EQ(cov8[s->y[i]][s->x[i]], -1);   /* each pixel once */
            float c = s->coverage[i];
            cov8[s->y[i]][s->x[i]] = c >= 1.0f ? 255 : (int)(c * 255.0f + 0.5f);
            (*drawn)++;
        }
    }
}

/* Random lines in every octant, ends at 1/64 px and anywhere, some far
 * outside: the steps' pixels and weights are exactly what sr_draw_line
 * writes white on black (the weight blended in linear light, then the
 * sRGB code; every other pixel stays black). */
SR_TEST(wu_steps_are_the_pixels_sr_draw_line_writes)
{
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    sr_rng rng = { 0x5eedu };
    steps st = { 0 };
    int octants[8] = { 0 }, total = 0, ends = 0;
    static int cov8[H][W];
    const sr_line_desc wu = { .algorithm = SR_LINE_WU };
    for (int n = 0; n < 3000; n++) {
        sr_point2 a, b;
        if (n % 10 == 9) {   /* far ends: only the visible steps are taken */
            a = (sr_point2){ sr_rng_range(&rng, -4000, 4000), sr_rng_range(&rng, -4000, 4000) };
            b = (sr_point2){ sr_rng_range(&rng, -4000, 4000), sr_rng_range(&rng, -4000, 4000) };
        } else if (n % 2) {
            a = (sr_point2){ sr_rng_int(&rng, -256, 56 * 64) / 64.0,
                             sr_rng_int(&rng, -256, 48 * 64) / 64.0 };
            b = (sr_point2){ sr_rng_int(&rng, -256, 56 * 64) / 64.0,
                             sr_rng_int(&rng, -256, 48 * 64) / 64.0 };
        } else {
            a = (sr_point2){ sr_rng_range(&rng, -3, W + 3), sr_rng_range(&rng, -3, H + 3) };
            b = (sr_point2){ a.x + sr_rng_range(&rng, -12, 12), a.y + sr_rng_range(&rng, -12, 12) };
        }
        double dx = b.x - a.x, dy = b.y - a.y;
        bool y_major = fabs(dy) > fabs(dx);
        octants[(dx < 0) * 4 + (dy < 0) * 2 + y_major]++;
        st.n = 0;
        REQUIRE(sr_line_steps(ctx, W, H, a, b, &wu, collect, &st) == SR_OK);
        memset(cov8, 0xff, sizeof cov8);   /* -1: not drawn */
        int drawn = 0;
        for (int i = 0; i < st.n; i++) {
            check_step(&st.s[i], i ? &st.s[i - 1] : NULL, y_major, cov8, &drawn);
            ends += st.s[i].first_end + st.s[i].last_end;
        }
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        REQUIRE(sr_draw_line(ctx, fb, a, b, (sr_rgba){ 1, 1, 1, 1 }, &wu) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(fb);
        int bad = 0;
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                int c = cov8[y][x] < 0 ? 0 : cov8[y][x];
                int want = sr_srgb_encode8((float)c / 255.0f), got = px[4 * (y * W + x)];
                bad += abs(got - want) > 1 || (c == 0) != (got == 0);
            }
        }
        if (bad) {
            printf("line (%.17g, %.17g) -> (%.17g, %.17g): %d pixels differ\n", a.x, a.y, b.x,
                   b.y, bad);
        }
        CHECK_EQ(bad, 0);
        total += drawn;
    }
    for (int o = 0; o < 8; o++) {
        CHECK(octants[o] > 100);
    }
    CHECK(total > 20000);
    CHECK(ends > 2000);
    printf("%d pixels over 3000 lines, %d end columns\n", total, ends);
    free(st.s);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

static void count_steps(void *user, const sr_line_step_info *step)
{
    (void)step;
    (*(int *)user)++;
}

SR_TEST(line_steps_refuses_bad_input)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK);
    int n = 0;
    const sr_line_desc wu = { .algorithm = SR_LINE_WU };
    sr_point2 a = { 1, 1 }, b = { 9, 4 };
    CHECK_EQ(sr_line_steps(NULL, W, H, a, b, &wu, count_steps, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_steps(ctx, W, H, a, b, &wu, NULL, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_steps(ctx, 0, H, a, b, &wu, count_steps, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_steps(ctx, W, -1, a, b, &wu, count_steps, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_line_steps(ctx, W, H, (sr_point2){ NAN, 1 }, b, &wu, count_steps, &n),
             SR_INVALID_ARG);
    CHECK_EQ(sr_line_steps(ctx, W, H, a, (sr_point2){ 1, 2e12 }, &wu, count_steps, &n),
             SR_TOO_LARGE);
    /* Only Wu's line is walked in steps. */
    CHECK_EQ(sr_line_steps(ctx, W, H, a, b, NULL, count_steps, &n), SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "SR_LINE_WU") != NULL);
    CHECK_EQ(n, 0);
    CHECK_EQ(sr_line_steps(ctx, W, H, a, b, &wu, count_steps, &n), SR_OK);
    CHECK_EQ(n, 9);   /* columns 1 to 9 */
    sr_destroy_context(ctx);
}
