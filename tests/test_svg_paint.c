/* test_svg_paint.c - the SVG reader's structure, styling and paint
 * servers: style sheets with the cascade, currentColor, CSS colors, defs
 * and use, linear and radial gradients, clip paths, masks and group
 * opacity in layers, nested viewports, dashed strokes, markers,
 * paint-order and patterns.  The drawings in
 * tests/data/svg are compared with references (checked against rsvg-convert when made;
 * channel tolerance 2, at most 0.5% of the pixels beyond it; the diff
 * image goes to the test output directory), and single pixels are
 * checked against values worked out by hand.  Reference cycles through
 * use, clip-path, mask, marker and pattern are refused with FILE:LINE. */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, for guard_alloc.h */
#include "guard_alloc.h"
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <stdlib.h>
#include <string.h>

static sr_framebuffer *render(sr_context *ctx, const char *svg, sr_result want, char *msg,
                              size_t n)
{
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    sr_result r = sr_render_svg(ctx, svg, strlen(svg),
                                &(sr_svg_desc){ .name = "t.svg", .background = { 1, 1, 1, 1 } },
                                &fb, NULL, &err);
    CHECK_EQ(r, want);
    if (msg) {
        snprintf(msg, n, "%s", err.message);
    }
    return fb;
}

static const uint8_t *pixel(const sr_framebuffer *fb, int x, int y)
{
    return sr_framebuffer_pixels(fb) + ((size_t)y * (size_t)sr_framebuffer_width(fb) + x) * 4;
}

static void check_drawing(const char *file, const char *ref)
{
    char in[1024];
    snprintf(in, sizeof in, "%s/data/svg/%s", sr_test_src_dir(), file);
    sr_context *ctx = sr_test_ctx();
    sr_framebuffer *fb = NULL;
    sr_svg_info info;
    sr_io_error err;
    CHECK_EQ(sr_render_svg_file(ctx, in,
                                &(sr_svg_desc){ .scale = 3, .background = { 1, 1, 1, 1 } }, &fb,
                                &info, &err),
             SR_OK);
    if (fb) {
        CHECK_EQ(info.warnings, 0);
        int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
        sr_test_check_image(ref, sr_framebuffer_pixels(fb), w, h, 2, (long)w * h / 200);
        sr_destroy_framebuffer(ctx, fb);
    }
}

/* styles: sheets, use, colors; gradients; layers: clip paths and group
 * opacity; clipbox: clips in bounding-box units; masks; nested svg
 * viewports; dashes: stroke-dasharray and -dashoffset on lines, curves
 * and closed shapes; markers: orient, markerUnits, viewBox, paint-order;
 * patterns: units, viewBox, patternTransform, href inheritance;
 * maskregion: mask regions and content units, mask-type in a sheet;
 * switch: systemLanguage and requiredExtensions in and out of a switch;
 * nonscaling: vector-effect="non-scaling-stroke"; origin: transform-origin;
 * blend: the sixteen mix-blend-modes and isolation; images: a JPEG file
 * and a PNG data: URI under preserveAspectRatio; svgimage: SVG documents
 * as images (a file and a percent-encoded data: URI), as vector content
 * clipped to the image's viewport; overflow: nested svg viewports that
 * clip and those with overflow visible; markerlayers: marker content in
 * layers of its own, cut to the marker's viewport; serverorigin:
 * transform-origin on gradientTransform and patternTransform; stopinherit:
 * stops inherit from the gradient's ancestors, not the shape's;
 * selectors: attribute tests, :first-child, sibling combinators;
 * clipchild: clip-path on the children of a clipPath, and on uses in it */
static const char *const names[] = { "styles", "gradients", "layers", "clipbox", "masks",
                                      "nested", "dashes", "markers", "patterns", "maskregion",
                                      "switch", "nonscaling", "origin", "blend", "images",
                                      "svgimage", "overflow", "markerlayers", "serverorigin",
                                      "stopinherit", "selectors", "clipchild" };
enum { DRAWINGS = sizeof names / sizeof names[0] };

SR_TEST(drawings_match_references)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    for (size_t i = 0; i < DRAWINGS; i++) {
        if (strcmp(names[i], "images") == 0 && !sr_io_have_jpeg()) {
            continue; /* its picture is a JPEG */
        }
        char file[64], ref[64];
        snprintf(file, sizeof file, "%s.svg", names[i]);
        snprintf(ref, sizeof ref, "svg_%s", names[i]);
        check_drawing(file, ref);
    }
}

