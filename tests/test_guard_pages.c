/* test_guard_pages.c - every path that reads or writes a framebuffer's
 * rows, at every SIMD level, on framebuffers whose buffers end at an
 * unmapped page (guard_alloc.h): the 2D fills, lines and Gouraud fills,
 * 3D lines and points, blending and stencil, MSAA with its resolve, the
 * clears, sr_read_pixels and its kin, and band rendering.  Sizes are
 * narrow (1, 3, 5, 7, 9, 15, 17 and 129 pixels wide, or one row high) so
 * each vector path ends rows in a partial block.  A lane touched past
 * a buffer's end faults at once (SIGSEGV); every level's bytes must be the
 * scalar level's, so each scene's output is asserted too. */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, for guard_alloc.h */
#include "guard_alloc.h"
#include "sr_test.h"
#include "softrast.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#ifdef GUARD_ALLOC_WORKS

/* Each a multiple of 64 pixels, so every buffer (colour, D16 and D24
 * depth, stencil, any sample count) is a multiple of 64 bytes and ends
 * exactly at its guard page. */
static const int sizes[][2] = { { 1, 64 }, { 3, 64 }, { 5, 64 }, { 7, 64 }, { 9, 64 },
                                { 15, 64 }, { 17, 64 }, { 64, 1 }, { 192, 1 }, { 16, 4 },
                                { 129, 64 } };
enum { SIZES = sizeof sizes / sizeof sizes[0], MAX_PIXELS = 129 * 64 };

/* The caller's arrays handed to the library (masks, pixels, vertices),
 * each ending at a guard page too. */
static guard caller;

typedef struct scene {
    sr_depth_format depth;
    int samples;
    bool stencil;
    /* Draws on fb (w x h); returns SR_OK. */
    sr_result (*draw)(sr_context *ctx, sr_framebuffer *fb, int w, int h);
} scene;

/* A block of `size` bytes whose last byte is the last before the guard
 * page (guard_alloc rounds up to 64 bytes; the start moves up instead). */
static void *guard_tail(guard *g, size_t size, void **block)
{
    size_t body = (size + 63) & ~(size_t)63;
    *block = guard_alloc(body, g);
    return *block ? (uint8_t *)*block + (body - size) : NULL;
}

/* What a framebuffer holds, read back through buffers ending at the
 * guard page: the whole image, its last column alone (an odd stride), and
 * depth and stencil when there are any. */
typedef struct readback {
    uint8_t color[MAX_PIXELS * 4], column[MAX_PIXELS * 4];
    float depth[MAX_PIXELS];
    uint8_t stencil[MAX_PIXELS];
} readback;

static bool read_back(guard *g, sr_context *ctx, sr_framebuffer *fb, int w, int h,
                      readback *out)
{
    size_t n = (size_t)w * (size_t)h;
    void *blocks[4] = { 0 };
    uint8_t *color = guard_tail(g, n * 4, &blocks[0]);
    uint8_t *column = guard_tail(g, (size_t)h * 4, &blocks[1]);
    float *depth = guard_tail(g, n * sizeof *depth, &blocks[2]);
    uint8_t *stencil = guard_tail(g, n, &blocks[3]);
    bool ok = color && column && depth && stencil &&
              sr_read_pixels(ctx, fb, 0, 0, w, h, color, (size_t)w * 4) == SR_OK &&
              sr_read_pixels(ctx, fb, w - 1, 0, 1, h, column, 4) == SR_OK;
    memset(out, 0, sizeof *out);
    if (ok) {
        memcpy(out->color, color, n * 4);
        memcpy(out->column, column, (size_t)h * 4);
        ok = memcmp(color, sr_framebuffer_pixels(fb), n * 4) == 0;
    }
    if (ok && sr_framebuffer_depth_format(fb) != SR_DEPTH_NONE) {
        ok = sr_read_depth(ctx, fb, 0, 0, w, h, depth, (size_t)w) == SR_OK;
        memcpy(out->depth, depth, n * sizeof *depth);
    }
    if (ok && sr_framebuffer_has_stencil(fb)) {
        ok = sr_read_stencil(ctx, fb, 0, 0, w, h, stencil, (size_t)w) == SR_OK;
        memcpy(out->stencil, stencil, n);
    }
    for (int i = 0; i < 4; i++) {
        guard_free(blocks[i], g);
    }
    return ok;
}

/* Runs the scene on every size at every SIMD level, each level's bytes
 * compared with the scalar level's. */
