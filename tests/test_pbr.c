/* test_pbr.c - the metallic-roughness program (sr_make_pbr_program) and
 * sr_mesh_compute_tangents: properties of the rendered pixels that follow
 * from glTF's Appendix B, each with its tolerance, and the images written
 * to the test output directory for a look. */
#include "image_compare.h"
#include "sr_test.h"

#include "context.h"
#include "fragment/pbr_layers.h"
#include "fragment/sheen.h"
#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CELL 64

/* A UV sphere of radius 1 at the origin: normals are the positions, u
 * around +y from -z, v from the south pole (0) to the north (1). */
typedef struct sphere {
    float *pos, *nrm, *uv;
    uint32_t *idx;
    size_t nv, ni;
} sphere;

static sphere make_sphere(int slices, int stacks)
{
    sphere s = { 0 };
    s.nv = (size_t)(slices + 1) * (size_t)(stacks + 1);
    s.ni = (size_t)slices * (size_t)stacks * 6;
    s.pos = calloc(s.nv * 3, sizeof(float));
    s.nrm = calloc(s.nv * 3, sizeof(float));
    s.uv = calloc(s.nv * 2, sizeof(float));
    s.idx = calloc(s.ni, sizeof(uint32_t));
    size_t v = 0, k = 0;
    for (int j = 0; j <= stacks; j++) {
        float th = 3.14159265f * (float)j / (float)stacks;   /* from the south pole */
        for (int i = 0; i <= slices; i++, v++) {
            float ph = 2.0f * 3.14159265f * (float)i / (float)slices;
            float p[3] = { -sinf(th) * sinf(ph), -cosf(th), -sinf(th) * cosf(ph) };
            memcpy(&s.pos[3 * v], p, sizeof p);
            memcpy(&s.nrm[3 * v], p, sizeof p);
            s.uv[2 * v] = (float)i / (float)slices;
            s.uv[2 * v + 1] = (float)j / (float)stacks;
        }
    }
    for (int j = 0; j < stacks; j++) {
        for (int i = 0; i < slices; i++) {
            uint32_t a = (uint32_t)(j * (slices + 1) + i), b = a + 1;
            uint32_t c = a + (uint32_t)(slices + 1), d = c + 1;
            uint32_t t[6] = { a, b, d, a, d, c };
            memcpy(&s.idx[k], t, sizeof t);
            k += 6;
        }
    }
    return s;
}

static void free_sphere(sphere *s)
{
    free(s->pos);
    free(s->nrm);
    free(s->uv);
    free(s->idx);
}

/* The camera of every test: orthographic down -z onto [-1.1, 1.1]^2. */
static sr_mat4 test_view(void)
{
    return sr_look_at((sr_vec3){ 0, 0, 5 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
}

static sr_mat4 test_projection(void)
{
    return sr_ortho(-1.1f, 1.1f, -1.1f, 1.1f, 1.0f, 10.0f, false);
}

/* A key light from the upper right front and a dim hemisphere. */
static sr_pbr_desc lit_desc(const sr_pbr_material *m, const sr_mat4 *view, const sr_mat4 *proj)
{
    sr_pbr_desc d = { .material = m, .view = view, .projection = proj };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { -1, -1, -1 },
                              .intensity = 3.0f };
    d.sky = (sr_vec3){ 0.3f, 0.3f, 0.35f };
    d.ground = (sr_vec3){ 0.1f, 0.1f, 0.1f };
    return d;
}

/* Draws the sphere with the program into the viewport cell (cx, cy). */
static sr_result draw_sphere(sr_framebuffer *fb, const sphere *s, const sr_pbr_desc *d, int cx,
                             int cy, const sr_blend *blend)
{
    sr_context *ctx = sr_test_ctx();
    sr_pbr *p;
    sr_result r = sr_make_pbr_program(ctx, d, &p);
    if (r != SR_OK) {
        return r;
    }
    sr_state st = { .program = sr_pbr_program(p), .cull = SR_CULL_BACK,
                    .viewport = { cx * CELL, cy * CELL, CELL, CELL } };
    if (blend) {
        st.blend = *blend;
        st.depth_write = SR_OFF;
    }
    r = sr_draw(ctx, fb, &st,
                &(sr_draw_desc){ .positions = s->pos, .normals = s->nrm, .texcoords = s->uv,
                                 .vertex_count = s->nv, .indices = s->idx,
                                 .index_type = SR_INDEX_U32, .index_count = s->ni });
    sr_destroy_pbr_program(ctx, p);
    return r;
}

static sr_framebuffer *make_fb(int cols, int rows, float gray)
{
    sr_framebuffer *fb = NULL;
    sr_context *ctx = sr_test_ctx();
    sr_framebuffer_desc desc = { .width = cols * CELL, .height = rows * CELL };
    if (sr_make_framebuffer(ctx, &desc, &fb) != SR_OK) {
        return NULL;
    }
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { gray, gray, gray, 1 } });
    return fb;
}

static void save(const sr_framebuffer *fb, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.png", sr_test_out_dir(), name);
    sr_io_error err;
    if (sr_write_png(path, sr_framebuffer_width(fb), sr_framebuffer_height(fb),
                     sr_framebuffer_pixels(fb), 4 * (size_t)sr_framebuffer_width(fb), NULL,
                     &err) != SR_OK) {
        fprintf(stderr, "%s\n", err.message);
    }
}

static const uint8_t *px(const sr_framebuffer *fb, int x, int y)
{
    size_t w = (size_t)sr_framebuffer_width(fb);
    return sr_framebuffer_pixels(fb) + 4 * ((size_t)y * w + (size_t)x);
}

/* The brightest pixel of a cell by its green channel, and the largest
 * green and red values in it. */
typedef struct cell_stats {
    int max_r, max_g, max_sum, lit;
    uint8_t peak[3];        /* the brightest pixel */
} cell_stats;

static cell_stats stats(const sr_framebuffer *fb, int cx, int cy, int bg)
{
    cell_stats s = { 0 };
    for (int y = cy * CELL; y < (cy + 1) * CELL; y++) {
        for (int x = cx * CELL; x < (cx + 1) * CELL; x++) {
            const uint8_t *c = px(fb, x, y);
            if (c[0] == bg && c[1] == bg && c[2] == bg) {
                continue;
            }
            s.lit++;
            s.max_r = c[0] > s.max_r ? c[0] : s.max_r;
            s.max_g = c[1] > s.max_g ? c[1] : s.max_g;
            if (c[0] + c[1] + c[2] > s.max_sum) {
                s.max_sum = c[0] + c[1] + c[2];
                memcpy(s.peak, c, 3);
            }
        }
    }
    return s;
}

/* A 5 x 5 grid of red spheres: metallic 0 .. 1 down, roughness 0 .. 1
 * across.  Dielectrics reflect the white light white, metals tint it
 * with their base color; highlights fade as roughness spreads them. */
SR_TEST(sphere_grid_metallic_roughness)
{
    sphere s = make_sphere(48, 24);
    sr_framebuffer *fb = make_fb(5, 5, 0.0f);
    REQUIRE(fb);
    sr_mat4 view = test_view(), proj = test_projection();
    for (int row = 0; row < 5; row++) {
        for (int col = 0; col < 5; col++) {
            sr_pbr_material m = sr_pbr_default_material();
            m.base_color[0] = 0.9f;
            m.base_color[1] = 0.05f;
            m.base_color[2] = 0.05f;
            m.metallic = (float)row / 4.0f;
            m.roughness = (float)col / 4.0f;
            sr_pbr_desc d = lit_desc(&m, &view, &proj);
            CHECK_EQ(draw_sphere(fb, &s, &d, col, row, NULL), SR_OK);
        }
    }
    save(fb, "pbr_sphere_grid");
    cell_stats plastic = stats(fb, 1, 0, 0), metal = stats(fb, 1, 4, 0);
    CHECK(plastic.lit > 2000 && metal.lit > 2000);
    /* The rough metal is darker than the rough plastic: no diffuse. */
    CHECK(stats(fb, 4, 4, 0).max_sum < stats(fb, 4, 0, 0).max_sum);
    /* Along the dielectric row the peak falls as roughness grows. */
    for (int col = 1; col < 5; col++) {
        cell_stats a = stats(fb, col - 1, 0, 0), b = stats(fb, col, 0, 0);
        CHECK(b.max_sum <= a.max_sum);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
}

/* Red plastic reflects the white light white, red metal reflects it red
 * (roughness 0.25; exposure -6 keeps the highlights under the tone
 * curve's shoulder, which would whiten both). */
SR_TEST(metal_highlights_take_the_base_color)
{
    sphere s = make_sphere(48, 24);
    sr_framebuffer *fb = make_fb(2, 1, 0.0f);
    REQUIRE(fb);
    sr_mat4 view = test_view(), proj = test_projection();
    for (int k = 0; k < 2; k++) {
        sr_pbr_material m = sr_pbr_default_material();
        m.base_color[1] = m.base_color[2] = 0.05f;
        m.metallic = (float)k;
        m.roughness = 0.25f;
        sr_pbr_desc d = lit_desc(&m, &view, &proj);
        d.sky = d.ground = (sr_vec3){ 0, 0, 0 };
        d.exposure = -6.0f;
        REQUIRE(draw_sphere(fb, &s, &d, k, 0, NULL) == SR_OK);
    }
    cell_stats plastic = stats(fb, 0, 0, 0), metal = stats(fb, 1, 0, 0);
    CHECK(plastic.peak[1] > plastic.peak[0] / 2);
    CHECK(metal.peak[0] > 100);
    CHECK(metal.peak[1] < metal.peak[0] / 4);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
}

/* KHR_materials_unlit: every fragment shows the base color, no matter the
 * lights, as radiance: with the tone curve off, encoded as it is, and
 * exposure scales it as it scales lit surfaces (as glTF viewers do). */
SR_TEST(unlit_shows_the_flat_base_color)
{
    sphere s = make_sphere(32, 16);
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    REQUIRE(fb);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[0] = 0.0f;
    m.base_color[1] = 1.0f;
    m.base_color[2] = 0.214f;   /* sRGB 0.5: code 128 */
    m.unlit = true;
    sr_pbr_desc d = lit_desc(&m, &view, &proj);
    d.tonemap = SR_TONEMAP_NONE;
    REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
    int covered = 0, wrong = 0;
    for (int y = 0; y < CELL; y++) {
        for (int x = 0; x < CELL; x++) {
            const uint8_t *c = px(fb, x, y);
            if (c[1] == 0) {
                continue;
            }
            covered++;
            wrong += c[0] != 0 || c[1] != 255 || abs(c[2] - 128) > 1;
        }
    }
    CHECK(covered > 2000);
    CHECK_EQ(wrong, 0);
    /* One stop up: blue doubles, green clips, red stays black. */
    d.exposure = 1.0f;
    sr_clear(sr_test_ctx(), fb, &(sr_clear_desc){ 0 });
    REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
    const uint8_t *c = px(fb, CELL / 2, CELL / 2);
    CHECK_EQ(c[0], 0);
    CHECK_EQ(c[1], 255);
    CHECK_NEAR(c[2], sr_srgb_encode8(0.428f), 1);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
}

/* A black base color with an orange emission and no light at all shows
 * the emission (tone curve off: exactly its sRGB codes). */
SR_TEST(emissive_on_black_shows_the_emission)
{
    sphere s = make_sphere(32, 16);
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    REQUIRE(fb);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[0] = m.base_color[1] = m.base_color[2] = 0.0f;
    m.emissive[0] = 1.0f;
    m.emissive[1] = 0.5f;
    m.emissive_strength = 0.8f;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE };
    REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
    const uint8_t *c = px(fb, CELL / 2, CELL / 2);
    CHECK_EQ(c[0], sr_srgb_encode8(0.8f));
    CHECK_EQ(c[1], sr_srgb_encode8(0.4f));
    CHECK_EQ(c[2], 0);
    /* The default tone curve keeps an emissive under its knee nearly as is. */
    d.tonemap = SR_TONEMAP_DEFAULT;
    m.emissive_strength = 0.5f;
    sr_clear(sr_test_ctx(), fb, &(sr_clear_desc){ 0 });
    REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
    CHECK_NEAR(px(fb, CELL / 2, CELL / 2)[0], sr_srgb_encode8(0.5f), 2);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
}

/* MASK drops fragments under the cutoff and writes the rest opaque;
 * BLEND writes alpha for source-over blending, on encoded values. */
SR_TEST(alpha_mask_and_blend)
{
    sphere s = make_sphere(32, 16);
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    REQUIRE(fb);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.unlit = true;
    m.base_color[3] = 0.4f;
    m.alpha_mode = SR_ALPHA_MASK;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE };
    REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
    CHECK_EQ(px(fb, CELL / 2, CELL / 2)[0], 0);
    m.alpha_cutoff = 0.3f;
    sr_clear(sr_test_ctx(), fb, &(sr_clear_desc){ 0 });
    REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
    CHECK_EQ(px(fb, CELL / 2, CELL / 2)[0], 255);
    CHECK_EQ(px(fb, CELL / 2, CELL / 2)[3], 255);

    sr_clear(sr_test_ctx(), fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    m.alpha_mode = SR_ALPHA_BLEND;
    sr_blend over = { .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                      .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA, .src_alpha = SR_BLEND_ONE,
                      .dst_alpha = SR_BLEND_ONE_MINUS_SRC_ALPHA };
    REQUIRE(draw_sphere(fb, &s, &d, 0, 0, &over) == SR_OK);
    CHECK_NEAR(px(fb, CELL / 2, CELL / 2)[0], 0.4 * 255, 1);
    /* Opaque ignores alpha. */
    m.alpha_mode = SR_ALPHA_OPAQUE;
    sr_clear(sr_test_ctx(), fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    REQUIRE(draw_sphere(fb, &s, &d, 0, 0, &over) == SR_OK);
    CHECK_EQ(px(fb, CELL / 2, CELL / 2)[0], 255);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
}

/* ---- flat quads: normal maps, texture transforms ------------------------ */

/* The square [-1, 1]^2 at z = 0 facing +z, texcoords (u, v) = ((x+1)/2,
 * (y+1)/2), or u mirrored. */
static void draw_quad(sr_framebuffer *fb, const sr_pbr_desc *d, bool mirror_u)
{
    const float pos[] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    const float nrm[] = { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    float uv[] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    if (mirror_u) {
        for (int i = 0; i < 4; i++) {
            uv[2 * i] = 1.0f - uv[2 * i];
        }
    }
    const uint32_t idx[] = { 0, 1, 2, 0, 2, 3 };
    sr_pbr *p;
    REQUIRE(sr_make_pbr_program(sr_test_ctx(), d, &p) == SR_OK);
    CHECK_EQ(sr_draw(sr_test_ctx(), fb, &(sr_state){ .program = sr_pbr_program(p) },
                     &(sr_draw_desc){ .positions = pos, .normals = nrm, .texcoords = uv,
                                      .vertex_count = 4, .indices = idx,
                                      .index_type = SR_INDEX_U32, .index_count = 6 }),
             SR_OK);
    sr_destroy_pbr_program(sr_test_ctx(), p);
}

static sr_texture *solid_texture(const uint8_t rgba[4], bool srgb)
{
    uint8_t px4[16];
    for (int i = 0; i < 4; i++) {
        memcpy(&px4[4 * i], rgba, 4);
    }
    sr_texture *t = NULL;
    sr_make_texture(sr_test_ctx(), &(sr_texture_desc){ .width = 2, .height = 2, .pixels = px4,
                                                       .srgb = srgb },
                    &t);
    return t;
}

/* An sRGB base colour map is decoded to linear light before it multiplies
 * the factor (glTF: "the texture's sRGB values are converted to linear"):
 * an unlit quad with no tone curve shows the texel's own code, not the
 * code of the code read as linear. */
SR_TEST(srgb_base_color_map_reaches_the_shader_linear)
{
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    REQUIRE(fb);
    const uint8_t gray[4] = { 128, 64, 200, 255 };
    sr_texture *t = solid_texture(gray, true);
    REQUIRE(t);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.unlit = true;
    m.base_color_texture.texture = t;
    m.base_color_texture.filter = SR_FILTER_TRILINEAR;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE };
    draw_quad(fb, &d, false);
    const uint8_t *c = px(fb, CELL / 2, CELL / 2);
    CHECK_NEAR(c[0], 128, 1);
    CHECK_NEAR(c[1], 64, 1);
    CHECK_NEAR(c[2], 200, 1);
    sr_destroy_texture(sr_test_ctx(), t);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* Luminance-ish sum at the quad's centre lit from +x by a grazing light,
 * through a normal map of one tilted normal. */
static int tilted_brightness(const uint8_t tilt[4], bool mirror_u, const float *tangents)
{
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    if (!fb) {
        return -1;
    }
    sr_texture *nt = solid_texture(tilt, false);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.metallic = 0.0f;
    m.normal_texture.texture = nt;
    m.normal_texture.filter = SR_FILTER_NEAREST;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { -1, 0, -0.3f },
                              .intensity = 3.0f };
    d.vertex_count = 4;
    d.tangents = tangents;
    draw_quad(fb, &d, mirror_u);
    const uint8_t *c = px(fb, CELL / 2, CELL / 2);
    int sum = c[0] + c[1] + c[2];
    sr_destroy_texture(sr_test_ctx(), nt);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    return sum;
}

/* A normal map tilted towards +u (the texture's right) faces a light
 * standing on the +u side and turns from one on the -u side, whether the
 * frame comes from tangents or from derivatives; mirrored texcoords
 * (tangent w = -1 in the file) mirror it. */
SR_TEST(normal_map_bumps_light_from_the_right_side)
{
    const uint8_t flat[4] = { 128, 128, 255, 255 };
    const uint8_t right[4] = { 218, 128, 218, 255 };   /* about (0.7, 0, 0.7) */
    const uint8_t left[4] = { 38, 128, 218, 255 };
    const float tan_plus[] = { 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1 };
    const float tan_minus[] = { -1, 0, 0, 1, -1, 0, 0, 1, -1, 0, 0, 1, -1, 0, 0, 1 };
    int f = tilted_brightness(flat, false, NULL);
    int r = tilted_brightness(right, false, NULL);
    int l = tilted_brightness(left, false, NULL);
    CHECK(r > f + 30);
    CHECK(l < f - 30);
    CHECK_NEAR(tilted_brightness(right, false, tan_plus), r, 3);
    CHECK_NEAR(tilted_brightness(left, false, tan_plus), l, 3);
    /* u runs along -x: "right" in the texture is -x on screen. */
    CHECK(tilted_brightness(right, true, NULL) < f - 30);
    CHECK_NEAR(tilted_brightness(right, true, tan_minus), tilted_brightness(right, true, NULL), 3);
    /* A flat map lights the same in any frame. */
    CHECK_NEAR(tilted_brightness(flat, true, NULL), tilted_brightness(flat, true, tan_minus), 3);
}

/* KHR_texture_transform on a 4 x 4 image of distinct texels, nearest and
 * clamped: the spec's example (offset (0, 1), rotation pi/2, scale 0.5:
 * the lower-left quadrant turned clockwise) lands each corner of the quad
 * on the texel the spec's matrix names. */
SR_TEST(texture_transform_follows_the_extension)
{
    uint8_t img[4 * 4 * 4];
    for (int i = 0; i < 16; i++) {
        img[4 * i] = (uint8_t)(16 * (i % 4) + 8);   /* column in red */
        img[4 * i + 1] = (uint8_t)(16 * (i / 4) + 8);   /* row (from the top) in green */
        img[4 * i + 2] = 0;
        img[4 * i + 3] = 255;
    }
    sr_texture *t = NULL;
    sr_texture_desc td = { .width = 4, .height = 4, .pixels = img };
    REQUIRE(sr_make_texture(sr_test_ctx(), &td, &t) == SR_OK);
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    REQUIRE(fb);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.unlit = true;
    m.base_color_texture = (sr_texture_slot){ .texture = t, .filter = SR_FILTER_NEAREST,
                                              .wrap_u = SR_WRAP_CLAMP, .wrap_v = SR_WRAP_CLAMP,
                                              .scale = { 1, 1 } };
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj };
    /* The quad spans pixels 3..60; sample 4 pixels in from its corners. */
    int lo = 7, hi = CELL - 8;
    /* Texels are linear values, encoded on output: column 8 + 16 c in
     * red, row 8 + 16 r in green. */
    draw_quad(fb, &d, false);
    /* No transform: screen top-left is uv (0, 1) = the image's top-left. */
    const uint8_t *tl = px(fb, lo, lo), *br = px(fb, hi, hi);
    uint8_t want_tl[2] = { sr_srgb_encode8(8 / 255.0f), sr_srgb_encode8(8 / 255.0f) };
    uint8_t want_br[2] = { sr_srgb_encode8(56 / 255.0f), sr_srgb_encode8(56 / 255.0f) };
    CHECK_EQ(tl[0], want_tl[0]);
    CHECK_EQ(tl[1], want_tl[1]);
    CHECK_EQ(br[0], want_br[0]);
    CHECK_EQ(br[1], want_br[1]);
    /* The example as a glTF reader stores it in sr_texture's frame
     * (docs/gltf.md): offset' = (o.x + s.y sin r, 1 - o.y - s.y cos r). */
    const float o[2] = { 0, 1 }, r = 1.57079632679f, sc = 0.5f;
    m.base_color_texture.offset[0] = o[0] + sc * sinf(r);
    m.base_color_texture.offset[1] = 1.0f - o[1] - sc * cosf(r);
    m.base_color_texture.rotation = r;
    m.base_color_texture.scale[0] = m.base_color_texture.scale[1] = sc;
    sr_clear(sr_test_ctx(), fb, &(sr_clear_desc){ 0 });
    draw_quad(fb, &d, false);
    /* glTF (0, 0) -> (0, 1): column 0, row 3.  (1, 0) (screen top-right)
     * -> (0, 0.5): column 0, row 2.  (0, 1) (bottom-left) -> (0.5, 1):
     * column 1, row 3. */
    const uint8_t *c0 = px(fb, lo, lo), *c1 = px(fb, hi, lo), *c2 = px(fb, lo, hi);
    CHECK_EQ(c0[0], sr_srgb_encode8(8 / 255.0f));
    CHECK_EQ(c0[1], sr_srgb_encode8(56 / 255.0f));
    CHECK_EQ(c1[0], sr_srgb_encode8(8 / 255.0f));
    CHECK_EQ(c1[1], sr_srgb_encode8(40 / 255.0f));
    CHECK_EQ(c2[0], sr_srgb_encode8(24 / 255.0f));
    CHECK_EQ(c2[1], sr_srgb_encode8(56 / 255.0f));
    save(fb, "pbr_texture_transform");
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    sr_destroy_texture(sr_test_ctx(), t);
}