/* A drawing of tests/data/svg at scale 3 (NULL after a failure, counted). */
static sr_framebuffer *render_file(sr_context *ctx, const char *file)
{
    char in[1024];
    snprintf(in, sizeof in, "%s/data/svg/%s", sr_test_src_dir(), file);
    sr_framebuffer *fb = NULL;
    CHECK_EQ(sr_render_svg_file(ctx, in, &(sr_svg_desc){ .scale = 3 }, &fb, NULL, NULL), SR_OK);
    return fb;
}

SR_TEST(server_transform_origin_is_the_transform_moved_there_and_back)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* each transform-origin O of a gradient or pattern draws what
     * translate(O) T translate(-O) does, byte for byte */
    sr_framebuffer *a = render_file(ctx, "serverorigin.svg");
    sr_framebuffer *b = render_file(ctx, "serverorigin-expanded.svg");
    REQUIRE(a && b);
    size_t n = (size_t)sr_framebuffer_width(a) * (size_t)sr_framebuffer_height(a) * 4;
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), n) == 0);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
}

SR_TEST(an_empty_pattern_tile_paints_the_fallback_color)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* tiles of no width, of no height, of neither (no size given, an href
     * to nothing): the fallback green paints; without one, nothing does
     * (the white background stays) */
    sr_framebuffer *fb = render(ctx,
        "<svg xmlns='http://www.w3.org/2000/svg' width='40' height='10'>"
        "<pattern id='w' width='0' height='4' patternUnits='userSpaceOnUse'>"
        "<rect width='4' height='4' fill='red'/></pattern>"
        "<pattern id='h' width='1' height='0'><rect width='1' height='1' fill='red'/></pattern>"
        "<pattern id='n' href='#missing'><rect width='10' height='10' fill='red'/></pattern>"
        "<rect width='10' height='10' fill='url(#w) #0f0'/>"
        "<rect x='10' width='10' height='10' fill='url(#h) #0f0'/>"
        "<rect x='20' width='10' height='10' fill='url(#n) #0f0'/>"
        "<rect x='30' width='10' height='10' fill='url(#n)'/></svg>",
        SR_OK, NULL, 0);
    REQUIRE(fb);
    for (int i = 0; i < 4; i++) {
        const uint8_t *p = pixel(fb, i * 10 + 5, 5);
        CHECK(p[0] == (i < 3 ? 0 : 255) && p[1] == 255 && p[2] == (i < 3 ? 0 : 255));
    }
    sr_destroy_framebuffer(ctx, fb);
}

/* The document `doc` rendered as it is (*a) and with every reference
 * that starts with `ref` made to name server 1 of its letter (the digit
 * of "url(#p2)" made 1: *b). */
static void render_uses(sr_context *ctx, const char *doc, const char *ref, sr_framebuffer **a,
                        sr_framebuffer **b)
{
    size_t n = strlen(doc);
    char *same = malloc(n + 1);
    REQUIRE(same);
    memcpy(same, doc, n + 1);
    for (char *s = same; (s = strstr(s, ref)) != NULL; s += 6) {
        s[6] = '1';
    }
    *a = render(ctx, doc, SR_OK, NULL, 0);
    *b = render(ctx, same, SR_OK, NULL, 0);
    free(same);
}

/* A pattern's uses: one after another with the same map (its tile kept),
 * under another map, with other patterns between (one of the same size)
 * and inside. */
static const char pattern_uses[] =
    "<svg xmlns='http://www.w3.org/2000/svg' width='60' height='20'>"
    "<pattern id='q' width='1' height='1' patternUnits='userSpaceOnUse'>"
    "<rect width='1' height='1' fill='#f00'/></pattern>"
    "<pattern id='p1' width='4' height='4' patternUnits='userSpaceOnUse'>"
    "<rect width='4' height='4' fill='#00f'/><rect width='2' height='2' fill='url(#q)'/></pattern>"
    "<pattern id='p2' href='#p1'/><pattern id='p3' href='#p1'/><pattern id='p4' href='#p1'/>"
    "<rect width='10' height='20' fill='url(#p1)'/>"
    "<pattern id='g' width='4' height='4' patternUnits='userSpaceOnUse'>"
    "<rect width='4' height='4' fill='#0f0'/></pattern>"
    "<rect x='40' width='10' height='20' fill='url(#g)'/>"
    "<rect x='10' width='10' height='20' fill='url(#p2)'/>"
    "<g transform='translate(20 0.5) scale(2)'><rect width='10' height='10' fill='url(#p3)'/></g>"
    "<rect x='50' width='10' height='20' fill='url(#p4)'/></svg>";

