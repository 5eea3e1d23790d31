/* test_draw2d_paint_row.c - the row blend (which reuses the last result
 * for runs of equal pixel and coverage, blends 4 or, at the AVX-512
 * level, 16 pixels at a time, and looks the blend over opaque pixels up in
 * a fill's table) against sr__paint_pixel on every pixel, byte for byte:
 * random colors (opaque, translucent, linear light), rows with runs of
 * equal and of random pixels (transparent, translucent, opaque) and
 * coverages, with and without a coverage array.  Fixed seeds. */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, for guard_alloc.h */
#include "draw2d/paint.h"
#include "guard_alloc.h"
#include "sr_test.h"

#include <string.h>

/* Whether this CPU runs the 16-pixel blend (sr__paint.wide). */
static bool cpu_runs_wide(void)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
#else
    return false;
#endif
}

SR_TEST(paint_row_equals_paint_pixel_on_every_pixel)
{
    enum { N = 97 };
    sr_rng rng = { 0x5eed2d0eu };
    long differ = 0, blended = 0, wide_rows = 0;
    bool wide = cpu_runs_wide();
    for (int iter = 0; iter < 4000; iter++) {
        sr_rgba color = { (float)sr_rng_unit(&rng), (float)sr_rng_unit(&rng),
                          (float)sr_rng_unit(&rng),
                          iter % 3 == 0 ? 1.0f : (float)sr_rng_range(&rng, -0.1, 1.1) };
        sr__paint p;
        REQUIRE(sr__paint_init(&p, color, iter % 5 == 0));
        uint32_t row[N], want[N], row16[N];
        uint8_t cov[N];
        uint32_t px = 0;
        unsigned c = 255;
        for (int i = 0; i < N; i++) {
            /* Runs: keep the previous pixel or coverage most of the time. */
            if (sr_rng_int(&rng, 0, 3) == 0) {
                px = (uint32_t)sr_rng_next(&rng);
                int kind = sr_rng_int(&rng, 0, 3);
                px = kind == 0 ? 0 : kind == 1 ? px | sr__pack_rgba8((uint8_t[4]){ 0, 0, 0, 255 })
                                                : px;
            }
            if (sr_rng_int(&rng, 0, 3) == 0) {
                c = (unsigned)sr_rng_int(&rng, 0, 3) == 0 ? 255u : (unsigned)sr_rng_int(&rng, 0, 255);
            }
            row[i] = want[i] = px;
            cov[i] = (uint8_t)c;
        }
        bool with_cov = iter % 2 == 0;
        for (int i = 0; i < N; i++) {
            sr__paint_pixel(&p, &want[i], with_cov ? cov[i] : 255);
            blended += want[i] != row[i];
        }
        memcpy(row16, row, sizeof row);
        sr__paint_row(&p, row, with_cov ? cov : NULL, N);
        differ += memcmp(row, want, sizeof row) != 0;
        if (wide) {
            p.wide = true;
            sr__paint_row(&p, row16, with_cov ? cov : NULL, N);
            differ += memcmp(row16, want, sizeof row) != 0;
            wide_rows++;
        }
    }
    CHECK_EQ(differ, 0);
    CHECK(!wide || wide_rows == 4000);
    CHECK(blended > 100000); /* the rows were really painted */
}

/* One memo kept over many rows of one paint (as a fill keeps it): pixels
 * and coverages drawn from small palettes, so pairs come back row after
 * row, from the memo, and collide in its slots. */
SR_TEST(paint_row_memo_over_many_rows_equals_paint_pixel)
{
    enum { N = 61, ROWS = 40, PALETTE = 200 };
    sr_rng rng = { 0x3e3001u };
    long differ = 0, hits = 0;
    bool wide = cpu_runs_wide();
    for (int iter = 0; iter < 300; iter++) {
        sr_rgba color = { (float)sr_rng_unit(&rng), (float)sr_rng_unit(&rng),
                          (float)sr_rng_unit(&rng),
                          iter % 4 == 0 ? 1.0f : (float)sr_rng_range(&rng, 0.0, 1.0) };
        sr__paint p;
        REQUIRE(sr__paint_init(&p, color, iter % 7 == 0));
        p.wide = wide && iter % 2 == 0;
        uint32_t palette[PALETTE];
        for (int k = 0; k < PALETTE; k++) {
            palette[k] = (uint32_t)sr_rng_next(&rng);
            if (k % 3 == 0) {
                palette[k] |= sr__pack_rgba8((uint8_t[4]){ 0, 0, 0, 255 });
            } else if (k % 3 == 1) { /* empty, with a color */
                palette[k] &= sr__pack_rgba8((uint8_t[4]){ 255, 255, 255, 0 });
            }
        }
        palette[1] = 0;
        sr__blend_memo memo;
        sr__blend_memo_init(&memo);
        int used = 2 + (int)sr_rng_int(&rng, 0, PALETTE - 2);
        for (int y = 0; y < ROWS; y++) {
            uint32_t row[N], want[N];
            uint8_t cov[N];
            int k = 0;
            unsigned c = 255;
            for (int i = 0; i < N; i++) {
                if (sr_rng_int(&rng, 0, 4) == 0) {
                    k = sr_rng_int(&rng, 0, used - 1);
                }
                if (sr_rng_int(&rng, 0, 5) == 0) {
                    c = sr_rng_int(&rng, 0, 2) == 0 ? 255u : (unsigned)sr_rng_int(&rng, 0, 8) * 31;
                }
                row[i] = want[i] = palette[k];
                cov[i] = (uint8_t)c;
            }
            bool with_cov = y % 3 != 0;
            for (int i = 0; i < N; i++) {
                sr__paint_pixel(&p, &want[i], with_cov ? cov[i] : 255);
            }
            sr__paint_row_memo(&p, &memo, row, with_cov ? cov : NULL, N);
            differ += memcmp(row, want, sizeof row) != 0;
        }
        for (int s = 0; s < SR__BLEND_MEMO; s++) {
            hits += memo.cov[s] != 256;
        }
    }
    CHECK_EQ(differ, 0);
    CHECK(hits > 300 * SR__BLEND_MEMO / 2); /* the memo was really filled */
}