/* A slot on coordinate set 1 drawn without texcoords1 reads set 0, as
 * sr_pbr_desc promises, also when no other slot reads set 0 (the
 * program used to lay out no coordinates then and drop the texture:
 * softrast render's --normals flat drops set 1). */
SR_TEST(a_slot_on_set_1_without_its_array_reads_set_0)
{
    uint8_t img[2 * 2 * 4] = { 200, 0, 0, 255, 0, 200, 0, 255, 0, 0, 200, 255, 200, 200, 0, 255 };
    sr_texture *t = NULL;
    REQUIRE(sr_make_texture(sr_test_ctx(), &(sr_texture_desc){ .width = 2, .height = 2,
                                                               .pixels = img }, &t) == SR_OK);
    sr_framebuffer *fb[2] = { make_fb(1, 1, 0.0f), make_fb(1, 1, 0.0f) };
    REQUIRE(fb[0] && fb[1]);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.unlit = true;
    m.base_color_texture = (sr_texture_slot){ .texture = t, .filter = SR_FILTER_NEAREST };
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj };
    for (int set = 0; set < 2; set++) {
        m.base_color_texture.texcoord = set;
        draw_quad(fb[set], &d, false);
    }
    size_t n = 4 * (size_t)sr_framebuffer_width(fb[0]) * (size_t)sr_framebuffer_height(fb[0]);
    CHECK(memcmp(sr_framebuffer_pixels(fb[0]), sr_framebuffer_pixels(fb[1]), n) == 0);
    const uint8_t *c = px(fb[1], 7, 7);
    CHECK(c[0] > 100 || c[1] > 100 || c[2] > 100);   /* a texel, not black */
    CHECK(!(c[0] > 250 && c[1] > 250 && c[2] > 250));  /* nor the untextured white */
    for (int k = 0; k < 2; k++) {
        sr_destroy_framebuffer(sr_test_ctx(), fb[k]);
    }
    sr_destroy_texture(sr_test_ctx(), t);
}

/* sr_texture_slot_uv gives the coordinates the program samples: the
 * extension's example (as the test above stores it) takes the corners of
 * the unit square, in sr_texture's frame, to the spec's quadrant turned
 * clockwise; the identity slot leaves them as they are, bit for bit;
 * and it refuses what it cannot transform. */
SR_TEST(texture_slot_uv_applies_the_transform)
{
    sr_context *ctx = sr_test_ctx();
    const float r = 1.57079632679f, sc = 0.5f;
    sr_texture_slot s = { .rotation = r, .scale = { sc, sc } };
    s.offset[0] = sc * sinf(r);
    s.offset[1] = 1.0f - 1.0f - sc * cosf(r);
    /* sr_texture's (0, 1), (1, 1), (0, 0): glTF's (0, 0), (1, 0), (0, 1). */
    float uv[6] = { 0, 1, 1, 1, 0, 0 }, out[6];
    REQUIRE(sr_texture_slot_uv(ctx, &s, uv, 3, out) == SR_OK);
    /* glTF's (0, 1), (0, 0.5), (0.5, 1) are sr_texture's (0, 0), (0, 0.5), (0.5, 0). */
    const float want[6] = { 0, 0, 0, 0.5f, 0.5f, 0 };
    for (int i = 0; i < 6; i++) {
        CHECK_NEAR(out[i], want[i], 1e-6);
    }
    sr_texture_slot id = { 0 };   /* a zeroed scale (not set) reads as 1 */
    const float odd[4] = { -0.3f, 1.7f, 1e-8f, 123.456f };
    float same[4];
    REQUIRE(sr_texture_slot_uv(ctx, &id, odd, 2, same) == SR_OK);
    CHECK(memcmp(odd, same, sizeof odd) == 0);
    /* A scale of 0 that is set (KHR_texture_transform's) collapses every
     * coordinate onto the offset, on one axis or both. */
    sr_texture_slot zero = { .offset = { 0.375f, 0.625f }, .scale_set = true };
    REQUIRE(sr_texture_slot_uv(ctx, &zero, odd, 2, same) == SR_OK);
    for (int i = 0; i < 4; i++) {
        CHECK_NEAR(same[i], zero.offset[i & 1], 0);
    }
    zero.scale[1] = 2.0f;
    REQUIRE(sr_texture_slot_uv(ctx, &zero, odd, 2, same) == SR_OK);
    CHECK_NEAR(same[0], 0.375f, 0);
    CHECK_NEAR(same[1], 0.625f + 2.0f * 1.7f, 1e-6);
    CHECK_EQ(sr_texture_slot_uv(ctx, NULL, uv, 3, out), SR_INVALID_ARG);
    CHECK_EQ(sr_texture_slot_uv(ctx, &s, NULL, 3, out), SR_INVALID_ARG);
    CHECK_EQ(sr_texture_slot_uv(ctx, &s, NULL, 0, NULL), SR_OK);
    s.rotation = NAN;
    CHECK_EQ(sr_texture_slot_uv(ctx, &s, uv, 3, out), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "not finite");
}

/* A quad whose u runs along +x has tangent (1, 0, 0, +1); with u along -x
 * it has (-1, 0, 0) and w = -1 (N x T = -y against B = +y). */
SR_TEST(tangents_of_a_quad)
{
    float pos[] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    float nrm[] = { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    float uv[] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    uint32_t idx[] = { 0, 1, 2, 0, 2, 3 };
    sr_mesh m = { .vertex_count = 4, .positions = pos, .normals = nrm, .texcoords = uv,
                  .triangle_count = 2, .indices = idx };
    float t[16];
    REQUIRE(sr_mesh_compute_tangents(sr_test_ctx(), &m, t) == SR_OK);
    for (int v = 0; v < 4; v++) {
        CHECK_NEAR(t[4 * v], 1, 1e-6);
        CHECK_NEAR(t[4 * v + 1], 0, 1e-6);
        CHECK_NEAR(t[4 * v + 2], 0, 1e-6);
        CHECK_EQ(t[4 * v + 3], 1);
    }
    for (int v = 0; v < 4; v++) {
        uv[2 * v] = 1.0f - uv[2 * v];
    }
    REQUIRE(sr_mesh_compute_tangents(sr_test_ctx(), &m, t) == SR_OK);
    for (int v = 0; v < 4; v++) {
        CHECK_NEAR(t[4 * v], -1, 1e-6);
        CHECK_EQ(t[4 * v + 3], -1);
    }
    /* A tilted normal: the tangent is made orthogonal to it. */
    nrm[0] = 0.6f;
    nrm[2] = 0.8f;
    REQUIRE(sr_mesh_compute_tangents(sr_test_ctx(), &m, t) == SR_OK);
    CHECK_NEAR(t[0] * 0.6f + t[2] * 0.8f, 0, 1e-6);
    CHECK_NEAR(t[0] * t[0] + t[1] * t[1] + t[2] * t[2], 1, 1e-6);
    /* The sphere's tangents point along +u (around the axis). */
    sphere s = make_sphere(16, 8);
    sr_mesh sm = { .vertex_count = s.nv, .positions = s.pos, .normals = s.nrm, .texcoords = s.uv,
                   .triangle_count = s.ni / 3, .indices = s.idx };
    float *st = malloc(s.nv * 4 * sizeof(float));
    REQUIRE(st);
    REQUIRE(sr_mesh_compute_tangents(sr_test_ctx(), &sm, st) == SR_OK);
    size_t v = 4 * 17 + 4;   /* stack 4 (the equator), slice 4 (phi = pi/2): at -x */
    CHECK_NEAR(s.pos[3 * v], -1, 1e-5);
    CHECK_NEAR(st[4 * v + 2], 1, 1e-3);   /* u grows towards +z there */
    CHECK_EQ(st[4 * v + 3], 1);
    free(st);
    free_sphere(&s);
    /* Bad input. */
    CHECK_EQ(sr_mesh_compute_tangents(sr_test_ctx(), NULL, t), SR_INVALID_ARG);
    CHECK_EQ(sr_mesh_compute_tangents(sr_test_ctx(), &m, NULL), SR_INVALID_ARG);
    m.texcoords = NULL;
    CHECK_EQ(sr_mesh_compute_tangents(sr_test_ctx(), &m, t), SR_INVALID_ARG);
    m.texcoords = uv;
    idx[5] = 9;
    CHECK_EQ(sr_mesh_compute_tangents(sr_test_ctx(), &m, t), SR_INVALID_ARG);
}

SR_TEST(default_material_is_gltf_default)
{
    sr_pbr_material m = sr_pbr_default_material();
    CHECK_EQ(m.base_color[0], 1);
    CHECK_EQ(m.base_color[3], 1);
    CHECK_EQ(m.metallic, 1);
    CHECK_EQ(m.roughness, 1);
    CHECK_EQ(m.normal_scale, 1);
    CHECK_EQ(m.occlusion_strength, 1);
    CHECK_EQ(m.emissive[0], 0);
    CHECK_EQ(m.alpha_mode, SR_ALPHA_OPAQUE);
    CHECK_NEAR(m.alpha_cutoff, 0.5, 0);
    CHECK_EQ(m.base_color_texture.scale[0], 1);
    CHECK(!m.double_sided && !m.unlit);
}

SR_TEST(bad_descs_are_refused)
{
    sr_context *ctx = sr_test_ctx();
    sr_pbr *p = (sr_pbr *)1;
    CHECK_EQ(sr_make_pbr_program(NULL, &(sr_pbr_desc){ 0 }, &p), SR_INVALID_ARG);
    CHECK_EQ(sr_make_pbr_program(ctx, NULL, &p), SR_INVALID_ARG);
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ 0 }, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .exposure = 100 }, &p), SR_INVALID_ARG);
    CHECK(p == NULL);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "exposure");
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .tonemap = 9 }, &p), SR_INVALID_ARG);
    sr_mat4 inf_model = sr_mat4_identity();
    inf_model.m[0] = INFINITY;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .model = &inf_model }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_pbr_desc.model has a NaN or infinite entry");
    CHECK(p == NULL);
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .tangents = (const float *)&p }, &p),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "vertex_count");
    sr_pbr_material m = sr_pbr_default_material();
    m.roughness = NAN;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    m = sr_pbr_default_material();
    uint8_t white[4] = { 255, 255, 255, 255 };
    sr_texture *t = solid_texture(white, true);
    REQUIRE(t);
    m.occlusion_texture.texture = t;
    m.occlusion_texture.texcoord = 2;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "occlusion_texture.texcoord");
    m.occlusion_texture.texcoord = 1;
    m.alpha_mode = 7;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    sr_pbr_desc d = { 0 };
    d.lights[2].type = SR_LIGHT_POINT;
    d.lights[2].vector.x = INFINITY;
    CHECK_EQ(sr_make_pbr_program(ctx, &d, &p), SR_INVALID_ARG);
    CHECK(sr_pbr_program(NULL) == NULL);
    sr_destroy_pbr_program(ctx, NULL);
    sr_destroy_texture(ctx, t);
}

/* The white furnace: a white sphere under a uniform white ambient, no
 * lights, tone curve off, exposure -1 (so 1 encodes below white).  A
 * dielectric's diffuse and specular parts and a metal's single and
 * multiple scattering sum to 1 within 3% at every roughness (printed per
 * roughness and metallic). */
static double srgb_decode(int code)
{
    double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* The lowest, highest and summed radiance (exposure -1 undone) of the
 * sphere's pixels (red not 0) in cell 0, and their count. */
static int furnace_range(const sr_framebuffer *fb, double *lo, double *hi, double *sum)
{
    int n = 0;
    *lo = 1e9, *hi = 0, *sum = 0;
    for (int y = 0; y < CELL; y++) {
        for (int x = 0; x < CELL; x++) {
            const uint8_t *c = px(fb, x, y);
            if (c[0] == 0) {
                continue;
            }
            double lin = srgb_decode(c[0]) * 2.0;
            *lo = lin < *lo ? lin : *lo;
            *hi = lin > *hi ? lin : *hi;
            *sum += lin;
            n++;
        }
    }
    return n;
}

/* Draws the furnace sphere for metallic 0 and 1 over roughness 0..1
 * under `env` (NULL: a white hemisphere) and bounds every pixel. */
static void furnace(const sr_environment *env, const char *label, double hi_bound)
{
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    for (int k = 0; k <= 8; k++) {
        sr_framebuffer *fb = make_fb(1, 1, 0.0f);
        REQUIRE(fb);
        sr_pbr_material m = sr_pbr_default_material();
        m.metallic = k > 4 ? 1.0f : 0.0f;
        m.roughness = (float)(k > 4 ? k - 4 : k) / 4.0f;
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                          .environment = env, .exposure = -1.0f,
                          .tonemap = SR_TONEMAP_NONE };
        if (!env) {
            d.sky = d.ground = (sr_vec3){ 1, 1, 1 };
        }
        REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
        double lo, hi, sum;
        int n = furnace_range(fb, &lo, &hi, &sum);
        REQUIRE(n > 2000);
        fprintf(stderr, "furnace (%s) metallic %.0f roughness %.2f: min %.3f mean %.3f max %.3f\n",
                label, (double)m.metallic, (double)m.roughness, lo, sum / n, hi);
        CHECK(lo > 0.97);
        CHECK(hi < hi_bound);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    free_sphere(&s);
}

SR_TEST(white_furnace_hemisphere)
{
    furnace(NULL, "hemisphere", 1.03);
}

/* A uniform white environment: an equirectangular image of ones. */
static sr_environment *white_environment(void)
{
    float white[8 * 4 * 3];
    for (int i = 0; i < 8 * 4 * 3; i++) {
        white[i] = 1.0f;
    }
    sr_environment *env = NULL;
    if (sr_make_environment(sr_test_ctx(),
                            &(sr_environment_desc){ .pixels = white, .width = 8, .height = 4 },
                            &env) != SR_OK) {
        return NULL;
    }
    return env;
}

/* The same furnace through image-based light: a uniform white
 * environment (an equirectangular image of ones) in place of the
 * hemisphere; its prefiltered levels allow 1% more at the rim. */
SR_TEST(white_furnace_environment)
{
    sr_environment *env = white_environment();
    REQUIRE(env);
    furnace(env, "environment", 1.04);
    sr_destroy_environment(sr_test_ctx(), env);
}

#define PI_D 3.14159265358979323846
/* The split sum's scale A and bias B at N.V = 1 by quadrature over the
 * light's polar angle (V = N makes the integral symmetric about N): the
 * GGX D with alpha = roughness^2 and the height-correlated Smith
 * visibility times N.L, split by Schlick's Fresnel into F0 (1 - Fc) + Fc.
 * Independent of the build's table, which samples half vectors. */
static void dfg_head_on(double roughness, double *a, double *b)
{
    const int steps = 20000;
    double a2 = roughness * roughness * roughness * roughness;
    *a = *b = 0;
    for (int i = 0; i < steps; i++) {
        double tl = (i + 0.5) * (PI_D / 2) / steps, nl = cos(tl);
        double nh = cos(tl / 2), vh = nh;   /* H halves L and V = N */
        double dd = nh * nh * (a2 - 1) + 1;
        double d = a2 / (PI_D * dd * dd);
        double vis = 0.5 / (nl + sqrt(nl * nl * (1 - a2) + a2));   /* N.V = 1 */
        double fc = pow(1 - vh, 5);
        double w = d * vis * nl * sin(tl) * 2 * PI_D * (PI_D / 2) / steps;
        *a += (1 - fc) * w;
        *b += fc * w;
    }
}

/* A grey metal (F0 = 0.5) under the uniform white environment: seen head
 * on, it reflects FssEss = F0 A + B and FmsEms (Fdez-Aguera) of the
 * radiance, with A and B the BRDF's own integral.  A white metal (the
 * furnace above) cannot tell a wrong A + B, as multiple scattering then
 * returns whatever single scattering misses; a grey one can.  Within 2%
 * (8-bit encoding is 0.5% here) at every roughness. */
SR_TEST(grey_metal_reflects_the_split_sum_integral)
{
    sr_environment *env = white_environment();
    REQUIRE(env);
    sphere s = make_sphere(96, 48);
    sr_mat4 view = test_view(), proj = test_projection();
    for (int k = 1; k <= 4; k++) {
        sr_framebuffer *fb = make_fb(1, 1, 0.0f);
        REQUIRE(fb);
        sr_pbr_material m = sr_pbr_default_material();
        m.base_color[0] = m.base_color[1] = m.base_color[2] = 0.5f;
        m.roughness = (float)k / 4.0f;
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                          .environment = env, .exposure = -1.0f,
                          .tonemap = SR_TONEMAP_NONE };
        REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
        double a, b;
        dfg_head_on(m.roughness, &a, &b);
        double f0 = 0.5, fss = f0 * a + b, ems = 1 - (a + b), favg = f0 + (1 - f0) / 21;
        double want = fss + ems * fss * favg / (1 - ems * favg);
        double got = 0;
        for (int y = CELL / 2 - 1; y <= CELL / 2; y++) {
            for (int x = CELL / 2 - 1; x <= CELL / 2; x++) {
                got += srgb_decode(px(fb, x, y)[1]) * 2.0 / 4;
            }
        }
        fprintf(stderr, "grey metal roughness %.2f: A %.3f B %.3f, want %.3f got %.3f\n",
                (double)m.roughness, a, b, want, got);
        CHECK_NEAR(got, want, 0.02 * want);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    free_sphere(&s);
    sr_destroy_environment(sr_test_ctx(), env);
}

/* A white furnace of lights: a white metal seen head on, lit by
 * directional lights at every polar angle (64 of them, 8 a draw, each of
 * radiance 2 pi sin(theta) dtheta, so that they sum to a uniform white
 * sky), reflects all of it once the lights' multiple-scattering
 * compensation is in; single scattering alone gives Ess, 0.31 at
 * roughness 1.  Within 3% (the quadrature and 8 encodings of 8 bits). */
SR_TEST(white_metal_under_a_furnace_of_lights)
{
    sphere s = make_sphere(96, 48);
    sr_mat4 view = test_view(), proj = test_projection();
    const int draws = 8, steps = draws * SR_MAX_LIGHTS;
    const double dt = PI_D / 2 / steps;
    for (int k = 2; k <= 4; k += 2) {
        sr_pbr_material m = sr_pbr_default_material();   /* white metal */
        m.roughness = (float)k / 4.0f;
        double got = 0;
        for (int dr = 0; dr < draws; dr++) {
            sr_framebuffer *fb = make_fb(1, 1, 0.0f);
            REQUIRE(fb);
            sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                              .exposure = 1.0f, .tonemap = SR_TONEMAP_NONE };
            for (int l = 0; l < SR_MAX_LIGHTS; l++) {
                double t = (dr * SR_MAX_LIGHTS + l + 0.5) * dt;
                d.lights[l] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL,
                                          .vector = { (float)-sin(t), 0, (float)-cos(t) },
                                          .intensity = (float)(2 * PI_D * sin(t) * dt) };
            }
            REQUIRE(draw_sphere(fb, &s, &d, 0, 0, NULL) == SR_OK);
            for (int y = CELL / 2 - 1; y <= CELL / 2; y++) {
                for (int x = CELL / 2 - 1; x <= CELL / 2; x++) {
                    got += srgb_decode(px(fb, x, y)[1]) / 2.0 / 4;
                }
            }
            sr_destroy_framebuffer(sr_test_ctx(), fb);
        }
        fprintf(stderr, "furnace of lights roughness %.2f: %.3f\n", (double)m.roughness, got);
        CHECK_NEAR(got, 1.0, 0.03);
    }
    free_sphere(&s);
}

