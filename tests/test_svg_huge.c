/* test_svg_huge.c - SVG geometry far beyond the 2D fixed-point budget
 * (SR_MAX_COORD2D): a point a million pixels off the page, a viewBox
 * zoomed a million times, a stroke and an even-odd hole around such
 * shapes, a blur reading past the image, circles of radius 1e7 and
 * 1e10 px, a stroked curve zoomed 2e6 times, dashes along 1e9-px lines.  Each is
 * drawn where it is seen: as the same drawing with the geometry cut by
 * hand at 2e5 px (within the budget, written with 17 digits; dashed
 * lines just past the image), within 2 codes a channel (4 for a curve,
 * flattened in other pieces).  Needs expat. */
#include "softrast_io.h"
#include "image_compare.h"
#include "sr_test.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static sr_framebuffer *render(const char *svg)
{
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    sr_result r = sr_render_svg(sr_test_ctx(), svg, strlen(svg),
                                &(sr_svg_desc){ .name = "huge.svg" }, &fb, NULL, &err);
    CHECK_EQ(r, SR_OK);
    if (r != SR_OK) {
        fprintf(stderr, "%s\n", err.message);
    }
    return fb;
}

/* The far drawing and the near one (cut by hand) give the same pixels,
 * within tol codes a channel. */
static void check_within(const char *name, const char *far, const char *near, int tol)
{
    sr_framebuffer *a = render(far), *b = render(near);
    if (a && b) {
        CHECK(sr_test_compare_images(name, sr_framebuffer_pixels(a), sr_framebuffer_pixels(b),
                                     sr_framebuffer_width(a), sr_framebuffer_height(a), tol, 0));
    }
    sr_destroy_framebuffer(sr_test_ctx(), a);
    sr_destroy_framebuffer(sr_test_ctx(), b);
}

static void check_same(const char *name, const char *far, const char *near)
{
    check_within(name, far, near, 2);
}

#define HEAD "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='200'>" \
             "<rect width='200' height='200' fill='white'/>"

/* y on the line through (x0, y0) and (x1, y1) at x. */
static double at(double x0, double y0, double x1, double y1, double x)
{
    return y0 + (x - x0) * (y1 - y0) / (x1 - x0);
}

SR_TEST(a_point_a_million_pixels_off_the_page_is_drawn)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    const char *far = HEAD "<path d='M10 10 L 1000000 100 L 10 190 z' fill='blue'/>"
                           "<circle cx='100' cy='100' r='30' fill='red'/></svg>";
    char near[512];
    snprintf(near, sizeof near,
             HEAD "<path d='M10 10 L 200000 %.17g L 200000 %.17g L 10 190 z' fill='blue'/>"
                  "<circle cx='100' cy='100' r='30' fill='red'/></svg>",
             at(10, 10, 1e6, 100, 2e5), at(10, 190, 1e6, 100, 2e5));
    check_same("huge_point", far, near);
}

SR_TEST(a_viewbox_zoomed_a_million_times_is_drawn)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* (0.0001, 0.00005) -> (100, 50) px, (1, 0.6) -> (1e6, 6e5) px */
    const char *far =
        "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='200' "
        "viewBox='0 0 0.0002 0.0002'><rect width='1' height='1' fill='white'/>"
        "<path d='M0.0001 0.00005 L 1 0.6 L 0.00005 0.0002 z' fill='green'/></svg>";
    char near[512];
    snprintf(near, sizeof near,
             HEAD "<path d='M100 50 L 200000 %.17g L 200000 %.17g L 50 200 z' fill='green'/></svg>",
             at(100, 50, 1e6, 6e5, 2e5), at(50, 200, 1e6, 6e5, 2e5));
    check_same("huge_zoom", far, near);
}

SR_TEST(strokes_and_holes_around_huge_shapes_are_drawn)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    const char *far = HEAD
        "<path d='M-3000000 20 L 3000000 180' stroke='navy' stroke-width='8'/>"
        "<path fill-rule='evenodd' fill='#383' d='M-1e6 -1e6 L 1e6 -1e6 L 1e6 1e6 L -1e6 1e6 z "
        "M 50 50 L 150 50 L 150 150 L 50 150 z'/></svg>";
    char near[640];
    snprintf(near, sizeof near, HEAD
             "<path d='M-200000 %.17g L 200000 %.17g' stroke='navy' stroke-width='8'/>"
             "<path fill-rule='evenodd' fill='#383' d='M-2e5 -2e5 L 2e5 -2e5 L 2e5 2e5 L -2e5 2e5 z "
             "M 50 50 L 150 50 L 150 150 L 50 150 z'/></svg>",
             at(-3e6, 20, 3e6, 180, -2e5), at(-3e6, 20, 3e6, 180, 2e5));
    check_same("huge_stroke_hole", far, near);
}

