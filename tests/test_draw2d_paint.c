/* test_draw2d_paint.c - the public paint API (sr_fill_polygon_paint,
 * sr_fill_path_paint): a linear gradient, a radial one with a focal
 * circle, each spread method, a transformed gradient and a rotated
 * pattern give the bytes sr_render_svg gives for the equivalent document,
 * at every SIMD level; the gradients' colors are their stops' at their
 * ends and a moved pattern's texels are where it moved them; every field
 * of an sr_paint is validated and a refused call draws nothing; a fill
 * with other stops than the last gets its own color table; fills on
 * framebuffers and images ending at a guard page stay inside them and
 * give every SIMD level the same bytes. */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, for guard_alloc.h */
#include "guard_alloc.h"
#include "softrast.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { W = 64, H = 48 };

/* The shape every case fills: a pentagon off the pixel grid, so that its
 * edges have partial coverage. */
static const sr_point2 shape[] = { { 3.25, 4.5 }, { 58.5, 2.75 }, { 61.0, 40.25 },
                                   { 30.5, 45.5 }, { 1.75, 30.0 } };
#define SHAPE_SVG "<polygon points='3.25,4.5 58.5,2.75 61,40.25 30.5,45.5 1.75,30'"

/* The stops of every gradient case, as the SVG's stops spell them. */
static const sr_gradient_stop stops[] = {
    { 0.0, { 0x20 / 255.0f, 0x60 / 255.0f, 0xc0 / 255.0f, 1 } },
    { 0.4, { 0xf0 / 255.0f, 0xc0 / 255.0f, 0x10 / 255.0f, 0.5f } },
    { 0.4, { 0x10 / 255.0f, 0xa0 / 255.0f, 0x40 / 255.0f, 1 } },
    { 1.0, { 0xc0 / 255.0f, 0x20 / 255.0f, 0x30 / 255.0f, 1 } },
};
#define STOPS_SVG                                                                  \
    "<stop offset='0' stop-color='#2060c0'/>"                                      \
    "<stop offset='0.4' stop-color='#f0c010' stop-opacity='0.5'/>"                 \
    "<stop offset='0.4' stop-color='#10a040'/><stop offset='1' stop-color='#c02030'/>"

/* The 4 x 4 tile of the pattern case, flat 2 x 2 quarters (the SVG draws
 * them as pixel-aligned rects: their tile's bytes are these). */
static uint8_t tile[4 * 4 * 4];
static const uint8_t quarter[4][4] = {
    { 0xe0, 0x30, 0x30, 255 }, { 0x30, 0xb0, 0x40, 255 },
    { 0x30, 0x50, 0xd0, 255 }, { 0xf0, 0xe0, 0x20, 255 } };
#define TILE_SVG                                                                   \
    "<rect width='2' height='2' fill='#e03030'/>"                                  \
    "<rect x='2' width='2' height='2' fill='#30b040'/>"                            \
    "<rect y='2' width='2' height='2' fill='#3050d0'/>"                            \
    "<rect x='2' y='2' width='2' height='2' fill='#f0e020'/>"

static void make_tile(void)
{
    for (int y = 0; y < 4; y++) {
        for (int x = 0; x < 4; x++) {
            memcpy(tile + (y * 4 + x) * 4, quarter[(y / 2) * 2 + x / 2], 4);
        }
    }
}

static const sr_affine2 skew = { 0.8, 0.3, -0.2, 1.1, 4, -3 };
static const sr_affine2 turn = { 0.8, 0.6, -0.6, 0.8, 0, 0 };

typedef struct paint_case {
    const char *name;
    const char *svg;      /* the document's defs and fill */
    sr_paint paint;
} paint_case;

static const sr_point2 focal = { 22, 15 };