/* A ground square under a smaller square, the key light straight down,
 * seen from above: with the shadow map the ground under the occluder
 * gets only the ambient; without it, the light everywhere. */
SR_TEST(shadow_map_darkens_the_key_light)
{
    sr_context *ctx = sr_test_ctx();
    const float ground[] = { -1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1 };
    const float up[] = { 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0 };
    const float blocker[] = { -0.3f, 0.5f, 0.3f, 0.3f, 0.5f, 0.3f, 0.3f, 0.5f, -0.3f,
                              -0.3f, 0.5f, -0.3f };
    const uint32_t idx[] = { 0, 1, 2, 0, 2, 3 };
    sr_shadow_map *sm = NULL;
    REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 0, -1, 0 },
                                                       .bounds_min = { -1, 0, -1 },
                                                       .bounds_max = { 1, 0.5f, 1 }, .size = 256 },
                               &sm) == SR_OK);
    REQUIRE(sr_shadow_map_clear(ctx, sm) == SR_OK);
    REQUIRE(sr_shadow_map_draw(ctx, sm, &(sr_draw_desc){ .positions = blocker, .vertex_count = 4,
                                                         .indices = idx,
                                                         .index_type = SR_INDEX_U32,
                                                         .index_count = 6 }) == SR_OK);
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 5, 0 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 0, -1 });
    sr_mat4 proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.metallic = 0.0f;
    int centre[2], corner[2];
    for (int k = 0; k < 2; k++) {
        sr_framebuffer *fb = make_fb(1, 1, 0.0f);
        REQUIRE(fb);
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                          .sky = { 0.1f, 0.1f, 0.1f }, .ground = { 0.1f, 0.1f, 0.1f },
                          .shadow = k ? sm : NULL };
        d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, -1, 0 },
                                  .intensity = 2.0f };
        sr_pbr *p;
        REQUIRE(sr_make_pbr_program(ctx, &d, &p) == SR_OK);
        CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ .program = sr_pbr_program(p) },
                         &(sr_draw_desc){ .positions = ground, .normals = up, .vertex_count = 4,
                                          .indices = idx, .index_type = SR_INDEX_U32,
                                          .index_count = 6 }),
                 SR_OK);
        sr_destroy_pbr_program(ctx, p);
        centre[k] = px(fb, CELL / 2, CELL / 2)[1];
        corner[k] = px(fb, 8, 8)[1];
        if (k) {
            save(fb, "pbr_shadow");
        }
        sr_destroy_framebuffer(ctx, fb);
    }
    CHECK_EQ(centre[0], corner[0]);          /* no map: lit alike */
    CHECK_EQ(corner[1], corner[0]);          /* outside the shadow: as lit */
    CHECK(centre[1] < corner[1] - 60);       /* under the blocker: the ambient only */
    sr_destroy_shadow_map(ctx, sm);
}

/* One roughness for the whole material: the environment's prefiltered
 * radiance comes from a table made with the program (an octahedral map)
 * instead of a query per fragment.  The same material with a white
 * metallic-roughness texture (so the roughness is per fragment and the
 * query runs) gives the same picture within 3 codes. */
SR_TEST(environment_table_matches_the_query)
{
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(sr_test_ctx(), NULL, &env) == SR_OK);
    const uint8_t white[4] = { 255, 255, 255, 255 };
    sr_texture *t = solid_texture(white, false);
    REQUIRE(t);
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_framebuffer *fb = make_fb(2, 2, 0.0f);
    REQUIRE(fb);
    for (int k = 0; k < 4; k++) {
        sr_pbr_material m = sr_pbr_default_material();
        m.base_color[1] = 0.6f;
        m.base_color[2] = 0.3f;
        m.metallic = k / 2 ? 1.0f : 0.0f;
        m.roughness = k / 2 ? 0.4f : 0.6f;
        if (k % 2) {
            m.metallic_roughness_texture.texture = t;
        }
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj, .environment = env };
        REQUIRE(draw_sphere(fb, &s, &d, k % 2, k / 2, NULL) == SR_OK);
    }
    save(fb, "pbr_environment_table");
    for (int row = 0; row < 2; row++) {
        int worst = 0, lit = 0;
        for (int y = row * CELL; y < (row + 1) * CELL; y++) {
            for (int x = 0; x < CELL; x++) {
                const uint8_t *a = px(fb, x, y), *b = px(fb, x + CELL, y);
                for (int c = 0; c < 3; c++) {
                    int e = abs((int)a[c] - (int)b[c]);
                    worst = e > worst ? e : worst;
                }
                lit += a[1] > 0;
            }
        }
        CHECK(lit > 2000);
        CHECK(worst <= 3);
        fprintf(stderr, "environment table vs query, row %d: worst %d codes\n", row, worst);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
    sr_destroy_texture(sr_test_ctx(), t);
    sr_destroy_environment(sr_test_ctx(), env);
}

/* The default rig follows the camera: in a turned basis the key light
 * still comes from the viewer's upper left, and the program's lighting
 * is that rig as radiance with the sky over the ground. */
SR_TEST(default_lights_follow_the_camera)
{
    sr_camera_basis b;
    REQUIRE(sr_camera_frame((sr_vec3){ 3, 1, 2 }, (sr_vec3){ -3, -1, -2 }, (sr_vec3){ 0, 1, 0 },
                            &b));
    sr_light l[SR_MAX_LIGHTS];
    REQUIRE(sr_default_lights(&b, l) == SR_OK);
    for (int i = 0; i < SR_MAX_LIGHTS; i++) {
        CHECK_EQ(l[i].type, i < SR_DEFAULT_LIGHT_COUNT ? SR_LIGHT_DIRECTIONAL : SR_LIGHT_OFF);
    }
    /* The key travels away from the upper left and towards the scene:
     * along +u, -v and -w. */
    sr_vec3 key = l[0].vector;
    CHECK(sr_vec3_dot(key, b.u) > 0.4f);
    CHECK(sr_vec3_dot(key, b.v) < -0.5f);
    CHECK(sr_vec3_dot(key, b.w) < -0.3f);
    CHECK_NEAR(sr_vec3_length(key), 1.0f, 1e-6f);
    /* The rim comes from behind: it travels towards the viewer. */
    CHECK(sr_vec3_dot(l[2].vector, b.w) > 0.5f);
    CHECK(l[0].intensity > l[2].intensity && l[2].intensity > l[1].intensity);

    sr_pbr_desc d = { 0 };
    REQUIRE(sr_pbr_default_lighting(l, &d) == SR_OK);
    CHECK_NEAR(d.lights[0].intensity, l[0].intensity * SR_PBR_LIGHT_SCALE, 1e-6f);
    CHECK_NEAR(d.lights[5].intensity, SR_PBR_LIGHT_SCALE, 1e-6f);   /* zero means 1 */
    CHECK_EQ(d.lights[5].type, SR_LIGHT_OFF);
    CHECK(d.sky.y > d.ground.y && d.ground.y > 0.0f);

    sr_camera_basis bad = b;
    bad.v = (sr_vec3){ 0, 2, 0 };
    CHECK_EQ(sr_default_lights(&bad, l), SR_INVALID_ARG);
    CHECK_EQ(sr_default_lights(NULL, l), SR_INVALID_ARG);
    CHECK_EQ(sr_default_lights(&b, NULL), SR_INVALID_ARG);
    l[1].intensity = NAN;
    CHECK_EQ(sr_pbr_default_lighting(l, &d), SR_INVALID_ARG);
    CHECK_EQ(sr_pbr_default_lighting(NULL, &d), SR_INVALID_ARG);
    /* A light type outside the enum is refused here, not only later by
     * sr_make_pbr_program; desc is left as it was. */
    l[1].intensity = 1;
    l[2].type = (sr_light_type)7;
    sr_pbr_desc before;
    memcpy(&before, &d, sizeof d);
    CHECK_EQ(sr_pbr_default_lighting(l, &d), SR_INVALID_ARG);
    CHECK(memcmp(&before, &d, sizeof d) == 0);
}

/* A scene's own lights in place of the rig or before it, as softrast
 * render's --lights file|both: dark ones skipped, the strongest
 * directional one first; with the rig, the rig first when the scene has
 * no directional light. */
SR_TEST(scene_lights_replace_or_precede_the_rig)
{
    sr_light rig[SR_MAX_LIGHTS] = { 0 };
    for (int i = 0; i < 3; i++) {
        rig[i] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, -1, 0 },
                             .color = { 1, 1, 1 }, .intensity = 10.0f + (float)i };
    }
    const sr_light own[4] = {
        { .type = SR_LIGHT_POINT, .vector = { 0, 2, 0 }, .color = { 1, 1, 1 }, .intensity = 5 },
        { .type = SR_LIGHT_DIRECTIONAL, .vector = { 1, 0, 0 }, .color = { 0.5f, 0, 0 },
          .intensity = 2 },
        { .type = SR_LIGHT_OFF, .color = { 1, 1, 1 }, .intensity = 0 },
        { .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, 0, -1 }, .color = { 1, 1, 1 },
          .intensity = 3 },
    };
    sr_light l[SR_MAX_LIGHTS];
    memcpy(l, rig, sizeof l);
    REQUIRE(sr_pbr_scene_lights(own, 4, false, l) == SR_OK);
    /* the strongest directional (3 x 1 against 2 x 0.5) first, then the
     * file's order without the dark one */
    CHECK(l[0].type == SR_LIGHT_DIRECTIONAL && l[0].intensity == 3);
    CHECK(l[1].type == SR_LIGHT_POINT && l[2].intensity == 2);
    CHECK_EQ(l[3].type, SR_LIGHT_OFF);
    memcpy(l, rig, sizeof l);
    REQUIRE(sr_pbr_scene_lights(own, 4, true, l) == SR_OK);
    CHECK(l[0].intensity == 3 && l[3].intensity == 10 && l[5].intensity == 12);
    CHECK_EQ(l[6].type, SR_LIGHT_OFF);
    /* no directional light of its own: the rig's key goes first */
    memcpy(l, rig, sizeof l);
    REQUIRE(sr_pbr_scene_lights(own, 1, true, l) == SR_OK);
    CHECK(l[0].intensity == 10 && l[3].type == SR_LIGHT_POINT);
    memcpy(l, rig, sizeof l);
    REQUIRE(sr_pbr_scene_lights(NULL, 0, false, l) == SR_OK);
    CHECK_EQ(l[0].type, SR_LIGHT_OFF);
    CHECK_EQ(sr_pbr_scene_lights(NULL, 2, false, l), SR_INVALID_ARG);
    CHECK_EQ(sr_pbr_scene_lights(own, 4, false, NULL), SR_INVALID_ARG);
    sr_light odd = { .type = (sr_light_type)9 };
    memcpy(l, rig, sizeof l);
    CHECK_EQ(sr_pbr_scene_lights(&odd, 1, false, l), SR_INVALID_ARG);
    CHECK(memcmp(l, rig, sizeof l) == 0);
}

/* Without textures every lane's color is its own (the shadow's quad
 * verdict equals the lanes' tests), so the program lets the rasterizer
 * fill calls from several quads: the same bytes as quad by quad, for a
 * sphere under the studio and the key light's soft shadow on a ground.
 * A texture reads lane differences: then quads stay whole. */
SR_TEST(untextured_program_packs_lanes_to_the_same_bytes)
{
    sr_context *ctx = sr_test_ctx();
    sphere s = make_sphere(24, 16);
    const float ground[] = { -3, -1, 3, 3, -1, 3, 3, -1, -3, -3, -1, -3 };
    const float up[] = { 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0 };
    const uint32_t quad_idx[] = { 0, 1, 2, 0, 2, 3 };
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(ctx, NULL, &env) == SR_OK);
    sr_shadow_map *sm = NULL;
    REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { -0.3f, -1, -0.2f },
                                                       .bounds_min = { -3, -1, -3 },
                                                       .bounds_max = { 3, 1, 3 }, .size = 256 },
                               &sm) == SR_OK);
    REQUIRE(sr_shadow_map_clear(ctx, sm) == SR_OK);
    REQUIRE(sr_shadow_map_draw(ctx, sm, &(sr_draw_desc){ .positions = s.pos,
                                                         .vertex_count = s.nv, .indices = s.idx,
                                                         .index_type = SR_INDEX_U32,
                                                         .index_count = s.ni }) == SR_OK);
    sr_mat4 view = sr_look_at((sr_vec3){ 2, 3, 5 }, (sr_vec3){ 0, -0.5f, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.8f, 1.0f, 1.0f, 20.0f, false);
    sr_pbr_material m = sr_pbr_default_material();
    m.metallic = 0.3f;
    m.roughness = 0.45f;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj, .environment = env,
                      .shadow = sm };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { -0.3f, -1, -0.2f },
                              .intensity = 3.0f };
    sr_pbr *p;
    REQUIRE(sr_make_pbr_program(ctx, &d, &p) == SR_OK);
    CHECK(sr_pbr_program(p)->independent_lanes);
    const uint8_t *pixels[2];
    sr_framebuffer *fb[2];
    for (int k = 0; k < 2; k++) {
        sr_program prog = *sr_pbr_program(p);
        prog.independent_lanes = k == 1;
        fb[k] = make_fb(3, 3, 0.0f);
        REQUIRE(fb[k]);
        sr_clear(ctx, fb[k], &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
        CHECK_EQ(sr_draw(ctx, fb[k], &(sr_state){ .program = &prog },
                         &(sr_draw_desc){ .positions = ground, .normals = up, .vertex_count = 4,
                                          .indices = quad_idx, .index_type = SR_INDEX_U32,
                                          .index_count = 6 }),
                 SR_OK);
        CHECK_EQ(sr_draw(ctx, fb[k], &(sr_state){ .program = &prog, .cull = SR_CULL_BACK },
                         &(sr_draw_desc){ .positions = s.pos, .normals = s.nrm,
                                          .vertex_count = s.nv, .indices = s.idx,
                                          .index_type = SR_INDEX_U32, .index_count = s.ni }),
                 SR_OK);
        pixels[k] = sr_framebuffer_pixels(fb[k]);
    }
    save(fb[1], "pbr_packed_lanes");
    size_t bytes = 4 * (size_t)(3 * CELL) * (size_t)(3 * CELL);
    int lit = 0;
    for (size_t i = 0; i < bytes; i += 4) {
        lit += pixels[1][i + 1] > 0;
    }
    CHECK(lit > (int)(bytes / 4 / 2));
    CHECK(memcmp(pixels[0], pixels[1], bytes) == 0);
    sr_destroy_pbr_program(ctx, p);
    const uint8_t white[4] = { 255, 255, 255, 255 };
    sr_texture *t = solid_texture(white, false);
    REQUIRE(t);
    m.metallic_roughness_texture.texture = t;
    REQUIRE(sr_make_pbr_program(ctx, &d, &p) == SR_OK);
    CHECK(!sr_pbr_program(p)->independent_lanes);
    sr_destroy_pbr_program(ctx, p);
    sr_destroy_texture(ctx, t);
    for (int k = 0; k < 2; k++) {
        sr_destroy_framebuffer(ctx, fb[k]);
    }
    sr_destroy_shadow_map(ctx, sm);
    sr_destroy_environment(ctx, env);
    free_sphere(&s);
}

/* ---- the extensions: ior, specular, clearcoat, sheen --------------------- */

/* The sphere drawn alone into a fresh 1 x 1 cell framebuffer; the
 * caller destroys it. */
static sr_framebuffer *sphere_alone(const sphere *s, const sr_pbr_desc *d)
{
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    if (fb && draw_sphere(fb, s, d, 0, 0, NULL) != SR_OK) {
        sr_destroy_framebuffer(sr_test_ctx(), fb);
        return NULL;
    }
    return fb;
}