static void check_scene(const char *name, const scene *s)
{
    static guard g;
    static readback first, got;
    int runs = 0;
    for (int si = 0; si < SIZES; si++) {
        int w = sizes[si][0], h = sizes[si][1];
        for (int level = SR_SIMD_OFF; level <= SR_SIMD_AVX512; level++) {
            sr_context *ctx = NULL;
            sr_framebuffer *fb = NULL;
            REQUIRE(guard_context(&g, level, &ctx) == SR_OK);
            REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
                .width = w, .height = h, .depth_format = s->depth, .samples = s->samples,
                .stencil = s->stencil }, &fb) == SR_OK);
            REQUIRE(sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.2f, 0.4f, 0.6f, 0.8f } })
                    == SR_OK);
            sr_result r = s->draw(ctx, fb, w, h);
            if (r != SR_OK) {
                sr_test_fail(__FILE__, __LINE__, "%s %dx%d, SIMD level %d: %s (%s)", name, w, h,
                             level, sr_result_name(r), sr_context_error(ctx));
            }
            bool read = read_back(&g, ctx, fb, w, h, level == SR_SIMD_OFF ? &first : &got);
            /* The scene drew: not every pixel is the clear color. */
            size_t drawn = 0;
            for (int i = 0; read && level == SR_SIMD_OFF && i < w * h; i++) {
                drawn += memcmp(&first.color[4 * i], (const uint8_t[]){ 51, 102, 153, 204 }, 4) != 0;
            }
            if (level == SR_SIMD_OFF && drawn == 0) {
                sr_test_fail(__FILE__, __LINE__, "%s %dx%d: nothing drawn", name, w, h);
            }
            if (!read) {
                sr_test_fail(__FILE__, __LINE__, "%s %dx%d, SIMD level %d: reading back failed",
                             name, w, h, level);
            } else if (level != SR_SIMD_OFF && memcmp(&first, &got, sizeof got) != 0) {
                sr_test_fail(__FILE__, __LINE__, "%s %dx%d, SIMD level %d: not the scalar "
                             "level's bytes", name, w, h, level);
            }
            sr_destroy_framebuffer(ctx, fb);
            sr_destroy_context(ctx);
            runs++;
        }
    }
    CHECK_EQ(g.live, 0);
    CHECK_EQ(caller.live, 0);
    CHECK_EQ(runs, SIZES * (SR_SIMD_AVX512 - SR_SIMD_OFF + 1));
}

static const sr_rgba translucent = { 0.9f, 0.3f, 0.1f, 0.55f }, opaque = { 0.1f, 0.8f, 0.3f, 1 };

/* Shapes crossing every edge of the framebuffer, so spans end at the
 * last pixel of a row and rows at the last row. */
