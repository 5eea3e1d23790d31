/* test_svg_syntax.c - how the SVG reader reads values written in ways SVG
 * and CSS allow or forbid: path data and points lists in error are drawn
 * up to the error, with one warning naming FILE:LINE (SVG's error
 * processing for path data), and units are read in any case, as CSS
 * reads them.  Pixels are checked against what the drawing says. */
#include "softrast_io.h"
#include "sr_test.h"

#include <stdlib.h>
#include <string.h>

/* The drawing over white, its warnings in *w (NULL after a failure,
 * counted). */
static sr_framebuffer *render(const char *svg, sr_test_warnings *w)
{
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    *w = (sr_test_warnings){ 0 };
    CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg),
                           &(sr_svg_desc){ .name = "t.svg", .background = { 1, 1, 1, 1 },
                                           .warn = sr_test_collect_warning, .warn_user = w },
                           &fb, NULL, &err),
             SR_OK);
    return fb;
}

/* Whether the pixel's red, green and blue are all v: 0 where black is
 * drawn, 255 where the white background shows. */
static bool gray_is(const sr_framebuffer *fb, int x, int y, int v)
{
    const uint8_t *p =
        sr_framebuffer_pixels(fb) + ((size_t)y * (size_t)sr_framebuffer_width(fb) + x) * 4;
    return p[0] == v && p[1] == v && p[2] == v;
}

#define black(fb, x, y) gray_is(fb, x, y, 0)
#define white(fb, x, y) gray_is(fb, x, y, 255)