/* Whether two materials draw the very same bytes under desc d. */
static bool same_bytes(const sphere *s, sr_pbr_desc d, const sr_pbr_material *a,
                       const sr_pbr_material *b)
{
    d.material = a;
    sr_framebuffer *fa = sphere_alone(s, &d);
    d.material = b;
    sr_framebuffer *fb = sphere_alone(s, &d);
    bool same = fa && fb &&
                memcmp(sr_framebuffer_pixels(fa), sr_framebuffer_pixels(fb), 4 * CELL * CELL) == 0;
    if (fa) {
        sr_destroy_framebuffer(sr_test_ctx(), fa);
    }
    if (fb) {
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    return same;
}

/* F0 from the index of refraction, against the numbers worked by hand:
 * ((1.5 - 1) / 2.5)^2 = 0.04, (1 / 3)^2 for 2, 0 for 1 (no reflection). */
SR_TEST(ior_gives_the_fresnel_at_normal_incidence)
{
    CHECK_EQ(sr__ior_f0(1.5f), 0.04f);
    CHECK_EQ(sr__ior_f0(0.0f), 0.04f);
    CHECK_NEAR(sr__ior_f0(2.0f), 1.0 / 9.0, 1e-7);
    CHECK_NEAR(sr__ior_f0(1.33f), (0.33 / 2.33) * (0.33 / 2.33), 1e-7);
    CHECK_EQ(sr__ior_f0(1.0f), 0.0f);
}

/* The extensions' zero values draw the base's very bytes, and so do the
 * values that mean "as without": ior 1.5, specular 1 in white, a coat
 * or a sheen of weight zero through a black texture; and an unlit
 * material ignores them. */
SR_TEST(absent_or_neutral_extensions_draw_the_base_bytes)
{
    sphere s = make_sphere(32, 16);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(sr_test_ctx(), NULL, &env) == SR_OK);
    const uint8_t black[4] = { 0, 0, 0, 0 };
    sr_texture *t = solid_texture(black, false);
    REQUIRE(t);
    sr_pbr_material base = sr_pbr_default_material();
    base.base_color[0] = 0.8f;
    base.base_color[1] = 0.3f;
    base.metallic = 0.2f;
    base.roughness = 0.4f;
    for (int lightk = 0; lightk < 2; lightk++) {
        sr_pbr_desc d = lit_desc(&base, &view, &proj);
        if (lightk) {
            d.environment = env;
        }
        sr_pbr_material m = base;
        m.ior = 1.5f;
        CHECK(same_bytes(&s, d, &base, &m));
        m = base;
        m.specular_set = true;
        m.specular = 1.0f;
        m.specular_color[0] = m.specular_color[1] = m.specular_color[2] = 1.0f;
        CHECK(same_bytes(&s, d, &base, &m));
        m = base;
        m.clearcoat = 1.0f;
        m.clearcoat_roughness = 0.2f;
        m.clearcoat_texture.texture = t;   /* R = 0: weight 0 everywhere */
        CHECK(same_bytes(&s, d, &base, &m));
        m = base;
        m.sheen_color[0] = m.sheen_color[1] = m.sheen_color[2] = 1.0f;
        m.sheen_roughness = 0.5f;
        m.sheen_color_texture.texture = t;   /* black sheen */
        CHECK(same_bytes(&s, d, &base, &m));
        /* Unlit excludes the layers. */
        sr_pbr_material flat = base;
        flat.unlit = true;
        m = flat;
        m.clearcoat = 1.0f;
        m.sheen_color[0] = 1.0f;
        m.ior = 2.0f;
        CHECK(same_bytes(&s, d, &flat, &m));
    }
    sr_destroy_texture(sr_test_ctx(), t);
    sr_destroy_environment(sr_test_ctx(), env);
    free_sphere(&s);
}

/* Under a uniform hemisphere of radiance L, tone curve off: the sphere's
 * centre (N = V) in linear radiance, red, green and blue. */
static sr_pbr_desc uniform_desc(const sr_pbr_material *m, const sr_mat4 *view,
                                const sr_mat4 *proj, float L)
{
    return (sr_pbr_desc){ .material = m, .view = view, .projection = proj,
                          .sky = { L, L, L }, .ground = { L, L, L },
                          .tonemap = SR_TONEMAP_NONE };
}

static bool centre_linear(const sphere *s, const sr_pbr_desc *d, double out[3])
{
    sr_framebuffer *fb = sphere_alone(s, d);
    if (!fb) {
        return false;
    }
    const uint8_t *c = px(fb, CELL / 2, CELL / 2);
    for (int k = 0; k < 3; k++) {
        out[k] = srgb_decode(c[k]);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    return true;
}

/* A black, smooth dielectric under a uniform white hemisphere reflects F0
 * L plus the split sum's small bias at the sphere's centre (N = V): the
 * difference between two indices is (F0(n) - 0.04) L, F0 worked by hand.
 * Specular 0 leaves a black dielectric black; a red specular color
 * reflects red only; a metal ignores both. */
SR_TEST(ior_and_specular_set_the_dielectric_reflection)
{
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    const double L = 4.0;
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[0] = m.base_color[1] = m.base_color[2] = 0.0f;
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    sr_pbr_desc d = uniform_desc(&m, &view, &proj, (float)L);
    double ref[3], got[3];
    sr_framebuffer *fb;
    REQUIRE(centre_linear(&s, &d, ref));
    const float iors[] = { 1.33f, 1.76f, 2.0f, 2.42f };
    for (int i = 0; i < 4; i++) {
        m.ior = iors[i];
        REQUIRE(centre_linear(&s, &d, got));
        double f0 = ((iors[i] - 1.0) / (iors[i] + 1.0)) * ((iors[i] - 1.0) / (iors[i] + 1.0));
        double want = (f0 - 0.04) * L;
        fprintf(stderr, "ior %.2f: centre %+.4f over ior 1.5, F0 says %+.4f\n", (double)iors[i],
                got[1] - ref[1], want);
        /* 3% of the difference, plus an sRGB code's width near 0.2 */
        CHECK_NEAR(got[1] - ref[1], want, 0.03 * fabs(want) + 0.003);
    }
    m.ior = 0.0f;
    /* No specular: nothing to reflect, no diffuse from black: black. */
    m.specular_set = true;
    m.specular = 0.0f;
    m.specular_color[0] = m.specular_color[1] = m.specular_color[2] = 1.0f;
    sr_pbr_desc dl = lit_desc(&m, &view, &proj);
    dl.tonemap = SR_TONEMAP_NONE;
    REQUIRE((fb = sphere_alone(&s, &dl)));
    cell_stats st = stats(fb, 0, 0, 0);
    CHECK_EQ(st.lit, 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    /* A red F0 tint: green and blue keep only the grazing bias. */
    m.specular = 1.0f;
    m.specular_color[1] = m.specular_color[2] = 0.0f;
    REQUIRE(centre_linear(&s, &d, got));
    CHECK_NEAR(got[0], ref[0], 0.003);
    CHECK(got[1] < ref[1] / 4);
    /* A metal reflects its base color whatever the dielectric's terms. */
    sr_pbr_material metal = sr_pbr_default_material(), metal_spec;
    metal.base_color[1] = 0.5f;
    metal.roughness = 0.3f;
    metal_spec = metal;
    metal_spec.specular_set = true;
    metal_spec.ior = 2.5f;
    dl.material = &metal;
    sr_framebuffer *fa = sphere_alone(&s, &dl);
    dl.material = &metal_spec;
    sr_framebuffer *fm = sphere_alone(&s, &dl);
    REQUIRE(fa && fm);
    CHECK(sr_test_compare_images("pbr_metal_ignores_specular", sr_framebuffer_pixels(fm),
                                 sr_framebuffer_pixels(fa), CELL, CELL, 1, 0));
    sr_destroy_framebuffer(sr_test_ctx(), fa);
    sr_destroy_framebuffer(sr_test_ctx(), fm);
    free_sphere(&s);
}

/* The coat at the sphere's centre under a uniform hemisphere L: the
 * extension's layering, base (1 - c Fc) + c Fc L E, with Fc = 0.04 at
 * N = V and E (the lobe's albedo, Fresnel 1) 1 within the split sum's
 * fit there, computed from the base pixel drawn without the coat. */
SR_TEST(clearcoat_layers_over_the_base_as_the_extension_says)
{
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    const double L = 0.6;
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[0] = 0.7f;
    m.base_color[1] = 0.1f;
    m.base_color[2] = 0.1f;
    m.metallic = 0.0f;
    m.roughness = 0.8f;
    sr_pbr_desc d = uniform_desc(&m, &view, &proj, (float)L);
    double base[3], coat[3];
    sr_framebuffer *fb;
    REQUIRE(centre_linear(&s, &d, base));
    const float weights[] = { 0.5f, 1.0f };
    for (int i = 0; i < 2; i++) {
        m.clearcoat = weights[i];
        m.clearcoat_roughness = 0.1f;
        REQUIRE(centre_linear(&s, &d, coat));
        for (int k = 0; k < 3; k++) {
            double w = weights[i] * 0.04;
            double want = base[k] * (1.0 - w) + w * L;
            CHECK_NEAR(coat[k], want, 0.02 * want + 0.002);
        }
    }
    /* Under a key light the coat adds a sharp highlight to the rough
     * base: the peak rises, the red-over-green tint of it falls. */
    m.clearcoat = 0.0f;
    sr_pbr_desc dl = lit_desc(&m, &view, &proj);
    dl.exposure = -2.0f;
    REQUIRE((fb = sphere_alone(&s, &dl)));
    cell_stats plain = stats(fb, 0, 0, 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    m.clearcoat = 1.0f;
    m.clearcoat_roughness = 0.05f;
    REQUIRE((fb = sphere_alone(&s, &dl)));
    cell_stats coated = stats(fb, 0, 0, 0);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    CHECK(coated.max_sum > plain.max_sum + 60);
    CHECK(coated.peak[1] > plain.peak[1] + 40);
    free_sphere(&s);
}

/* The coat's own normal map: a flat map draws as no map (within a code,
 * the map's 8-bit texel is not exactly +z); a tilted one moves the coat's
 * highlight and leaves the base's alone. */
SR_TEST(clearcoat_normal_map_bends_the_coat_only)
{
    const uint8_t flat[4] = { 128, 128, 255, 255 };
    const uint8_t right[4] = { 218, 128, 218, 255 };
    sr_texture *tf = solid_texture(flat, false), *tr = solid_texture(right, false);
    REQUIRE(tf && tr);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[1] = m.base_color[2] = 0.2f;
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    m.clearcoat = 1.0f;
    m.clearcoat_roughness = 0.1f;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj };
    /* The light's mirror direction about +z is the view: the flat coat's
     * highlight fills the quad; tilted, it leaves. */
    d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, 0, -1 },
                              .intensity = 2.0f };
    int sums[3];
    for (int k = 0; k < 3; k++) {
        m.clearcoat_normal_texture.texture = k == 0 ? NULL : k == 1 ? tf : tr;
        sr_framebuffer *fb = make_fb(1, 1, 0.0f);
        REQUIRE(fb);
        draw_quad(fb, &d, false);
        const uint8_t *c = px(fb, CELL / 2, CELL / 2);
        sums[k] = c[0] + c[1] + c[2];
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    CHECK_NEAR(sums[1], sums[0], 3);
    CHECK(sums[2] < sums[0] - 60);
    sr_destroy_texture(sr_test_ctx(), tf);
    sr_destroy_texture(sr_test_ctx(), tr);
}

/* Charlie's distribution is normalized: the integral of D (N.H) over the
 * hemisphere is 1 at every roughness (midpoint rule over cos theta_h;
 * no part of the table's code). */
SR_TEST(sheen_distribution_is_normalized)
{
    const float rough[] = { 0.1f, 0.3f, 0.6f, 1.0f };
    for (int k = 0; k < 4; k++) {
        float a = sr__sheen_alpha(rough[k]);
        double sum = 0;
        const int n = 20000;
        for (int i = 0; i < n; i++) {
            double c = (i + 0.5) / n;
            sum += (double)sr__charlie_d(a, (float)c) * c * 2.0 * 3.14159265358979 / n;
        }
        CHECK_NEAR(sum, 1.0, 2e-3);
    }
}

/* The build's albedo table against a Monte Carlo estimate of the same
 * integral (uniform directions, a fixed seed), and its shape: more
 * sheen at grazing view than head-on, all of it below 1. */
SR_TEST(sheen_albedo_table_matches_a_monte_carlo_estimate)
{
    uint32_t seed = 12345;
    const float rough[] = { 0.3f, 0.7f, 1.0f };
    const float cosv[] = { 0.2f, 0.5f, 0.9f };
    for (int r = 0; r < 3; r++) {
        float a = sr__sheen_alpha(rough[r]);
        for (int c = 0; c < 3; c++) {
            float nv = cosv[c], v[3] = { sqrtf(1 - nv * nv), 0, nv };
            double sum = 0;
            const int n = 200000;
            for (int i = 0; i < n; i++) {
                seed = seed * 1664525u + 1013904223u;
                float z = (float)((seed >> 8) * (1.0 / 16777216.0));
                seed = seed * 1664525u + 1013904223u;
                float phi = (float)((seed >> 8) * (6.28318530718 / 16777216.0));
                if (z <= 0.0f) {
                    continue;
                }
                float sz = sqrtf(1 - z * z), l[3] = { sz * cosf(phi), sz * sinf(phi), z };
                float h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] };
                float hl = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                sum += sr__sheen_lobe(a, z, nv, h[2] / hl);
            }
            double mc = sum * 2.0 * 3.14159265358979 / n;   /* uniform pdf 1 / (2 pi) */
            float table = sr__sheen_albedo(nv, rough[r]);
            fprintf(stderr, "sheen E(%.1f, roughness %.1f): table %.4f, Monte Carlo %.4f\n",
                    (double)nv, (double)rough[r], (double)table, mc);
            CHECK_NEAR(table, mc, 0.03 * mc + 0.005);
            CHECK(table < 1.0f);
        }
        CHECK(sr__sheen_albedo(0.2f, rough[r]) > sr__sheen_albedo(0.9f, rough[r]));
    }
}

/* The sheen's albedo scaling keeps the white furnace white: a white
 * sheen over a white dielectric under a uniform white hemisphere takes
 * from the base what it reflects, within the base furnace's 3%; under a
 * light the sheen of a black base gathers at the rim. */
SR_TEST(sheen_keeps_the_furnace_and_lights_the_rim)
{
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    const float rough[] = { 0.3f, 0.6f, 1.0f };
    for (int k = 0; k < 3; k++) {
        sr_pbr_material m = sr_pbr_default_material();
        m.metallic = 0.0f;
        m.roughness = 0.5f;
        m.sheen_color[0] = m.sheen_color[1] = m.sheen_color[2] = 1.0f;
        m.sheen_roughness = rough[k];
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                          .sky = { 1, 1, 1 }, .ground = { 1, 1, 1 }, .exposure = -1.0f,
                          .tonemap = SR_TONEMAP_NONE };
        sr_framebuffer *fb = sphere_alone(&s, &d);
        REQUIRE(fb);
        double lo, hi, sum;
        REQUIRE(furnace_range(fb, &lo, &hi, &sum) > 2000);
        fprintf(stderr, "sheen furnace roughness %.1f: min %.3f max %.3f\n", (double)rough[k],
                lo, hi);
        CHECK(lo > 0.97 && hi < 1.03);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[0] = m.base_color[1] = m.base_color[2] = 0.0f;
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    m.specular_set = true;   /* specular 0: the sheen alone */
    m.sheen_color[0] = m.sheen_color[1] = m.sheen_color[2] = 1.0f;
    m.sheen_roughness = 0.5f;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, 0, -1 },
                              .intensity = 3.0f };
    sr_framebuffer *fb = sphere_alone(&s, &d);
    REQUIRE(fb);
    save(fb, "pbr_sheen_rim");
    /* Along the horizontal diameter: the centre against 90% out. */
    int centre = px(fb, CELL / 2, CELL / 2)[1];
    int rim = px(fb, CELL / 2 + (int)(0.9 * CELL / 2 / 1.1), CELL / 2)[1];
    CHECK(rim > centre + 20);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
}

/* The sphere drawn with p into two fresh cells: fb[0] quad by quad,
 * fb[1] with the lanes packed as the program allows. */
static bool draw_both_ways(const sphere *s, const sr_pbr *p, sr_framebuffer *fb[2])
{
    bool ok = true;
    for (int k = 0; k < 2; k++) {
        sr_program prog = *sr_pbr_program(p);
        prog.independent_lanes = k == 1;
        fb[k] = make_fb(1, 1, 0.0f);
        ok = ok && fb[k] &&
             sr_draw(sr_test_ctx(), fb[k], &(sr_state){ .program = &prog, .cull = SR_CULL_BACK },
                     &(sr_draw_desc){ .positions = s->pos, .normals = s->nrm,
                                      .texcoords = s->uv, .vertex_count = s->nv,
                                      .indices = s->idx, .index_type = SR_INDEX_U32,
                                      .index_count = s->ni }) == SR_OK;
    }
    return ok;
}

/* The coat's prefiltered radiance from the program's table (one coat
 * roughness) and from the query (a white coat-roughness texture) agree
 * within 3 codes, as the base's do; and a material with every layer
 * packs lanes to the same bytes as quad by quad. */
SR_TEST(layers_agree_between_table_and_query_and_packed_lanes)
{
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(sr_test_ctx(), NULL, &env) == SR_OK);
    const uint8_t white[4] = { 255, 255, 255, 255 };
    sr_texture *t = solid_texture(white, false);
    REQUIRE(t);
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[1] = 0.4f;
    m.metallic = 0.0f;
    m.roughness = 0.9f;
    m.clearcoat = 1.0f;
    m.clearcoat_roughness = 0.5f;
    m.sheen_color[2] = 0.8f;
    m.sheen_roughness = 0.4f;
    m.ior = 1.8f;
    sr_pbr_desc d = lit_desc(&m, &view, &proj);
    d.environment = env;
    sr_pbr *p;
    REQUIRE(sr_make_pbr_program(sr_test_ctx(), &d, &p) == SR_OK);
    CHECK(sr_pbr_program(p)->independent_lanes);
    sr_framebuffer *fb[3];
    REQUIRE(draw_both_ways(&s, p, fb));
    sr_destroy_pbr_program(sr_test_ctx(), p);
    CHECK(sr_test_compare_images("pbr_layers_packed", sr_framebuffer_pixels(fb[1]),
                                 sr_framebuffer_pixels(fb[0]), CELL, CELL, 0, 0));
    m.clearcoat_roughness_texture.texture = t;
    REQUIRE((fb[2] = sphere_alone(&s, &d)));
    CHECK(sr_test_compare_images("pbr_coat_table_vs_query", sr_framebuffer_pixels(fb[2]),
                                 sr_framebuffer_pixels(fb[0]), CELL, CELL, 3, 0));
    for (int k = 0; k < 3; k++) {
        sr_destroy_framebuffer(sr_test_ctx(), fb[k]);
    }
    free_sphere(&s);
    sr_destroy_texture(sr_test_ctx(), t);
    sr_destroy_environment(sr_test_ctx(), env);
}

/* Out-of-domain extension values are refused by the program: an ior
 * (or a film's) between 0 and 1, a NaN factor, a negative film
 * thickness, a negative dispersion, a diffuse transmission or its color
 * outside 0..1. */
SR_TEST(bad_extension_values_are_refused)
{
    sr_context *ctx = sr_test_ctx();
    sr_pbr *p = NULL;
    sr_pbr_material m = sr_pbr_default_material();
    m.ior = 0.5f;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_pbr_material.ior 0.5");
    m.ior = -1.0f;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    m.ior = 1.0f;
    m.sheen_roughness = NAN;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "extension's factor is not finite");
    m.sheen_roughness = 0.0f;
    m.clearcoat_normal_texture.texture = (const sr_texture *)&m;
    m.clearcoat_normal_texture.texcoord = 3;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "clearcoat_normal_texture.texcoord");
    m = sr_pbr_default_material();
    m.iridescence_ior = 0.5f;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "iridescence_ior 0.5");
    m.iridescence_ior = 0.0f;
    m.iridescence_thickness_min = -1.0f;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "thicknesses must be >= 0");
    m.iridescence_thickness_min = 0.0f;
    m.anisotropy_strength = NAN;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    /* Dispersion and diffuse transmission, naming the field. */
    m = sr_pbr_default_material();
    m.dispersion = -0.1f;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_pbr_material.dispersion -0.1");
    m.dispersion = INFINITY;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "not finite");
    m.dispersion = 0.0f;
    m.diffuse_transmission = 1.5f;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_pbr_material.diffuse_transmission 1.5");
    m.diffuse_transmission = NAN;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    m.diffuse_transmission = 0.5f;
    m.diffuse_transmission_color[2] = -1.0f;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "diffuse_transmission_color[2]");
    m.diffuse_transmission_color[2] = 1.0f;
    m.diffuse_transmission_color_texture.texture = (const sr_texture *)&m;
    m.diffuse_transmission_color_texture.texcoord = 2;
    CHECK_EQ(sr_make_pbr_program(ctx, &(sr_pbr_desc){ .material = &m }, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "diffuse_transmission_color_texture.texcoord");
    CHECK(p == NULL);
}

/* The row the docs show (docs/pbr.md), under softrast render's default
 * lights and hemisphere, against its reference: a red dielectric at ior
 * 1.5 and 2.4, specular 0.3, a yellow specular color, a clear coat,
 * a rough coat, blue velvet (sheen) and a coated sheen.  A pixel
 * differs when a channel is off by more than 3 (libm between C
 * libraries: powf and expf in the sheen); at most 0.5% may. */
