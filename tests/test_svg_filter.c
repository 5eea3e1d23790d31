/* test_svg_filter.c - the SVG reader's filter effects (svg_filter.c):
 * drawings of each primitive in tests/data/svg against references
 * (checked against rsvg-convert and resvg when made, see docs/draw2d.md;
 * channel tolerance 2, at most 0.5% of the pixels beyond it), a drop
 * shadow against rsvg-convert's own rendering, and properties: a blur
 * keeps the total alpha, sigma 0 and an empty offset are the identity,
 * whole-pixel offsets shift exactly, linearRGB and sRGB give the values
 * worked out by hand, and broken filters do what the docs say. */
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The document drawn at its own size on transparent black, its result
 * checked; warnings collected when warn is given, the message kept. */
static sr_framebuffer *render(const char *svg, sr_result want, sr_test_warnings *warn,
                              char *msg, size_t n)
{
    sr_svg_desc d = { .name = "t.svg" };
    if (warn) {
        d.warn = sr_test_collect_warning;
        d.warn_user = warn;
    }
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg), &d, &fb, NULL, &err), want);
    if (msg) {
        snprintf(msg, n, "%s", err.message);
    }
    return fb;
}

static const uint8_t *pixel(const sr_framebuffer *fb, int x, int y)
{
    return sr_framebuffer_pixels(fb) + ((size_t)y * (size_t)sr_framebuffer_width(fb) + x) * 4;
}

static sr_framebuffer *render_file(const char *file, double scale, bool white)
{
    char in[1024];
    snprintf(in, sizeof in, "%s/data/svg/%s", sr_test_src_dir(), file);
    sr_framebuffer *fb = NULL;
    sr_svg_info info;
    sr_io_error err;
    sr_svg_desc d = { .scale = scale };
    if (white) {
        d.background = (sr_rgba){ 1, 1, 1, 1 };
    }
    CHECK_EQ(sr_render_svg_file(sr_test_ctx(), in, &d, &fb, &info, &err), SR_OK);
    if (fb) {
        CHECK_EQ(info.warnings, 0);
    }
    return fb;
}

/* filters: blurs (exact and box, anisotropic, edgeMode), offset, flood
 * in a subregion, composite operators, merge, objectBoundingBox units,
 * a rotated blur; filtercolor: color matrices, component transfer,
 * blend modes, a blur in sRGB and in linearRGB; filtermisc: morphology,
 * tile, drop shadows (one rotated and scaled), a glow; filterimage:
 * feImage of a picture file (preserveAspectRatio) and of an element;
 * filteredge: offset, blur, shadow and morphology bringing in content
 * drawn beyond the image. */
SR_TEST(filter_drawings_match_references)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char *const names[] = { "filters", "filtercolor", "filtermisc",
                                          "filterimage", "filteredge" };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        if (strcmp(names[i], "filterimage") == 0 && !sr_io_have_jpeg()) {
            continue; /* its picture is a JPEG */
        }
        char file[64], ref[64];
        snprintf(file, sizeof file, "%s.svg", names[i]);
        snprintf(ref, sizeof ref, "svg_%s", names[i]);
        sr_framebuffer *fb = render_file(file, 2, true);
        if (fb) {
            int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
            sr_test_check_image(ref, sr_framebuffer_pixels(fb), w, h, 2, (long)w * h / 200);
            sr_destroy_framebuffer(sr_test_ctx(), fb);
        }
    }
}

/* tests/ref/svg_filtershadow_rsvg.png is rsvg-convert 2.54.7's own image:
 *   rsvg-convert -z 2 -b white tests/data/svg/filtershadow.svg
 * (not to be rewritten with SR_UPDATE_REFS).  Within 8 of 255 on all but
 * 1% of the pixels: the shapes' own antialiased edges differ that much
 * between the two without any filter. */
