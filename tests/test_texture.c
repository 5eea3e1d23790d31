/* test_texture.c - textures: the mip chain, nearest and bilinear sampling
 * against analytic values, wrap modes, the level of detail, and mip level
 * selection in a real draw (a 1-texel checkerboard minified 4x must come
 * out as flat gray under trilinear filtering, and as raw texels under
 * nearest). */
#include "fragment/texture.h"
#include "raster_util.h"

static sr_texture *make_tex(sr_context *ctx, int w, int h, const uint8_t *px)
{
    sr_texture *t = NULL;
    CHECK_EQ(sr_make_texture(ctx, &(sr_texture_desc){ .width = w, .height = h, .pixels = px }, &t),
             SR_OK);
    return t;
}

SR_TEST(mip_chain_halves_down_to_one_texel_with_box_averages)
{
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    uint8_t px[5 * 3 * 4];
    for (int i = 0; i < 5 * 3 * 4; i++) {
        px[i] = (uint8_t)(i * 7);
    }
    sr_texture *t = make_tex(ctx, 5, 3, px);
    REQUIRE(t);
    CHECK_EQ(sr_texture_levels(t), 3);   /* 5x3, 2x1, 1x1 */
    CHECK_EQ(t->width[1], 2);
    CHECK_EQ(t->height[1], 1);
    /* Level 1 texel (0, 0) averages texels (0,0) (1,0) (0,1) (1,1). */
    for (int c = 0; c < 4; c++) {
        int sum = px[0 * 4 + c] + px[1 * 4 + c] + px[5 * 4 + c] + px[6 * 4 + c];
        CHECK_NEAR(t->texels[1][c], sum / 4.0, 0.51);
    }
    sr_destroy_texture(ctx, t);
    sr_destroy_context(ctx);
}

SR_TEST(sampling_matches_analytic_values)
{
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    /* 2x1: left texel black, right white (red channel). */
    uint8_t px[8] = { 0, 0, 0, 255, 255, 0, 0, 255 };
    sr_texture *t = make_tex(ctx, 2, 1, px);
    REQUIRE(t);
    float c[4];
    sr__texture_sample(t, SR_FILTER_NEAREST, SR_WRAP_CLAMP, SR_WRAP_CLAMP, 0.25f, 0.5f, 0, c);
    CHECK_NEAR(c[0], 0.0, 1e-6);
    sr__texture_sample(t, SR_FILTER_NEAREST, SR_WRAP_CLAMP, SR_WRAP_CLAMP, 0.75f, 0.5f, 0, c);
    CHECK_NEAR(c[0], 1.0, 1e-6);
    /* Bilinear: texel centres at u = 1/4 and 3/4; halfway is the mean,
     * and the value is linear in between. */
    for (int i = 0; i <= 10; i++) {
        float u = 0.25f + 0.05f * (float)i;
        sr__texture_sample(t, SR_FILTER_BILINEAR, SR_WRAP_CLAMP, SR_WRAP_CLAMP, u, 0.5f, 0, c);
        CHECK_NEAR(c[0], (u - 0.25) * 2.0, 1e-5);
    }
    sr_destroy_texture(ctx, t);
    /* v = 0 is the bottom row: a 1x2 texture with white on top. */
    uint8_t col[8] = { 255, 255, 255, 255, 0, 0, 0, 255 };
    t = make_tex(ctx, 1, 2, col);
    sr__texture_sample(t, SR_FILTER_NEAREST, SR_WRAP_CLAMP, SR_WRAP_CLAMP, 0.5f, 0.9f, 0, c);
    CHECK_NEAR(c[0], 1.0, 1e-6);
    sr__texture_sample(t, SR_FILTER_NEAREST, SR_WRAP_CLAMP, SR_WRAP_CLAMP, 0.5f, 0.1f, 0, c);
    CHECK_NEAR(c[0], 0.0, 1e-6);
    sr_destroy_texture(ctx, t);
    sr_destroy_context(ctx);
}