static const paint_case cases[] = {
    { "linear pad",
      "<linearGradient id='p' gradientUnits='userSpaceOnUse' x1='10' y1='8' x2='50' "
      "y2='30'>" STOPS_SVG "</linearGradient>",
      { .kind = SR_PAINT_LINEAR_GRADIENT, .x1 = 10, .y1 = 8, .x2 = 50, .y2 = 30,
        .stops = stops, .stop_count = 4 } },
    { "linear reflect",
      "<linearGradient id='p' gradientUnits='userSpaceOnUse' x1='20' y1='10' x2='30' "
      "y2='14' spreadMethod='reflect'>" STOPS_SVG "</linearGradient>",
      { .kind = SR_PAINT_LINEAR_GRADIENT, .x1 = 20, .y1 = 10, .x2 = 30, .y2 = 14,
        .stops = stops, .stop_count = 4, .spread = SR_SPREAD_REFLECT } },
    { "linear repeat, transformed",
      "<linearGradient id='p' gradientUnits='userSpaceOnUse' x1='0' y1='0' x2='12' y2='0' "
      "spreadMethod='repeat' gradientTransform='matrix(0.8 0.3 -0.2 1.1 4 -3)'>" STOPS_SVG
      "</linearGradient>",
      { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 12, .stops = stops, .stop_count = 4,
        .spread = SR_SPREAD_REPEAT, .transform = &skew } },
    { "radial pad, focal",
      "<radialGradient id='p' gradientUnits='userSpaceOnUse' cx='30' cy='20' r='18' "
      "fx='22' fy='15' fr='2'>" STOPS_SVG "</radialGradient>",
      { .kind = SR_PAINT_RADIAL_GRADIENT, .cx = 30, .cy = 20, .r = 18, .focal = &focal,
        .fr = 2, .stops = stops, .stop_count = 4 } },
    { "radial reflect",
      "<radialGradient id='p' gradientUnits='userSpaceOnUse' cx='30' cy='20' r='9' "
      "spreadMethod='reflect'>" STOPS_SVG "</radialGradient>",
      { .kind = SR_PAINT_RADIAL_GRADIENT, .cx = 30, .cy = 20, .r = 9, .stops = stops,
        .stop_count = 4, .spread = SR_SPREAD_REFLECT } },
    { "radial repeat, focal, transformed",
      "<radialGradient id='p' gradientUnits='userSpaceOnUse' cx='30' cy='20' r='7' "
      "fx='22' fy='15' spreadMethod='repeat' "
      "gradientTransform='matrix(0.8 0.3 -0.2 1.1 4 -3)'>" STOPS_SVG "</radialGradient>",
      { .kind = SR_PAINT_RADIAL_GRADIENT, .cx = 30, .cy = 20, .r = 7, .focal = &focal,
        .stops = stops, .stop_count = 4, .spread = SR_SPREAD_REPEAT, .transform = &skew } },
    { "pattern, rotated",
      "<pattern id='p' patternUnits='userSpaceOnUse' width='4' height='4' "
      "patternTransform='matrix(0.8 0.6 -0.6 0.8 0 0)'>" TILE_SVG "</pattern>",
      { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4, .image_height = 4,
        .transform = &turn } },
    { "pattern at half opacity",
      "<pattern id='p' patternUnits='userSpaceOnUse' width='4' height='4'>" TILE_SVG
      "</pattern>",
      { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4, .image_height = 4,
        .opacity = 0.5f } },
};
enum { CASES = sizeof cases / sizeof cases[0] };

static sr_framebuffer *svg_image(sr_context *ctx, const paint_case *c)
{
    char doc[4096];
    snprintf(doc, sizeof doc,
             "<svg xmlns='http://www.w3.org/2000/svg' width='%d' height='%d'><defs>%s</defs>"
             SHAPE_SVG " fill='url(#p)'%s/></svg>",
             W, H, c->svg, c->paint.opacity > 0 ? " fill-opacity='0.5'" : "");
    sr_framebuffer *fb = NULL;
    sr_io_error err = { 0 };
    if (sr_render_svg(ctx, doc, strlen(doc), &(sr_svg_desc){ 0 }, &fb, NULL, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s: %s", c->name, err.message);
    }
    return fb;
}

static sr_framebuffer *blank(sr_context *ctx, int w, int h)
{
    sr_framebuffer *fb = NULL;
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                         .depth_format = SR_DEPTH_NONE },
                            &fb) != SR_OK) {
        return NULL;
    }
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    return fb;
}