SR_TEST(a_kept_pattern_tile_paints_as_a_new_one)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* each use its own pattern (a tile drawn for each), then all of them
     * the same one (its tile kept where the map allows) */
    sr_framebuffer *a, *b;
    render_uses(ctx, pattern_uses, "url(#p", &a, &b);
    REQUIRE(a && b);
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), 60 * 20 * 4) == 0);
    /* the scaled use has 4 px red squares: the tile drawn again at twice the size */
    CHECK(pixel(b, 21, 2)[0] == 255 && pixel(b, 24, 2)[2] == 255 && pixel(b, 21, 9)[0] == 255);
    /* a tile of the same size and map from another pattern */
    CHECK(pixel(b, 45, 10)[1] == 255 && pixel(b, 45, 10)[0] == 0);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
}

/* A gradient's uses: one after another (its stops and color table kept),
 * with another gradient between, on boxes of other sizes and places. */
static const char gradient_uses[] =
    "<svg xmlns='http://www.w3.org/2000/svg' width='80' height='40'>"
    "<linearGradient id='l' x2='0.7' spreadMethod='reflect'><stop offset='0.1' stop-color='#e22'/>"
    "<stop offset='0.5' stop-color='#2c4' stop-opacity='0.6'/><stop offset='1' stop-color='#35f'/>"
    "</linearGradient>"
    "<radialGradient id='r' fx='0.3'><stop stop-color='#fc0'/><stop offset='1' stop-color='#306'/>"
    "</radialGradient>"
    "<linearGradient id='l1' href='#l'/><linearGradient id='l2' href='#l'/>"
    "<linearGradient id='l3' href='#l'/><linearGradient id='l4' href='#l'/>"
    "<radialGradient id='r1' href='#r'/><radialGradient id='r2' href='#r'/>"
    "<rect width='80' height='40' fill='url(#l1)'/>"
    "<rect x='3.3' y='2.5' width='7' height='30' fill='url(#l2)'/>"
    "<rect x='20.5' y='5' width='31' height='9.7' fill='url(#l3)'/>"
    "<rect x='10' y='10' width='40' height='25' fill='url(#r1)' fill-opacity='0.7'/>"
    "<rect x='52' y='1.2' width='6.5' height='6.5' fill='url(#r2)'/>"
    "<rect x='60' y='20' width='19' height='19' fill='url(#l4)'/></svg>";

SR_TEST(a_kept_gradient_paints_as_a_new_one)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* each use its own gradient element (stops read for each), then each
     * kind the same one (its stops and table kept between uses) */
    sr_framebuffer *a, *b;
    render_uses(ctx, gradient_uses, "url(#", &a, &b);
    REQUIRE(a && b);
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), 80 * 40 * 4) == 0);
    /* the gradients painted: the radial one's centre is yellow-ish */
    CHECK(pixel(b, 55, 4)[0] > 150 && pixel(b, 55, 4)[2] < 100);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
}

SR_TEST(the_marker_shorthand_is_a_property_not_an_attribute)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* a 4 x 4 red marker at each vertex of two unstroked lines: through
     * style="marker: ..." it is drawn, through marker="..." not */
    sr_framebuffer *fb = render(ctx,
        "<svg xmlns='http://www.w3.org/2000/svg' width='20' height='20'>"
        "<marker id='m' markerWidth='4' markerHeight='4' refX='2' refY='2'"
        " markerUnits='userSpaceOnUse'><rect width='4' height='4' fill='#f00'/></marker>"
        "<path d='M5 5 H15' style='marker: url(#m)'/>"
        "<path d='M5 15 H15' marker='url(#m)'/></svg>",
        SR_OK, NULL, 0);
    REQUIRE(fb);
    CHECK(pixel(fb, 5, 5)[0] == 255 && pixel(fb, 5, 5)[1] == 0);
    CHECK(pixel(fb, 15, 5)[0] == 255 && pixel(fb, 15, 5)[1] == 0);
    CHECK(pixel(fb, 5, 15)[1] == 255 && pixel(fb, 15, 15)[1] == 255);
    sr_destroy_framebuffer(ctx, fb);
}

