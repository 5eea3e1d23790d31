/* test_demo_aa.c - `softrast demo aa` end to end: the image through the
 * CLI, compared with tests/ref/demo_aa.png (a channel may be off by 2 on
 * at most 0.5% of the pixels, as in test_demo3d.c; SR_UPDATE_REFS=1
 * rewrites the reference), then the antialiasing measured in its panels
 * (DEMO3D_LAYOUT_AA at DEMO3D_AA_SCALE; each panel pixel is read at the
 * centre of its magnified block, clear of the pixel grid drawn over it).
 *
 * The shapes are unlit ink on a flat ground, so a pixel's red channel is
 * its coverage: c = (R - R_ground) / (R_ink - R_ground).  The exact-area
 * panel is the box-filtered truth; the others are compared with it. */
#include "../apps/softrast/demo3d_layout.h"
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>

/* Panel indices, row-major, as in apps/softrast/demo_aa.c. */
enum { NO_AA, MSAA4, MSAA8, MSAA16, EXACT, POS4, POS8, POS16, BOX, TENT, GAUSS, MITCHELL };

typedef struct image {
    int w, h;
    uint8_t *px;
} image;

static image render_aa(void)
{
    image im = { 0, 0, NULL };
    char out[1024];
    snprintf(out, sizeof out, "%s/demo_aa.png", sr_test_out_dir());
    int status = sr_test_run_cli((const char *[]){ "demo", "aa", "-o", out, NULL });
    CHECK_EQ(status, 0);
    if (status != 0) {
        return im;
    }
    sr_io_error err;
    if (sr_read_png(out, NULL, &im.w, &im.h, &im.px, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "reading %s: %s", out, err.message);
        im.px = NULL;
        return im;
    }
    sr_test_check_image("demo_aa", im.px, im.w, im.h, 2, (long)im.w * im.h / 200);
    return im;
}

/* Panel pixel (x, y) of panel `index`: the centre of its block. */
static const uint8_t *at(const image *im, int index, int x, int y)
{
    demo3d_layout l = DEMO3D_LAYOUT_AA;
    int s = DEMO3D_AA_SCALE, ox, oy;
    demo3d_cell_origin(l, s, 0, index, &ox, &oy);
    size_t ix = (size_t)(ox + x * s + s / 2), iy = (size_t)(oy + y * s + s / 2);
    return im->px + 4 * (iy * (size_t)im->w + ix);
}

/* Distinct colors among the panel's pixels (counted up to CAP). */
static int levels(const image *im, int index)
{
    enum { CAP = 512 };
    uint32_t seen[CAP];
    int n = 0;
    demo3d_layout l = DEMO3D_LAYOUT_AA;
    for (int y = 0; y < l.cell_h; y++) {
        for (int x = 0; x < l.cell_w; x++) {
            const uint8_t *c = at(im, index, x, y);
            uint32_t key = (uint32_t)c[0] << 16 | (uint32_t)c[1] << 8 | c[2];
            bool found = false;
            for (int k = 0; k < n && !found; k++) {
                found = seen[k] == key;
            }
            if (!found && n < CAP) {
                seen[n++] = key;
            }
        }
    }
    return n;
}

/* Mean |coverage - exact coverage| over the panel, coverage from red. */
static double coverage_error(const image *im, int index, int r_ground, int r_ink)
{
    demo3d_layout l = DEMO3D_LAYOUT_AA;
    double sum = 0;
    for (int y = 0; y < l.cell_h; y++) {
        for (int x = 0; x < l.cell_w; x++) {
            double a = (at(im, index, x, y)[0] - r_ground) / (double)(r_ink - r_ground);
            double e = (at(im, EXACT, x, y)[0] - r_ground) / (double)(r_ink - r_ground);
            sum += fabs(a - e);
        }
    }
    return sum / (l.cell_w * l.cell_h);
}

SR_TEST(demo_aa_levels_follow_the_sample_counts)
{
    image im = render_aa();
    REQUIRE(im.px);
    /* One sample per pixel: covered or not, two colors and nothing else. */
    CHECK_EQ(levels(&im, NO_AA), 2);
    /* MSAA n: k of n samples covered, k = 0..n - at most n + 1 levels
     * (one shading per pixel, a constant color) - and more than n/2 + 1,
     * more than half the samples could make. */
    CHECK(levels(&im, MSAA4) > 3 && levels(&im, MSAA4) <= 5);
    CHECK(levels(&im, MSAA8) > 5 && levels(&im, MSAA8) <= 9);
    CHECK(levels(&im, MSAA16) > 9 && levels(&im, MSAA16) <= 17);
    /* SSAA 4x4 box: k/16 again, 17 at most; the weighted filters and the
     * exact area blend neighbouring samples or areas: many more. */
    CHECK(levels(&im, BOX) > 9 && levels(&im, BOX) <= 17);
    CHECK(levels(&im, TENT) > 40);
    CHECK(levels(&im, GAUSS) > 40);
    CHECK(levels(&im, MITCHELL) > 40);
    CHECK(levels(&im, EXACT) > 40);
    free(im.px);
}

SR_TEST(demo_aa_every_method_is_closer_to_exact_area_than_no_aa)
{
    image im = render_aa();
    REQUIRE(im.px);
    /* The ground and the ink: the no-AA panel's two reds. */
    demo3d_layout l = DEMO3D_LAYOUT_AA;
    int lo = 255, hi = 0;
    for (int y = 0; y < l.cell_h; y++) {
        for (int x = 0; x < l.cell_w; x++) {
            int r = at(&im, NO_AA, x, y)[0];
            lo = r < lo ? r : lo;
            hi = r > hi ? r : hi;
        }
    }
    REQUIRE(hi - lo > 100);
    double none = coverage_error(&im, NO_AA, lo, hi);
    static const int aa[] = { MSAA4, MSAA8, MSAA16, BOX, TENT, GAUSS, MITCHELL };
    double err[MITCHELL + 1] = { 0 };
    for (size_t i = 0; i < sizeof aa / sizeof aa[0]; i++) {
        err[aa[i]] = coverage_error(&im, aa[i], lo, hi);
        CHECK(err[aa[i]] < none);
    }
    CHECK(err[MSAA16] < err[MSAA4]);
    free(im.px);
}