/* The shape as a path, for sr_fill_path_paint. */
static sr_path *shape_path(sr_context *ctx)
{
    sr_path *p = NULL;
    if (sr_make_path(ctx, 0, &p) != SR_OK) {
        return NULL;
    }
    sr_path_move_to(p, shape[0].x, shape[0].y);
    for (int i = 1; i < 5; i++) {
        sr_path_line_to(p, shape[i].x, shape[i].y);
    }
    sr_path_close(p);
    return p;
}

SR_TEST(paints_give_the_svg_readers_bytes_at_every_simd_level)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    make_tile();
    static uint8_t scalar[CASES][W * H * 4];
    int compared = 0;
    for (int level = SR_SIMD_OFF; level <= SR_SIMD_AVX512; level++) {
        sr_context *ctx = NULL;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1, .simd = (sr_simd_level)level },
                                &ctx) == SR_OK);
        sr_path *path = shape_path(ctx);
        REQUIRE(path);
        for (int i = 0; i < CASES; i++) {
            const paint_case *c = &cases[i];
            sr_framebuffer *want = svg_image(ctx, c), *got = blank(ctx, W, H);
            REQUIRE(want && got);
            /* half the cases through the path, half through the polygon */
            sr_result r = i % 2 ? sr_fill_path_paint(ctx, got, path, &c->paint, &(sr_fill_desc){
                                      .antialias = SR_AA_AREA })
                                : sr_fill_polygon_paint(ctx, got, &(sr_polygon2){ shape, 5, NULL, 0 },
                                                        &c->paint,
                                                        &(sr_fill_desc){ .antialias = SR_AA_AREA });
            CHECK_EQ(r, SR_OK);
            const uint8_t *a = sr_framebuffer_pixels(want), *b = sr_framebuffer_pixels(got);
            int differ = 0, painted = 0;
            for (int k = 0; k < W * H; k++) {
                differ += memcmp(a + k * 4, b + k * 4, 4) != 0;
                painted += b[k * 4 + 3] != 0;
            }
            if (differ) {
                sr_test_fail(__FILE__, __LINE__, "%s at SIMD level %d: %d pixels differ from "
                             "sr_render_svg's", c->name, level, differ);
            }
            CHECK(painted > W * H / 2); /* the shape covers most of the image */
            if (level == SR_SIMD_OFF) {
                memcpy(scalar[i], b, sizeof scalar[i]);
            } else if (memcmp(scalar[i], b, sizeof scalar[i]) != 0) {
                sr_test_fail(__FILE__, __LINE__, "%s at SIMD level %d: not the scalar level's",
                             c->name, level);
            }
            compared++;
            sr_destroy_framebuffer(ctx, want);
            sr_destroy_framebuffer(ctx, got);
        }
        sr_destroy_path(ctx, path);
        sr_destroy_context(ctx);
    }
    CHECK_EQ(compared, CASES * (SR_SIMD_AVX512 - SR_SIMD_OFF + 1));
}

/* Away from the stops, a pad gradient along x gives each column the color
 * of its t, mixed between the two stops around it: pixel centre 8.5 of a
 * gradient from x 0 to 40 is t = 0.2125, half way to the 0.4 stop. */