SR_TEST(cascade_orders_attributes_sheets_style_and_important)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* column 0: a sheet rule beats the attribute; 1: the id beats the
     * class; 2: style="" beats the sheet; 3: !important beats style="";
     * 4: the child selector misses a grandchild; 5: currentColor from
     * the color of an ancestor's class */
    sr_framebuffer *fb = render(ctx,
        "<svg xmlns='http://www.w3.org/2000/svg' width='60' height='10'>"
        "<style>.a{fill:#00f} #b{fill:#0f0} .a{stroke:none} rect.i{fill:#f00 !important}"
        " svg > .c{fill:#f00} .t{color:#ff0}</style>"
        "<rect class='a' width='10' height='10' fill='#f00'/>"
        "<rect id='b' class='a' x='10' width='10' height='10'/>"
        "<rect class='a' x='20' width='10' height='10' style='fill:#0f0'/>"
        "<rect class='i' x='30' width='10' height='10' style='fill:#000'/>"
        "<g><rect class='c' x='40' width='10' height='10'/></g>"
        "<g class='t'><rect x='50' width='10' height='10' fill='currentColor'/></g></svg>",
        SR_OK, NULL, 0);
    REQUIRE(fb);
    static const uint8_t want[6][3] = { { 0, 0, 255 }, { 0, 255, 0 }, { 0, 255, 0 },
                                        { 255, 0, 0 }, { 0, 0, 0 },   { 255, 255, 0 } };
    for (int i = 0; i < 6; i++) {
        const uint8_t *p = pixel(fb, i * 10 + 5, 5);
        CHECK(p[0] == want[i][0] && p[1] == want[i][1] && p[2] == want[i][2]);
    }
    sr_destroy_framebuffer(ctx, fb);
}

SR_TEST(css_color_syntaxes_give_the_same_color)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* the same orange at half opacity over white, eight ways */
    static const char *forms[] = { "#ff800080", "#ff8000' fill-opacity='0.502",
                                   "rgba(255, 128, 0, 0.502)", "rgb(255 128 0 / 50.2%)",
                                   "rgb(100%, 50.2%, 0%, 0.502)", "hsla(30.12, 100%, 50%, 0.502)",
                                   "hsl(30.12deg 100% 50% / 0.502)", "#f80' fill-opacity='0.502" };
    for (size_t i = 0; i < sizeof forms / sizeof forms[0]; i++) {
        char svg[512];
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>"
                 "<rect width='4' height='4' fill='%s'/></svg>", forms[i]);
        sr_framebuffer *fb = render(ctx, svg, SR_OK, NULL, 0);
        REQUIRE(fb);
        const uint8_t *p = pixel(fb, 2, 2);
        int g = i == 7 ? 195 : 191; /* #f80 is 136 of green, not 128 */
        if (!(p[0] == 255 && abs(p[1] - g) <= 1 && abs(p[2] - 127) <= 1)) {
            sr_test_fail(__FILE__, __LINE__, "%s: %d %d %d", forms[i], p[0], p[1], p[2]);
        }
        sr_destroy_framebuffer(ctx, fb);
    }
    /* too many hex digits: not a color (warned), the fill stays black */
    sr_framebuffer *fb = render(ctx, "<svg xmlns='http://www.w3.org/2000/svg' width='4' "
                                     "height='4'><rect width='4' height='4' "
                                     "fill='#ff8000ff00ff8000ff'/></svg>", SR_OK, NULL, 0);
    REQUIRE(fb);
    CHECK_EQ(pixel(fb, 2, 2)[0], 0);
    sr_destroy_framebuffer(ctx, fb);
}

SR_TEST(linear_gradient_interpolates_between_stops)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* black to white over x = 0..100: pixel x (centre x + 0.5) is
     * 255 (x + 0.5) / 100, padded beyond the vector's ends */
    sr_framebuffer *fb = render(ctx,
        "<svg xmlns='http://www.w3.org/2000/svg' width='120' height='4'>"
        "<linearGradient id='g' gradientUnits='userSpaceOnUse' x2='100'>"
        "<stop stop-color='#000'/><stop offset='1' stop-color='#fff'/></linearGradient>"
        "<rect width='120' height='4' fill='url(#g)'/></svg>",
        SR_OK, NULL, 0);
    REQUIRE(fb);
    for (int x = 0; x < 120; x += 7) {
        double want = x >= 100 ? 255 : 255 * (x + 0.5) / 100;
        CHECK(abs(pixel(fb, x, 2)[0] - (int)(want + 0.5)) <= 1);
    }
    sr_destroy_framebuffer(ctx, fb);
}