#ifdef GUARD_ALLOC_WORKS
/* A block of `size` bytes ending at a guard page: a lane read or
 * written past a row's end faults. */
static void *guard_tail(guard *g, size_t size, void **block)
{
    size_t body = (size + 63) & ~(size_t)63;
    *block = guard_alloc(body, g);
    return *block ? (uint8_t *)*block + (body - size) : NULL;
}

/* A fill's memo kept over many rows of mostly opaque pixels at full
 * coverage, as a translucent shape over earlier opaque ones meets them:
 * the table is made and serves runs of them, cut by translucent and
 * empty pixels and partial coverage; rows of odd widths end at a guard
 * page, at both widths of the lanes (the table: AVX-512 with VBMI). */
SR_TEST(paint_row_table_over_opaque_pixels_equals_paint_pixel)
{
    enum { ROWS = 24, MAX_W = 200 };
    static const int widths[] = { 1, 3, 15, 16, 17, 31, 33, 47, 64, 97, 128, 131, 200 };
    sr_rng rng = { 0x7ab1e5u };
    guard g = { 0 };
    long differ = 0, made = 0, wide_fills = 0;
    bool wide = cpu_runs_wide();
#if defined(__x86_64__) && defined(__GNUC__)
    bool tables = wide && __builtin_cpu_supports("avx512vbmi");
#else
    bool tables = false;
#endif
    for (int iter = 0; iter < 400; iter++) {
        float alpha = iter % 10 == 0   ? 0.9999999f
                      : iter % 10 == 1 ? 0.001f
                                       : (float)sr_rng_range(&rng, 0.0, 1.0);
        sr_rgba color = { (float)sr_rng_unit(&rng), (float)sr_rng_unit(&rng),
                          (float)sr_rng_unit(&rng), iter % 17 == 0 ? 1.0f : alpha };
        sr__paint p;
        REQUIRE(sr__paint_init(&p, color, iter % 23 == 0));
        p.wide = wide && iter % 2 == 0;
        sr__blend_memo memo;
        sr__blend_memo_init(&memo);
        /* How often a pixel is not opaque, a coverage not full. */
        int rare = sr_rng_int(&rng, 8, 200);
        for (int y = 0; y < ROWS; y++) {
            int n = widths[sr_rng_int(&rng, 0, (int)(sizeof widths / sizeof widths[0]) - 1)];
            void *row_block, *cov_block;
            uint32_t *row = guard_tail(&g, (size_t)n * 4, &row_block);
            uint8_t *cov = guard_tail(&g, (size_t)n, &cov_block);
            REQUIRE(row && cov);
            uint32_t want[MAX_W];
            for (int i = 0; i < n; i++) {
                uint32_t px = (uint32_t)sr_rng_next(&rng);
                int kind = sr_rng_int(&rng, 0, rare);
                px = kind == 0 ? px & sr__pack_rgba8((uint8_t[4]){ 255, 255, 255, 0 })
                     : kind == 1 ? px
                                 : px | sr__pack_rgba8((uint8_t[4]){ 0, 0, 0, 255 });
                row[i] = want[i] = i > 0 && sr_rng_int(&rng, 0, 5) == 0 ? row[i - 1] : px;
                cov[i] = sr_rng_int(&rng, 0, rare) == 0 ? (uint8_t)sr_rng_int(&rng, 0, 255) : 255;
            }
            bool with_cov = y % 4 != 0;
            for (int i = 0; i < n; i++) {
                sr__paint_pixel(&p, &want[i], with_cov ? cov[i] : 255);
            }
            sr__paint_row_memo(&p, &memo, row, with_cov ? cov : NULL, n);
            differ += memcmp(row, want, (size_t)n * 4) != 0;
            guard_free(row_block, &g);
            guard_free(cov_block, &g);
        }
        made += memo.table_wait < 0;
        wide_fills += p.wide;
    }
    CHECK_EQ(differ, 0);
    CHECK_EQ(g.live, 0);
    /* The tables were really made (where this CPU makes them). */
    CHECK(tables ? made > wide_fills / 2 : made == 0);
}
#endif