SR_TEST(drop_shadow_matches_rsvg_convert)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_framebuffer *fb = render_file("filtershadow.svg", 2, true);
    if (fb) {
        int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
        sr_test_check_image("svg_filtershadow_rsvg", sr_framebuffer_pixels(fb), w, h, 8,
                            (long)w * h / 100);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

/* tests/ref/svg_filterturb_rsvg.png and svg_filterlight_rsvg.png are
 * rsvg-convert 2.54.7's images too:
 *   rsvg-convert -z 2 -b white tests/data/svg/filterturb.svg (filterlight.svg)
 * The noise is the specification's, so within 8 of 255 on all but 0.1%
 * of the pixels (rounding on the steepest edges); the lights within 8 on
 * all but 0.5% (the lit circle's antialiased rim). */
SR_TEST(turbulence_and_lighting_match_rsvg_convert)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const struct { const char *file, *ref; int per_bad; } cases[] = {
        { "filterturb.svg", "svg_filterturb_rsvg", 1000 },
        { "filterlight.svg", "svg_filterlight_rsvg", 200 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sr_framebuffer *fb = render_file(cases[i].file, 2, true);
        if (fb) {
            int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
            sr_test_check_image(cases[i].ref, sr_framebuffer_pixels(fb), w, h, 8,
                                (long)w * h / cases[i].per_bad);
            sr_destroy_framebuffer(sr_test_ctx(), fb);
        }
    }
}

static double total_alpha(const sr_framebuffer *fb)
{
    double s = 0;
    for (int y = 0; y < sr_framebuffer_height(fb); y++) {
        for (int x = 0; x < sr_framebuffer_width(fb); x++) {
            s += pixel(fb, x, y)[3];
        }
    }
    return s;
}

SR_TEST(a_blur_keeps_the_total_alpha_away_from_the_region_edge)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char *const sigmas[] = { "0.7", "1.5", "2", "3.3", "5" };
    for (size_t i = 0; i < sizeof sigmas / sizeof sigmas[0]; i++) {
        char svg[512];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='100' height='100'>"
                 "<filter id='b' x='-2' y='-2' width='5' height='5'>"
                 "<feGaussianBlur stdDeviation='%s'/></filter>"
                 "<rect x='40' y='40' width='20' height='20' fill='#08f' filter='url(#b)'/>"
                 "<rect x='40' y='40' width='20' height='20' fill='#08f' opacity='0'/></svg>",
                 sigmas[i]);
        sr_framebuffer *fb = render(svg, SR_OK, NULL, NULL, 0);
        REQUIRE(fb);
        /* 400 pixels of 255: each spread pixel rounds by half a code at most */
        CHECK_NEAR(total_alpha(fb), 400 * 255.0, 400 * 255.0 * 0.01);
        CHECK(pixel(fb, 40, 50)[3] < 250); /* and it did blur */
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

/* The same drawing with the filter and without: every byte equal. */
static void check_same(const char *filter_body, const char *shape)
{
    char a[1024], b[1024];
    snprintf(a, sizeof a,
             "<svg xmlns='http://www.w3.org/2000/svg' width='40' height='30'>"
             "<filter id='f' x='-1' y='-1' width='3' height='3'>%s</filter>"
             "<g filter='url(#f)'>%s</g></svg>",
             filter_body, shape);
    snprintf(b, sizeof b,
             "<svg xmlns='http://www.w3.org/2000/svg' width='40' height='30'><g>%s</g></svg>",
             shape);
    sr_framebuffer *fa = render(a, SR_OK, NULL, NULL, 0), *fb = render(b, SR_OK, NULL, NULL, 0);
    if (fa && fb) {
        CHECK_EQ(memcmp(sr_framebuffer_pixels(fa), sr_framebuffer_pixels(fb), 40 * 30 * 4), 0);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fa);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

static const char shape[] =
    "<circle cx='15' cy='14' r='9.3' fill='#c84' fill-opacity='0.7' stroke='#136'/>";

SR_TEST(a_blur_of_sigma_zero_and_an_offset_of_zero_are_the_identity)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    check_same("<feGaussianBlur stdDeviation='0'/>", shape);
    check_same("<feGaussianBlur stdDeviation='-3'/>", shape); /* Filter Effects 1, resvg */
    check_same("<feOffset/>", shape);
    check_same("<feOffset dx='3' dy='-2'/><feOffset dx='-3' dy='2'/>", shape);
    /* sRGB and linearRGB and back */
    check_same("<feColorMatrix type='saturate' values='1'/>", shape);
    /* a kernel of one 1 at its target (turned half a turn), a displacement
     * of scale 0 */
    check_same("<feConvolveMatrix kernelMatrix='0 0 0 0 1 0 0 0 0'/>", shape);
    check_same("<feConvolveMatrix order='2' kernelMatrix='1 0 0 0' targetX='1' targetY='1'"
               " edgeMode='none'/>",
               shape);
    check_same("<feTurbulence result='t'/><feDisplacementMap in='SourceGraphic' in2='t'/>", shape);
}

SR_TEST(an_offset_by_whole_pixels_shifts_exactly)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    const char *plain =
        "<svg xmlns='http://www.w3.org/2000/svg' width='40' height='30'>%s</svg>";
    char a[1024], b[1024], body[512];
    snprintf(body, sizeof body,
             "<filter id='f' x='-1' y='-1' width='3' height='3'><feOffset dx='1.5' dy='-1'/>"
             "</filter><g transform='scale(2)' filter='url(#f)'>"
             "<circle cx='7' cy='8' r='4.3' fill='#c84' fill-opacity='0.7'/></g>");
    snprintf(a, sizeof a, plain, body);
    snprintf(b, sizeof b, plain,
             "<circle cx='17' cy='14' r='8.6' fill='#c84' fill-opacity='0.7'/>");
    sr_framebuffer *fa = render(a, SR_OK, NULL, NULL, 0), *fb = render(b, SR_OK, NULL, NULL, 0);
    REQUIRE(fa && fb);
    /* user (1.5, -1) under scale(2) is (3, -2) pixels */
    for (int y = 0; y < 30; y++) {
        for (int x = 0; x < 40; x++) {
            CHECK_EQ(memcmp(pixel(fa, x, y), pixel(fb, x, y), 4), 0);
        }
    }
    sr_destroy_framebuffer(sr_test_ctx(), fa);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* White through feFuncR/G/B linear slope 0.25: in sRGB 0.25 * 255 = 64;
 * in linearRGB 1 -> 0.25 -> 1.055 * 0.25^(1/2.4) - 0.055 = 0.5371 = 137. */
SR_TEST(linear_rgb_and_srgb_give_the_values_worked_out_by_hand)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const struct { const char *space; int want; } cases[] = {
        { "sRGB", 64 }, { "linearRGB", 137 }, { NULL, 137 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char svg[640], cif[64] = "";
        if (cases[i].space) {
            snprintf(cif, sizeof cif, " color-interpolation-filters='%s'", cases[i].space);
        }
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'>"
                 "<filter id='f'%s><feComponentTransfer><feFuncR type='linear' slope='0.25'/>"
                 "<feFuncG type='linear' slope='0.25'/><feFuncB type='linear' slope='0.25'/>"
                 "</feComponentTransfer></filter>"
                 "<rect width='10' height='10' fill='#fff' filter='url(#f)'/></svg>",
                 cif);
        sr_framebuffer *fb = render(svg, SR_OK, NULL, NULL, 0);
        REQUIRE(fb);
        const uint8_t *p = pixel(fb, 5, 5);
        CHECK_EQ(p[0], cases[i].want);
        CHECK_EQ(p[2], cases[i].want);
        CHECK_EQ(p[3], 255);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

/* flood-color and flood-opacity from style="": the same straight color
 * whichever space the flood is made in. */
SR_TEST(a_flood_takes_its_color_and_opacity_in_either_space)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char *const spaces[] = { "sRGB", "linearRGB" };
    for (int i = 0; i < 2; i++) {
        char svg[512];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'>"
                 "<filter id='f' color-interpolation-filters='%s'>"
                 "<feFlood style='flood-color: #804020; flood-opacity: 0.5'/></filter>"
                 "<rect width='10' height='10' filter='url(#f)'/></svg>",
                 spaces[i]);
        sr_framebuffer *fb = render(svg, SR_OK, NULL, NULL, 0);
        REQUIRE(fb);
        const uint8_t *p = pixel(fb, 5, 5);
        CHECK(abs(p[0] - 0x80) <= 1 && abs(p[1] - 0x40) <= 1 && abs(p[2] - 0x20) <= 1);
        CHECK_EQ(p[3], 128);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

/* The drawing's alpha at (x, y) and a warning that names `warned`. */
static void check_broken(const char *body, int x, int y, int alpha, const char *warned)
{
    char svg[1024];
    snprintf(svg, sizeof svg,
             "<svg xmlns='http://www.w3.org/2000/svg' width='20' height='10'>%s</svg>", body);
    sr_test_warnings w = { 0 };
    sr_framebuffer *fb = render(svg, SR_OK, &w, NULL, 0);
    if (fb) {
        CHECK_EQ(pixel(fb, x, y)[3], alpha);
        CHECK_STR_CONTAINS(w.text, warned);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* requiredFeatures holds for the filter features, so a switch takes a
 * filtered drawing over its fallback. */
SR_TEST(filter_features_are_claimed_for_a_switch)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char *const features[] = { "Filter", "BasicFilter" };
    for (int i = 0; i < 2; i++) {
        char svg[1024];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'><switch>"
                 "<rect width='4' height='4' fill='#00ff00' "
                 "requiredFeatures='http://www.w3.org/TR/SVG11/feature#%s'/>"
                 "<rect width='4' height='4' fill='#ff0000'/></switch></svg>",
                 features[i]);
        sr_framebuffer *fb = render(svg, SR_OK, NULL, NULL, 0);
        if (fb) {
            CHECK_EQ(pixel(fb, 2, 2)[0], 0);
            CHECK_EQ(pixel(fb, 2, 2)[1], 255);
        }
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

SR_TEST(broken_filters_do_what_the_docs_say)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* a missing filter: the element is not drawn (SVG 1.1, resvg) */
    check_broken("<rect width='10' height='10' filter='url(#none)'/>", 5, 5, 0, "url(#none)");
    /* an empty filter: not drawn; an unknown primitive: left out */
    static const char filters[] = "<filter id='e'/><filter id='u'><feFoo/><feOffset dx='2'/>"
                                  "</filter><rect x='10' width='8' height='10' filter='url(#u)'/>";
    char body[512];
    snprintf(body, sizeof body, "%s<rect width='8' height='10' filter='url(#e)'/>", filters);
    check_broken(body, 4, 5, 0, "feFoo");
    check_broken(body, 11, 5, 0, "feFoo"); /* moved 2 to the right */
    check_broken(body, 12, 5, 255, "feFoo");
    /* an input naming no result: the previous result (Filter Effects 1, resvg);
     * the region ends at 8.8 */
    check_broken("<filter id='f'><feOffset in='nothing' dx='2'/></filter>"
                 "<rect width='8' height='10' filter='url(#f)'/>",
                 8, 5, 255, "nothing");
    /* a kernel of the wrong size: transparent black, with a warning */
    check_broken("<filter id='f'><feConvolveMatrix kernelMatrix='1 2 3'/></filter>"
                 "<rect width='8' height='10' filter='url(#f)'/>",
                 4, 5, 0, "1 2 3");
    /* BackgroundImage: transparent black, with a warning */
    check_broken("<filter id='f'><feMerge><feMergeNode in='BackgroundImage'/></feMerge>"
                 "</filter><rect width='8' height='10' filter='url(#f)'/>",
                 4, 5, 0, "BackgroundImage");
}

SR_TEST(huge_deviations_and_radii_end_quickly_or_are_refused)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    char msg[512];
    /* a blur's cost does not grow with sigma */
    sr_framebuffer *fb = render("<svg xmlns='http://www.w3.org/2000/svg' width='200' height='200'>"
                                "<filter id='f'><feGaussianBlur stdDeviation='1e30'/></filter>"
                                "<rect width='100' height='100' filter='url(#f)'/></svg>",
                                SR_OK, NULL, NULL, 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    /* nor a morphology's with its radius (bounded by the region) */
    fb = render("<svg xmlns='http://www.w3.org/2000/svg' width='2000' height='2000'>"
                "<filter id='f' x='0' y='0' width='1' height='1'>"
                "<feMorphology radius='1e9'/><feMorphology radius='1e9'/>"
                "<feMorphology radius='1e9'/><feMorphology radius='1e9'/></filter>"
                "<rect width='2000' height='2000' filter='url(#f)'/></svg>",
                SR_OK, NULL, NULL, 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    /* a filter that passes the work budget is refused at its primitive */
    fb = render("<svg xmlns='http://www.w3.org/2000/svg' width='2000' height='2000'>"
                "<filter id='f' x='0' y='0' width='1' height='1'>\n"
                "<feMorphology radius='1e9'/><feMorphology radius='1e9'/>"
                "<feMorphology radius='1e9'/><feMorphology radius='1e9'/>\n"
                "<feMorphology radius='1e9'/></filter>"
                "<rect width='2000' height='2000' filter='url(#f)'/></svg>",
                SR_TOO_LARGE, NULL, msg, sizeof msg);
    CHECK_STR_CONTAINS(msg, "t.svg:3: the drawing costs more than");
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

SR_TEST(fe_image_draws_an_element_and_refuses_a_cycle)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_framebuffer *fb = render("<svg xmlns='http://www.w3.org/2000/svg' width='20' height='10'>"
                                "<defs><rect id='r' x='12' width='4' height='10' fill='#00f'/></defs>"
                                "<filter id='f' filterUnits='userSpaceOnUse' x='0' y='0' width='20'"
                                " height='10'><feImage href='#r'/></filter>"
                                "<rect width='4' height='10' fill='#f00' filter='url(#f)'/></svg>",
                                SR_OK, NULL, NULL, 0);
    REQUIRE(fb);
    CHECK_EQ(pixel(fb, 2, 5)[3], 0);   /* the element itself is replaced */
    CHECK_EQ(pixel(fb, 14, 5)[2], 255); /* by the rect it names */
    CHECK_EQ(pixel(fb, 14, 5)[3], 255);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    char msg[512];
    fb = render("<svg xmlns='http://www.w3.org/2000/svg' width='20' height='10'>\n"
                "<filter id='f'>\n<feImage href='#g'/></filter>\n"
                "<rect id='g' width='4' height='10' filter='url(#f)'/></svg>",
                SR_BAD_FORMAT, NULL, msg, sizeof msg);
    CHECK_STR_CONTAINS(msg, "t.svg:");
    CHECK_STR_CONTAINS(msg, "reference cycle through \"#f\"");
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* Values at the ends of double's range: drawn or refused, never undefined
 * behaviour (the sanitizer builds run this). */
SR_TEST(values_at_the_ends_of_the_range_draw_or_are_refused)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char *const prims[] = {
        "<feConvolveMatrix order='1e30' kernelMatrix='1'/>",
        "<feConvolveMatrix kernelMatrix='1 1 1 1 1 1 1 1 1' targetX='1e30' divisor='1e-300'"
        " bias='1e308'/>",
        "<feTurbulence baseFrequency='1e300' numOctaves='1e30' seed='1e300'/>",
        "<feTurbulence baseFrequency='1e300 -1' stitchTiles='stitch'/>",
        "<feTurbulence baseFrequency='0.5' stitchTiles='stitch' seed='-1e300'/>",
        "<feTurbulence result='t'/><feDisplacementMap in='SourceGraphic' in2='t' scale='1e308'/>",
        "<feMorphology radius='1e308'/>",
        "<feOffset dx='1e308' dy='-1e308'/>",
        "<feGaussianBlur stdDeviation='1e308 0'/>",
        "<feComposite operator='arithmetic' k1='1e308' k2='-1e308' k3='1e308' k4='1e308'/>",
        "<feComponentTransfer><feFuncR type='gamma' exponent='1e308' amplitude='1e308'/>"
        "<feFuncA type='table' tableValues='1e308 -1e308'/></feComponentTransfer>",
        "<feColorMatrix type='hueRotate' values='1e308'/>",
        "<feDiffuseLighting surfaceScale='1e308'><fePointLight x='1e308' z='-1e308'/>"
        "</feDiffuseLighting>",
        "<feSpecularLighting specularExponent='128' specularConstant='1e308'>"
        "<feSpotLight specularExponent='1e308' limitingConeAngle='1e308'/></feSpecularLighting>",
        "<feDropShadow dx='1e308' stdDeviation='1e308'/>",
    };
    for (size_t i = 0; i < sizeof prims / sizeof prims[0]; i++) {
        char svg[1024];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='20' height='20'>"
                 "<filter id='f' x='-1e300' y='-1' width='1e308' height='3'>%s</filter>"
                 "<rect width='10' height='10' transform='scale(1e-300 1e300)' filter='url(#f)'/>"
                 "<rect width='10' height='10' filter='url(#f)'/></svg>",
                 prims[i]);
        sr_framebuffer *fb = NULL;
        sr_io_error err;
        sr_result r = sr_render_svg(sr_test_ctx(), svg, strlen(svg),
                                    &(sr_svg_desc){ .name = "t.svg" }, &fb, NULL, &err);
        CHECK(r == SR_OK || r == SR_TOO_LARGE || r == SR_BAD_FORMAT);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

/* A filter's float images (16 bytes a pixel of its region each, results
 * kept alive by later readers) count against sr_svg_desc.max_layer_bytes
 * as layers do: eight named floods merged hold nine images at once. */
SR_TEST(a_filter_past_the_memory_left_for_layers_is_refused)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    char svg[2048] = "<svg xmlns='http://www.w3.org/2000/svg' width='64' height='64'>"
                     "<filter id='f'>";
    for (int i = 0; i < 8; i++) {
        snprintf(svg + strlen(svg), sizeof svg - strlen(svg),
                 "<feFlood flood-color='#%06x' flood-opacity='0.2' result='r%d'/>", i * 0x1f1f1f,
                 i);
    }
    strcat(svg, "<feMerge>");
    for (int i = 0; i < 8; i++) {
        snprintf(svg + strlen(svg), sizeof svg - strlen(svg), "<feMergeNode in='r%d'/>", i);
    }
    strcat(svg, "</feMerge></filter><rect width='64' height='64' filter='url(#f)'/></svg>");
    sr_framebuffer *fb = NULL, *unlimited = NULL;
    sr_io_error err;
    sr_svg_info info;
    CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg),
                           &(sr_svg_desc){ .name = "t.svg", .max_layer_bytes = 256 << 10 }, &fb,
                           &info, &err),
             SR_TOO_LARGE);
    CHECK(fb == NULL);
    CHECK(info.over_layer_limit);
    /* nine images of 64 x 64 x 16 bytes, the layer (6 a pixel) and its copy (4) */
    CHECK_STR_CONTAINS(err.message, "t.svg:1: filter \"#f\": its results and the layers open "
                                    "(9 float images of the filter region at once) need about "
                                    "616 KiB besides the image, more than the 256 KiB left for "
                                    "them: draw it smaller");
    /* enough for them: the pixels drawn without a limit */
    CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg),
                           &(sr_svg_desc){ .max_layer_bytes = 616 << 10 }, &fb, &info, &err),
             SR_OK);
    CHECK(!info.over_layer_limit);
    CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg), &(sr_svg_desc){ 0 }, &unlimited,
                           NULL, &err),
             SR_OK);
    if (fb && unlimited) {
        CHECK(memcmp(sr_framebuffer_pixels(fb), sr_framebuffer_pixels(unlimited), 64 * 64 * 4) ==
              0);
        CHECK(pixel(fb, 30, 30)[3] > 0);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    sr_destroy_framebuffer(sr_test_ctx(), unlimited);
}