SR_TEST(layer_spheres_match_reference)
{
#ifndef SR_TEST_HAVE_PNG
    SKIP("this build reads no PNG, so not the reference image");
#endif
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_framebuffer *fb = make_fb(8, 1, 0.1f);
    REQUIRE(fb);
    sr_camera_basis b;
    REQUIRE(sr_camera_frame((sr_vec3){ 0, 0, 5 }, (sr_vec3){ 0, 0, -1 }, (sr_vec3){ 0, 1, 0 }, &b));
    sr_light l[SR_MAX_LIGHTS];
    REQUIRE(sr_default_lights(&b, l) == SR_OK);
    for (int k = 0; k < 8; k++) {
        sr_pbr_material m = sr_pbr_default_material();
        m.base_color[0] = 0.8f;
        m.base_color[1] = 0.08f;
        m.base_color[2] = 0.05f;
        m.metallic = 0.0f;
        m.roughness = 0.5f;
        switch (k) {
        case 0: break;
        case 1: m.ior = 2.4f; break;
        case 2: m.specular_set = true; m.specular = 0.3f;
                m.specular_color[0] = m.specular_color[1] = m.specular_color[2] = 1.0f; break;
        case 3: m.specular_set = true; m.specular = 1.0f;
                m.specular_color[0] = m.specular_color[1] = 2.0f; break;
        case 4: m.clearcoat = 1.0f; m.clearcoat_roughness = 0.05f; break;
        case 5: m.clearcoat = 1.0f; m.clearcoat_roughness = 0.4f; break;
        case 6: case 7:
            m.base_color[0] = 0.02f, m.base_color[1] = 0.02f, m.base_color[2] = 0.15f;
            m.roughness = 0.9f;
            m.sheen_color[0] = 0.4f, m.sheen_color[1] = 0.5f, m.sheen_color[2] = 1.0f;
            m.sheen_roughness = 0.5f;
            if (k == 7) {
                m.clearcoat = 0.8f;
                m.clearcoat_roughness = 0.1f;
            }
            break;
        }
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj };
        REQUIRE(sr_pbr_default_lighting(l, &d) == SR_OK);
        CHECK_EQ(draw_sphere(fb, &s, &d, k, 0, NULL), SR_OK);
    }
    save(fb, "pbr_layer_spheres");
    sr_test_check_image("pbr_layer_spheres", sr_framebuffer_pixels(fb), 8 * CELL, CELL, 3,
                        8L * CELL * CELL / 200);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
}

/* ---- KHR_materials_transmission and KHR_materials_volume ---------------- */

static double srgb_encode(double l)
{
    l = l < 0 ? 0 : l > 1 ? 1 : l;
    return 255.0 * (l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1 / 2.4) - 0.055);
}

/* A w x h sRGB texture: left half `left`, right half `right`. */
static sr_texture *split_texture(int w, int h, const uint8_t left[4], const uint8_t right[4])
{
    uint8_t *p = malloc((size_t)w * (size_t)h * 4);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            memcpy(&p[4 * ((size_t)y * (size_t)w + (size_t)x)], x < w / 2 ? left : right, 4);
        }
    }
    sr_texture *t = NULL;
    sr_make_texture(sr_test_ctx(), &(sr_texture_desc){ .width = w, .height = h, .pixels = p,
                                                       .srgb = true },
                    &t);
    free(p);
    return t;
}

/* Clear glass: white, smooth, a dielectric that lets everything through. */
static sr_pbr_material glass(void)
{
    sr_pbr_material m = sr_pbr_default_material();
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    m.transmission = 1.0f;
    return m;
}

/* What smooth glass facing the viewer reflects: F0 A + B at N.V = 1. */
static double smooth_reflectance(void)
{
    float ab[2];
    sr_brdf_table(1.0f, 0.0f, ab);
    return 0.04 * ab[0] + ab[1];
}

/* The centre pixel of the sphere drawn with d into a fresh black cell. */
static bool centre_of(const sphere *s, const sr_pbr_desc *d, uint8_t out[4])
{
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    bool ok = fb && draw_sphere(fb, s, d, 0, 0, NULL) == SR_OK;
    if (ok) {
        memcpy(out, px(fb, CELL / 2, CELL / 2), 4);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    return ok;
}

/* Zero transmission is the extension absent: the volume's fields, a
 * transmission texture and a source change no byte of a lit sphere. */
SR_TEST(zero_transmission_keeps_the_old_pixels)
{
    sphere s = make_sphere(32, 16);
    sr_mat4 view = test_view(), proj = test_projection();
    const uint8_t c[4] = { 200, 120, 60, 255 };
    sr_texture *src = solid_texture(c, true);
    REQUIRE(src);
    sr_pbr_material m = sr_pbr_default_material();
    m.metallic = 0.0f;
    m.roughness = 0.3f;
    sr_pbr_desc d = lit_desc(&m, &view, &proj);
    sr_framebuffer *fb[2] = { make_fb(1, 1, 0.2f), make_fb(1, 1, 0.2f) };
    REQUIRE(fb[0] && fb[1]);
    REQUIRE(draw_sphere(fb[0], &s, &d, 0, 0, NULL) == SR_OK);
    m.thickness = 0.5f;
    m.attenuation_distance = 0.2f;
    m.attenuation_color[1] = 0.1f;
    m.transmission_texture.texture = src;
    d.transmission_source = src;
    REQUIRE(draw_sphere(fb[1], &s, &d, 0, 0, NULL) == SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(fb[0]), sr_framebuffer_pixels(fb[1]),
                 4 * CELL * CELL) == 0);
    for (int k = 0; k < 2; k++) {
        sr_destroy_framebuffer(sr_test_ctx(), fb[k]);
    }
    sr_destroy_texture(sr_test_ctx(), src);
    free_sphere(&s);
}

/* The flat background of the glass tests, and the centre pixel of the
 * unit sphere drawn with m over it, lit by a hemisphere of gray amb. */
static const uint8_t flat_color[4] = { 200, 120, 60, 255 };

static bool glass_over_flat(const sr_pbr_material *m, double amb, uint8_t out[4])
{
    sphere s = make_sphere(32, 16);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_texture *src = solid_texture(flat_color, true);
    float a = (float)amb;
    sr_pbr_desc d = { .material = m, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE, .transmission_source = src,
                      .sky = { a, a, a }, .ground = { a, a, a } };
    bool ok = src && centre_of(&s, &d, out);
    sr_destroy_texture(sr_test_ctx(), src);
    free_sphere(&s);
    return ok;
}

/* Clear glass (white, smooth, transmission 1) over a flat background of
 * color C: where it faces the viewer it shows C times what the specular
 * lobe does not reflect, 1 - (F0 A + B), plus that lobe's reflection of
 * the hemisphere; no tone curve, so within 1.5 codes of the formula (the
 * program's ambient uses the split sum's fit, the formula its table). */
SR_TEST(clear_glass_shows_the_background_less_the_fresnel)
{
    sr_pbr_material m = glass();
    double es = smooth_reflectance();
    const double amb[2] = { 0.0, 0.1 };
    for (int k = 0; k < 2; k++) {
        uint8_t p[4];
        REQUIRE(glass_over_flat(&m, amb[k], p));
        for (int ch = 0; ch < 3; ch++) {
            double want = srgb_encode(srgb_decode(flat_color[ch]) * (1.0 - es) + es * amb[k]);
            CHECK_NEAR(p[ch], want, 1.5);
        }
        /* Not the old opaque white. */
        CHECK(p[2] < 100);
    }
}

/* The volume: along thickness t (object units times the model's scale)
 * white light keeps attenuation_color^(t / distance) (Beer-Lambert), so
 * twice as thick is the square; the base color tints what comes through. */
SR_TEST(volume_attenuates_with_thickness_and_base_color_tints)
{
    sphere s = make_sphere(32, 16);
    sr_mat4 view = test_view(), proj = test_projection();
    const uint8_t white[4] = { 255, 255, 255, 255 };
    sr_texture *src = solid_texture(white, true);
    REQUIRE(src);
    sr_pbr_material m = glass();
    for (int c = 0; c < 3; c++) {
        m.attenuation_color[c] = 0.5f;
    }
    m.attenuation_distance = 0.5f;
    double es = smooth_reflectance();
    const float thick[2] = { 0.25f, 0.5f };
    sr_mat4 scale2 = sr_mat4_scale(2, 2, 2);
    for (int k = 0; k < 2; k++) {
        m.thickness = thick[k];
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                          .tonemap = SR_TONEMAP_NONE, .transmission_source = src };
        /* The unit sphere scaled by 2 in a cell twice as far out: thickness
         * in object units counts twice. */
        sr_mat4 p2 = sr_ortho(-2.2f, 2.2f, -2.2f, 2.2f, 1.0f, 10.0f, false);
        d.model = &scale2;
        d.projection = &p2;
        uint8_t p[4];
        REQUIRE(centre_of(&s, &d, p));
        double keep = pow(0.5, 2.0 * thick[k] / 0.5);
        CHECK_NEAR(p[1], srgb_encode((1.0 - es) * keep), 1.5);
    }
    m.attenuation_distance = 0.0f;
    m.base_color[0] = 0.2f;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE, .transmission_source = src };
    uint8_t p[4];
    REQUIRE(centre_of(&s, &d, p));
    CHECK_NEAR(p[0], srgb_encode(0.2 * (1.0 - es)), 1.5);
    CHECK_NEAR(p[1], srgb_encode(1.0 - es), 1.5);
    sr_destroy_texture(sr_test_ctx(), src);
    free_sphere(&s);
}

/* Without a source, glass shows the environment: in a uniform one of
 * radiance L, clear glass passes L (1 - Es) and reflects Es L, so its
 * centre is L, thin-walled or thick; a volume keeps attenuation_color^
 * (t / distance) of the passing share.  Without an environment too,
 * nothing shows through: black, as before. */
SR_TEST(glass_without_a_source_shows_the_environment)
{
    const float L[3] = { 0.3f, 0.5f, 0.2f };
    float pixels[8 * 4 * 3];
    for (int i = 0; i < 8 * 4 * 3; i++) {
        pixels[i] = L[i % 3];
    }
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(sr_test_ctx(),
                                &(sr_environment_desc){ .pixels = pixels, .width = 8, .height = 4 },
                                &env) == SR_OK);
    sphere s = make_sphere(32, 16);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = glass();
    double es = smooth_reflectance();
    for (int k = 0; k < 3; k++) {
        m.thickness = k == 0 ? 0.0f : 0.5f;
        m.attenuation_distance = k == 2 ? 0.5f : 0.0f;
        for (int c = 0; c < 3; c++) {
            m.attenuation_color[c] = 0.5f;
        }
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                          .tonemap = SR_TONEMAP_NONE, .environment = env };
        uint8_t p[4];
        REQUIRE(centre_of(&s, &d, p));
        /* The centre's ray leaves one thickness further on. */
        double keep = k == 2 ? pow(0.5, 0.5 / 0.5) : 1.0;
        for (int c = 0; c < 3; c++) {
            CHECK_NEAR(p[c], srgb_encode(L[c] * ((1.0 - es) * keep + es)), 1.5);
        }
    }
    m.thickness = 0.0f;
    m.attenuation_distance = 0.0f;
    sr_pbr_desc dark = { .material = &m, .view = &view, .projection = &proj,
                         .tonemap = SR_TONEMAP_NONE };
    uint8_t p[4];
    REQUIRE(centre_of(&s, &dark, p));
    CHECK(p[0] <= 1 && p[1] <= 1 && p[2] <= 1);
    free_sphere(&s);
    sr_destroy_environment(sr_test_ctx(), env);
}

/* A fresh black cell with the sphere drawn with m (and model, or NULL)
 * over a black | white edge down the middle of the screen, or NULL. */
static sr_framebuffer *glass_over_edge(const sr_pbr_material *m, const sr_mat4 *model)
{
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    const uint8_t black[4] = { 0, 0, 0, 255 }, white[4] = { 255, 255, 255, 255 };
    sr_texture *src = split_texture(CELL, CELL, black, white);
    sr_pbr_desc d = { .material = m, .model = model, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE, .transmission_source = src };
    sr_framebuffer *fb = src ? make_fb(1, 1, 0.0f) : NULL;
    if (fb && draw_sphere(fb, &s, &d, 0, 0, NULL) != SR_OK) {
        sr_destroy_framebuffer(sr_test_ctx(), fb);
        fb = NULL;
    }
    sr_destroy_texture(sr_test_ctx(), src);
    free_sphere(&s);
    return fb;
}

/* Roughness blurs what is seen through: over a black | white edge, a
 * smooth sphere shows the edge sharp, a rough one a ramp across it. */
SR_TEST(rough_transmission_blurs_the_background)
{
    sr_pbr_material m = glass();
    int ramp[2];
    for (int k = 0; k < 2; k++) {
        m.roughness = k ? 0.6f : 0.0f;
        sr_framebuffer *fb = glass_over_edge(&m, NULL);
        REQUIRE(fb);
        save(fb, k ? "pbr_transmission_rough" : "pbr_transmission_smooth");
        /* Pixels of the middle row between dark and bright. */
        ramp[k] = 0;
        for (int x = CELL / 4; x < 3 * CELL / 4; x++) {
            int g = px(fb, x, CELL / 2)[1];
            ramp[k] += g > 30 && g < 200;
        }
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    CHECK(ramp[0] <= 2);
    CHECK(ramp[1] >= 8);
}

/* KHR_materials_ior bends the refracted view ray: behind thick smooth
 * glass a sphere left of a black | white edge, the part over the white
 * (normals leaning right) looks back left into the black, the further the
 * higher the ior; ior 1 does not bend it, and 1.5 is the extension
 * absent, the same bytes as ior 0. */
SR_TEST(ior_moves_what_is_seen_through)
{
    sr_pbr_material m = glass();
    m.thickness = 0.5f;
    sr_mat4 move = sr_mat4_translate(-0.4f, 0, 0), size = sr_mat4_scale(0.6f, 0.6f, 0.6f);
    sr_mat4 model = sr_mat4_mul(&move, &size);
    const float ior[4] = { 0.0f, 1.5f, 1.0f, 2.0f };
    sr_framebuffer *fb[4];
    int dark[4];
    for (int k = 0; k < 4; k++) {
        m.ior = ior[k];
        fb[k] = glass_over_edge(&m, &model);
        REQUIRE(fb[k]);
        dark[k] = 0;
        for (int x = 0; x < CELL; x++) {
            dark[k] += px(fb[k], x, CELL / 2)[1] < 128;
        }
    }
    save(fb[3], "pbr_transmission_ior2");
    CHECK(memcmp(sr_framebuffer_pixels(fb[0]), sr_framebuffer_pixels(fb[1]),
                 4 * CELL * CELL) == 0);
    CHECK(dark[2] < dark[1]);
    CHECK(dark[1] + 1 < dark[3]);
    for (int k = 0; k < 4; k++) {
        sr_destroy_framebuffer(sr_test_ctx(), fb[k]);
    }
}

/* Glass drawn with only a directional light behind it, shining towards
 * the camera (+z): no ambient, nothing behind to see, no tone curve. */
static sr_framebuffer *glass_backlit(const sr_pbr_material *m, float intensity)
{
    sphere s = make_sphere(32, 16);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_desc d = { .material = m, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, 0, 1 },
                              .intensity = intensity };
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    if (fb && draw_sphere(fb, &s, &d, 0, 0, NULL) != SR_OK) {
        sr_destroy_framebuffer(sr_test_ctx(), fb);
        fb = NULL;
    }
    free_sphere(&s);
    return fb;
}

/* The sample viewer's punctual transmission, in double, at the point of
 * the unit sphere under pixel (x, y) of the cell, for a directional light
 * along +z: the light mirrored through the surface, GGX D and the
 * height-correlated visibility at alpha = roughness^2 (ior 1.5 keeps
 * it), times 1 - F(V.H) with F0 0.04. */
static double backlit_radiance(int x, int y, double rough, double intensity)
{
    double wx = ((x + 0.5) / CELL * 2.0 - 1.0) * 1.1, wy = (1.0 - (y + 0.5) / CELL * 2.0) * 1.1;
    double n[3] = { wx, wy, sqrt(1.0 - wx * wx - wy * wy) }, l[3] = { 0, 0, -1 };
    double v[3] = { -n[0], -n[1], 5.0 - n[2] }, lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double nl = 0, nv = 0, lm[3], h[3], hh = 0;
    for (int k = 0; k < 3; k++) {
        v[k] /= lv;
        nl += n[k] * l[k];
        nv += n[k] * v[k];
    }
    for (int k = 0; k < 3; k++) {
        lm[k] = l[k] - 2.0 * nl * n[k];
        h[k] = lm[k] + v[k];
        hh += h[k] * h[k];
    }
    double nh = 0, vh = 0, nlm = 0;
    for (int k = 0; k < 3; k++) {
        nh += n[k] * h[k] / sqrt(hh);
        vh += v[k] * h[k] / sqrt(hh);
        nlm += n[k] * lm[k];
    }
    double a = rough * rough, a2 = a * a, dd = nh * nh * (a2 - 1.0) + 1.0;
    double dgx = a2 / (3.14159265358979 * dd * dd);
    double vis = 0.5 / (nlm * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nlm * nlm * (1.0 - a2) + a2));
    double f = 0.04 + 0.96 * pow(1.0 - vh, 5.0);
    return (1.0 - f) * dgx * vis * intensity;
}

/* A light behind smooth glass shines through it (KHR_materials_
 * transmission's punctual BTDF, as the sample viewer draws it): the
 * centre shows the formula evaluated here within 2 codes; through a
 * volume (thickness 0.5, attenuation color 0.5 over distance 0.25) the
 * centre's straight path of 0.5 keeps 0.5^2 of it. */