SR_TEST(dashes_and_gaps_fall_where_the_pattern_says)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* dashes of 4 from x = 0, 8, 16 (the offset -2 moves them to 2, 10,
     * 18); a closed square whose last dash runs on over its start */
    sr_framebuffer *fb = render(ctx,
                                "<svg xmlns='http://www.w3.org/2000/svg' width='24' height='24'>"
                                "<g stroke='#000' stroke-width='2' fill='none'>"
                                "<line y1='1' x2='24' y2='1' stroke-dasharray='4'/>"
                                "<line y1='5' x2='24' y2='5' stroke-dasharray='4'"
                                " stroke-dashoffset='-2'/>"
                                "<rect x='4' y='10' width='10' height='10'"
                                " stroke-dasharray='6 4' stroke-dashoffset='3'/></g></svg>",
                                SR_OK, NULL, 0);
    REQUIRE(fb != NULL);
    for (int x = 0; x < 24; x++) {
        CHECK_EQ(pixel(fb, x, 0)[0], (x / 4) % 2 ? 255 : 0);
        CHECK_EQ(pixel(fb, x, 4)[0], ((x + 2) / 4) % 2 ? 0 : 255);
    }
    /* the square's dash over its corner (4, 10): 3 before it, 3 after */
    CHECK_EQ(pixel(fb, 5, 10)[0], 0);
    CHECK_EQ(pixel(fb, 4, 17)[0], 0);
    CHECK_EQ(pixel(fb, 4, 14)[0], 255);
    CHECK_EQ(pixel(fb, 9, 10)[0], 255);
    sr_destroy_framebuffer(ctx, fb);
}

SR_TEST(inherit_takes_the_parents_value_of_properties_not_inherited)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* opacity 0.5 on the group and again on the rect: a quarter of black
     * over white; the grey mask (x < 4) on the group and again on the
     * rect: black at (128/255)^2, nothing at x >= 4 */
    sr_framebuffer *fb = render(ctx,
                                "<svg xmlns='http://www.w3.org/2000/svg' width='8' height='4'>"
                                "<mask id='m'><rect width='4' height='4' fill='#808080'/></mask>"
                                "<g opacity='0.5'><rect width='8' height='2' opacity='inherit'/></g>"
                                "<g mask='url(#m)'><rect y='2' width='8' height='2'"
                                " style='mask: inherit'/></g>"
                                "<linearGradient id='g' stop-color='#00f'><stop stop-color='inherit'/>"
                                "</linearGradient><rect x='6' width='2' height='2' fill='url(#g)'/>"
                                "</svg>",
                                SR_OK, NULL, 0);
    REQUIRE(fb != NULL);
    CHECK_NEAR(pixel(fb, 1, 0)[0], 191, 1); /* 255 * (1 - 0.5 * 0.5) */
    CHECK_NEAR(pixel(fb, 1, 3)[0], 191, 2);
    CHECK_EQ(pixel(fb, 6, 3)[0], 255);
    /* stop-color: inherit takes the gradient's */
    CHECK(pixel(fb, 7, 0)[2] == 255 && pixel(fb, 7, 0)[0] == 0);
    sr_destroy_framebuffer(ctx, fb);
}

SR_TEST(images_that_do_not_read_or_lie_outside_are_skipped_with_a_warning)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* a path climbing out, an absolute one, a URL, a missing file, a
     * broken data: URI, text that is no picture: none is read */
    static const char *const hrefs[] = { "../images.svg", "/etc/hostname", "http://x/a.png",
                                         "missing.png", "data:image/png;base64,!!",
                                         "data:text/plain;base64,aGVsbG8=" };
    char name[1024], svg[512];
    snprintf(name, sizeof name, "%s/data/svg/t.svg", sr_test_src_dir());
    for (size_t i = 0; i < sizeof hrefs / sizeof hrefs[0]; i++) {
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>"
                 "<image href='%s' width='4' height='4'/></svg>", hrefs[i]);
        sr_framebuffer *fb = NULL;
        sr_svg_info info;
        sr_io_error err;
        CHECK_EQ(sr_render_svg(ctx, svg, strlen(svg), &(sr_svg_desc){ .name = name }, &fb, &info,
                               &err),
                 SR_OK);
        CHECK_EQ(info.warnings, 1);
        REQUIRE(fb != NULL);
        CHECK_EQ(pixel(fb, 2, 2)[3], 0);
        sr_destroy_framebuffer(ctx, fb);
    }
}