static sr_result fills_2d(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    const sr_point2 cover[] = { { -3, -2 }, { w + 3.3, -1 }, { w + 2.7, h + 2.5 }, { -1.4, h + 3 } };
    const sr_point2 wedge[] = { { 0.3, 0.2 }, { w + 0.6, h * 0.5 }, { 0.1, h + 0.4 } };
    const sr_polygon2 all = { cover, 4, NULL, 0 }, tri = { wedge, 3, NULL, 0 };
    const sr_rgba colors[4] = { { 1, 0, 0, 1 }, { 0, 1, 0, 0.5f }, { 0, 0, 1, 0.8f }, { 1, 1, 0, 1 } };
    sr_result r = SR_OK;
    for (int aa = SR_AA_NONE; aa <= SR_AA_SUPERSAMPLE && r == SR_OK; aa++) {
        for (int linear = 0; linear < 2 && r == SR_OK; linear++) {
            sr_fill_desc d = { .antialias = (sr_antialias)aa, .samples = 3, .linear_light = linear };
            r = sr_fill_polygon(ctx, fb, &tri, translucent, &d);
            if (r == SR_OK) {
                r = sr_fill_polygon(ctx, fb, &all, linear ? translucent : opaque, &d);
            }
        }
    }
    /* A translucent fill over the opaque pixels: its rows' runs of them
     * go through the fill's table. */
    if (r == SR_OK) {
        r = sr_fill_polygon(ctx, fb, &all, translucent, &(sr_fill_desc){ .antialias = SR_AA_AREA });
    }
    for (int m = SR_GOURAUD_DIRECT; m <= SR_GOURAUD_INCREMENTAL && r == SR_OK; m++) {
        r = sr_fill_gouraud(ctx, fb, &all, colors, &(sr_gouraud_desc){
                                .method = (sr_gouraud_method)m });
    }
    if (r == SR_OK) {
        r = sr_fill_triangle_gouraud(ctx, fb, wedge, colors);
    }
    void *block = NULL;
    uint8_t *mask = guard_tail(&caller, (size_t)w * (size_t)h, &block);
    if (r == SR_OK && !mask) {
        r = SR_OUT_OF_MEMORY;
    }
    if (r == SR_OK) {
        r = sr_polygon_coverage(ctx, &tri, &(sr_fill_desc){ .antialias = SR_AA_AREA }, 0, 0, w, h,
                                mask, (size_t)w);
    }
    for (int i = 0; i < w * h && r == SR_OK; i++) {
        mask[i] = (uint8_t)(mask[i] ^ i * 37);
    }
    if (r == SR_OK) {
        r = sr_draw_coverage(ctx, fb, 0, 0, w, h, mask, (size_t)w, translucent);
    }
    guard_free(block, &caller);
    /* Midpoint ellipses, text and a stroked path over the right and
     * bottom edges, then a flood fill from the last pixel. */
    for (int filled = 0; filled < 2 && r == SR_OK; filled++) {
        r = sr_draw_ellipse(ctx, fb, w - 0.5, h - 0.5, w * 0.6, 2.5 + filled, opaque, filled);
    }
    if (r == SR_OK) {
        r = sr_draw_text(ctx, fb, w - 4, h - 5, 1, "g8", translucent);
    }
    sr_path *path = NULL;
    if (r == SR_OK) {
        r = sr_make_path(ctx, 0, &path);
    }
    if (r == SR_OK) {
        sr_path_move_to(path, -1, h - 0.3);
        sr_path_cubic_to(path, w * 0.3, -2, w * 0.8, h + 2, w + 1, 0.5);
        for (int aa = SR_AA_NONE; aa <= SR_AA_SUPERSAMPLE && r == SR_OK; aa++) {
            r = sr_stroke_path(ctx, fb, path, aa == SR_AA_AREA ? opaque : translucent,
                               &(sr_stroke_desc){ .width = 1.7, .cap = SR_STROKE_CAP_ROUND,
                                                  .antialias = (sr_antialias)aa });
        }
    }
    sr_destroy_path(ctx, path);
    if (r == SR_OK) {
        r = sr_flood_fill(ctx, fb, w - 1, h - 1, opaque,
                          &(sr_region_fill_desc){ .tolerance = 40 }, NULL);
    }
    return r;
}

/* Every line algorithm along the last row and column, across the
 * framebuffer and at a slant, opaque and translucent. */
static sr_result lines_2d(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    const sr_point2 ends[][2] = {
        { { -2, h - 0.5 }, { w + 2, h - 0.5 } },   /* the last row */
        { { w - 0.5, -2 }, { w - 0.5, h + 2 } },   /* the last column */
        { { -1, -1 }, { w + 1.5, h + 1 } },        /* the diagonal */
        { { w + 1, 0.4 }, { -0.3, h - 0.2 } },
    };
    sr_result r = SR_OK;
    for (int a = SR_LINE_DDA_NAIVE; a <= SR_LINE_WIDE && r == SR_OK; a++) {
        for (int e = 0; e < 4 && r == SR_OK; e++) {
            sr_line_desc d = { .algorithm = (sr_line_algorithm)a, .width = 2.5,
                               .cap = e & 1 ? SR_LINE_CAP_ROUND : SR_LINE_CAP_SQUARE };
            r = sr_draw_line(ctx, fb, ends[e][0], ends[e][1], e & 2 ? translucent : opaque, &d);
        }
    }
    return r;
}

/* A 3D draw in pixel coordinates (the viewport's: x right, y down). */
static sr_result draw_pixels(sr_context *ctx, sr_framebuffer *fb, const sr_state *state,
                             sr_primitive prim, const float (*xyz)[3], int count, int w, int h)
{
    float pos[64 * 3], col[64 * 4];
    for (int i = 0; i < count; i++) {
        pos[3 * i] = 2.0f * xyz[i][0] / (float)w - 1.0f;
        pos[3 * i + 1] = 1.0f - 2.0f * xyz[i][1] / (float)h;
        pos[3 * i + 2] = xyz[i][2];
        col[4 * i] = (float)(i % 3) * 0.5f;
        col[4 * i + 1] = (float)(i % 5) * 0.25f;
        col[4 * i + 2] = 1.0f - (float)(i % 2);
        col[4 * i + 3] = 0.3f + 0.1f * (float)(i % 7);
    }
    return sr_draw(ctx, fb, state, &(sr_draw_desc){ .primitive = prim, .vertex_count = (size_t)count,
                                                    .positions = pos, .colors = col });
}