/* A merge reads every node, each a pass over the region: thousands of
 * nodes cost their passes of the work budget instead of 65. */
SR_TEST(a_merge_of_many_nodes_costs_each_of_the_budget)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    size_t cap = 200000, len = 0;
    char *svg = malloc(cap);
    REQUIRE(svg);
    len += (size_t)snprintf(svg, cap, "<svg xmlns='http://www.w3.org/2000/svg' width='64' "
                                      "height='64'><filter id='f'><feMerge>");
    for (int i = 0; i < 6000; i++) {
        len += (size_t)snprintf(svg + len, cap - len, "<feMergeNode/>");
    }
    snprintf(svg + len, cap - len,
             "</feMerge></filter><rect width='64' height='64' filter='url(#f)'/></svg>");
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    sr_svg_info info;
    CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg), &(sr_svg_desc){ .name = "t.svg" },
                           &fb, &info, &err),
             SR_TOO_LARGE);
    CHECK(!info.over_layer_limit); /* work, not memory */
    CHECK_STR_CONTAINS(err.message, "pixel operations");
    CHECK(info.work_used <= info.work_budget);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free(svg);
}

/* The SourceGraphic is drawn over the filter region beyond the image as
 * far as the primitives can move it in: a square drawn left of the image
 * and offset into it shows; where the memory left for layers holds only
 * the image, it is drawn up to the image's edges with one warning. */
