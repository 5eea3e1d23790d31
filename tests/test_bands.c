/* test_bands.c - sr_render_bands: a frame drawn band by band gives the
 * bytes of the same draws on a whole framebuffer, for band heights that
 * split tiles, quads and blocks anywhere, with clears, blending, a
 * scissor, lines, points, stencil and multisampling. */
#include "sr_test.h"
#include "softrast.h"

#include <stdlib.h>
#include <string.h>

enum { W = 320, H = 240 };

typedef struct scene {
    const sr_mesh *pot;
    int variant;             /* 0: teapot; 1: + clears, blending, scissor, lines, points, stencil */
    sr_pixel_format format;  /* what the bands are asked for (0: RGBA8) */
    uint8_t *image;          /* W * H * 4: the frame assembled from the bands */
    int bands_seen, next_y;
} scene;

static sr_result draw_scene(sr_context *ctx, sr_framebuffer *fb, const sr_band *band, void *user)
{
    (void)band;
    scene *s = user;
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 2.2f, 6.5f }, (sr_vec3){ 0, 0.6f, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.8f, (float)W / H, 1, 20, false);
    sr_state st = { .shading = SR_SHADING_PHONG, .cull = SR_CULL_BACK,
                    .material = { .diffuse = { 0.85f, 0.5f, 0.25f }, .specular = { 0.5f, 0.5f, 0.5f } },
                    .ambient = { 0.15f, 0.15f, 0.2f },
                    .lights = { { .type = SR_LIGHT_DIRECTIONAL, .vector = { -0.5f, -1, -0.7f } } } };
    sr_draw_desc d = { .positions = s->pot->positions, .normals = s->pot->normals,
                       .vertex_count = s->pot->vertex_count, .indices = s->pot->indices,
                       .index_type = SR_INDEX_U32, .index_count = 3 * s->pot->triangle_count,
                       .view = &view, .projection = &proj };
    sr_result r = sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.12f, 0.3f, 1 } });
    if (r == SR_OK && s->variant == 1) {
        st.stencil = (sr_stencil){ .enabled = true,
                                   .front = { .func = SR_ALWAYS, .pass = SR_STENCIL_REPLACE, .ref = 1 } };
    }
    if (r == SR_OK) {
        r = sr_draw(ctx, fb, &st, &d);
    }
    if (r != SR_OK || s->variant != 1) {
        return r;
    }
    /* A second clear of depth only, a translucent quad under a scissor
     * and over the teapot only (the stencil), lines and points. */
    r = sr_clear(ctx, fb, &(sr_clear_desc){ .color_action = SR_ACTION_KEEP,
                                            .stencil_action = SR_ACTION_KEEP });
    static const float quad[] = { -0.9f, -0.7f, 0, 0.6f, -0.9f, 0, 0.6f, 0.75f, 0, -0.9f, 0.75f, 0 };
    static const float quad_colors[] = { 1, 0, 0, 0.5f, 0, 1, 0, 0.25f, 0, 0, 1, 0.75f, 1, 1, 1, 0.4f };
    static const uint32_t quad_idx[] = { 0, 1, 2, 0, 2, 3 };
    sr_state blend = { .blend = { .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                  .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA },
                       .scissor = { .enabled = true, .x = 13, .y = 29, .width = 250, .height = 171 },
                       .stencil = { .enabled = true, .front = { .func = SR_EQUAL, .ref = 1 } } };
    if (r == SR_OK) {
        r = sr_draw(ctx, fb, &blend, &(sr_draw_desc){ .positions = quad, .colors = quad_colors,
                                                      .vertex_count = 4, .indices = quad_idx,
                                                      .index_type = SR_INDEX_U32, .index_count = 6 });
    }
    static const float lines[] = { -1, -1, 0, 1, 1, 0, -1, 0.9f, 0, 1, -0.95f, 0, 0.2f, -1, 0, 0.25f, 1, 0 };
    if (r == SR_OK) {
        r = sr_draw(ctx, fb, &(sr_state){ .line_width = 3, .depth_test = SR_OFF },
                    &(sr_draw_desc){ .primitive = SR_PRIM_LINES, .positions = lines, .vertex_count = 6 });
    }
    if (r == SR_OK) {
        r = sr_draw(ctx, fb, &(sr_state){ .point_size = 9, .round_points = true, .smooth_points = true },
                    &(sr_draw_desc){ .primitive = SR_PRIM_POINTS, .positions = lines, .vertex_count = 6 });
    }
    return r;
}