SR_TEST(a_linear_gradient_gives_its_stops_colors)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = blank(ctx, 48, 4);
    REQUIRE(fb);
    sr_gradient_stop two[] = { { 0, { 0, 0, 1, 1 } }, { 1, { 1, 0, 0, 1 } } };
    sr_paint p = { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 40, .stops = two, .stop_count = 2 };
    sr_point2 box[] = { { 0, 0 }, { 48, 0 }, { 48, 4 }, { 0, 4 } };
    REQUIRE(sr_fill_polygon_paint(ctx, fb, &(sr_polygon2){ box, 4, NULL, 0 }, &p, NULL) == SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int x = 0; x < 48; x++) {
        double t = fmin((x + 0.5) / 40, 1);
        const uint8_t *q = px + (2 * 48 + x) * 4;
        CHECK(abs(q[0] - (int)lround(t * 255)) <= 1);
        CHECK_EQ(q[1], 0);
        CHECK(abs(q[2] - (int)lround((1 - t) * 255)) <= 1);
        CHECK_EQ(q[3], 255);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* A radial gradient is t = 0 at its focal point and t = 1 on its end
 * circle, on both sides (the focal side and the far side); a pattern
 * moved by its transform gives each pixel the texel the move brings. */
SR_TEST(a_radial_gradient_and_a_pattern_follow_their_geometry)
{
    make_tile();
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = blank(ctx, 48, 16);
    REQUIRE(fb);
    sr_point2 box[] = { { 0, 0 }, { 48, 0 }, { 48, 16 }, { 0, 16 } };
    sr_polygon2 poly = { box, 4, NULL, 0 };
    sr_gradient_stop two[] = { { 0, { 1, 0, 0, 1 } }, { 1, { 0, 0, 1, 1 } } };
    sr_point2 f = { 10.5, 8.5 };
    sr_paint rad = { .kind = SR_PAINT_RADIAL_GRADIENT, .cx = 20.5, .cy = 8.5, .r = 16,
                     .focal = &f, .stops = two, .stop_count = 2 };
    REQUIRE(sr_fill_polygon_paint(ctx, fb, &poly, &rad, NULL) == SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    const uint8_t *at_focal = px + (8 * 48 + 10) * 4, *far = px + (8 * 48 + 36) * 4;
    const uint8_t *near = px + (8 * 48 + 4) * 4; /* 6 px before f: the circle of t = 1 */
    CHECK(at_focal[0] == 255 && at_focal[2] == 0);
    CHECK(far[0] == 0 && far[2] == 255);
    CHECK(near[0] <= 1 && near[2] >= 254);
    sr_affine2 move = { 1, 0, 0, 1, 1, 2 };
    sr_paint pat = { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                     .image_height = 4, .transform = &move };
    REQUIRE(sr_fill_polygon_paint(ctx, fb, &poly, &pat, NULL) == SR_OK);
    int wrong = 0;
    for (int y = 0; y < 16; y++) {
        for (int x = 0; x < 48; x++) {
            const uint8_t *t = tile + (((y + 2) % 4) * 4 + (x + 3) % 4) * 4;
            wrong += memcmp(px + (y * 48 + x) * 4, t, 4) != 0;
        }
    }
    CHECK_EQ(wrong, 0);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* Each bad field is refused with SR_INVALID_ARG, a message naming it, and
 * nothing drawn. */
SR_TEST(every_paint_field_is_validated)
{
    make_tile();
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = blank(ctx, 16, 16);
    REQUIRE(fb);
    sr_polygon2 poly = { shape, 5, NULL, 0 };
    const sr_paint lin = { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 10, .stops = stops,
                           .stop_count = 4 };
    const sr_paint rad = { .kind = SR_PAINT_RADIAL_GRADIENT, .r = 5, .stops = stops,
                           .stop_count = 4 };
    const sr_paint pat = { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                           .image_height = 4 };
    sr_gradient_stop backwards[] = { { 0.5, { 1, 0, 0, 1 } }, { 0.2, { 0, 1, 0, 1 } } };
    sr_gradient_stop above[] = { { 0, { 1, 0, 0, 1 } }, { 1.5, { 0, 1, 0, 1 } } };
    sr_gradient_stop nan_off[] = { { NAN, { 1, 0, 0, 1 } } };
    sr_gradient_stop nan_col[] = { { 0, { 1, NAN, 0, 1 } } };
    static sr_gradient_stop many[SR_MAX_GRADIENT_STOPS + 1];
    sr_affine2 singular = { 1, 2, 2, 4, 0, 0 }, inf = { INFINITY, 0, 0, 1, 0, 0 };
    sr_point2 nan_focal = { NAN, 0 };
    struct { const char *field; sr_paint p; } bad[] = {
        { "kind", { .kind = (sr_paint_kind)99 } },
        { "color", { .kind = SR_PAINT_COLOR, .color = { NAN, 0, 0, 1 } } },
        { "stop_count", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = stops } },
        { "stop_count", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = many,
                          .stop_count = SR_MAX_GRADIENT_STOPS + 1 } },
        { "stop_count", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = stops,
                          .stop_count = -3 } },
        { "stops", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stop_count = 2 } },
        { "offset", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = backwards,
                      .stop_count = 2 } },
        { "offset", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = above,
                      .stop_count = 2 } },
        { "offset", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = nan_off,
                      .stop_count = 1 } },
        { "color", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = nan_col,
                     .stop_count = 1 } },
        { "x1", { .kind = SR_PAINT_LINEAR_GRADIENT, .x1 = NAN, .stops = stops, .stop_count = 4 } },
        { "r", { .kind = SR_PAINT_RADIAL_GRADIENT, .stops = stops, .stop_count = 4 } },
        { "r", { .kind = SR_PAINT_RADIAL_GRADIENT, .r = -2, .stops = stops, .stop_count = 4 } },
        { "r", { .kind = SR_PAINT_RADIAL_GRADIENT, .r = INFINITY, .stops = stops,
                 .stop_count = 4 } },
        { "fr", { .kind = SR_PAINT_RADIAL_GRADIENT, .r = 5, .fr = -1, .stops = stops,
                  .stop_count = 4 } },
        { "focal", { .kind = SR_PAINT_RADIAL_GRADIENT, .r = 5, .focal = &nan_focal,
                     .stops = stops, .stop_count = 4 } },
        { "spread", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = stops,
                      .stop_count = 4, .spread = (sr_gradient_spread)7 } },
        { "opacity", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = stops,
                       .stop_count = 4, .opacity = 1.5f } },
        { "opacity", { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                       .image_height = 4, .opacity = NAN } },
        { "opacity", { .kind = SR_PAINT_COLOR, .color = { 1, 0, 0, 1 }, .opacity = -0.5f } },
        { "transform", { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1, .stops = stops,
                         .stop_count = 4, .transform = &singular } },
        { "transform", { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                         .image_height = 4, .transform = &inf } },
        { "image", { .kind = SR_PAINT_PATTERN, .image_width = 4, .image_height = 4 } },
        { "image_width", { .kind = SR_PAINT_PATTERN, .image = tile, .image_height = 4 } },
        { "image_width", { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = -4,
                           .image_height = 4 } },
        { "image_width", { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                           .image_height = SR_MAX_FRAMEBUFFER_SIZE + 1 } },
        { "image_stride", { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                            .image_height = 4, .image_stride = 15 } },
        { "image_stride", { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                            .image_height = 4, .image_stride = SIZE_MAX } },
