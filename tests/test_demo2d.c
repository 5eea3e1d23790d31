/* test_demo2d.c - `softrast demo fill`, `demo floodfill`, `demo clip` and
 * `demo curves` end to end: the CLI renders each 2D toolkit demo at --scale 4 and the
 * image is compared with tests/ref/demo_NAME.png.
 *
 * Tolerance: a channel may be off by 2 and at most 0.5% of the pixels may
 * differ; on one machine the output is bit-exact, the slack absorbs libm
 * differences (cos, sin, acos) in the vector overlays. */
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <stdlib.h>
#include <string.h>

static void check_demo(const char *demo)
{
    char out[1024], name[64];
    snprintf(name, sizeof name, "demo_%s", demo);
    snprintf(out, sizeof out, "%s/%s.png", sr_test_out_dir(), name);
    int status = sr_test_run_cli((const char *[]){ "demo", demo, "--scale", "4", "-o", out, NULL });
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
    sr_test_check_image(name, px, w, h, 2, (long)w * h / 200);
    free(px);
}

SR_TEST(demo_fill_matches_reference) { check_demo("fill"); }
SR_TEST(demo_floodfill_matches_reference) { check_demo("floodfill"); }
SR_TEST(demo_clip_matches_reference) { check_demo("clip"); }
SR_TEST(demo_curves_matches_reference) { check_demo("curves"); }