SR_TEST(a_filter_brings_in_what_lies_beyond_the_image)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char svg[] =
        "<svg xmlns='http://www.w3.org/2000/svg' width='64' height='64'>"
        "<filter id='f' filterUnits='userSpaceOnUse' x='-64' y='0' width='192' height='64'>"
        "<feOffset dx='50'/></filter>"
        "<rect x='-40' y='10' width='30' height='40' fill='#00f' filter='url(#f)'/></svg>";
    sr_framebuffer *fb = render(svg, SR_OK, NULL, NULL, 0);
    REQUIRE(fb);
    CHECK_EQ(pixel(fb, 20, 30)[2], 255); /* moved in from x = -30 */
    CHECK_EQ(pixel(fb, 20, 30)[3], 255);
    CHECK_EQ(pixel(fb, 45, 30)[3], 0);
    CHECK_EQ(pixel(fb, 20, 5)[3], 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    /* 166 x 64 pixels would hold two images of the region, the layer and
     * its copy (about 446 KiB); the image's 64 x 64 about 172 KiB */
    sr_test_warnings warn = { 0 };
    sr_io_error err;
    CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg),
                           &(sr_svg_desc){ .name = "t.svg", .max_layer_bytes = 300 << 10,
                                           .warn = sr_test_collect_warning, .warn_user = &warn },
                           &fb, NULL, &err),
             SR_OK);
    REQUIRE(fb);
    CHECK_EQ(warn.count, 1);
    CHECK_STR_CONTAINS(warn.text, "t.svg:1: warning: filter region beyond the image: its source "
                                  "drawn up to the image's edges, as the memory left for layers "
                                  "holds no more");
    CHECK_EQ(pixel(fb, 20, 30)[3], 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* Nor does the larger layer make a drawing refused that drew before: where
 * it would pass the work budget (a tile reaches the whole region, here
 * three times the image each way) or the largest framebuffer (an offset
 * of 7000 pixels on an image 8000 wide), the source is drawn up to the
 * image's edges, with one warning. */
SR_TEST(a_filter_region_beyond_the_image_stays_within_the_budgets)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const struct { const char *svg, *why; } cases[] = {
        { "<svg xmlns='http://www.w3.org/2000/svg' width='700' height='700'>"
          "<filter id='f' filterUnits='userSpaceOnUse' x='-2000' y='-2000' width='5000'"
          " height='5000'><feTile/><feOffset dx='1'/><feOffset dx='1'/></filter>"
          "<rect width='700' height='700' fill='#00f' filter='url(#f)'/></svg>",
          "as the work budget holds no more" },
        { "<svg xmlns='http://www.w3.org/2000/svg' width='8000' height='4'>"
          "<filter id='f' filterUnits='userSpaceOnUse' x='-8000' y='0' width='16000'"
          " height='4'><feOffset dx='7000'/></filter>"
          "<rect x='-7000' width='100' height='4' fill='#00f' filter='url(#f)'/></svg>",
          "as the largest layer holds no more" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sr_test_warnings warn = { 0 };
        sr_framebuffer *fb = render(cases[i].svg, SR_OK, &warn, NULL, 0);
        CHECK_EQ(warn.count, 1);
        CHECK_STR_CONTAINS(warn.text, cases[i].why);
        if (fb) {
            CHECK_EQ(pixel(fb, 5, 1)[3], i == 0 ? 255 : 0); /* drawn; not moved in */
            CHECK_EQ(pixel(fb, 5, 1)[2], i == 0 ? 255 : 0);
        }
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

/* The document drawn at its own size, its counted work in *info. */
static sr_result render_info(const char *svg, sr_svg_info *info, char *msg, size_t n)
{
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    sr_result r = sr_render_svg(sr_test_ctx(), svg, strlen(svg), &(sr_svg_desc){ .name = "t.svg" },
                                &fb, info, &err);
    if (msg) {
        snprintf(msg, n, "%s", err.message);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    return r;
}

/* A morphology's window costs the same whatever its radius (van Herk and
 * Gil-Werman's blocks), and is what the direct min and max give: a
 * dilated pixel becomes a (2 rx + 1) x (2 ry + 1) box, an eroded square
 * shrinks by the radius each side. */
SR_TEST(morphology_is_exact_and_its_cost_does_not_grow_with_the_radius)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_framebuffer *fb = render("<svg xmlns='http://www.w3.org/2000/svg' width='40' height='40'>"
                                "<filter id='d' filterUnits='userSpaceOnUse' x='0' y='0' width='40'"
                                " height='40'><feMorphology operator='dilate' radius='3 5'/></filter>"
                                "<filter id='e' filterUnits='userSpaceOnUse' x='0' y='0' width='40'"
                                " height='40'><feMorphology radius='2'/></filter>"
                                "<rect x='20' y='20' width='1' height='1' filter='url(#d)'/>"
                                "<rect x='2' y='2' width='10' height='12' filter='url(#e)'/></svg>",
                                SR_OK, NULL, NULL, 0);
    if (fb) {
        int wrong = 0;
        for (int y = 0; y < 40; y++) {
            for (int x = 0; x < 40; x++) {
                bool in = (x >= 17 && x <= 23 && y >= 15 && y <= 25) ||
                          (x >= 4 && x < 10 && y >= 4 && y < 12);
                wrong += pixel(fb, x, y)[3] != (in ? 255 : 0);
            }
        }
        CHECK_EQ(wrong, 0);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    /* radius 3 and 10^9 over a 1000 x 1000 image: the same work counted,
     * within the budget (the direct window counted 56 passes for 3) */
    double used[2];
    for (int i = 0; i < 2; i++) {
        char svg[512];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='1000' height='1000'>"
                 "<filter id='f' x='0' y='0' width='1' height='1'>"
                 "<feMorphology radius='%s'/></filter>"
                 "<rect width='1000' height='1000' filter='url(#f)'/></svg>",
                 i ? "1e9" : "3");
        sr_svg_info info;
        CHECK_EQ(render_info(svg, &info, NULL, 0), SR_OK);
        CHECK(info.work_used <= info.work_budget);
        used[i] = info.work_used;
    }
    CHECK_EQ(used[0], used[1]);
}

/* A blur counts its taps along each axis: the exact kernel's 2 ceil(3 s)
 * + 1 below a deviation of 2 pixels, three running sums from 2 up, none
 * for 0; and so does a drop shadow's.  Otherwise a chain of small blurs
 * costs many times the work it was counted for. */
SR_TEST(a_blur_counts_its_taps_in_the_work)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char *const prims[] = {
        "<feGaussianBlur stdDeviation='0'/>", "<feGaussianBlur stdDeviation='1'/>",
        "<feGaussianBlur stdDeviation='1.9 0'/>", "<feGaussianBlur stdDeviation='5'/>",
        "<feDropShadow stdDeviation='0' dx='0' dy='0'/>",
        "<feDropShadow stdDeviation='1' dx='0' dy='0'/>",
    };
    double used[6];
    for (int i = 0; i < 6; i++) {
        char svg[512];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='100' height='100'>"
                 "<filter id='f' x='0' y='0' width='1' height='1'>%s</filter>"
                 "<rect width='100' height='100' filter='url(#f)'/></svg>",
                 prims[i]);
        sr_svg_info info;
        CHECK_EQ(render_info(svg, &info, NULL, 0), SR_OK);
        CHECK(info.work_used <= info.work_budget);
        used[i] = info.work_used;
    }
    CHECK_EQ(used[1] - used[0], (7 + 7) * 100.0 * 100);
    CHECK_EQ(used[2] - used[0], 13 * 100.0 * 100);
    CHECK_EQ(used[3] - used[0], (3 + 3) * 100.0 * 100);
    CHECK_EQ(used[5] - used[4], (7 + 7) * 100.0 * 100);
}

/* What grows with a primitive's attributes is counted before it runs,
 * and refused at the primitive's line: a convolution's kernel (order 64,
 * 4096 entries a pixel), noise's octaves, a chain of many primitives. */
SR_TEST(primitives_whose_work_grows_are_refused_at_their_line)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static char kernel[4096 * 2 + 1];
    for (int i = 0; i < 4096; i++) {
        memcpy(kernel + 2 * i, "1 ", 2);
    }
    static char chain[1024 * 40 + 1];
    for (int i = 0; i < 1000; i++) {
        strcat(chain, "<feColorMatrix type='saturate'/>");
    }
    static const char *const head =
        "<svg xmlns='http://www.w3.org/2000/svg' width='1000' height='1000'>\n"
        "<filter id='f' x='0' y='0' width='1' height='1'>\n";
    const char *prims[3] = { NULL, "<feTurbulence baseFrequency='0.1' numOctaves='1000'/>", chain };
    char conv[4096 * 2 + 128];
    snprintf(conv, sizeof conv, "<feConvolveMatrix order='64' kernelMatrix='%s'/>", kernel);
    prims[0] = conv;
    for (int i = 0; i < 3; i++) {
        size_t n = strlen(head) + strlen(prims[i]) + 256;
        char *svg = malloc(n), msg[512];
        snprintf(svg, n, "%s%s</filter>\n<rect width='1000' height='1000' filter='url(#f)'/></svg>",
                 head, prims[i]);
        sr_svg_info info;
        sr_test_warnings warn = { 0 };
        sr_framebuffer *fb = NULL;
        sr_io_error err;
        sr_svg_desc d = { .name = "t.svg", .warn = sr_test_collect_warning, .warn_user = &warn };
        CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg), &d, &fb, &info, &err),
                 SR_TOO_LARGE);
        snprintf(msg, sizeof msg, "%s", err.message);
        CHECK_STR_CONTAINS(msg, "t.svg:3: the drawing costs more than");
        CHECK_EQ(warn.count, 0); /* refused, not drawn transparent with a warning */
        CHECK(info.work_used <= info.work_budget);
        CHECK(!info.over_layer_limit);
        free(svg);
    }
}