#if SIZE_MAX <= UINT32_MAX
        /* rows a 32-bit address space cannot hold */
        { "image_stride", { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                            .image_height = SR_MAX_FRAMEBUFFER_SIZE,
                            .image_stride = (size_t)SR_MAX_FRAMEBUFFER_SIZE * 64 } },
#endif
        { "image_wrap", { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4,
                          .image_height = 4, .image_wrap = SR_WRAP_MIRROR } },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        CHECK_EQ(sr_fill_polygon_paint(ctx, fb, &poly, &bad[i].p, NULL), SR_INVALID_ARG);
        const char *msg = sr_context_error(ctx);
        if (!msg || !strstr(msg, bad[i].field)) {
            sr_test_fail(__FILE__, __LINE__, "case %zu: message \"%s\" does not name %s", i,
                         msg ? msg : "(none)", bad[i].field);
        }
    }
    /* the arguments around the paint */
    CHECK_EQ(sr_fill_polygon_paint(NULL, fb, &poly, &lin, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_polygon_paint(ctx, NULL, &poly, &lin, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_polygon_paint(ctx, fb, NULL, &rad, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_polygon_paint(ctx, fb, &poly, NULL, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_path_paint(ctx, fb, NULL, &pat, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_fill_polygon_paint(ctx, fb, &poly, &lin,
                                   &(sr_fill_desc){ .linear_light = true }),
             SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "linear_light") != NULL);
    CHECK_EQ(sr_fill_polygon_paint(ctx, fb, &(sr_polygon2){ NULL, 3, NULL, 0 }, &lin, NULL),
             SR_INVALID_ARG);
    /* a point the coverage refuses: the message names the call made */
    sr_point2 nan_pt[] = { { NAN, 0 }, { 9, 1 }, { 2, 9 } };
    CHECK_EQ(sr_fill_polygon_paint(ctx, fb, &(sr_polygon2){ nan_pt, 3, NULL, 0 }, &pat, NULL),
             SR_INVALID_ARG);
    CHECK(strstr(sr_context_error(ctx), "sr_fill_polygon_paint") != NULL);
    /* nothing was drawn by any of them */
    const uint8_t *px = sr_framebuffer_pixels(fb);
    int touched = 0;
    for (int k = 0; k < 16 * 16 * 4; k++) {
        touched += px[k] != 0;
    }
    CHECK_EQ(touched, 0);
    /* and the valid ones draw */
    CHECK_EQ(sr_fill_polygon_paint(ctx, fb, &poly, &rad, NULL), SR_OK);
    CHECK_EQ(sr_fill_polygon_paint(ctx, fb, &poly, &pat, NULL), SR_OK);
    CHECK(px[(8 * 16 + 8) * 4 + 3] == 255);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* A color paint is sr_fill_polygon's fill, its alpha times the opacity. */
SR_TEST(a_color_paint_is_the_color_fill)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *a = blank(ctx, W, H), *b = blank(ctx, W, H);
    REQUIRE(a && b);
    sr_polygon2 poly = { shape, 5, NULL, 0 };
    sr_fill_desc d = { .antialias = SR_AA_AREA, .linear_light = true };
    CHECK_EQ(sr_fill_polygon(ctx, a, &poly, (sr_rgba){ 0.2f, 0.6f, 0.9f, 0.8f * 0.5f }, &d), SR_OK);
    sr_paint p = { .kind = SR_PAINT_COLOR, .color = { 0.2f, 0.6f, 0.9f, 0.8f }, .opacity = 0.5f };
    CHECK_EQ(sr_fill_polygon_paint(ctx, b, &poly, &p, &d), SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), W * H * 4) == 0);
    CHECK(sr_framebuffer_pixels(b)[(20 * W + 30) * 4 + 3] > 0);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

/* A pattern image's stride is honoured: a tile stored with padding after
 * each row gives the bytes of the same tile packed. */
SR_TEST(a_pattern_reads_rows_at_its_stride)
{
    make_tile();
    uint8_t padded[4 * 24];
    memset(padded, 0xee, sizeof padded);
    for (int y = 0; y < 4; y++) {
        memcpy(padded + y * 24, tile + y * 16, 16);
    }
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *a = blank(ctx, W, H), *b = blank(ctx, W, H);
    REQUIRE(a && b);
    sr_polygon2 poly = { shape, 5, NULL, 0 };
    sr_paint p = { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = 4, .image_height = 4,
                   .transform = &skew };
    CHECK_EQ(sr_fill_polygon_paint(ctx, a, &poly, &p, NULL), SR_OK);
    p.image = padded;
    p.image_stride = 24;
    CHECK_EQ(sr_fill_polygon_paint(ctx, b, &poly, &p, NULL), SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), W * H * 4) == 0);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

/* Framebuffers and pattern images ending at an unmapped page, narrow
 * enough that the spans end in partial blocks, at every SIMD level. */
SR_TEST(paints_stay_inside_buffers_at_guard_pages)
{
#ifndef GUARD_ALLOC_WORKS
    SKIP("no mmap here to put a guard page after a buffer");
#else
    make_tile();
    static guard g, caller;
    static const int sizes[][2] = { { 1, 64 }, { 3, 64 }, { 17, 16 }, { 64, 1 }, { 129, 64 } };
    static uint8_t first[5][129 * 64 * 4];
    int runs = 0;
    for (int level = SR_SIMD_OFF; level <= SR_SIMD_AVX512; level++) {
        for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
            int w = sizes[s][0], h = sizes[s][1];
            sr_context *ctx = NULL;
            REQUIRE(guard_context(&g, level, &ctx) == SR_OK);
            sr_framebuffer *fb = blank(ctx, w, h);
            REQUIRE(fb);
            /* a 3 x 5 image (15 texels: 60 bytes, rounded to 64) ending at the page */
            uint8_t *block = guard_alloc(64, &caller), *img = block + 4;
            REQUIRE(block);
            for (int k = 0; k < 60; k++) {
                img[k] = k % 4 == 3 ? 255 : (uint8_t)(k * 37 + 11); /* opaque texels */
            }
            sr_point2 big[] = { { -3.5, -2.25 }, { w + 4.5, -1.0 }, { w + 2.0, h + 3.5 },
                                { -1.0, h + 2.0 } };
            sr_polygon2 poly = { big, 4, NULL, 0 };
            sr_paint pats[] = {
                { .kind = SR_PAINT_PATTERN, .image = img, .image_width = 3, .image_height = 5 },
                { .kind = SR_PAINT_PATTERN, .image = img, .image_width = 3, .image_height = 5,
                  .image_wrap = SR_WRAP_CLAMP, .transform = &skew },
                { .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 7, .stops = stops, .stop_count = 4,
                  .spread = SR_SPREAD_REFLECT },
                { .kind = SR_PAINT_RADIAL_GRADIENT, .cx = 2, .cy = 2, .r = 9, .focal = &focal,
                  .stops = stops, .stop_count = 4, .spread = SR_SPREAD_REPEAT,
                  .opacity = 0.7f },
            };
            for (size_t i = 0; i < sizeof pats / sizeof pats[0]; i++) {
                CHECK_EQ(sr_fill_polygon_paint(ctx, fb, &poly, &pats[i],
                                               &(sr_fill_desc){ .antialias = SR_AA_AREA }),
                         SR_OK);
                runs++;
            }
            const uint8_t *px = sr_framebuffer_pixels(fb);
            /* the opaque pattern covered every pixel first */
            CHECK(px[3] == 255 && px[((size_t)w * h - 1) * 4 + 3] == 255);
            if (level == SR_SIMD_OFF) {
                memcpy(first[s], px, (size_t)w * h * 4);
            } else if (memcmp(first[s], px, (size_t)w * h * 4) != 0) {
                sr_test_fail(__FILE__, __LINE__, "%dx%d at SIMD level %d: not the scalar "
                             "level's bytes", w, h, level);
            }
            guard_free(block, &caller);
            sr_destroy_framebuffer(ctx, fb);
            sr_destroy_context(ctx);
        }
    }
    CHECK_EQ(runs, 4 * 5 * (SR_SIMD_AVX512 - SR_SIMD_OFF + 1));
#endif
}