SR_TEST(an_image_has_a_bounding_box_for_clips_in_its_units)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* a 6 x 6 PNG whose top left quarter is opaque #639, drawn 8 x 8 and
     * clipped to the left quarter of its box */
    static const char svg[] =
        "<svg xmlns='http://www.w3.org/2000/svg' width='8' height='8'>"
        "<clipPath id='c' clipPathUnits='objectBoundingBox'>"
        "<rect width='0.25' height='1'/></clipPath>"
        "<image clip-path='url(#c)' width='8' height='8' href='data:image/png;base64,"
        "iVBORw0KGgoAAAANSUhEUgAAAAYAAAAGCAYAAADgzO9IAAAAN0lEQVR4AXXBQQHAQAgDsIKl"
        "eio2zkbxhCb23YcEolf0il78JA6JQ/ZU9FT0VIh+op/olzgkDh9FPBEhoKXwywAAAABJRU5E"
        "rkJggg=='/></svg>";
    sr_framebuffer *fb = render(ctx, svg, SR_OK, NULL, 0);
    REQUIRE(fb != NULL);
    CHECK(pixel(fb, 1, 1)[0] == 0x66 && pixel(fb, 1, 1)[2] == 0x99);
    CHECK_EQ(pixel(fb, 3, 1)[0], 255);
    sr_destroy_framebuffer(ctx, fb);
}

SR_TEST(reference_cycles_are_refused_with_file_and_line)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    static const struct { const char *body, *want; } cases[] = {
        { "<g id='a'>\n<use href='#b'/></g>\n<g id='b'>\n<use href='#a'/></g>",
          "t.svg:5: use: reference cycle through \"#a\"" },
        { "<g id='s'><use href='#s'/></g>", "t.svg:2: use: reference cycle" },
        { "<mask id='m'>\n<rect width='4' height='4' fill='white' mask='url(#m)'/></mask>\n"
          "<rect width='4' height='4' mask='url(#m)'/>",
          "t.svg:3: mask: reference cycle through \"#m\"" },
        { "<clipPath id='a' clip-path='url(#b)'/><clipPath id='b' clip-path='url(#a)'/>\n"
          "<rect width='4' height='4' clip-path='url(#a)'/>",
          "t.svg:3: clip-path: reference cycle through \"#a\"" },
        { "<marker id='m'>\n<path d='M0 0 L1 1' marker-end='url(#m)'/></marker>\n"
          "<path d='M0 0 L2 2' marker-start='url(#m)'/>",
          "t.svg:2: marker: reference cycle through \"#m\"" },
        { "<pattern id='p' width='2' height='2' patternUnits='userSpaceOnUse'>\n"
          "<rect width='1' height='1' fill='url(#p)'/></pattern>\n"
          "<rect width='4' height='4' fill='url(#p)'/>",
          "t.svg:2: pattern: reference cycle through \"#p\"" },
        { "<pattern id='a' href='#b'/>\n<pattern id='b' href='#a'/>\n"
          "<rect width='4' height='4' fill='url(#a)'/>",
          "t.svg:2: pattern: href chain through \"#a\" is a cycle" },
    };
    char msg[1024], svg[1024];
    sr_framebuffer *fb;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(svg, sizeof svg,
                 "<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>\n%s</svg>",
                 cases[i].body);
        fb = render(ctx, svg, SR_BAD_FORMAT, msg, sizeof msg);
        CHECK(fb == NULL);
        CHECK_STR_CONTAINS(msg, cases[i].want);
    }
    /* uses nested a thousand times over: refused by the budget, quickly */
    char big[4096];
    int n = snprintf(big, sizeof big, "<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>"
                                      "<defs><g id='l0'><rect width='1' height='1' fill='none'/></g>");
    for (int i = 1; i < 30; i++) {
        n += snprintf(big + n, sizeof big - (size_t)n,
                      "<g id='l%d'><use href='#l%d'/><use href='#l%d'/></g>", i, i - 1, i - 1);
    }
    snprintf(big + n, sizeof big - (size_t)n, "</defs><use href='#l29'/></svg>");
    fb = render(ctx, big, SR_TOO_LARGE, msg, sizeof msg);
    CHECK(fb == NULL);
}

/* A document as a percent-encoded data: URI of an <image> (malloc'd). */
static char *svg_data_image(const char *doc)
{
    char *out = malloc(strlen(doc) * 3 + 64), *o = out;
    if (!out) {
        abort();
    }
    o += sprintf(o, "data:image/svg+xml,");
    for (const char *c = doc; *c; c++) {
        o += strchr("%<>'\"&#", *c) ? sprintf(o, "%%%02X", (unsigned char)*c)
                                    : sprintf(o, "%c", *c);
    }
    return out;
}