static void take_band(const sr_band *band, void *user)
{
    scene *s = user;
    s->bands_seen++;
    sr_pixel_format want = s->format ? s->format : SR_PIXEL_RGBA8;
    size_t bpp = want == SR_PIXEL_RGBA8 ? 4 : want == SR_PIXEL_RGB565 ? 2 : 1;
    if (band->y != s->next_y || band->width != W || band->format != want ||
        band->stride != W * bpp) {
        return; /* leaves the image short: the comparison fails */
    }
    s->next_y = band->y + band->rows;
    for (int r = 0; r < band->rows; r++) {
        memcpy(s->image + ((size_t)(band->y + r) * W) * bpp, band->pixels + (size_t)r * band->stride,
               (size_t)W * bpp);
    }
}

/* The frame drawn on a whole framebuffer (RGBA8, W * H * 4 bytes). */
static uint8_t *whole_frame(sr_context *ctx, scene *s, int samples)
{
    sr_framebuffer *fb = NULL;
    uint8_t *out = malloc((size_t)W * H * 4);
    sr_band all = { .y = 0, .rows = H, .width = W };
    bool ok = out && sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                         .samples = samples, .stencil = true }, &fb) == SR_OK &&
              draw_scene(ctx, fb, &all, s) == SR_OK &&
              sr_read_pixels(ctx, fb, 0, 0, W, H, out, (size_t)W * 4) == SR_OK;
    sr_destroy_framebuffer(ctx, fb);
    if (!ok) {
        free(out);
        return NULL;
    }
    return out;
}

static void check_bands(int threads, int variant, int samples)
{
    sr_context *ctx = NULL;
    sr_mesh pot = { 0 };
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads }, &ctx) == SR_OK);
    REQUIRE(sr_make_teapot(ctx, 8, &pot) == SR_OK);
    scene s = { .pot = &pot, .variant = variant };
    uint8_t *whole = whole_frame(ctx, &s, samples);
    s.image = malloc((size_t)W * H * 4);
    REQUIRE(whole && s.image);
    /* The scene is there: the teapot's middle is not the background. */
    CHECK(memcmp(whole + ((size_t)(H / 2) * W + W / 2) * 4, whole, 4) != 0);
    static const int heights[] = { 1, 7, 16, 129, 240 };
    for (size_t i = 0; i < sizeof heights / sizeof heights[0]; i++) {
        memset(s.image, 0x5a, (size_t)W * H * 4);
        s.bands_seen = 0;
        s.next_y = 0;
        sr_result r = sr_render_bands(ctx, &(sr_bands_desc){
            .width = W, .height = H, .band_rows = heights[i], .samples = samples, .stencil = true,
            .draw = draw_scene, .output = take_band, .user = &s });
        CHECK_EQ(r, SR_OK);
        CHECK_EQ(s.bands_seen, (H + heights[i] - 1) / heights[i]);
        CHECK_EQ(s.next_y, H);
        if (memcmp(s.image, whole, (size_t)W * H * 4) != 0) {
            sr_test_fail(__FILE__, __LINE__, "bands of %d rows (variant %d, %d samples, %d threads) "
                         "differ from the whole frame", heights[i], variant, samples, threads);
        }
    }
    free(s.image);
    free(whole);
    sr_destroy_mesh(ctx, &pot);
    sr_destroy_context(ctx);
}

/* The embedded profile (SR_EMBEDDED) and WebAssembly have one thread. */
#if defined(SR_EMBEDDED) || defined(__EMSCRIPTEN__)
#define MORE_THREADS 1
#else
#define MORE_THREADS 2
#endif

SR_TEST(teapot_in_bands_is_the_whole_frame)
{
    check_bands(1, 0, 1);
    check_bands(MORE_THREADS, 0, 1);
}

SR_TEST(blending_scissor_lines_points_stencil_in_bands)
{
    check_bands(1, 1, 1);
    check_bands(MORE_THREADS, 1, 1);
}

SR_TEST(multisampled_bands_are_the_whole_frame)
{
    check_bands(MORE_THREADS, 1, 4);
}

/* The reference conversion: each channel to the nearest n-bit value,
 * rounded in double precision. */
static unsigned nearest(uint8_t c, int bits)
{
    double max = (double)((1 << bits) - 1);
    return (unsigned)(c * max / 255.0 + 0.5);
}