/* Lines and points along the right and bottom edges and across, thin,
 * wide and smooth, square and round, blended and depth-tested. */
static sr_result lines_points_3d(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    float W = (float)w, H = (float)h;
    const float segs[][3] = { { -1, H - 0.5f, 0.2f }, { W + 1, H - 0.5f, -0.2f },
                              { W - 0.5f, -1, 0.1f }, { W - 0.5f, H + 1, 0.1f },
                              { 0.2f, 0.3f, 0.5f }, { W - 0.1f, H - 0.2f, -0.5f },
                              { W + 0.5f, 0.5f, 0 }, { 0.5f, H + 0.5f, 0 } };
    const float dots[][3] = { { W - 0.5f, H - 0.5f, 0 }, { W - 1.2f, 0.5f, 0.3f },
                              { 0.5f, H - 0.7f, -0.3f }, { W * 0.5f, H * 0.5f, 0 },
                              { W, H, 0.6f } };
    sr_result r = SR_OK;
    for (int v = 0; v < 8 && r == SR_OK; v++) {
        sr_state s = { .line_width = (float)(1 + (v & 3) * 2), .point_size = (float)(1 + v),
                       .round_points = v & 1, .smooth_lines = v & 4, .smooth_points = v & 2,
                       .blend = { .enabled = v & 1, .src_rgb = SR_BLEND_SRC_ALPHA,
                                  .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA } };
        r = draw_pixels(ctx, fb, &s, SR_PRIM_LINES, segs, 8, w, h);
        if (r == SR_OK) {
            r = draw_pixels(ctx, fb, &s, SR_PRIM_POINTS, dots, 5, w, h);
        }
    }
    return r;
}

/* Triangles covering the whole framebuffer in overlapping layers:
 * depth-tested, blended (a different equation per layer) and stencilled
 * when the framebuffer has a stencil buffer. */
static sr_result layers_3d(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    float W = (float)w, H = (float)h;
    const sr_blend_factor factors[] = { SR_BLEND_SRC_ALPHA, SR_BLEND_ONE_MINUS_DST_COLOR,
                                        SR_BLEND_CONSTANT_COLOR, SR_BLEND_SRC_ALPHA_SATURATE };
    sr_result r = SR_OK;
    for (int layer = 0; layer < 4 && r == SR_OK; layer++) {
        float z = 0.6f - 0.3f * (float)layer, dx = 0.37f * (float)layer;
        const float tri[][3] = { { -1 + dx, -1, z }, { W + 1, -0.5f, -z }, { 0.2f, H + 1 - dx, z },
                                 { W + 0.7f, H + 0.4f, z }, { W - 0.3f - dx, 0.4f, -z },
                                 { 0.6f + dx, H - 0.2f, z } };
        sr_stencil_face face = { .func = layer & 1 ? SR_EQUAL : SR_ALWAYS, .ref = 1,
                                 .fail = SR_STENCIL_INCR, .depth_fail = SR_STENCIL_INVERT,
                                 .pass = layer == 2 ? SR_STENCIL_DECR_WRAP : SR_STENCIL_INCR_WRAP };
        sr_state s = { .cull = SR_CULL_NONE,
                       .blend = { .enabled = layer > 0, .src_rgb = factors[layer],
                                  .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA,
                                  .op_rgb = (sr_blend_op)(SR_BLEND_ADD + layer),
                                  .constant = { 0.25f, 0.5f, 0.75f, 0.5f } },
                       .depth_func = layer == 3 ? SR_GREATER : SR_LESS,
                       .stencil = { .enabled = sr_framebuffer_has_stencil(fb), .front = face } };
        r = draw_pixels(ctx, fb, &s, SR_PRIM_TRIANGLES, tri, 6, w, h);
    }
    return r;
}

/* Triangles of cells `cell` pixels wide over the framebuffer (the whole
 * of a small one), in one draw: two a cell, at alternating depths, so the walks for tiny, small
 * and larger triangles (and their 32-bit and double edge lanes) all end
 * rows at the buffer's last pixel.  Variant 0 blends unlit colors, 1
 * lights per pixel, 2 samples a texture of odd size. */