SR_TEST(a_blur_reads_huge_geometry_beyond_the_image)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* The filter region reaches 50 px past the image; the wedge's edges
     * run at 45 degrees, so the near one has the same lines exactly. */
    const char *filter = "<filter id='b' filterUnits='userSpaceOnUse' x='-50' y='-50' "
                         "width='300' height='300'><feGaussianBlur stdDeviation='6'/></filter>";
    char far[640], near[640];
    snprintf(far, sizeof far, HEAD "%s<path d='M100 100 L 4e6 -3999800 L 4e6 4000000 z' "
             "filter='url(#b)'/></svg>", filter);
    snprintf(near, sizeof near, HEAD "%s<path d='M100 100 L 2e5 -199800 L 2e5 200000 z' "
             "filter='url(#b)'/></svg>", filter);
    check_same("huge_blur", far, near);
}

SR_TEST(a_circle_of_radius_1e7_is_drawn_where_it_is_seen)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* Its left edge at x = 100 bows out by 1/2000 px over the image. */
    sr_framebuffer *fb = render(HEAD "<circle cx='10000100' cy='100' r='1e7' fill='blue'/></svg>");
    if (fb) {
        const uint8_t *px = sr_framebuffer_pixels(fb);
        for (int y = 0; y < 200; y += 33) {
            const uint8_t *l = px + ((size_t)y * 200 + 98) * 4, *r = px + ((size_t)y * 200 + 101) * 4;
            CHECK(l[0] == 255 && l[1] == 255 && l[2] == 255);
            CHECK(r[0] == 0 && r[1] == 0 && r[2] == 255);
        }
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* The parabola y = 100 + k (x - 100)^2 (device pixels) from x0 to x1 as
 * a cubic path's data, mapped back to user units by dividing by s. */
static void parabola(char *out, size_t size, double k, double x0, double x1, double s)
{
    double y0 = 100 + k * (x0 - 100) * (x0 - 100), y1 = 100 + k * (x1 - 100) * (x1 - 100);
    /* the quadratic's control point: the tangents' meeting point */
    double xm = (x0 + x1) / 2, ym = y0 + 2 * k * (x0 - 100) * (xm - x0);
    double c1x = x0 + 2 * (xm - x0) / 3, c1y = y0 + 2 * (ym - y0) / 3;
    double c2x = x1 + 2 * (xm - x1) / 3, c2y = y1 + 2 * (ym - y1) / 3;
    snprintf(out, size, "M%.17g %.17g C%.17g %.17g %.17g %.17g %.17g %.17g", x0 / s, y0 / s,
             c1x / s, c1y / s, c2x / s, c2y / s, x1 / s, y1 / s);
}

SR_TEST(a_stroked_curve_zoomed_two_million_times_is_drawn)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* 2e6 px a user unit: the curve's ends lie 2e6 px to the sides and
     * 2e10 px down; by hand it is cut where it leaves y = 2e5. */
    const double k = 0.005, s = 2e6, cut = sqrt((2e5 - 100) / k);
    char d[256], far[640], near[640];
    parabola(d, sizeof d, k, 100 - s, 100 + s, s);
    snprintf(far, sizeof far,
             "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='200' "
             "viewBox='0 0 0.0001 0.0001'><rect width='1' height='1' fill='white'/>"
             "<path d='%s' fill='none' stroke='purple' stroke-width='0.000003'/></svg>", d);
    parabola(d, sizeof d, k, 100 - cut, 100 + cut, 1);
    snprintf(near, sizeof near,
             HEAD "<path d='%s' fill='none' stroke='purple' stroke-width='6'/></svg>", d);
    /* The far curve is cut in halves before it is flattened, the near one
     * is not: their chords differ by hundredths of a pixel. */
    check_within("huge_curve", far, near, 4);
}

SR_TEST(a_dashed_line_a_billion_pixels_long_draws_its_visible_dashes)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* By hand the lines end just past the image, within the dashes'
     * reach of it (nothing is skipped): the second starts 1e9 - 16 px
     * later, a whole number of 12 px periods. */
    const char *dash = "stroke='black' stroke-width='4' stroke-linecap='square' "
                       "stroke-dasharray='7 5'";
    /* The diagonal's pattern stands (1e9 - 12) sqrt 2 px on at (-12, -12). */
    const char *diag = "stroke='red' stroke-width='3' stroke-linecap='round' "
                       "stroke-dasharray='20 6 2 6'";
    char far[800], near[800];
    snprintf(far, sizeof far,
             HEAD "<path d='M10 50 H 1e9 M -1e9 150 H 1e9' %s stroke-dashoffset='3'/>"
                  "<path d='M-1e9 -1e9 L 1e9 1e9' %s/></svg>",
             dash, diag);
    snprintf(near, sizeof near,
             HEAD "<path d='M10 50 H 216 M -16 150 H 216' %s stroke-dashoffset='3'/>"
                  "<path d='M-12 -12 L 212 212' %s stroke-dashoffset='%.17g'/></svg>",
             dash, diag, fmod((1e9 - 12) * sqrt(2), 34));
    check_same("huge_dash", far, near);
}