SR_TEST(light_behind_glass_shines_through)
{
    sr_pbr_material m = glass();
    m.roughness = 0.2f;
    const float intensity = 0.01f;
    sr_framebuffer *fb = glass_backlit(&m, intensity);
    REQUIRE(fb);
    save(fb, "pbr_transmission_backlit");
    double want = backlit_radiance(CELL / 2, CELL / 2, 0.2, intensity);
    CHECK(want > 0.3 && want < 0.8);
    for (int ch = 0; ch < 3; ch++) {
        CHECK_NEAR(px(fb, CELL / 2, CELL / 2)[ch], srgb_encode(want), 2.0);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    m.thickness = 0.5f;
    m.attenuation_distance = 0.25f;
    m.attenuation_color[0] = m.attenuation_color[1] = m.attenuation_color[2] = 0.5f;
    fb = glass_backlit(&m, intensity);
    REQUIRE(fb);
    for (int ch = 0; ch < 3; ch++) {
        CHECK_NEAR(px(fb, CELL / 2, CELL / 2)[ch], srgb_encode(want * 0.25), 2.0);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* Without transmission the light behind adds nothing: the sphere's
 * bytes are those drawn with no light at all, as before the BTDF. */
SR_TEST(light_behind_opaque_sphere_adds_nothing)
{
    sr_pbr_material m = glass();
    m.roughness = 0.2f;
    m.transmission = 0.0f;
    sr_framebuffer *fb[2] = { glass_backlit(&m, 0.01f), glass_backlit(&m, 0.0f) };
    REQUIRE(fb[0] && fb[1]);
    CHECK(memcmp(sr_framebuffer_pixels(fb[0]), sr_framebuffer_pixels(fb[1]),
                 4 * CELL * CELL) == 0);
    m.transmission = 1.0f;
    sr_framebuffer *lit = glass_backlit(&m, 0.01f);
    REQUIRE(lit);
    CHECK(px(lit, CELL / 2, CELL / 2)[1] > px(fb[0], CELL / 2, CELL / 2)[1] + 100);
    sr_destroy_framebuffer(sr_test_ctx(), lit);
    for (int k = 0; k < 2; k++) {
        sr_destroy_framebuffer(sr_test_ctx(), fb[k]);
    }
}

/* The transmitted highlight widens with the roughness: with the
 * intensity scaled by alpha^2 so that the peaks match, the pixels of the
 * middle row above half the centre's radiance are more than twice as
 * many at roughness 0.4 as at 0.2, and the formula agrees on both. */
SR_TEST(transmitted_highlight_widens_with_roughness)
{
    sr_pbr_material m = glass();
    const float rough[2] = { 0.2f, 0.4f };
    int wide[2];
    for (int k = 0; k < 2; k++) {
        m.roughness = rough[k];
        float a = rough[k] * rough[k] / 0.04f;
        sr_framebuffer *fb = glass_backlit(&m, 0.01f * a * a);
        REQUIRE(fb);
        if (k) {
            save(fb, "pbr_transmission_backlit_rough");
        }
        double peak = srgb_decode(px(fb, CELL / 2, CELL / 2)[1]);
        wide[k] = 0;
        int model = 0;
        for (int x = 0; x < CELL; x++) {
            wide[k] += srgb_decode(px(fb, x, CELL / 2)[1]) > 0.5 * peak;
            double r = fabs((x + 0.5) / CELL * 2.0 - 1.0) * 1.1 < 0.95
                           ? backlit_radiance(x, CELL / 2, rough[k], 0.01 * a * a)
                           : 0.0;
            model += r > 0.5 * backlit_radiance(CELL / 2, CELL / 2, rough[k], 0.01 * a * a);
        }
        CHECK_NEAR(wide[k], model, 2);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    CHECK(wide[1] > 2 * wide[0]);
}

/* The transmitted light is the base layer's (the extensions' layering):
 * with no light but what comes through, clear glass over C shows C (1 -
 * Es) as before; Es is F0 A + F90 B of KHR_materials_specular's F0 and
 * F90 (specular 0: nothing reflected, C itself); a clear coat keeps 1 -
 * 0.04 of it facing the viewer, and a sheen its albedo scaling,
 * 1 - E(1, roughness). */
SR_TEST(layers_lie_over_the_transmitted_light)
{
    float ab[2];
    sr_brdf_table(1.0f, 0.0f, ab);
    double sheen_keep = 1.0 - sr__sheen_albedo(1.0f, 0.5f);
    /* Plain, specular 0, a coat, a sheen: what C keeps. */
    const double keep[4] = { 1.0 - (0.04 * ab[0] + ab[1]), 1.0,
                             (1.0 - (0.04 * ab[0] + ab[1])) * 0.96,
                             (1.0 - (0.04 * ab[0] + ab[1])) * sheen_keep };
    for (int k = 0; k < 4; k++) {
        sr_pbr_material m = glass();
        if (k == 1) {
            m.specular_set = true;
            m.specular = 0.0f;
            m.specular_color[0] = m.specular_color[1] = m.specular_color[2] = 1.0f;
        } else if (k == 2) {
            m.clearcoat = 1.0f;
        } else if (k == 3) {
            m.sheen_color[0] = m.sheen_color[1] = m.sheen_color[2] = 1.0f;
            m.sheen_roughness = 0.5f;
        }
        uint8_t p[4];
        REQUIRE(glass_over_flat(&m, 0.0, p));
        for (int ch = 0; ch < 3; ch++) {
            CHECK_NEAR(p[ch], srgb_encode(srgb_decode(flat_color[ch]) * keep[k]), 1.5);
        }
    }
}

/* ---- KHR_materials_anisotropy and KHR_materials_iridescence ------------- */

/* The film's reflectance at normal incidence against the exact Airy
 * reflectance of the film per wavelength integrated against the CIE 1931
 * matching functions (tests/thin_film_reference.py, numpy), clamped at 0
 * as the shader clamps: the shader's series stops at the second order and
 * its matching functions are another fit, so 0.01 apart at most (the
 * script's numbers and the series differ by 0.005 at most). */
SR_TEST(thin_film_matches_the_airy_spectrum)
{
    static const struct {
        float thickness, ior, f0[3];
        double rgb[3];
    } cases[] = {
        { 400.0f, 1.30f, { 0.04f, 0.04f, 0.04f }, { 0.0077, 0.0378, 0.0159 } },
        { 250.0f, 1.33f, { 0.00f, 0.00f, 0.00f }, { 0.0, 0.0347, 0.0760 } },
        { 300.0f, 1.80f, { 0.04f, 0.04f, 0.04f }, { 0.0967, 0.0430, 0.1222 } },
        { 550.0f, 1.50f, { 0.90f, 0.60f, 0.30f }, { 0.8414, 0.5636, 0.1336 } },
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        float out[3];
        sr__thin_film(1.0f, cases[k].thickness, cases[k].ior, cases[k].f0, out);
        for (int c = 0; c < 3; c++) {
            CHECK_NEAR(out[c], cases[k].rgb[c], 0.01);
        }
    }
    /* No film is the base alone, F0 at normal incidence, but for the
     * trace the series' floor on R12 R23 (1e-5) leaves, under 0.01. */
    float f0[3] = { 0.04f, 0.5f, 0.9f }, out[3];
    sr__thin_film(1.0f, 0.0f, 1.3f, f0, out);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(out[c], f0[c], 0.01);
    }
}

/* KHR_materials_iridescence replaces the Fresnel term of each of glTF's
 * two BRDFs (Appendix B mixes the dielectric's and the metal's by
 * metallic): a half-metal's film is the mean of the film over the
 * dielectric's F0 and the film over the base color, within 1e-6, not the
 * film over the mixed F0 (0.05 and more apart in a channel here); lanes
 * of metallic 0 and 1 are those films themselves. */
SR_TEST(iridescence_mixes_the_dielectric_and_metal_films)
{
    sr__pbr_layers x;
    memset(&x, 0, sizeof x);
    x.ir_ior = 1.8f;
    x.ir_thick = (v4f){ 450, 450, 450, 450 };
    const float base[3] = { 0.9f, 0.6f, 0.3f }, cos_v = 0.8f;
    v4f f0d[3], col[3], metal = { 0.0f, 1.0f, 0.5f, 0.25f }, nv = { cos_v, cos_v, cos_v, cos_v };
    for (int c = 0; c < 3; c++) {
        f0d[c] = (v4f){ 0.04f, 0.04f, 0.04f, 0.04f };
        col[c] = (v4f){ base[c], base[c], base[c], base[c] };
    }
    sr__iridescence_begin(&x, nv, f0d, col, metal);
    const float d[3] = { 0.04f, 0.04f, 0.04f };
    float fd[3], fm[3], mixed[3], half[3];
    sr__thin_film(cos_v, 450.0f, 1.8f, d, fd);
    sr__thin_film(cos_v, 450.0f, 1.8f, base, fm);
    for (int c = 0; c < 3; c++) {
        half[c] = 0.5f * (0.04f + base[c]);
    }
    sr__thin_film(cos_v, 450.0f, 1.8f, half, mixed);
    double apart = 0.0;
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(x.ir_f[c][0], fd[c], 1e-6);
        CHECK_NEAR(x.ir_f[c][1], fm[c], 1e-6);
        CHECK_NEAR(x.ir_f[c][2], 0.5 * (fd[c] + fm[c]), 1e-6);
        CHECK_NEAR(x.ir_f[c][3], 0.75 * fd[c] + 0.25 * fm[c], 1e-6);
        double gap = fabs(x.ir_f[c][2] - mixed[c]);
        apart = gap > apart ? gap : apart;
    }
    fprintf(stderr, "half-metal film: mean of the two films vs film over the mixed F0: %.3f apart\n",
            apart);
    CHECK(apart > 0.05);
}

/* Under a clear coat the film's upper medium is the coat, ior 1.5
 * (KHR_materials_iridescence's "Clearcoat"): a film of ior 1.5 on a
 * dielectric of ior 1.5 (F0 0.04) under a full coat is one index-matched
 * stack with nothing to reflect below the coat, within 0.005 of black,
 * while the same film under air reflects 0.02 and more; a half coat is
 * the mean of the two within 1e-6, and no coat the air's film exactly. */
SR_TEST(iridescence_under_a_coat_sees_the_coat_above)
{
    sr__pbr_layers x;
    memset(&x, 0, sizeof x);
    x.coat = true;
    x.cc = (v4f){ 0.0f, 1.0f, 0.5f, 0.0f };
    x.ir_ior = 1.5f;
    x.ir_thick = (v4f){ 350, 350, 350, 350 };
    const float cos_v = 0.9f;
    v4f f0d[3], col[3], metal = { 0 }, nv = { cos_v, cos_v, cos_v, cos_v };
    for (int c = 0; c < 3; c++) {
        f0d[c] = (v4f){ 0.04f, 0.04f, 0.04f, 0.04f };
        col[c] = (v4f){ 0.5f, 0.5f, 0.5f, 0.5f };
    }
    sr__iridescence_begin(&x, nv, f0d, col, metal);
    const float d[3] = { 0.04f, 0.04f, 0.04f };
    float air[3];
    sr__thin_film(cos_v, 350.0f, 1.5f, d, air);
    for (int c = 0; c < 3; c++) {
        CHECK(air[c] > 0.02f);
        CHECK_EQ(x.ir_f[c][0], air[c]);
        CHECK_NEAR(x.ir_f[c][1], 0.0, 0.005);
        CHECK_NEAR(x.ir_f[c][2], 0.5 * (x.ir_f[c][0] + x.ir_f[c][1]), 1e-6);
    }
}

/* Strength 0 and film weight 0 are the extensions absent: a rotation, a
 * texture, a film's ior and thicknesses change no byte, under the
 * hemisphere and the environment, on a plain and on a coated base. */
SR_TEST(zero_anisotropy_and_iridescence_draw_the_base_bytes)
{
    sphere s = make_sphere(32, 16);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(sr_test_ctx(), NULL, &env) == SR_OK);
    const uint8_t grey[4] = { 90, 200, 30, 255 };
    sr_texture *t = solid_texture(grey, false);
    REQUIRE(t);
    for (int k = 0; k < 4; k++) {
        sr_pbr_material base = sr_pbr_default_material();
        base.base_color[0] = 0.8f;
        base.base_color[1] = 0.5f;
        base.metallic = 0.6f;
        base.roughness = 0.35f;
        if (k & 2) {
            base.clearcoat = 0.7f;
        }
        sr_pbr_desc d = lit_desc(&base, &view, &proj);
        if (k & 1) {
            d.environment = env;
        }
        sr_pbr_material m = base;
        m.anisotropy_rotation = 1.0f;
        m.anisotropy_texture.texture = t;
        CHECK(same_bytes(&s, d, &base, &m));
        m = base;
        m.iridescence_ior = 1.8f;
        m.iridescence_thickness_min = 200.0f;
        m.iridescence_thickness_max = 700.0f;
        m.iridescence_texture.texture = t;
        m.iridescence_thickness_texture.texture = t;
        CHECK(same_bytes(&s, d, &base, &m));
    }
    sr_destroy_texture(sr_test_ctx(), t);
    sr_destroy_environment(sr_test_ctx(), env);
    free_sphere(&s);
}

/* KHR_materials_iridescence: a film 0 nm thick is no film.  With
 * iridescence_thickness_set, thicknesses of 0 everywhere (untextured:
 * the maximum; textured: both) draw the base's very bytes, textured or
 * not, plain or coated; unset, both zeros stay the extension's defaults
 * (100 to 400 nm), which do tint.  Before, sr_pbr_material could not
 * say 0 nm: both zeros always drew the default film. */
SR_TEST(a_film_0_nm_thick_draws_no_film)
{
    sphere s = make_sphere(32, 16);
    sr_mat4 view = test_view(), proj = test_projection();
    const uint8_t texel[4] = { 90, 200, 30, 255 };
    sr_texture *t = solid_texture(texel, false);
    REQUIRE(t);
    for (int coat = 0; coat < 2; coat++) {
        sr_pbr_material base = sr_pbr_default_material();
        base.base_color[0] = 0.3f;
        base.base_color[1] = 0.3f;
        base.roughness = 0.3f;
        base.clearcoat = coat ? 0.7f : 0.0f;
        sr_pbr_desc d = lit_desc(&base, &view, &proj);
        sr_pbr_material m = base;
        m.iridescence = 1.0f;
        m.iridescence_thickness_set = true;
        m.iridescence_thickness_texture.texture = t;
        CHECK(same_bytes(&s, d, &base, &m));          /* textured, 0 to 0 nm */
        m.iridescence_thickness_texture.texture = NULL;
        m.iridescence_thickness_min = 100.0f;
        CHECK(same_bytes(&s, d, &base, &m));          /* untextured, the maximum 0 */
        m.iridescence_thickness_texture.texture = t;
        CHECK(!same_bytes(&s, d, &base, &m));         /* textured, 100 to 0 nm: a film */
        sr_pbr_material unset = m, defaults = m;
        unset.iridescence_thickness_set = false;
        unset.iridescence_thickness_min = unset.iridescence_thickness_max = 0.0f;
        defaults.iridescence_thickness_min = 100.0f;
        defaults.iridescence_thickness_max = 400.0f;
        CHECK(same_bytes(&s, d, &unset, &defaults));
        CHECK(!same_bytes(&s, d, &base, &unset));
    }
    sr_destroy_texture(sr_test_ctx(), t);
    free_sphere(&s);
}

/* The sphere's tangents along u, (-z, 0, x) / |(x, z)|, w 1; (1, 0, 0)
 * at the poles.  The caller frees them. */
static float *sphere_tangents(const sphere *s)
{
    float *tan = calloc(s->nv * 4, sizeof(float));
    for (size_t v = 0; tan && v < s->nv; v++) {
        float x = s->pos[3 * v], z = s->pos[3 * v + 2], l = sqrtf(x * x + z * z);
        tan[4 * v] = l > 0 ? -z / l : 1.0f;
        tan[4 * v + 2] = l > 0 ? x / l : 0.0f;
        tan[4 * v + 3] = 1.0f;
    }
    return tan;
}

/* The half-width (sphere radii) of GGX's highlight on a unit sphere seen
 * and lit along the view axis, H = V = L: along the stretch's direction
 * D falls to half where (x / a)^2 + 1 - x^2 = sqrt 2, x the sine off the
 * centre along it (T.H) and a that direction's alpha. */
static double half_width(double a)
{
    return sqrt((sqrt(2.0) - 1.0) / (1.0 / (a * a) - 1.0));
}

/* Pixels of row (dy 0) or column (dx 0) through (x0, y0) whose green
 * radiance is at least half the peak's. */
static int extent(const sr_framebuffer *fb, int x0, int y0, int dx, int dy, double half)
{
    int n = 0, w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    for (int dir = -1; dir <= 1; dir += 2) {
        for (int x = x0, y = y0; x >= 0 && y >= 0 && x < w && y < h;
             x += dir * dx, y += dir * dy) {
            if (srgb_decode(px(fb, x, y)[1]) < half) {
                break;
            }
            n++;
        }
    }
    return n - 1;        /* the peak counted twice */
}

/* A white metal sphere lit from the viewer: anisotropy 0.5 at roughness
 * 0.4 stretches the highlight along T, alpha_t = mix(alpha, 1, 0.25)
 * against alpha across it, and the measured widths at half the peak
 * match the half-widths worked from D alone within 10% and 2 pixels
 * (the visibility, N.L and the compensation change them by 4%).  Rotation 0 runs along u
 * (around the sphere: across the image), from the coordinates'
 * derivatives; pi/2 along v (up the image), from the draw's tangents. */
SR_TEST(anisotropic_highlight_stretches_along_the_rotated_tangent)
{
    enum { SIZE = 256 };
    sphere s = make_sphere(96, 48);
    float *tan = sphere_tangents(&s);
    REQUIRE(tan);
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 0, 100 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_ortho(-1.1f, 1.1f, -1.1f, 1.1f, 90.0f, 110.0f, false);
    double alpha = 0.4 * 0.4, at = alpha + (1.0 - alpha) * 0.25;
    double px_per_unit = SIZE / 2.2;
    for (int k = 0; k < 3; k++) {
        sr_pbr_material m = sr_pbr_default_material();
        m.roughness = 0.4f;
        m.anisotropy_strength = k < 2 ? 0.5f : 0.0f;
        m.anisotropy_rotation = k == 1 ? 3.14159265f / 2 : 0.0f;
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                          .tonemap = SR_TONEMAP_NONE };
        d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, 0, -1 },
                                  .intensity = 0.25f };
        if (k == 1) {
            d.tangents = tan;
            d.vertex_count = s.nv;
        }
        sr_framebuffer *fb = NULL;
        REQUIRE(sr_make_framebuffer(sr_test_ctx(),
                                    &(sr_framebuffer_desc){ .width = SIZE, .height = SIZE },
                                    &fb) == SR_OK);
        sr_clear(sr_test_ctx(), fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
        sr_pbr *p;
        REQUIRE(sr_make_pbr_program(sr_test_ctx(), &d, &p) == SR_OK);
        CHECK_EQ(sr_draw(sr_test_ctx(), fb,
                         &(sr_state){ .program = sr_pbr_program(p), .cull = SR_CULL_BACK },
                         &(sr_draw_desc){ .positions = s.pos, .normals = s.nrm,
                                          .texcoords = s.uv, .vertex_count = s.nv,
                                          .indices = s.idx, .index_type = SR_INDEX_U32,
                                          .index_count = s.ni }),
                 SR_OK);
        sr_destroy_pbr_program(sr_test_ctx(), p);
        char name[64];
        snprintf(name, sizeof name, "pbr_anisotropy_%d", k);
        save(fb, name);
        int bx = 0, by = 0, best = -1;
        for (int y = 0; y < SIZE; y++) {
            for (int x = 0; x < SIZE; x++) {
                if (px(fb, x, y)[1] > best) {
                    best = px(fb, x, y)[1], bx = x, by = y;
                }
            }
        }
        /* The lights' multiple-scattering compensation grows as N.V falls,
         * which flattens the stretched highlight's top: its first
         * brightest pixel is up to 3 from the centre. */
        CHECK(abs(bx - SIZE / 2) <= 3 && abs(by - SIZE / 2) <= 3);
        CHECK(best < 255);       /* not clipped: the half level is the peak's */
        double half = 0.5 * srgb_decode((uint8_t)best);
        double wx = extent(fb, bx, by, 1, 0, half), wy = extent(fb, bx, by, 0, 1, half);
        double ex = 2.0 * half_width(k == 0 ? at : alpha) * px_per_unit;
        double ey = 2.0 * half_width(k == 1 ? at : alpha) * px_per_unit;
        printf("anisotropy %d: widths %.0f x %.0f px, worked %.1f x %.1f\n", k, wx, wy, ex, ey);
        CHECK(fabs(wx - ex) <= 0.1 * ex + 2.0);
        CHECK(fabs(wy - ey) <= 0.1 * ey + 2.0);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    free(tan);
    free_sphere(&s);
}

/* Both extensions with tangents pack lanes to the same bytes as quad by
 * quad under lights and the environment; without tangents the frame
 * comes from lane differences, so the program says its lanes depend on
 * each other. */
SR_TEST(anisotropy_and_iridescence_pack_lanes_to_the_same_bytes)
{
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(sr_test_ctx(), NULL, &env) == SR_OK);
    sphere s = make_sphere(48, 24);
    float *tan = sphere_tangents(&s);
    REQUIRE(tan);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[2] = 0.5f;
    m.metallic = 0.7f;
    m.roughness = 0.3f;
    m.anisotropy_strength = 0.8f;
    m.anisotropy_rotation = 0.6f;
    m.iridescence = 0.9f;
    m.iridescence_thickness_max = 520.0f;
    sr_pbr_desc d = lit_desc(&m, &view, &proj);
    d.environment = env;
    d.tangents = tan;
    d.vertex_count = s.nv;
    sr_pbr *p;
    REQUIRE(sr_make_pbr_program(sr_test_ctx(), &d, &p) == SR_OK);
    CHECK(sr_pbr_program(p)->independent_lanes);
    sr_framebuffer *fb[2];
    REQUIRE(draw_both_ways(&s, p, fb));
    sr_destroy_pbr_program(sr_test_ctx(), p);
    CHECK(sr_test_compare_images("pbr_aniso_packed", sr_framebuffer_pixels(fb[1]),
                                 sr_framebuffer_pixels(fb[0]), CELL, CELL, 0, 0));
    d.tangents = NULL;
    d.vertex_count = 0;
    REQUIRE(sr_make_pbr_program(sr_test_ctx(), &d, &p) == SR_OK);
    CHECK(!sr_pbr_program(p)->independent_lanes);
    sr_destroy_pbr_program(sr_test_ctx(), p);
    for (int k = 0; k < 2; k++) {
        sr_destroy_framebuffer(sr_test_ctx(), fb[k]);
    }
    free(tan);
    free_sphere(&s);
    sr_destroy_environment(sr_test_ctx(), env);
}

