/* test_lines_demo.c - `softrast demo lines` end to end: the CLI renders
 * the line-algorithm star (every algorithm of sr_draw_line, magnified)
 * and the image is compared with tests/ref/demo_lines.png.
 *
 * Tolerance: a channel may be off by 2 and at most 0.5% of the pixels
 * may differ; on one machine the output is bit-exact, the slack absorbs
 * libm differences in the sRGB transfer functions (powf) that the
 * antialiased panels blend through. */
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <stdlib.h>
#include <string.h>


SR_TEST(demo_lines_matches_reference)
{
    char out[1024];
    snprintf(out, sizeof out, "%s/demo_lines.png", sr_test_out_dir());
    /* --scale 3 keeps the reference small; the docs show the default 6. */
    int status = sr_test_run_cli((const char *[]){ "demo", "lines", "--scale", "3", "-o", out, NULL });
    CHECK_EQ(status, 0);
    if (status != 0) {
        return;
    }
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(out, NULL, &w, &h, &px, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "reading %s: %s", out, err.message);
        return;
    }
    sr_test_check_image("demo_lines", px, w, h, 2, (long)w * h / 200);
    free(px);
}

SR_TEST(demo_lines_default_scale_is_6)
{
    char out[1024];
    snprintf(out, sizeof out, "%s/demo_lines_default.png", sr_test_out_dir());
    CHECK_EQ(sr_test_run_cli((const char *[]){ "demo", "lines", "-o", out, NULL }), 0);
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    REQUIRE(sr_read_png(out, NULL, &w, &h, &px, &err) == SR_OK);
    CHECK_EQ(w, 4 * 48 * 6 + 5 * 12);   /* default scale 6 */
    free(px);
}