SR_TEST(wrap_modes_repeat_clamp_and_mirror)
{
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    /* 4x1 with red = 0, 85, 170, 255. */
    uint8_t px[16];
    for (int i = 0; i < 4; i++) {
        px[i * 4] = (uint8_t)(i * 85);
        px[i * 4 + 1] = px[i * 4 + 2] = 0;
        px[i * 4 + 3] = 255;
    }
    sr_texture *t = make_tex(ctx, 4, 1, px);
    struct { float u; sr_texture_wrap w; int texel; } cases[] = {
        { 1.125f, SR_WRAP_REPEAT, 0 }, { -0.125f, SR_WRAP_REPEAT, 3 },
        { 1.125f, SR_WRAP_CLAMP, 3 },  { -0.125f, SR_WRAP_CLAMP, 0 },
        { 1.125f, SR_WRAP_MIRROR, 3 }, { 1.375f, SR_WRAP_MIRROR, 2 }, { -0.125f, SR_WRAP_MIRROR, 0 },
        { 2.125f, SR_WRAP_MIRROR, 0 },
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        float c[4];
        sr__texture_sample(t, SR_FILTER_NEAREST, cases[i].w, SR_WRAP_CLAMP, cases[i].u, 0.5f, 0, c);
        CHECK_NEAR(c[0] * 255.0f, cases[i].texel * 85, 0.01);
    }
    sr_destroy_texture(ctx, t);
    sr_destroy_context(ctx);
}

SR_TEST(level_of_detail_is_log2_of_the_footprint)
{
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    uint8_t px[256 * 256 * 4] = { 0 };
    sr_texture *t = make_tex(ctx, 256, 256, px);
    CHECK_NEAR(sr__texture_lod(t, 1.0f / 256, 0, 0, 1.0f / 256), 0.0, 1e-6);   /* 1:1 */
    CHECK_NEAR(sr__texture_lod(t, 4.0f / 256, 0, 0, 4.0f / 256), 2.0, 1e-5);   /* 4 texels/px */
    CHECK_NEAR(sr__texture_lod(t, 1.0f / 256, 0, 0, 8.0f / 256), 3.0, 1e-5);   /* larger side */
    CHECK_NEAR(sr__texture_lod(t, 0.25f / 256, 0, 0, 0.25f / 256), 0.0, 1e-6); /* magnified */
    sr_destroy_texture(ctx, t);
    sr_destroy_context(ctx);
}

/* A 256x256 checkerboard of single texels on a 64x64 screen-aligned quad:
 * four texels per pixel, level of detail 2, where every texel of the mip
 * level averages 4x4 checker texels: flat mid-gray. */
static void draw_checker(sr_texture_filter filter, int *lo, int *hi)
{
    rt_target t = rt_make(64, 64, 1);
    static uint8_t px[256 * 256 * 4];
    for (int y = 0; y < 256; y++) {
        for (int x = 0; x < 256; x++) {
            uint8_t v = ((x + y) & 1) ? 255 : 0;
            uint8_t *p = &px[(y * 256 + x) * 4];
            p[0] = p[1] = p[2] = v;
            p[3] = 255;
        }
    }
    sr_texture *tex = make_tex(t.ctx, 256, 256, px);
    float pos[12] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    float uv[8] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    rt_clear(&t);
    sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                    .texture = tex, .texture_filter = filter };
    CHECK_EQ(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .positions = pos, .texcoords = uv,
                                                       .vertex_count = 4, .indices = idx,
                                                       .index_type = SR_INDEX_U32,
                                                       .index_count = 6 }), SR_OK);
    const uint8_t *p = sr_framebuffer_pixels(t.fb);
    *lo = 255;
    *hi = 0;
    for (int i = 0; i < 64 * 64; i++) {
        *lo = p[i * 4] < *lo ? p[i * 4] : *lo;
        *hi = p[i * 4] > *hi ? p[i * 4] : *hi;
    }
    sr_destroy_texture(t.ctx, tex);
    rt_free(&t);
}

SR_TEST(minified_checkerboard_selects_the_averaged_mip_level)
{
    int lo, hi;
    draw_checker(SR_FILTER_TRILINEAR, &lo, &hi);
    CHECK(lo >= 125 && hi <= 130);
    /* Nearest takes one level-0 texel per pixel: raw black or white (here
     * every centre lands on a black texel - aliasing, which is the point). */
    draw_checker(SR_FILTER_NEAREST, &lo, &hi);
    CHECK(lo == 0 || lo == 255);
    CHECK(hi == 0 || hi == 255);
}

SR_TEST(texture_arguments_are_validated)
{
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    sr_texture *t = NULL;
    uint8_t px[4] = { 0 };
    CHECK_EQ(sr_make_texture(ctx, &(sr_texture_desc){ .width = 0, .height = 1, .pixels = px }, &t),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_texture_desc.width");
    CHECK_EQ(sr_make_texture(ctx, &(sr_texture_desc){ .width = 1, .height = 1 }, &t),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "pixels");
    /* A textured draw needs texcoords. */
    sr_framebuffer *fb;
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb);
    t = make_tex(ctx, 1, 1, px);
    float pos[9] = { 0 };
    sr_state st = { .texture = t };
    CHECK_EQ(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 }),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "texcoords");
    sr_destroy_texture(ctx, t);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