static sr_result grid_3d(sr_context *ctx, sr_framebuffer *fb, int w, int h, float cell,
                         int variant)
{
    enum { MAX_VERTS = 6 * 256 };
    static float pos[MAX_VERTS * 3], nrm[MAX_VERTS * 3], col[MAX_VERTS * 4], uv[MAX_VERTS * 2];
    static const uint8_t texels[3 * 5 * 4] = { 255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 255,
                                               9, 80, 200, 30, 250, 250, 0, 255, 70, 7, 99, 255 };
    size_t n = 0;
    /* From the bottom-right corner (cells crossing the last row and
     * column) up and left, as far as MAX_VERTS reaches. */
    for (float y = (float)h + 0.4f - cell; y > -cell && n + 6 <= MAX_VERTS; y -= cell) {
        for (float x = (float)w + 0.3f - cell; x > -cell && n + 6 <= MAX_VERTS; x -= cell) {
            const float corner[6][2] = { { x, y }, { x + cell, y }, { x, y + cell },
                                         { x + cell, y }, { x + cell, y + cell }, { x, y + cell } };
            float z = ((int)(x / cell) + (int)(y / cell)) & 1 ? -0.4f : 0.3f;
            for (int i = 0; i < 6; i++, n++) {
                pos[3 * n] = 2.0f * corner[i][0] / (float)w - 1.0f;
                pos[3 * n + 1] = 1.0f - 2.0f * corner[i][1] / (float)h;
                pos[3 * n + 2] = z + 0.01f * (float)i;
                nrm[3 * n] = 0.3f * (float)(i % 3) - 0.3f;
                nrm[3 * n + 1] = 0.2f * (float)(n % 4);
                nrm[3 * n + 2] = 1;
                for (int c = 0; c < 4; c++) {
                    col[4 * n + c] = (float)((n * 7 + (size_t)c * 3) % 11) / 10.0f;
                }
                uv[2 * n] = corner[i][0] / 3.7f;
                uv[2 * n + 1] = corner[i][1] / 2.9f;
            }
        }
    }
    sr_texture *tex = NULL;
    sr_result r = variant == 2 ? sr_make_texture(ctx, &(sr_texture_desc){
                                     .width = 3, .height = 5, .pixels = texels }, &tex)
                               : SR_OK;
    sr_state s = { .cull = SR_CULL_NONE, .texture = tex,
                   .shading = variant == 1 ? SR_SHADING_PHONG : SR_SHADING_UNLIT,
                   .lights = { { .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.3f, 0.5f, 1 } } },
                   .material = { .specular = { 0.5f, 0.5f, 0.5f } },
                   .blend = { .enabled = variant == 0, .src_rgb = SR_BLEND_SRC_ALPHA,
                              .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA } };
    if (r == SR_OK) {
        r = sr_draw(ctx, fb, &s, &(sr_draw_desc){ .vertex_count = n, .positions = pos,
                                                  .normals = nrm, .colors = col,
                                                  .texcoords = uv });
    }
    sr_destroy_texture(ctx, tex);
    return r;
}

/* The grids through each rasterizer, polygon mode, a color mask, a
 * scissor and viewport ending one pixel inside the right and bottom
 * edges, alpha to coverage, polygon offset and the painter's algorithm. */
static sr_result raster_options(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    sr_result r = SR_OK;
    for (int v = 0; v < 6 && r == SR_OK; v++) {
        sr_state s = { .cull = SR_CULL_NONE,
                       .rasterizer = (sr_rasterizer)(SR_RASTER_HALFSPACE + v % 3),
                       .polygon_mode_front = (sr_polygon_mode)(SR_POLYGON_FILL + v % 3),
                       .polygon_mode_back = (sr_polygon_mode)(SR_POLYGON_FILL + (v + 1) % 3),
                       .color_mask = v == 1 ? SR_COLOR_MASK_R | SR_COLOR_MASK_A : 0,
                       .scissor = { .enabled = v & 1, .x = w > 1, .y = h > 1,
                                    .width = w - 1 > 0 ? w - 1 : 1, .height = h - 1 > 0 ? h - 1 : 1 },
                       .viewport = { .x = v == 4, .width = v == 4 ? w : 0, .height = v == 4 ? h : 0 },
                       .alpha_to_coverage = v == 2, .offset = { .factor = v == 3 ? 1.0f : 0.0f,
                                                              .units = v == 3 ? 2.0f : 0.0f },
                       .visibility = v == 5 ? SR_VISIBILITY_PAINTER : SR_VISIBILITY_Z_BUFFER };
        float W = (float)w, H = (float)h;
        for (float cell = 1.5f; cell < 8 && r == SR_OK; cell *= 2.3f) {
            float tri[3 * 3 * 8];
            int n = 0;
            for (int i = 0; i < 8; i++, n += 3) {
                float x = W - cell * (float)(i % 4) - 0.3f, y = H - cell * (float)(i / 4) - 0.6f;
                const float t[3][3] = { { x - cell, y - cell, 0.1f * (float)i - 0.4f },
                                        { x + 0.8f, y - 0.5f * cell, 0.3f },
                                        { x - 0.2f * cell, y + 0.9f, -0.3f } };
                memcpy(&tri[3 * n], t, sizeof t);
            }
            r = draw_pixels(ctx, fb, &s, SR_PRIM_TRIANGLES, (const float (*)[3])tri, n, w, h);
        }
    }
    return r;
}

