/* test_draw2d_paint_row.c - the row blend (which reuses the last result
 * for runs of equal pixel and coverage) against sr__paint_pixel on every
 * pixel, byte for byte: random colors (opaque, translucent, linear
 * light), rows with runs of equal and of random pixels and coverages,
 * with and without a coverage array.  Fixed seeds. */
#include "draw2d/paint.h"
#include "sr_test.h"

#include <string.h>

SR_TEST(paint_row_equals_paint_pixel_on_every_pixel)
{
    enum { N = 97 };
    sr_rng rng = { 0x5eed2d0eu };
    long differ = 0, blended = 0;
    for (int iter = 0; iter < 4000; iter++) {
        sr_rgba color = { (float)sr_rng_unit(&rng), (float)sr_rng_unit(&rng),
                          (float)sr_rng_unit(&rng),
                          iter % 3 == 0 ? 1.0f : (float)sr_rng_range(&rng, -0.1, 1.1) };
        sr__paint p;
        REQUIRE(sr__paint_init(&p, color, iter % 5 == 0));
        uint32_t row[N], want[N];
        uint8_t cov[N];
        uint32_t px = 0;
        unsigned c = 255;
        for (int i = 0; i < N; i++) {
            /* Runs: keep the previous pixel or coverage most of the time. */
            if (sr_rng_int(&rng, 0, 3) == 0) {
                px = (uint32_t)sr_rng_next(&rng);
                px = sr_rng_int(&rng, 0, 2) == 0 ? 0 : px;
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
        sr__paint_row(&p, row, with_cov ? cov : NULL, N);
        differ += memcmp(row, want, sizeof row) != 0;
    }
    CHECK_EQ(differ, 0);
    CHECK(blended > 100000); /* the rows were really painted */
}