/* The document "<svg ...>\n<image href='URI of inner'/></svg>" (malloc'd). */
static char *svg_wrapping(const char *inner)
{
    char *uri = svg_data_image(inner);
    char *doc = malloc(strlen(uri) + 256);
    if (!doc) {
        abort();
    }
    sprintf(doc, "<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>\n"
                 "<image href='%s' width='4' height='4'/></svg>", uri);
    free(uri);
    return doc;
}

SR_TEST(svg_images_that_include_themselves_or_nest_too_deep_are_refused)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* a file that includes itself, and two that include each other: the
     * line is the <image> that closes the cycle, in the file that has it */
    static const struct { const char *file, *want; } files[] = {
        { "cycle-self.svg", "cycle-self.svg:3: image: reference cycle through \"./cycle-self.svg\"" },
        { "cycle-a.svg", "cycle-b.svg:3: image: reference cycle through \"cycle-a.svg\"" },
    };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char in[1024];
        snprintf(in, sizeof in, "%s/data/svg/%s", sr_test_src_dir(), files[i].file);
        sr_framebuffer *fb = NULL;
        sr_io_error err;
        CHECK_EQ(sr_render_svg_file(ctx, in, &(sr_svg_desc){ 0 }, &fb, NULL, &err),
                 SR_BAD_FORMAT);
        CHECK(fb == NULL);
        CHECK_STR_CONTAINS(err.message, files[i].want);
    }
    /* data: URIs inside each other: 7 deep draw (a green square at the
     * bottom), 8 deep are refused at the outer document's image line
     * (each is drawn in a layer of its own) */
    char *doc = strdup("<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>"
                       "<rect width='4' height='4' fill='#0f0'/></svg>");
    REQUIRE(doc);
    for (int depth = 1; depth <= 8; depth++) {
        char *outer = svg_wrapping(doc);
        free(doc);
        doc = outer;
        char msg[1024];
        sr_framebuffer *fb = render(ctx, doc, depth < 8 ? SR_OK : SR_BAD_FORMAT, msg, sizeof msg);
        if (depth < 8) {
            REQUIRE(fb);
            CHECK(pixel(fb, 2, 2)[0] == 0 && pixel(fb, 2, 2)[1] == 255);
            sr_destroy_framebuffer(ctx, fb);
            /* the images' work counts within the (grown) budgets: each
             * document read costs its bytes (over 100), more than its
             * layer and the 4 x 4 square cost */
            sr_svg_info info;
            CHECK_EQ(sr_render_svg(ctx, doc, strlen(doc), &(sr_svg_desc){ .name = "t.svg" }, &fb,
                                   &info, NULL),
                     SR_OK);
            sr_destroy_framebuffer(ctx, fb);
            CHECK(info.points_used > depth && info.points_used <= info.points_budget);
            CHECK(info.work_used >= 100.0 * depth && info.work_used <= info.work_budget);
        } else {
            CHECK(fb == NULL);
            CHECK_STR_CONTAINS(msg, "t.svg:2: image: SVG images nested deeper than 7");
        }
    }
    free(doc);
    /* malformed content of a data: URI: one line naming the image's line */
    doc = svg_wrapping("<svg xmlns='http://www.w3.org/2000/svg'>\n\n<circle r='1q'/></svg>");
    char msg[1024];
    CHECK(render(ctx, doc, SR_BAD_FORMAT, msg, sizeof msg) == NULL);
    CHECK_STR_CONTAINS(msg, "t.svg:2: ");
    CHECK(strchr(msg, '\n') == NULL);
    free(doc);
    doc = svg_wrapping("<svg xmlns='http://www.w3.org/2000/svg'><rect></svg>");
    CHECK(render(ctx, doc, SR_BAD_FORMAT, msg, sizeof msg) == NULL);
    CHECK_STR_CONTAINS(msg, "t.svg:2: mismatched tag");
    free(doc);
}