/* The layers, then grids of tiny, small and larger triangles. */
static sr_result triangles_3d(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    sr_result r = layers_3d(ctx, fb, w, h);
    /* Tiny triangles in each variant, small ones lit, larger textured. */
    const float cells[] = { 1.5f, 1.5f, 1.5f, 3.0f, 7.0f };
    const int variants[] = { 0, 1, 2, 1, 2 };
    for (int i = 0; i < 5 && r == SR_OK; i++) {
        r = grid_3d(ctx, fb, w, h, cells[i], variants[i]);
    }
    return r;
}

/* Vertex arrays and indices each ending at the guard page (the caller's
 * memory: no stage may read a vertex or an index past the count), for
 * counts that leave partial groups of 4, 8 and 16, drawn as triangles,
 * lines and points, lit per vertex (the AVX-512 vertex stage) and per
 * pixel, with 3 and 4 floats a position and each index type. */
static sr_result vertex_arrays(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    (void)w;
    (void)h;
    static const int counts[] = { 1, 2, 3, 6, 9, 15, 16, 17, 33, 48, 50 };
    sr_result r = SR_OK;
    for (size_t ci = 0; ci < sizeof counts / sizeof counts[0] && r == SR_OK; ci++) {
        int n = counts[ci];
        void *blocks[7] = { 0 };
        float *pos = guard_tail(&caller, (size_t)n * 4 * sizeof(float), &blocks[0]);
        float *nrm = guard_tail(&caller, (size_t)n * 3 * sizeof(float), &blocks[1]);
        float *col = guard_tail(&caller, (size_t)n * 3 * sizeof(float), &blocks[2]);
        float *uv = guard_tail(&caller, (size_t)n * 2 * sizeof(float), &blocks[3]);
        uint8_t *i8 = guard_tail(&caller, (size_t)n, &blocks[4]);
        uint16_t *i16 = guard_tail(&caller, (size_t)n * 2, &blocks[5]);
        uint32_t *i32 = guard_tail(&caller, (size_t)n * 4, &blocks[6]);
        if (!pos || !nrm || !col || !uv || !i8 || !i16 || !i32) {
            r = SR_OUT_OF_MEMORY;
        }
        for (int i = 0; i < n && r == SR_OK; i++) {
            float a = (float)i * 2.4f;
            pos[4 * i] = 1.1f * sinf(a) * (float)(i % 3) * 0.5f;
            pos[4 * i + 1] = 1.1f * cosf(a) * (float)((i + 1) % 3) * 0.5f;
            pos[4 * i + 2] = 0.1f * (float)(i % 5) - 0.2f;
            pos[4 * i + 3] = 1.0f + 0.05f * (float)(i % 4);
            nrm[3 * i] = 0.2f * (float)(i % 3);
            nrm[3 * i + 1] = 0.1f * (float)(i % 7);
            nrm[3 * i + 2] = 1;
            col[3 * i] = (float)(i % 2);
            col[3 * i + 1] = (float)(i % 5) / 4.0f;
            col[3 * i + 2] = (float)(i % 3) / 2.0f;
            uv[2 * i] = (float)i * 0.3f;
            uv[2 * i + 1] = (float)(i % 4) * 0.25f;
            i8[i] = (uint8_t)(n - 1 - i);
            i16[i] = (uint16_t)((i * 5) % n);
            i32[i] = (uint32_t)((i * 7 + 1) % n);
        }
        const void *indices[] = { NULL, i8, i16, i32 };
        for (int prim = SR_PRIM_TRIANGLES; prim <= SR_PRIM_POINTS && r == SR_OK; prim++) {
            for (int it = SR_INDEX_NONE; it <= SR_INDEX_U32 && r == SR_OK; it++) {
                sr_state s = { .cull = SR_CULL_NONE,
                               .shading = it & 2 ? SR_SHADING_PHONG : SR_SHADING_GOURAUD,
                               .lights = { { .type = SR_LIGHT_DIRECTIONAL,
                                             .vector = { 0.2f, -0.4f, -1 } } },
                               .point_size = 2 };
                r = sr_draw(ctx, fb, &s, &(sr_draw_desc){
                    .primitive = (sr_primitive)prim, .vertex_count = (size_t)n,
                    .positions = pos, .position_size = 3 + (it & 1),
                    .position_stride = it & 1 ? 0 : 4 * sizeof(float), .normals = nrm,
                    .colors = col, .color_size = 3, .texcoords = uv, .indices = indices[it],
                    .index_type = (sr_index_type)it, .index_count = it ? (size_t)n : 0 });
            }
        }
        for (int i = 0; i < 7; i++) {
            guard_free(blocks[i], &caller);
        }
    }
    return r;
}