/* The row docs/pbr.md shows, under softrast render's default lights and
 * hemisphere, against its reference: brushed steel along u and along v
 * (tangents from the coordinates), a soap-film dielectric, an
 * oil-on-metal film and a film over a brushed metal.  A pixel differs
 * when a channel is off by more than 3 (cosf and expf between C
 * libraries); at most 0.5% may. */
SR_TEST(aniso_iridescence_spheres_match_reference)
{
#ifndef SR_TEST_HAVE_PNG
    SKIP("this build reads no PNG, so not the reference image");
#endif
    enum { N = 5 };
    sphere s = make_sphere(48, 24);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_framebuffer *fb = make_fb(N, 1, 0.1f);
    REQUIRE(fb);
    sr_camera_basis b;
    REQUIRE(sr_camera_frame((sr_vec3){ 0, 0, 5 }, (sr_vec3){ 0, 0, -1 }, (sr_vec3){ 0, 1, 0 }, &b));
    sr_light l[SR_MAX_LIGHTS];
    REQUIRE(sr_default_lights(&b, l) == SR_OK);
    for (int k = 0; k < N; k++) {
        sr_pbr_material m = sr_pbr_default_material();
        m.base_color[0] = 0.9f;
        m.base_color[1] = 0.9f;
        m.base_color[2] = 0.92f;
        m.metallic = 1.0f;
        m.roughness = 0.35f;
        switch (k) {
        case 0: m.anisotropy_strength = 0.8f; break;
        case 1: m.anisotropy_strength = 0.8f; m.anisotropy_rotation = 1.5707963f; break;
        case 2: m.base_color[0] = 0.05f, m.base_color[1] = 0.05f, m.base_color[2] = 0.08f;
                m.metallic = 0.0f; m.roughness = 0.15f; m.iridescence = 1.0f;
                m.iridescence_ior = 1.33f; m.iridescence_thickness_max = 380.0f; break;
        case 3: m.base_color[0] = 0.6f, m.base_color[1] = 0.6f, m.base_color[2] = 0.6f;
                m.roughness = 0.25f; m.iridescence = 1.0f; m.iridescence_ior = 1.5f;
                m.iridescence_thickness_max = 520.0f; break;
        case 4: m.anisotropy_strength = 0.6f; m.anisotropy_rotation = 0.5f;
                m.iridescence = 0.8f; m.iridescence_thickness_max = 450.0f; break;
        }
        sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj };
        REQUIRE(sr_pbr_default_lighting(l, &d) == SR_OK);
        CHECK_EQ(draw_sphere(fb, &s, &d, k, 0, NULL), SR_OK);
    }
    save(fb, "pbr_aniso_iridescence_spheres");
    sr_test_check_image("pbr_aniso_iridescence_spheres", sr_framebuffer_pixels(fb), N * CELL,
                        CELL, 3, (long)N * CELL * CELL / 200);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    free_sphere(&s);
}

/* ---- KHR_materials_dispersion ------------------------------------------- */

/* Where the view ray through pixel column x of the middle row leaves
 * glass_over_edge's sphere (centre c, radius r, thickness th object units)
 * for an ior, in double from Snell's law (the refracted direction of the
 * incident -v about the normal, GLSL's refract): the x of its exit point,
 * whose sign says whether the source's white half (x > 0) is seen there.
 * NaN off the sphere. */
static double exit_x(int x, double cx, double r, double th, double ior)
{
    double wx = ((x + 0.5) / CELL * 2.0 - 1.0) * 1.1, wy = (1.0 - (CELL / 2 + 0.5) / CELL * 2.0) * 1.1;
    double nx = (wx - cx) / r, ny = wy / r, s = 1.0 - nx * nx - ny * ny;
    if (s <= 0.0) {
        return NAN;
    }
    double n[3] = { nx, ny, sqrt(s) }, p[3] = { wx, wy, r * n[2] };
    double v[3] = { -p[0], -p[1], 5.0 - p[2] }, lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double ni = 0.0;
    for (int k = 0; k < 3; k++) {
        v[k] /= lv;
        ni -= n[k] * v[k];       /* N.I with I = -v */
    }
    double eta = 1.0 / ior, k2 = 1.0 - eta * eta * (1.0 - ni * ni);
    double t[3], tl = 0.0;
    for (int k = 0; k < 3; k++) {
        t[k] = -eta * v[k] - (eta * ni + sqrt(k2)) * n[k];
        tl += t[k] * t[k];
    }
    return p[0] + t[0] / sqrt(tl) * th * r;
}

/* KHR_materials_dispersion refracts each channel at its own ior, red
 * and blue half the spread (ior - 1) / V below and above green's (V =
 * 20 / dispersion): behind thick glass left of a black | white edge, the
 * middle row shows each channel's edge where its own ray's exit point
 * crosses the edge, within 1 pixel of Snell's law at that channel's
 * ior (the mesh's facets and the bilinear source), red's and blue's at
 * least 2.5 pixels apart (dispersion 8, iors 1.4, 1.5 and 1.6);
 * dispersion 0 draws the old bytes. */
SR_TEST(dispersion_separates_the_channels_by_their_iors)
{
    const double cx = -0.4, r = 1.0, th = 1.0, ior = 1.5, disp = 8.0;
    sr_pbr_material m = glass();
    m.thickness = (float)th;
    m.ior = (float)ior;
    sr_mat4 move = sr_mat4_translate((float)cx, 0, 0), size = sr_mat4_scale(1.0f, 1.0f, 1.0f);
    sr_mat4 model = sr_mat4_mul(&move, &size);
    sr_framebuffer *plain = glass_over_edge(&m, &model);
    m.dispersion = 0.0f;
    m.attenuation_color[0] = 0.7f;       /* absent without a distance */
    sr_framebuffer *zero = glass_over_edge(&m, &model);
    m.attenuation_color[0] = 1.0f;
    m.dispersion = (float)disp;
    sr_framebuffer *fb = glass_over_edge(&m, &model);
    REQUIRE(plain && zero && fb);
    save(fb, "pbr_dispersion_edge");
    CHECK(memcmp(sr_framebuffer_pixels(plain), sr_framebuffer_pixels(zero), 4 * CELL * CELL) == 0);
    double half = (ior - 1.0) / (20.0 / disp) / 2.0;
    const double iors[3] = { ior - half, ior, ior + half };
    double want[3], got[3];
    for (int c = 0; c < 3; c++) {
        /* The edge's sub-pixel position: where the exit point's x (from
         * Snell's law) and the channel's code (from the image) cross the
         * middle, between adjacent columns of the sphere's left part. */
        want[c] = got[c] = NAN;
        for (int x = 0; x + 1 < CELL; x++) {
            double a = exit_x(x, cx, r, th, iors[c]), b = exit_x(x + 1, cx, r, th, iors[c]);
            if (isnan(want[c]) && a <= 0.0 && b > 0.0) {
                want[c] = x + a / (a - b);
            }
            double ga = px(fb, x, CELL / 2)[c], gb = px(fb, x + 1, CELL / 2)[c];
            if (isnan(got[c]) && !isnan(a) && ga <= 186.0 && gb > 186.0) {
                got[c] = x + (186.0 - ga) / (gb - ga);
            }
        }
        CHECK(!isnan(want[c]) && !isnan(got[c]));
        fprintf(stderr, "channel %d: edge at %.2f, Snell %.2f\n", c, got[c], want[c]);
        CHECK_NEAR(got[c], want[c], 1.0);
    }
    /* Red bends least, blue most: their edges lie on either side of
     * green's, as far apart as the formula says. */
    CHECK(want[2] - want[0] >= 2.5);
    CHECK(got[0] < got[1] && got[1] < got[2]);
    sr_destroy_framebuffer(sr_test_ctx(), plain);
    sr_destroy_framebuffer(sr_test_ctx(), zero);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* ---- KHR_materials_diffuse_transmission --------------------------------- */

/* A square sheet of side 2 in z = 0 facing the camera (+z), drawn with m
 * into a fresh black cell under model, with a directional light along
 * `travel` (towards +z: from behind) and a uniform hemisphere of gray
 * amb, no tone curve. */
static sr_framebuffer *sheet(const sr_pbr_material *m, const sr_mat4 *model, const float travel[3],
                             float intensity, float amb)
{
    float pos[12] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    float nrm[12] = { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    float uv[8] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    sphere s = { .pos = pos, .nrm = nrm, .uv = uv, .idx = idx, .nv = 4, .ni = 6 };
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_desc d = { .material = m, .model = model, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE, .sky = { amb, amb, amb },
                      .ground = { amb, amb, amb } };
    if (travel) {
        d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL,
                                  .vector = { travel[0], travel[1], travel[2] },
                                  .intensity = intensity };
    }
    sr_framebuffer *fb = make_fb(1, 1, 0.0f);
    if (fb && draw_sphere(fb, &s, &d, 0, 0, NULL) != SR_OK) {
        sr_destroy_framebuffer(sr_test_ctx(), fb);
        fb = NULL;
    }
    return fb;
}

/* A leaf: a green dielectric letting all of its diffuse light through,
 * tinted yellow. */
static sr_pbr_material leaf(void)
{
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[0] = 0.2f, m.base_color[1] = 0.6f, m.base_color[2] = 0.1f;
    m.metallic = 0.0f;
    m.roughness = 0.5f;
    m.diffuse_transmission = 1.0f;
    m.diffuse_transmission_color[0] = 1.0f;
    m.diffuse_transmission_color[1] = 0.8f;
    m.diffuse_transmission_color[2] = 0.3f;
    return m;
}

/* The extension's BTDF, in double, at the centre pixel of the sheet for
 * a light of intensity i travelling along t (unit, t.z > 0): color / pi
 * times the irradiance i N.(-L), times 1 - F with F0 0.04 at V.H of the
 * light mirrored to the viewer's side, where it leaves the sheet. */
static double sheet_btdf(double color, const double t[3], double i)
{
    double wx = ((CELL / 2 + 0.5) / CELL * 2.0 - 1.0) * 1.1;
    double wy = (1.0 - (CELL / 2 + 0.5) / CELL * 2.0) * 1.1;
    double v[3] = { -wx, -wy, 5.0 }, lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double lm[3] = { -t[0], -t[1], t[2] }, h[3], hl = 0.0, vh = 0.0;
    for (int k = 0; k < 3; k++) {
        h[k] = lm[k] + v[k] / lv;
        hl += h[k] * h[k];
    }
    for (int k = 0; k < 3; k++) {
        vh += v[k] / lv * h[k] / sqrt(hl);
    }
    double f = 0.04 + 0.96 * pow(1.0 - vh, 5.0);
    return (1.0 - f) * color / 3.14159265358979 * i * t[2];
}

/* A sheet lit only from behind (a light 37 degrees off its axis) shows
 * the extension's Lambert BTDF in the diffuse transmission color (not
 * the base's, which is the reflected lobe's: the extension's
 * diffuse_btdf(color = diffuseTransmissionColor)) within 1.5 codes at
 * its centre; half the factor half the light; through a volume
 * (thickness 0.5, attenuation color 0.5 over 0.25) 0.5^2 of it; and a
 * factor of 0 with a color and texture set draws the material's old
 * bytes, black from behind. */
SR_TEST(backlit_sheet_shows_the_diffuse_btdf)
{
    const float travel[3] = { 0.6f, 0.0f, 0.8f };
    const double t[3] = { 0.6, 0.0, 0.8 }, intensity = 2.0;
    sr_pbr_material m = leaf();
    sr_framebuffer *fb = sheet(&m, NULL, travel, (float)intensity, 0.0f);
    REQUIRE(fb);
    save(fb, "pbr_diffuse_transmission_backlit");
    for (int c = 0; c < 3; c++) {
        double want = sheet_btdf(m.diffuse_transmission_color[c], t, intensity);
        CHECK_NEAR(px(fb, CELL / 2, CELL / 2)[c], srgb_encode(want), 1.5);
        CHECK_NEAR(px(fb, 5, 9)[c], srgb_encode(want), 2.0);     /* a directional light */
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    m.diffuse_transmission = 0.5f;
    fb = sheet(&m, NULL, travel, (float)intensity, 0.0f);
    REQUIRE(fb);
    for (int c = 0; c < 3; c++) {
        double want = sheet_btdf(m.diffuse_transmission_color[c], t, intensity) * 0.5;
        CHECK_NEAR(px(fb, CELL / 2, CELL / 2)[c], srgb_encode(want), 1.5);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    m.diffuse_transmission = 1.0f;
    m.thickness = 0.5f;
    m.attenuation_distance = 0.25f;
    m.attenuation_color[0] = m.attenuation_color[1] = m.attenuation_color[2] = 0.5f;
    fb = sheet(&m, NULL, travel, (float)intensity, 0.0f);
    REQUIRE(fb);
    for (int c = 0; c < 3; c++) {
        double want = sheet_btdf(m.diffuse_transmission_color[c], t, intensity) * 0.25;
        CHECK_NEAR(px(fb, CELL / 2, CELL / 2)[c], srgb_encode(want), 1.5);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
    /* Zero: the extension absent, from behind and from the front. */
    const uint8_t gray[4] = { 90, 160, 220, 255 };
    sr_texture *tex = solid_texture(gray, true);
    REQUIRE(tex);
    const float front[3] = { -0.3f, -0.4f, -0.866f };
    for (int k = 0; k < 2; k++) {
        sr_pbr_material old = leaf();
        old.diffuse_transmission = 0.0f;
        old.diffuse_transmission_color[0] = old.diffuse_transmission_color[1] =
            old.diffuse_transmission_color[2] = 1.0f;
        sr_pbr_material zero = leaf();
        zero.diffuse_transmission = 0.0f;
        zero.diffuse_transmission_texture.texture = tex;
        zero.diffuse_transmission_color_texture.texture = tex;
        sr_framebuffer *a = sheet(&old, NULL, k ? front : travel, 2.0f, 0.2f);
        sr_framebuffer *b = sheet(&zero, NULL, k ? front : travel, 2.0f, 0.2f);
        REQUIRE(a && b);
        CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), 4 * CELL * CELL) == 0);
        sr_destroy_framebuffer(sr_test_ctx(), a);
        sr_destroy_framebuffer(sr_test_ctx(), b);
    }
    sr_destroy_texture(sr_test_ctx(), tex);
}

/* KHR_materials_iridescence over diffuse transmission: the film's Fresnel
 * replaces the one that weighs the specular layer against the base, and
 * the BTDF is part of that base (the extensions' fresnel_mix; Khronos'
 * sample viewer mixes the BTDF into the diffuse before its Fresnel).  The
 * backlit sheet under a full film 300 nm thick of index 1.8, seen nearly
 * straight on, keeps 1 - F of the film at normal incidence
 * (tests/thin_film_reference.py's exact Airy figure, F (0.0967, 0.0430,
 * 0.1222), which the shader's series meets within 0.01), within 1.5
 * codes: 3 to 5 codes darker in red and blue than 1 - 0.04 draws. */
SR_TEST(a_thin_film_weighs_the_diffuse_btdf)
{
    const float travel[3] = { 0.6f, 0.0f, 0.8f };
    const double t[3] = { 0.6, 0.0, 0.8 }, intensity = 2.0;
    const double film[3] = { 0.0967, 0.0430, 0.1222 };
    sr_pbr_material m = leaf();
    m.iridescence = 1.0f;
    m.iridescence_ior = 1.8f;
    m.iridescence_thickness_set = true;
    m.iridescence_thickness_min = m.iridescence_thickness_max = 300.0f;
    sr_framebuffer *fb = sheet(&m, NULL, travel, (float)intensity, 0.0f);
    REQUIRE(fb);
    save(fb, "pbr_diffuse_transmission_film");
    for (int c = 0; c < 3; c++) {
        /* sheet_btdf's 1 - F is 0.96 here: the mirrored light's V.H is 0.95. */
        double plain = sheet_btdf(m.diffuse_transmission_color[c], t, intensity);
        double want = plain / 0.96 * (1.0 - film[c]);
        CHECK_NEAR(px(fb, CELL / 2, CELL / 2)[c], srgb_encode(want), 1.5);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* Under light that is the same from every side (a uniform hemisphere),
 * a sheet that lets all of its diffuse light through in color C looks
 * like an opaque one of base color C: the BTDF sees from behind the
 * irradiance the BRDF sees in front, weighted alike (the extension's
 * mix, for image-based light).  Within 1 code, tilted 60 degrees. */
SR_TEST(diffuse_transmission_sees_the_irradiance_from_behind)
{
    sr_mat4 tilt = sr_mat4_rotate(-1.0471976f, (sr_vec3){ 1, 0, 0 });
    sr_pbr_material through = leaf(), opaque_sheet = leaf();
    opaque_sheet.diffuse_transmission = 0.0f;
    memcpy(opaque_sheet.base_color, through.diffuse_transmission_color, 3 * sizeof(float));
    sr_framebuffer *a = sheet(&through, &tilt, NULL, 0.0f, 0.6f);
    sr_framebuffer *b = sheet(&opaque_sheet, &tilt, NULL, 0.0f, 0.6f);
    REQUIRE(a && b);
    CHECK(px(a, CELL / 2, CELL / 2)[0] > 100);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(px(a, CELL / 2, CELL / 2)[c], px(b, CELL / 2, CELL / 2)[c], 1.0);
    }
    sr_destroy_framebuffer(sr_test_ctx(), a);
    sr_destroy_framebuffer(sr_test_ctx(), b);
}

/* An allocator that counts the bytes asked of it. */
static void *counted_alloc(size_t size, void *user)
{
    *(size_t *)user += size;
    return malloc(size);
}
static void counted_free(void *ptr, void *user)
{
    (void)user;
    free(ptr);
}

/* The sphere drawn on a fresh framebuffer of ctx with a program made from
 * d, its bytes copied to out; *made the bytes making the program took. */
static void sphere_in(sr_context *ctx, const size_t *counter, const sphere *s,
                      const sr_pbr_desc *d, uint8_t *out, size_t *made)
{
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = CELL, .height = CELL },
                                &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    size_t before = counter ? *counter : 0;
    sr_pbr *p;
    REQUIRE(sr_make_pbr_program(ctx, d, &p) == SR_OK);
    if (made) {
        *made = *counter - before;
    }
    sr_state st = { .program = sr_pbr_program(p), .cull = SR_CULL_BACK };
    CHECK_EQ(sr_draw(ctx, fb, &st,
                     &(sr_draw_desc){ .positions = s->pos, .normals = s->nrm, .texcoords = s->uv,
                                      .vertex_count = s->nv, .indices = s->idx,
                                      .index_type = SR_INDEX_U32, .index_count = s->ni }),
             SR_OK);
    memcpy(out, sr_framebuffer_pixels(fb), 4 * CELL * CELL);
    sr_destroy_pbr_program(ctx, p);
    sr_destroy_framebuffer(ctx, fb);
}

/* Programs made with one context from one environment at one roughness
 * share the prefiltered radiance map (the second program allocates less
 * than a map) and draw the same bytes as the first; a new environment,
 * even where a destroyed one lay, gets its own map: the same bytes as in
 * a fresh context. */
SR_TEST(programs_of_one_environment_and_roughness_share_their_radiance_map)
{
    size_t counter = 0;
    sr_context *ctx, *fresh;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1,
                                                .allocator = { counted_alloc, counted_free,
                                                               &counter } },
                            &ctx) == SR_OK);
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &fresh) == SR_OK);
    sphere s = make_sphere(32, 16);
    REQUIRE(s.pos);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = { .base_color = { 0.8f, 0.5f, 0.3f, 1 }, .metallic = 0.3f,
                          .roughness = 0.6f };
    sr_pbr_desc d = lit_desc(&m, &view, &proj);
    sr_environment *env;
    REQUIRE(sr_make_environment(ctx, NULL, &env) == SR_OK);
    d.environment = env;
    static uint8_t first[4 * CELL * CELL], again[4 * CELL * CELL], other[4 * CELL * CELL];
    size_t made[3];
    const size_t map_bytes = 64 * 64 * 4 * sizeof(float);
    sphere_in(ctx, &counter, &s, &d, first, &made[0]);
    for (int k = 1; k < 3; k++) {
        sphere_in(ctx, &counter, &s, &d, again, &made[k]);
        CHECK(memcmp(first, again, sizeof first) == 0);
    }
    CHECK(made[0] >= map_bytes);
    CHECK(made[1] < map_bytes);
    CHECK(made[2] < map_bytes);
    sr_destroy_environment(ctx, env);
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .intensity = 2.0f }, &env) ==
            SR_OK);
    d.environment = env;
    sphere_in(ctx, &counter, &s, &d, again, NULL);
    CHECK(memcmp(first, again, sizeof first) != 0);
    sr_environment *env2;
    REQUIRE(sr_make_environment(fresh, &(sr_environment_desc){ .intensity = 2.0f }, &env2) ==
            SR_OK);
    d.environment = env2;
    sphere_in(fresh, NULL, &s, &d, other, NULL);
    CHECK(memcmp(other, again, sizeof other) == 0);
    sr_destroy_environment(fresh, env2);
    sr_destroy_environment(ctx, env);
    free_sphere(&s);
    sr_destroy_context(fresh);
    sr_destroy_context(ctx);
}