SR_TEST(rgb565_and_rgb332_bands_are_the_rounded_whole_frame)
{
    sr_context *ctx = NULL;
    sr_mesh pot = { 0 };
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    REQUIRE(sr_make_teapot(ctx, 8, &pot) == SR_OK);
    scene s = { .pot = &pot, .variant = 1 };
    uint8_t *whole = whole_frame(ctx, &s, 1);
    s.image = malloc((size_t)W * H * 4);
    uint8_t *want = malloc((size_t)W * H * 2);
    REQUIRE(whole && s.image && want);
    for (int f = 0; f < 2; f++) {
        s.format = f == 0 ? SR_PIXEL_RGB565 : SR_PIXEL_RGB332;
        size_t bpp = f == 0 ? 2 : 1;
        int distinct_low = 0;   /* pixels whose low bits the rounding must see */
        for (size_t i = 0; i < (size_t)W * H; i++) {
            const uint8_t *p = whole + 4 * i;
            if (f == 0) {
                unsigned v = nearest(p[0], 5) << 11 | nearest(p[1], 6) << 5 | nearest(p[2], 5);
                want[2 * i] = (uint8_t)(v >> 8);
                want[2 * i + 1] = (uint8_t)v;
            } else {
                want[i] = (uint8_t)(nearest(p[0], 3) << 5 | nearest(p[1], 3) << 2 | nearest(p[2], 2));
            }
            distinct_low += (p[0] >> 3) != nearest(p[0], 5);
        }
        CHECK(distinct_low > 0);
        memset(s.image, 0x5a, (size_t)W * H * 4);
        s.next_y = 0;
        CHECK_EQ(sr_render_bands(ctx, &(sr_bands_desc){
            .width = W, .height = H, .band_rows = 7, .stencil = true, .format = s.format,
            .draw = draw_scene, .output = take_band, .user = &s }), SR_OK);
        CHECK_EQ(s.next_y, H);
        CHECK(memcmp(s.image, want, (size_t)W * H * bpp) == 0);
    }
    free(want);
    free(s.image);
    free(whole);
    sr_destroy_mesh(ctx, &pot);
    sr_destroy_context(ctx);
}

static sr_result draw_nothing(sr_context *ctx, sr_framebuffer *fb, const sr_band *band, void *user)
{
    (void)band;
    (void)user;
    return sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
}

static sr_result draw_2d(sr_context *ctx, sr_framebuffer *fb, const sr_band *band, void *user)
{
    (void)band;
    (void)user;
    return sr_draw_text(ctx, fb, 0, 0, 1, "x", (sr_rgba){ 1, 1, 1, 1 });
}

static void ignore_band(const sr_band *band, void *user)
{
    (void)band;
    (void)user;
}

static sr_result read_outside(sr_context *ctx, sr_framebuffer *fb, const sr_band *band, void *user)
{
    uint8_t px[4];
    int *refused = user;
    CHECK(sr_framebuffer_pixels(fb) == NULL || band->rows == H);
    if (band->y > 0 && sr_read_pixels(ctx, fb, 0, band->y - 1, 1, 1, px, 4) == SR_INVALID_ARG) {
        (*refused)++;
    }
    return sr_read_pixels(ctx, fb, 0, band->y, 1, 1, px, 4);
}

SR_TEST(bands_refuse_bad_descs_and_whole_frame_calls)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_bands_desc d = { .width = 32, .height = 20, .band_rows = 8, .draw = draw_nothing,
                        .output = ignore_band };
    CHECK_EQ(sr_render_bands(NULL, &d), SR_INVALID_ARG);
    CHECK_EQ(sr_render_bands(ctx, NULL), SR_INVALID_ARG);
    sr_bands_desc bad = d;
    bad.band_rows = 0;
    CHECK_EQ(sr_render_bands(ctx, &bad), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "band_rows");
    bad.band_rows = 21;
    CHECK_EQ(sr_render_bands(ctx, &bad), SR_INVALID_ARG);
    bad = d;
    bad.output = NULL;
    CHECK_EQ(sr_render_bands(ctx, &bad), SR_INVALID_ARG);
    bad = d;
    bad.draw = NULL;
    CHECK_EQ(sr_render_bands(ctx, &bad), SR_INVALID_ARG);
    bad = d;
    bad.format = (sr_pixel_format)99;
    CHECK_EQ(sr_render_bands(ctx, &bad), SR_INVALID_ARG);
    bad = d;
    bad.width = 0;
    CHECK_EQ(sr_render_bands(ctx, &bad), SR_INVALID_ARG);
    /* The 2D toolkit draws on whole framebuffers only; the failure stops the frame. */
    bad = d;
    bad.draw = draw_2d;
    CHECK_EQ(sr_render_bands(ctx, &bad), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "band");
    /* Reading is limited to the band's rows. */
    int refused = 0;
    bad = d;
    bad.draw = read_outside;
    bad.user = &refused;
    CHECK_EQ(sr_render_bands(ctx, &bad), SR_OK);
    CHECK_EQ(refused, 2);
    CHECK_EQ(sr_render_bands(ctx, &d), SR_OK);
    sr_destroy_context(ctx);
}