/* The triangles, then a clear of colour alone and pixels written over
 * the last column and row, then the layers again on the kept depth. */
static sr_result clears_and_writes(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    void *block = NULL;
    uint8_t *rgba = guard_tail(&caller, (size_t)w * 4, &block);
    if (!rgba) {
        return SR_OUT_OF_MEMORY;
    }
    for (int i = 0; i < w * 4; i++) {
        rgba[i] = (uint8_t)(i * 13 + 7);
    }
    sr_result r = triangles_3d(ctx, fb, w, h);
    if (r == SR_OK) {
        r = sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 1, 0.5f, 0, 1 },
                                                .depth_action = SR_ACTION_KEEP,
                                                .stencil_action = SR_ACTION_KEEP });
    }
    if (r == SR_OK) {   /* the last column, from a buffer of w pixels */
        r = sr_write_pixels(ctx, fb, w - 1, h - (w < h ? w : h), 1, w < h ? w : h,
                            rgba, 4);
    }
    if (r == SR_OK) {
        r = sr_write_pixels(ctx, fb, 0, h - 1, w, 1, rgba, (size_t)w * 4);
    }
    guard_free(block, &caller);
    return r == SR_OK ? layers_3d(ctx, fb, w, h) : r;
}

/* The triangles, then sr_resolve into a single-sampled framebuffer whose
 * pixels are written back over the source's last row (so the resolve's
 * bytes are read back with the rest). */
static sr_result resolved(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    sr_framebuffer *dst = NULL;
    sr_result r = triangles_3d(ctx, fb, w, h);
    if (r == SR_OK) {
        r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                             .depth_format = SR_DEPTH_NONE }, &dst);
    }
    if (r == SR_OK) {
        r = sr_resolve(ctx, fb, dst);
    }
    if (r == SR_OK) {
        const uint8_t *px = sr_framebuffer_pixels(dst);
        r = sr_write_pixels(ctx, fb, 0, h - 1, w, 1, px + (size_t)(h - 1) * (size_t)w * 4,
                            (size_t)w * 4);
    }
    sr_destroy_framebuffer(ctx, dst);
    return r;
}

/* The frame's bands, in each pixel format: the layers and a grid drawn in
 * bands (a band framebuffer of a few rows, on the context's allocator),
 * each band's bytes copied into the frame, which is then written over fb. */
typedef struct band_frame {
    uint8_t bytes[MAX_PIXELS * 4];
    int w, h;
} band_frame;

static sr_result draw_band(sr_context *ctx, sr_framebuffer *fb, const sr_band *band, void *user)
{
    /* The grid only in bands of more than one row: each band draws the
     * whole frame's geometry, and 64 one-row bands of it were slow. */
    band_frame *f = user;
    sr_result r = layers_3d(ctx, fb, f->w, f->h);
    return r == SR_OK && band->rows > 1 ? grid_3d(ctx, fb, f->w, f->h, 3.0f, 1) : r;
}