/* The context keeps a gradient's color table for the next fill with the
 * same stops: fills whose stops differ in one color channel by a code, or
 * in one offset, each get their own table.  Every fill on one context
 * gives the bytes of the same fill on a fresh one. */
SR_TEST(a_fill_with_other_stops_gets_its_own_color_table)
{
    sr_gradient_stop tinted[4], moved[4];
    memcpy(tinted, stops, sizeof tinted);
    memcpy(moved, stops, sizeof moved);
    tinted[3].color.g += 1 / 255.0f;
    moved[1].offset = moved[2].offset = 0.45;
    const sr_gradient_stop *order[] = { stops, tinted, stops, moved, stops };
    enum { FILLS = sizeof order / sizeof order[0] };
    for (int kind = SR_PAINT_LINEAR_GRADIENT; kind <= SR_PAINT_RADIAL_GRADIENT; kind++) {
        sr_context *shared = NULL;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &shared) == SR_OK);
        for (int i = 0; i < FILLS; i++) {
            sr_paint p = { .kind = (sr_paint_kind)kind, .x1 = 4, .y1 = 4, .x2 = 60, .y2 = 44,
                           .cx = 32, .cy = 24, .r = 30, .stops = order[i], .stop_count = 4 };
            sr_context *fresh = NULL;
            REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &fresh) == SR_OK);
            sr_framebuffer *a = blank(shared, W, H), *b = blank(fresh, W, H);
            REQUIRE(a && b);
            const sr_polygon2 poly = { .points = shape, .point_count = 5 };
            CHECK_EQ(sr_fill_polygon_paint(shared, a, &poly, &p, NULL), SR_OK);
            CHECK_EQ(sr_fill_polygon_paint(fresh, b, &poly, &p, NULL), SR_OK);
            if (memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), W * H * 4) != 0) {
                sr_test_fail(__FILE__, __LINE__, "%s fill %d on a used context: not a fresh "
                             "context's bytes", kind == SR_PAINT_LINEAR_GRADIENT ? "linear"
                             : "radial", i);
            }
            sr_destroy_framebuffer(shared, a);
            sr_destroy_framebuffer(fresh, b);
            sr_destroy_context(fresh);
        }
        sr_destroy_context(shared);
    }
}