/* A circle of radius 1e10 px under a zoom of 1e5 px a user unit; its
 * edge passes (100, 100) at s = pi / 131072 from its leftmost point: the
 * middle of a chord when the circle is flattened in full into 2 x 65536
 * (the flattening's cap), which strays 2.9 px.  By hand the edge is cut
 * into lines where it leaves the image (bowing 2e-5 px).  The fill's
 * paint server is far_paint in the zoomed drawing, near_paint in the
 * other (defs, and the fill attribute's value). */
static void huge_circle(const char *name, const char *far_defs, const char *near_defs,
                        const char *fill)
{
    const double z = 1e5, r = 1e10, s = 3.14159265358979323846 / 131072;
    const double cx = 100 + r * cos(s), cy = 100 - r * sin(s);
    char far[1024], near[1024], d[256] = "M";
    snprintf(far, sizeof far,
             "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='200' "
             "viewBox='0 0 0.002 0.002'>%s<rect width='1' height='1' fill='white'/>"
             "<circle cx='%.17g' cy='%.17g' r='%.17g' fill='%s'/></svg>",
             far_defs, cx / z, cy / z, r / z, fill);
    const double ys[3] = { -1000, 100, 1200 };
    for (int i = 0; i < 3; i++) {
        /* x(y) = cx - sqrt(r^2 - (y - cy)^2) without cancelling */
        double u = ys[i] - cy, y = ys[i] - 100;
        double x = 100 + y * (y + 2 * r * sin(s)) / (r * cos(s) + sqrt(r * r - u * u));
        snprintf(d + strlen(d), sizeof d - strlen(d), "%.17g %.17g L", x, ys[i]);
    }
    snprintf(near, sizeof near,
             HEAD "%s<path d='%s 2000 1200 L 2000 -1000 z' fill='%s'/></svg>", near_defs, d,
             fill);
    check_same(name, far, near);
}

SR_TEST(a_circle_of_radius_1e10_px_under_a_zoom_is_drawn_where_it_is_seen)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    huge_circle("huge_arc", "", "", "blue");
}

SR_TEST(a_huge_circle_painted_in_user_space_is_drawn_where_it_is_seen)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* the same gradient across the image in both drawings' user units */
    const char *grad = "<defs><linearGradient id='g' gradientUnits='userSpaceOnUse' x1='0' "
                       "y1='0' x2='%s' y2='%s'><stop offset='0' stop-color='#0a0'/>"
                       "<stop offset='1' stop-color='#a0f'/></linearGradient></defs>";
    char far[400], near[400];
    snprintf(far, sizeof far, grad, "0.002", "0.001");
    snprintf(near, sizeof near, grad, "200", "100");
    huge_circle("huge_arc_gradient", far, near, "url(#g)");
}

SR_TEST(an_image_zoomed_1e300_times_is_drawn_where_it_is_seen)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* A 4 x 4 picture, texel (i, j) = (60 i, 60 j, 128).  Zoomed 1e300
     * times, the image sees its first texel (clamped past its centre);
     * sliced into 1e300 x 100, its first column's middle, halfway between
     * rows 1 and 2.  Their maps' determinants overflow a double. */
    const char *png = "href='data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAQAAAAECAYAAACp8Z5+"
                      "AAAAK0lEQVR42hXIMQEAMAzDsAArMJ8FFX6be+hRkn0jVCVjCHUuMITKRQ2h6gM5yCMxCQMMBw"
                      "AAAABJRU5ErkJggg=='";
    char far[640];
    snprintf(far, sizeof far,
             HEAD "<image width='1' height='1' transform='scale(1e300)' %s/></svg>", png);
    check_same("huge_image_zoom", far,
               HEAD "<rect width='200' height='200' fill='#000080'/></svg>");
    snprintf(far, sizeof far,
             HEAD "<image width='1e300' height='200' preserveAspectRatio='xMidYMid slice' %s/>"
                  "</svg>", png);
    check_same("huge_image_slice", far,
               HEAD "<rect width='200' height='200' fill='#005a80'/></svg>");
    /* beyond doubles, or off the image: nothing, and no failure */
    snprintf(far, sizeof far,
             HEAD "<image x='1e308' y='-1e308' width='1e308' height='1e308' %s/>"
                  "<image x='-1e308' width='1e308' height='1e308' %s/></svg>", png, png);
    check_same("huge_image_away", far, HEAD "</svg>");
}