static void take_band(const sr_band *band, void *user)
{
    band_frame *f = user;
    size_t row = (size_t)band->width * 4;
    for (int r = 0; r < band->rows; r++) {
        /* The small formats' bytes land at the start of each RGBA8 row. */
        memcpy(f->bytes + (size_t)(band->y + r) * row, band->pixels + (size_t)r * band->stride,
               band->stride < row ? band->stride : row);
    }
}

static sr_result bands(sr_context *ctx, sr_framebuffer *fb, int w, int h)
{
    static band_frame f;
    sr_result r = SR_OK;
    for (int format = SR_PIXEL_RGBA8; format <= SR_PIXEL_RGB332 && r == SR_OK; format++) {
        /* The fewest rows that make a band of a multiple of 64 pixels
         * (which then ends at its guard page), and one row in RGBA8. */
        int aligned = 1;
        while (aligned < h && w * aligned % 64 != 0) {
            aligned++;
        }
        int rows = format == SR_PIXEL_RGBA8 ? 1 : aligned;
        for (; rows <= aligned && r == SR_OK; rows = rows == aligned ? rows + 1 : aligned) {
            memset(f.bytes, 0, sizeof f.bytes);
            f.w = w;
            f.h = h;
            r = sr_render_bands(ctx, &(sr_bands_desc){
                .width = w, .height = h, .band_rows = rows, .depth_format = SR_DEPTH_D16,
                .samples = sr_framebuffer_samples(fb), .stencil = true,
                .format = (sr_pixel_format)format, .draw = draw_band, .output = take_band,
                .user = &f });
            if (r == SR_OK) {
                r = sr_write_pixels(ctx, fb, 0, 0, w, h, f.bytes, (size_t)w * 4);
            }
            if (r == SR_OK && format != SR_PIXEL_RGB332) {
                r = layers_3d(ctx, fb, w, h);   /* each format's frame seen blended */
            }
        }
    }
    return r;
}

SR_TEST(fills_2d_stay_inside_the_buffer)
{
    check_scene("fills", &(scene){ SR_DEPTH_NONE, 1, false, fills_2d });
}

SR_TEST(lines_2d_stay_inside_the_buffer)
{
    check_scene("lines", &(scene){ SR_DEPTH_NONE, 1, false, lines_2d });
}

SR_TEST(lines_and_points_3d_stay_inside_the_buffer)
{
    for (int samples = 1; samples <= 16; samples *= 4) {
        check_scene("3D lines and points", &(scene){ SR_DEPTH_D16, samples, false,
                                                     lines_points_3d });
    }
}

SR_TEST(blending_and_stencil_stay_inside_the_buffer)
{
    /* Single-sampled without a stencil test, the vector walks (the tiny
     * triangles' among them) draw; either sends a draw down the
     * per-sample path. */
    check_scene("blend, D16", &(scene){ SR_DEPTH_D16, 1, false, triangles_3d });
    check_scene("blend, D24, stencil, 4 samples", &(scene){ SR_DEPTH_D24, 4, true, triangles_3d });
    check_scene("blend, D32F, stencil", &(scene){ SR_DEPTH_D32F, 1, true, triangles_3d });
}

SR_TEST(msaa_and_its_resolve_stay_inside_the_buffer)
{
    check_scene("MSAA 4x", &(scene){ SR_DEPTH_D16, 4, false, resolved });
    check_scene("MSAA 16x", &(scene){ SR_DEPTH_D16, 16, true, resolved });
}

SR_TEST(clears_and_pixel_writes_stay_inside_the_buffer)
{
    check_scene("clears", &(scene){ SR_DEPTH_D24, 1, false, clears_and_writes });
    check_scene("clears, 16 samples", &(scene){ SR_DEPTH_D24, 16, true, clears_and_writes });
}

SR_TEST(raster_options_stay_inside_the_buffer)
{
    for (int samples = 1; samples <= 16; samples *= 4) {
        check_scene("raster options", &(scene){ SR_DEPTH_D32, samples, samples == 4,
                                                raster_options });
    }
}

SR_TEST(bands_stay_inside_the_buffer)
{
    for (int samples = 1; samples <= 4; samples *= 4) {
        check_scene("bands", &(scene){ SR_DEPTH_NONE, samples, false, bands });
    }
}

SR_TEST(vertex_arrays_are_read_only_up_to_their_count)
{
    check_scene("vertex arrays", &(scene){ SR_DEPTH_D16, 1, false, vertex_arrays });
}

#else

SR_TEST(guard_pages_need_mmap)
{
    SKIP("no mmap here to put a guard page after a buffer");
}

#endif