/* An allocator that counts the prefiltered radiance maps built (the
 * allocations of one 64 x 64 RGBA float map). */
#define MAP_BYTES ((size_t)64 * 64 * 4 * sizeof(float))
static void *map_counted_alloc(size_t size, void *user)
{
    *(size_t *)user += size == MAP_BYTES;
    return malloc(size);
}

/* The embedded profile (SR_EMBEDDED) and WebAssembly have one thread. */
#if defined(SR_EMBEDDED) || defined(__EMSCRIPTEN__)
#define MAP_THREADS 1
#else
#define MAP_THREADS 2
#endif

/* budget: sr_context_desc.radiance_cache_bytes. */
static sr_result map_counting_context(size_t budget, size_t *builds, sr_context **ctx)
{
    return sr_make_context(&(sr_context_desc){ .threads = MAP_THREADS,
                                               .allocator = { map_counted_alloc, counted_free,
                                                              builds },
                                               .radiance_cache_bytes = budget },
                           ctx);
}

/* A counting context on two threads, the default environment made with
 * it, a sphere and the test camera. */
typedef struct map_scene {
    size_t builds;
    sr_context *ctx;
    sr_environment *env;
    sphere s;
    sr_mat4 view, proj;
} map_scene;

static bool map_scene_open_within(map_scene *f, size_t budget)
{
    *f = (map_scene){ .view = test_view(), .proj = test_projection() };
    if (map_counting_context(budget, &f->builds, &f->ctx) != SR_OK) {
        return false;
    }
    f->s = make_sphere(16, 8);
    return f->s.pos && sr_make_environment(f->ctx, NULL, &f->env) == SR_OK;
}

static bool map_scene_open(map_scene *f)
{
    return map_scene_open_within(f, 0);
}

static void map_scene_close(map_scene *f)
{
    sr_destroy_environment(f->ctx, f->env);
    free_sphere(&f->s);
    sr_destroy_context(f->ctx);
}

/* A scene of 12 materials of distinct roughness drawn frame after frame
 * (a program per draw, as `softrast render` makes them) builds each map
 * once: the second frame finds all 12 (a cache of 8 maps without eviction
 * built the last 4 again every frame), and draws the same bytes. */
SR_TEST(a_scene_of_twelve_roughnesses_builds_each_radiance_map_once)
{
    map_scene f;
    REQUIRE(map_scene_open(&f));
    enum { N = 12 };
    static uint8_t first[N][4 * CELL * CELL], again[4 * CELL * CELL];
    for (int frame = 0; frame < 2; frame++) {
        for (int k = 0; k < N; k++) {
            sr_pbr_material m = { .base_color = { 0.8f, 0.5f, 0.3f, 1 }, .metallic = 0.5f,
                                  .roughness = 0.4f + 0.05f * (float)k };
            sr_pbr_desc d = lit_desc(&m, &f.view, &f.proj);
            d.environment = f.env;
            sphere_in(f.ctx, NULL, &f.s, &d, frame ? again : first[k], NULL);
            if (frame) {
                CHECK(memcmp(first[k], again, sizeof again) == 0);
            }
        }
        CHECK_EQ(f.builds, (size_t)N);
    }
    map_scene_close(&f);
}

/* An environment made anew every frame (animated): its maps go when it is
 * destroyed (they used to stay and make way), and the programs of the newest
 * environment share its map again however many came before (they used to
 * fill the cache for good, and every later program built its own). */
SR_TEST(the_radiance_maps_of_destroyed_environments_make_way)
{
    size_t builds = 0;
    sr_context *ctx;
    /* Room for 4 maps: the frames outnumber them. */
    REQUIRE(map_counting_context(4 * MAP_BYTES, &builds, &ctx) == SR_OK);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m = { .base_color = { 0.8f, 0.5f, 0.3f, 1 }, .roughness = 0.6f };
    sr_pbr_desc d = lit_desc(&m, &view, &proj);
    for (int frame = 0; frame < 8; frame++) {
        sr_environment *env;
        REQUIRE(sr_make_environment(
                    ctx, &(sr_environment_desc){ .intensity = 1.0f + 0.01f * (float)frame },
                    &env) == SR_OK);
        d.environment = env;
        size_t before = builds;
        for (int draw = 0; draw < 3; draw++) {
            sr_pbr *p;
            REQUIRE(sr_make_pbr_program(ctx, &d, &p) == SR_OK);
            sr_destroy_pbr_program(ctx, p);
        }
        CHECK_EQ(builds - before, (size_t)1);
        sr_destroy_environment(ctx, env);
    }
    sr_destroy_context(ctx);
}

/* A map a live program reads is never evicted: with as many programs of
 * distinct roughness alive as the budget holds maps (4), one more builds a
 * map of its own, and each of the first still draws what it drew when it
 * was made (AddressSanitizer sees a freed map read). */
SR_TEST(a_radiance_map_a_live_program_reads_is_not_evicted)
{
    map_scene f;
    REQUIRE(map_scene_open_within(&f, 4 * MAP_BYTES));
    enum { N = 5 };
    sr_pbr *live[N];
    sr_pbr_material m[N];
    static uint8_t drawn[4 * CELL * CELL], alone[4 * CELL * CELL];
    for (int k = 0; k < N; k++) {
        m[k] = (sr_pbr_material){ .base_color = { 0.3f, 0.5f, 0.8f, 1 }, .metallic = 0.7f,
                                  .roughness = 0.36f + 0.6f * (float)k / (float)N };
        sr_pbr_desc d = lit_desc(&m[k], &f.view, &f.proj);
        d.environment = f.env;
        REQUIRE(sr_make_pbr_program(f.ctx, &d, &live[k]) == SR_OK);
    }
    CHECK_EQ(f.builds, (size_t)N);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(f.ctx, &(sr_framebuffer_desc){ .width = CELL, .height = CELL },
                                &fb) == SR_OK);
    for (int k = 0; k < N; k += 8) {
        sr_clear(f.ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        sr_state st = { .program = sr_pbr_program(live[k]), .cull = SR_CULL_BACK };
        CHECK_EQ(sr_draw(f.ctx, fb, &st,
                         &(sr_draw_desc){ .positions = f.s.pos, .normals = f.s.nrm,
                                          .texcoords = f.s.uv, .vertex_count = f.s.nv,
                                          .indices = f.s.idx, .index_type = SR_INDEX_U32,
                                          .index_count = f.s.ni }),
                 SR_OK);
        memcpy(drawn, sr_framebuffer_pixels(fb), sizeof drawn);
        /* The same material alone in a fresh context. */
        sr_context *fresh;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &fresh) == SR_OK);
        sr_environment *fenv;
        REQUIRE(sr_make_environment(fresh, NULL, &fenv) == SR_OK);
        sr_pbr_desc d = lit_desc(&m[k], &f.view, &f.proj);
        d.environment = fenv;
        sphere_in(fresh, NULL, &f.s, &d, alone, NULL);
        CHECK(memcmp(drawn, alone, sizeof drawn) == 0);
        sr_destroy_environment(fresh, fenv);
        sr_destroy_context(fresh);
    }
    sr_destroy_framebuffer(f.ctx, fb);
    /* Once they are destroyed, their maps serve the next programs. */
    for (int k = 0; k < N; k++) {
        sr_destroy_pbr_program(f.ctx, live[k]);
    }
    size_t before = f.builds;
    for (int k = 0; k < N - 1; k++) {
        sr_pbr_desc d = lit_desc(&m[k], &f.view, &f.proj);
        d.environment = f.env;
        REQUIRE(sr_make_pbr_program(f.ctx, &d, &live[k]) == SR_OK);
        sr_destroy_pbr_program(f.ctx, live[k]);
    }
    CHECK_EQ(f.builds, before);
    map_scene_close(&f);
}

/* Programs of n roughnesses made and destroyed in turn, frame after frame
 * (a program per draw, as `softrast render` makes them), from f's
 * environment; the maps each frame built in builds[frame]. */
static void roughness_frames(map_scene *f, int n, int frames, size_t *builds)
{
    for (int frame = 0; frame < frames; frame++) {
        size_t before = f->builds;
        for (int k = 0; k < n; k++) {
            sr_pbr_material m = { .base_color = { 0.8f, 0.5f, 0.3f, 1 },
                                  .roughness = 0.4f + 0.55f * (float)k / (float)n };
            sr_pbr_desc d = lit_desc(&m, &f->view, &f->proj);
            d.environment = f->env;
            sr_pbr *p;
            REQUIRE(sr_make_pbr_program(f->ctx, &d, &p) == SR_OK);
            sr_destroy_pbr_program(f->ctx, p);
        }
        builds[frame] = f->builds - before;
    }
}

/* Scenes of n roughnesses drawn in turn, frame after frame, against a
 * budget of `fit` maps (0: the default's 256): within it, the second frame
 * builds none; past it, least-recently-used order alone would evict each
 * map just before it is asked for again and build all n every frame (as
 * it did past 256), where the cache keeps the maps it holds and builds
 * only the n - fit others from the third frame on, whose maps their
 * programs free.  The hit rate is printed. */
SR_TEST(a_scene_of_more_roughnesses_than_the_budget_holds_reuses_what_fits)
{
    static const struct {
        int n, fit;
    } cases[] = { { 100, 0 }, { 40, 16 }, { 300, 0 } };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        int n = cases[i].n, fit = cases[i].fit;
        size_t budget = fit ? (size_t)fit * MAP_BYTES : 0;
        if (!fit) {
            fit = (int)(SR_RADIANCE_CACHE_DEFAULT / MAP_BYTES);
        }
        map_scene f;
        REQUIRE(map_scene_open_within(&f, budget));
        size_t builds[3];
        roughness_frames(&f, n, 3, builds);
        fprintf(stderr, "%d roughnesses, room for %d maps: %zu, %zu, %zu built; hits %llu of "
                "%llu look-ups\n", n, fit, builds[0], builds[1], builds[2],
                (unsigned long long)f.ctx->oct.hits,
                (unsigned long long)(f.ctx->oct.hits + f.ctx->oct.misses));
        int kept = n < fit ? n : fit;
        CHECK_EQ(builds[0], (size_t)n);
        CHECK_EQ(builds[2], (size_t)(n - kept));
        CHECK_EQ(f.ctx->oct.count, kept);
        CHECK_EQ(f.ctx->oct.bytes, (size_t)kept * MAP_BYTES);
        map_scene_close(&f);
    }
}

/* The same scene of 24 roughnesses in a context whose budget holds 8 maps
 * (hits, maps turned away, maps evicted) draws, frame after frame and on
 * 1 or 2 threads, the bytes of each material drawn alone in a fresh
 * context: the cache's state changes the time, never a pixel. */
SR_TEST(a_warm_cache_draws_the_bytes_of_a_cold_one)
{
    enum { N = 24 };
    static uint8_t cold[N][4 * CELL * CELL], warm[4 * CELL * CELL];
    sphere s = make_sphere(16, 8);
    REQUIRE(s.pos);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_pbr_material m[N];
    for (int k = 0; k < N; k++) {
        m[k] = (sr_pbr_material){ .base_color = { 0.8f, 0.5f, 0.3f, 1 }, .metallic = 0.6f,
                                  .roughness = 0.36f + 0.6f * (float)k / (float)N };
        sr_context *fresh;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &fresh) == SR_OK);
        sr_environment *env;
        REQUIRE(sr_make_environment(fresh, NULL, &env) == SR_OK);
        sr_pbr_desc d = lit_desc(&m[k], &view, &proj);
        d.environment = env;
        sphere_in(fresh, NULL, &s, &d, cold[k], NULL);
        sr_destroy_environment(fresh, env);
        sr_destroy_context(fresh);
    }
    for (int threads = 1; threads <= MAP_THREADS; threads++) {
        sr_context *ctx;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads,
                                                    .radiance_cache_bytes = 8 * MAP_BYTES },
                                &ctx) == SR_OK);
        sr_environment *env;
        REQUIRE(sr_make_environment(ctx, NULL, &env) == SR_OK);
        int same = 0;
        for (int frame = 0; frame < 3; frame++) {
            for (int k = 0; k < N; k++) {
                sr_pbr_desc d = lit_desc(&m[k], &view, &proj);
                d.environment = env;
                sphere_in(ctx, NULL, &s, &d, warm, NULL);
                same += memcmp(warm, cold[k], sizeof warm) == 0;
            }
        }
        CHECK_EQ(same, 3 * N);
        CHECK(ctx->oct.hits > 0);
        CHECK_EQ(ctx->oct.count, 8);
        sr_destroy_environment(ctx, env);
        sr_destroy_context(ctx);
    }
    free_sphere(&s);
}

/* An allocator that keeps the radiance maps alive (allocated, not yet
 * freed). */
typedef struct live_maps {
    void *map[64];
    int count;
} live_maps;
static void *live_map_alloc(size_t size, void *user)
{
    live_maps *l = user;
    void *p = malloc(size);
    if (p && size == MAP_BYTES && l->count < 64) {
        l->map[l->count++] = p;
    }
    return p;
}
static void live_map_free(void *ptr, void *user)
{
    live_maps *l = user;
    for (int i = 0; i < l->count; i++) {
        if (l->map[i] == ptr) {
            l->map[i] = l->map[--l->count];
            break;
        }
    }
    free(ptr);
}

/* Destroying an environment frees its maps in the context's cache at once
 * (they used to stay until evicted), and a map a live program still reads
 * when the program is destroyed; the other environment's stay. */
SR_TEST(destroying_an_environment_frees_its_radiance_maps)
{
    live_maps live = { .count = 0 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = MAP_THREADS,
                                                .allocator = { live_map_alloc, live_map_free,
                                                               &live } },
                            &ctx) == SR_OK);
    sr_mat4 view = test_view(), proj = test_projection();
    sr_environment *a, *b;
    REQUIRE(sr_make_environment(ctx, NULL, &a) == SR_OK);
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .intensity = 2.0f }, &b) == SR_OK);
    enum { N = 5 };
    sr_pbr *kept = NULL;
    for (int k = 0; k < 2 * N; k++) {
        sr_pbr_material m = { .base_color = { 0.8f, 0.5f, 0.3f, 1 },
                              .roughness = 0.4f + 0.1f * (float)(k % N) };
        sr_pbr_desc d = lit_desc(&m, &view, &proj);
        d.environment = k < N ? a : b;
        sr_pbr *p;
        REQUIRE(sr_make_pbr_program(ctx, &d, &p) == SR_OK);
        if (k == 2 * N - 1) {
            kept = p;
        } else {
            sr_destroy_pbr_program(ctx, p);
        }
    }
    CHECK_EQ(live.count, 2 * N);
    sr_destroy_environment(ctx, a);
    CHECK_EQ(live.count, N);
    sr_destroy_environment(ctx, b);
    CHECK_EQ(live.count, 1);
    sr_destroy_pbr_program(ctx, kept);
    CHECK_EQ(live.count, 0);
    sr_destroy_context(ctx);
}

/* Programs of n roughnesses (from 0.4 in steps of 0.01) from env, each
 * made and destroyed. */
static void make_programs(sr_context *ctx, sr_environment *env, int n)
{
    sr_mat4 view = test_view(), proj = test_projection();
    for (int k = 0; k < n; k++) {
        sr_pbr_material m = { .base_color = { 0.8f, 0.5f, 0.3f, 1 },
                              .roughness = 0.4f + 0.01f * (float)k };
        sr_pbr_desc d = lit_desc(&m, &view, &proj);
        d.environment = env;
        sr_pbr *p;
        REQUIRE(sr_make_pbr_program(ctx, &d, &p) == SR_OK);
        sr_destroy_pbr_program(ctx, p);
    }
}

/* Past its budget the cache frees the maps it evicts (the allocator sees
 * no more than the budget's 4 alive), and its room for entries shrinks as
 * maps go: to none once the last goes, to its least once 40 of 43 do. */
SR_TEST(evicted_radiance_maps_are_freed_and_the_cache_shrinks)
{
    for (int part = 0; part < 2; part++) {
        live_maps live = { .count = 0 };
        sr_context *ctx;
        REQUIRE(sr_make_context(&(sr_context_desc){
                                    .threads = MAP_THREADS,
                                    .allocator = { live_map_alloc, live_map_free, &live },
                                    .radiance_cache_bytes = part ? 0 : 4 * MAP_BYTES },
                                &ctx) == SR_OK);
        sr_environment *a, *b;
        REQUIRE(sr_make_environment(ctx, NULL, &a) == SR_OK);
        REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .intensity = 2.0f }, &b) ==
                SR_OK);
        if (part == 0) {
            make_programs(ctx, a, 10);
            CHECK_EQ(live.count, 4);
            CHECK_EQ(ctx->oct.count, 4);
            CHECK_EQ(ctx->oct.bytes, 4 * MAP_BYTES);
        } else {
            make_programs(ctx, a, 40);
            CHECK_EQ(ctx->oct.count, 40);
            CHECK(ctx->oct.capacity >= 40);
            sr_destroy_environment(ctx, a);
            CHECK_EQ(live.count, 0);
            CHECK_EQ(ctx->oct.capacity, 0);
            CHECK_EQ(ctx->oct.bytes, (size_t)0);
            REQUIRE(sr_make_environment(ctx, NULL, &a) == SR_OK);
            make_programs(ctx, a, 40);
            make_programs(ctx, b, 3);
            CHECK_EQ(live.count, 43);
            sr_destroy_environment(ctx, a);
            a = NULL;
            CHECK_EQ(live.count, 3);
            CHECK_EQ(ctx->oct.capacity, SR_OCT_ROOM_MIN);
            CHECK_EQ(ctx->oct.bytes, 3 * MAP_BYTES);
        }
        sr_destroy_environment(ctx, a);
        sr_destroy_environment(ctx, b);
        sr_destroy_context(ctx);
        CHECK_EQ(live.count, 0);
    }
}