SR_TEST(path_data_in_error_is_drawn_up_to_the_error)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* Each path: a square at 0..10, then a subpath that gets three sides
     * of the square at 10..20 (filled as the triangle above its
     * diagonal) before the error; the command in error draws nothing
     * (it would fill the lower half) and neither does what follows it
     * (the square at 20..30). */
    static const char *const cases[][2] = {
        { "M0 0H10V10H0Z M10 0H20V10 L10 x L20 0 M20 0H30V10H20Z", "expected a number at offset 30" },
        { "M0 0H10V10H0Z M10 0H20V10 L10 K M20 0H30V10H20Z", "expected a number at offset 30" },
        { "M0 0H10V10H0Z M10 0H20V10 K10 10 M20 0H30V10H20Z", "unknown command 'K' at offset 26" },
        { "M0 0H10V10H0Z M10 0H20V10 A5 5 0 2 1 10 10 M20 0H30V10H20Z",
          "arc flag not 0 or 1 at offset 33" },
        { "M0 0H10V10H0Z M10 0H20V10 z 10 10 M20 0H30V10H20Z", "expected a command at offset 28" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char svg[512], want[128];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='30' height='10'>\n"
                 "<path d='%s' shape-rendering='crispEdges'/>\n</svg>\n",
                 cases[i][0]);
        sr_test_warnings w;
        sr_framebuffer *fb = render(svg, &w);
        if (!fb) {
            continue;
        }
        CHECK(black(fb, 2, 2) && black(fb, 8, 8));  /* the first square */
        CHECK(black(fb, 18, 2));                    /* above the diagonal */
        /* The closing 'z' case closes the triangle the same way: no
         * pixel below the diagonal in any case. */
        CHECK(white(fb, 12, 8));
        CHECK(white(fb, 22, 2) && white(fb, 28, 8)); /* after the error */
        CHECK_EQ(w.count, 1);
        snprintf(want, sizeof want, "t.svg:2: warning: path data: %s; drawn up to there|",
                 cases[i][1]);
        CHECK_STR_CONTAINS(w.text, want);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

SR_TEST(path_data_without_a_moveto_draws_nothing_but_the_rest)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_test_warnings w;
    sr_framebuffer *fb = render("<svg xmlns='http://www.w3.org/2000/svg' width='20' height='10'>"
                                "<path d='L0 0H10V10H0Z'/><rect x='10' width='10' height='10'/>"
                                "</svg>",
                                &w);
    REQUIRE(fb);
    CHECK(white(fb, 5, 5));
    CHECK(black(fb, 15, 5));
    CHECK_EQ(w.count, 1);
    CHECK_STR_CONTAINS(w.text, "t.svg:1: warning: path data: no moveto first at offset 0");
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

SR_TEST(points_in_error_draw_the_pairs_before_the_error)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* An odd coordinate is dropped (SVG 2): the polygon is the triangle
     * of the three pairs before it; the polyline's fill likewise. */
    sr_test_warnings w;
    sr_framebuffer *fb = render("<svg xmlns='http://www.w3.org/2000/svg' width='20' height='10'>"
                                "<polygon points='0,0 10,0 10,10 0' shape-rendering='crispEdges'/>"
                                "<polyline points='10,0 20,0 20,10 x' "
                                "shape-rendering='crispEdges'/></svg>",
                                &w);
    REQUIRE(fb);
    CHECK(black(fb, 8, 2) && white(fb, 2, 8));
    CHECK(black(fb, 18, 2) && white(fb, 12, 8));
    CHECK_EQ(w.count, 2);
    CHECK_STR_CONTAINS(w.text, "warning: polygon: points: expected a coordinate pair at offset 16");
    CHECK_STR_CONTAINS(w.text, "warning: polyline: points: expected a coordinate pair at offset 16");
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

SR_TEST(units_are_read_in_any_case)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* The same drawing with its units in lower and in mixed or upper
     * case, in attributes, style="" and a sheet, and an angle: the same
     * pixels, and no warning. */
    static const char form[] =
        "<svg xmlns='http://www.w3.org/2000/svg' width='64' height='64'>"
        "<style>#c { stroke-width: 3%s }</style>"
        "<rect x='1%s' y='0.25%s' width='3%s' height='2%s' fill='#00f'/>"
        "<circle id='c' cx='40' cy='20' r='1%s' fill='none' stroke='#0a0'/>"
        "<line x1='2' y1='50' x2='60' y2='50' stroke='#f00' style='stroke-width: 0.1%s'/>"
        "<line x1='2' y1='60' x2='60' y2='60' stroke='#f0f' stroke-width='0.05%s'/>"
        "<marker id='m' markerWidth='4' markerHeight='8' orient='90%s'>"
        "<rect width='4' height='8' fill='#00f'/></marker>"
        "<path d='M40 40 L60 40' stroke='#000' marker-start='url(#m)'/>"
        "</svg>";
    static const char *const cases[][9] = {
        { "pt", "px", "in", "mm", "pc", "em", "cm", "in", "deg" },
        { "PT", "PX", "IN", "Mm", "pC", "EM", "CM", "In", "DEG" },
    };
    sr_framebuffer *fb[2];
    for (int i = 0; i < 2; i++) {
        const char *const *u = cases[i];
        char svg[1024];
        snprintf(svg, sizeof svg, form, u[0], u[1], u[2], u[3], u[4], u[5], u[6], u[7], u[8]);
        sr_test_warnings w;
        fb[i] = render(svg, &w);
        CHECK_EQ(w.count, 0);
    }
    REQUIRE(fb[0] && fb[1]);
    CHECK(!white(fb[0], 5, 30)); /* the rect: x 1 to 12.3, y 24 to 56 */
    CHECK(white(fb[0], 5, 20));
    CHECK(!white(fb[0], 38, 41)); /* the marker turned 90 degrees: x 32 to 40, y 40 to 44 */
    size_t n = (size_t)sr_framebuffer_width(fb[0]) * (size_t)sr_framebuffer_height(fb[0]) * 4;
    CHECK(memcmp(sr_framebuffer_pixels(fb[0]), sr_framebuffer_pixels(fb[1]), n) == 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb[0]);
    sr_destroy_framebuffer(sr_test_ctx(), fb[1]);
}