/* A chain past the work budget is refused before any of it runs, not
 * after doing the work of the primitives before the one that passes it
 * (a chain of 500 blurs spent seconds so under the fuzz build): the
 * first blur's edgeMode, warned when it runs, is never warned. */
SR_TEST(a_filter_past_the_budget_is_refused_before_it_runs)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    char svg[2048] = "<svg xmlns='http://www.w3.org/2000/svg' width='1000' height='1000'>\n"
                     "<filter id='f' x='0' y='0' width='1' height='1'>\n"
                     "<feGaussianBlur stdDeviation='1' edgeMode='sideways'/>\n";
    for (int i = 0; i < 20; i++) {
        strcat(svg, "<feColorMatrix type='saturate'/>");
    }
    strcat(svg, "</filter>\n<rect width='1000' height='1000' filter='url(#f)'/></svg>");
    sr_test_warnings warn = { 0 };
    char msg[512];
    sr_framebuffer *fb = render(svg, SR_TOO_LARGE, &warn, msg, sizeof msg);
    CHECK(fb == NULL);
    CHECK_STR_CONTAINS(msg, "t.svg:4: the drawing costs more than");
    CHECK_EQ(warn.count, 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* The larger layer is chosen on the work the filter will count, kernels
 * included: a convolution of order 5 after an offset that brings content
 * in from 300 px beyond the image fits the budget on the image's layer,
 * not on the larger one, so the source is drawn up to the image's edges
 * with a warning instead of the drawing being refused. */
SR_TEST(a_larger_filter_layer_is_chosen_on_the_work_it_will_count)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_test_warnings warn = { 0 };
    sr_framebuffer *fb = render(
        "<svg xmlns='http://www.w3.org/2000/svg' width='1000' height='1000'>"
        "<filter id='f' filterUnits='userSpaceOnUse' x='-400' y='0' width='1400' height='1000'>"
        "<feOffset dx='300'/><feConvolveMatrix order='5' kernelMatrix='0 0 0 0 0 0 0 0 0 0 0 0 1"
        " 0 0 0 0 0 0 0 0 0 0 0 0'/></filter>"
        "<rect x='-300' width='1300' height='1000' fill='#00f' filter='url(#f)'/></svg>",
        SR_OK, &warn, NULL, 0);
    CHECK_EQ(warn.count, 1);
    CHECK_STR_CONTAINS(warn.text, "as the work budget holds no more");
    if (fb) {
        CHECK_EQ(pixel(fb, 100, 500)[3], 0);   /* not moved in */
        CHECK_EQ(pixel(fb, 400, 500)[3], 255); /* moved from the image */
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* The layer grows beyond the image only by what can reach it: not at all
 * for a filter that reads no source (a flood tiled over a region three
 * times the image's size), and for an offset only on the side it pulls
 * content from.  The layer's pixels are counted for each pass, so the
 * work counted shows its size: the same as with the region cut to the
 * image. */
SR_TEST(a_filter_layer_grows_only_by_what_can_reach_the_image)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const struct { const char *prims, *wide, *left; } cases[] = {
        { "<feFlood flood-color='#f00' x='10' y='10' width='5' height='5'/><feTile/>",
          "x='-400' y='-400' width='1200' height='1200'", NULL },
        { "<feOffset dx='20'/>", "x='0' y='0' width='900' height='400'",
          "x='-500' y='0' width='900' height='400'" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double used[3] = { 0, 0, 0 };
        const char *regions[3] = { "x='0' y='0' width='400' height='400'", cases[i].wide,
                                   cases[i].left };
        for (int k = 0; k < 3 && regions[k]; k++) {
            char svg[1024];
            snprintf(svg, sizeof svg,
                     "<svg xmlns='http://www.w3.org/2000/svg' width='400' height='400'>"
                     "<filter id='f' filterUnits='userSpaceOnUse' %s>%s</filter>"
                     "<rect x='-100' width='600' height='400' fill='#00f' filter='url(#f)'/></svg>",
                     regions[k], cases[i].prims);
            sr_svg_info info;
            CHECK_EQ(render_info(svg, &info, NULL, 0), SR_OK);
            used[k] = info.work_used;
        }
        /* an offset's extra pixel either side, for a shift between pixels */
        CHECK(used[1] >= used[0] && used[1] <= used[0] + (cases[i].left ? 400.0 * 8 : 0));
        if (cases[i].left) {
            /* 21 columns more (the shift and a pixel), counted per pass */
            CHECK(used[2] > used[0]);
            CHECK(used[2] < used[0] + 400.0 * 22 * 8);
        }
    }
}

/* A primitive subregion far beyond the region is empty: its pixel
 * coordinates are cut to the region before they become ints (an x of
 * 10^30 made the cut-off write far outside the image). */
SR_TEST(a_subregion_beyond_int_range_is_empty)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char *const subs[] = { "x='1e30' width='-5'", "x='1e30'", "y='-1e30' height='1'",
                                        "x='-1e300' width='1e-300'" };
    for (size_t i = 0; i < sizeof subs / sizeof subs[0]; i++) {
        char svg[512];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='64' height='64'>"
                 "<filter id='i'><feOffset %s/></filter>"
                 "<rect width='30' height='20' fill='#c36' filter='url(#i)'/></svg>",
                 subs[i]);
        sr_framebuffer *fb = render(svg, SR_OK, NULL, NULL, 0);
        if (fb) {
            CHECK_EQ(pixel(fb, 10, 10)[3], 0);
        }
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}