SR_TEST(group_opacity_is_one_layer_and_clips_cut)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = sr_test_ctx();
    /* two overlapping black squares at group opacity 0.5: where they
     * overlap the group is as light as where they do not (one layer);
     * then a clip keeps x < 30 of a rect drawn over x 20..40 */
    sr_framebuffer *fb = render(ctx,
        "<svg xmlns='http://www.w3.org/2000/svg' width='40' height='10'>"
        "<clipPath id='k'><rect width='30' height='10'/></clipPath>"
        "<g opacity='0.5'><rect width='10' height='10'/><rect x='5' width='10' height='10'/></g>"
        "<rect x='20' width='20' height='10' fill='#00f' clip-path='url(#k)'/></svg>",
        SR_OK, NULL, 0);
    REQUIRE(fb);
    CHECK_NEAR(pixel(fb, 2, 5)[0], 128, 1);
    CHECK_EQ(pixel(fb, 7, 5)[0], pixel(fb, 2, 5)[0]);
    CHECK_EQ(pixel(fb, 25, 5)[2], 255);
    CHECK_EQ(pixel(fb, 25, 5)[0], 0);
    CHECK_EQ(pixel(fb, 35, 5)[0], 255); /* clipped away: the white background */
    sr_destroy_framebuffer(ctx, fb);
    /* a clip on a clip: a disc cut to its left half (SVG intersects them;
     * rsvg-convert 2.54 ignores the outer clip) */
    fb = render(ctx,
        "<svg xmlns='http://www.w3.org/2000/svg' width='40' height='20'>"
        "<clipPath id='left'><rect width='20' height='20'/></clipPath>"
        "<clipPath id='disc' clip-path='url(#left)'><circle cx='20' cy='10' r='9'/></clipPath>"
        "<rect width='40' height='20' fill='#000' clip-path='url(#disc)'/></svg>",
        SR_OK, NULL, 0);
    REQUIRE(fb);
    CHECK_EQ(pixel(fb, 15, 10)[0], 0);
    CHECK_EQ(pixel(fb, 25, 10)[0], 255);
    CHECK_EQ(pixel(fb, 2, 10)[0], 255);
    sr_destroy_framebuffer(ctx, fb);
}

/* Every drawing above rendered small and narrow at every SIMD level, each
 * buffer the renderer allocates (framebuffer, layers, masks, pattern
 * tiles, images) ending at an unmapped page (guard_alloc.h): no paint
 * reads or writes a pixel past a row's buffer, and every level's image is
 * the scalar level's. */
SR_TEST(small_drawings_stay_inside_their_buffers_at_every_simd_level)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
#ifndef GUARD_ALLOC_WORKS
    SKIP("no mmap here to put a guard page after a buffer");
#else
    /* Each a multiple of 16 pixels: the framebuffer ends at the page. */
    static const int sizes[][2] = { { 3, 64 }, { 7, 32 }, { 9, 16 }, { 17, 16 }, { 64, 1 } };
    enum { SIZES = sizeof sizes / sizeof sizes[0] };
    static guard g;
    static uint8_t first[17 * 16 * 4];
    int runs = 0;
    for (size_t i = 0; i < DRAWINGS; i++) {
        if (strcmp(names[i], "images") == 0 && !sr_io_have_jpeg()) {
            continue; /* its picture is a JPEG */
        }
        char in[1024];
        snprintf(in, sizeof in, "%s/data/svg/%s.svg", sr_test_src_dir(), names[i]);
        for (int si = 0; si < SIZES; si++) {
            int w = sizes[si][0], h = sizes[si][1];
            for (int level = SR_SIMD_OFF; level <= SR_SIMD_AVX512; level++) {
                sr_context *ctx = NULL;
                sr_framebuffer *fb = NULL;
                REQUIRE(guard_context(&g, level, &ctx) == SR_OK);
                CHECK_EQ(sr_render_svg_file(ctx, in, &(sr_svg_desc){
                    .width = w, .height = h, .background = { 1, 1, 1, 0.5f } }, &fb, NULL, NULL),
                         SR_OK);
                if (fb) {
                    const uint8_t *px = sr_framebuffer_pixels(fb);
                    if (level == SR_SIMD_OFF) {
                        memcpy(first, px, (size_t)w * h * 4);
                    } else if (memcmp(first, px, (size_t)w * h * 4) != 0) {
                        sr_test_fail(__FILE__, __LINE__, "%s at %dx%d, SIMD level %d: not the "
                                     "scalar level's image", names[i], w, h, level);
                    }
                    runs++;
                }
                sr_destroy_framebuffer(ctx, fb);
                sr_destroy_context(ctx);
            }
        }
    }
    CHECK_EQ(g.live, 0);
    CHECK(runs >= (DRAWINGS - 1) * SIZES * (SR_SIMD_AVX512 - SR_SIMD_OFF + 1));
#endif
}
