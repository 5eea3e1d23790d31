/* test_arena.c - a context inside a fixed arena (sr_context_desc.arena):
 * it draws what a context with malloc draws - the embedded profile's
 * 320x240 teapot in 64 KiB - through a window of an indexed mesh's
 * vertices, reports its high-water mark, fails cleanly with
 * SR_OUT_OF_MEMORY when the arena runs out and reuses what it frees. */
#include "sr_test.h"
#include "softrast.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 320, H = 240, BAND = 8 };

typedef struct frame {
    const sr_mesh *pot;
    uint8_t *image;           /* the bands' pixels, assembled */
    size_t bpp;
} frame;

static sr_result draw_teapot(sr_context *ctx, sr_framebuffer *fb, const sr_band *band, void *user)
{
    (void)band;
    const frame *f = user;
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 2.2f, 6.5f }, (sr_vec3){ 0, 0.6f, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.8f, (float)W / H, 1, 20, false);
    sr_state st = { .shading = SR_SHADING_PHONG, .cull = SR_CULL_BACK,
                    .material = { .diffuse = { 0.85f, 0.5f, 0.25f }, .specular = { 0.5f, 0.5f, 0.5f } },
                    .lights = { { .type = SR_LIGHT_DIRECTIONAL, .vector = { -0.5f, -1, -0.7f } } } };
    sr_result r = sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.12f, 0.3f, 1 } });
    if (r != SR_OK) {
        return r;
    }
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){
        .positions = f->pot->positions, .normals = f->pot->normals,
        .vertex_count = f->pot->vertex_count, .indices = f->pot->indices,
        .index_type = SR_INDEX_U32, .index_count = 3 * f->pot->triangle_count,
        .view = &view, .projection = &proj });
}

static void keep_band(const sr_band *band, void *user)
{
    frame *f = user;
    for (int r = 0; r < band->rows; r++) {
        memcpy(f->image + (size_t)(band->y + r) * W * f->bpp, band->pixels + (size_t)r * band->stride,
               W * f->bpp);
    }
}

static sr_result render_depth(sr_context *ctx, frame *f, int band_rows, sr_pixel_format format,
                              sr_depth_format depth)
{
    return sr_render_bands(ctx, &(sr_bands_desc){
        .width = W, .height = H, .band_rows = band_rows, .depth_format = depth,
        .format = format, .draw = draw_teapot, .output = keep_band, .user = f });
}

static sr_result render(sr_context *ctx, frame *f, int band_rows, sr_pixel_format format)
{
    return render_depth(ctx, f, band_rows, format, SR_DEPTH_D16);
}

SR_TEST(teapot_in_bands_from_an_arena_is_the_malloc_frame)
{
    sr_context *heap = NULL, *ctx = NULL;
    sr_mesh pot = { 0 };
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &heap) == SR_OK);
    /* The mesh lives outside the arena: the budget is the working memory. */
    REQUIRE(sr_make_teapot(heap, 8, &pot) == SR_OK);
#ifdef SR_EMBEDDED
    /* The profile's budget: the whole frame's working memory in 64 KiB. */
    size_t size = 64 * 1024;
#else
    size_t size = 1024 * 1024;
#endif
    void *arena = malloc(size);
    frame want = { .pot = &pot, .image = malloc(W * H * 2), .bpp = 2 };
    frame got = { .pot = &pot, .image = malloc(W * H * 2), .bpp = 2 };
    REQUIRE(arena && want.image && got.image);
    REQUIRE(render(heap, &want, H, SR_PIXEL_RGB565) == SR_OK);
    /* Small batches of primitives: fewer set-up records at a time. */
    REQUIRE(sr_make_context(&(sr_context_desc){ .arena = arena, .arena_size = size,
                                                .batch_primitives = SR_BATCH_MIN }, &ctx) == SR_OK);
    CHECK_EQ(sr_context_threads(ctx), 1);
    CHECK_EQ(render(ctx, &got, BAND, SR_PIXEL_RGB565), SR_OK);
    CHECK(memcmp(want.image, got.image, W * H * 2) == 0);
    size_t peak = sr_context_arena_peak(ctx);
    printf("arena high-water mark, %dx%d teapot (%zu vertices) in bands of %d rows: %zu bytes\n",
           W, H, pot.vertex_count, BAND, peak);
    CHECK(peak > 0 && peak <= size);
    size_t first_peak = peak;
    /* Later frames reuse the freed memory: after the second, the mark
     * stays. */
    CHECK_EQ(render(ctx, &got, BAND, SR_PIXEL_RGB565), SR_OK);
    peak = sr_context_arena_peak(ctx);
    for (int i = 0; i < 3; i++) {
        CHECK_EQ(render(ctx, &got, BAND, SR_PIXEL_RGB565), SR_OK);
    }
    CHECK_EQ(sr_context_arena_peak(ctx), peak);
    CHECK_EQ(sr_context_arena_peak(heap), 0);
    sr_destroy_context(ctx);
    /* The band's D16 depth takes 2 bytes a pixel: the same first frame
     * with D24 (4) peaks higher by exactly the band's W x BAND x 2 bytes,
     * and draws the same pixels. */
    sr_context *ctx24 = NULL;
    frame got24 = { .pot = &pot, .image = malloc(W * H * 2), .bpp = 2 };
    REQUIRE(got24.image);
    REQUIRE(sr_make_context(&(sr_context_desc){ .arena = arena, .arena_size = size,
                                                .batch_primitives = SR_BATCH_MIN }, &ctx24) == SR_OK);
    CHECK_EQ(render_depth(ctx24, &got24, BAND, SR_PIXEL_RGB565, SR_DEPTH_D24), SR_OK);
    printf("the same frame with D24: %zu bytes\n", sr_context_arena_peak(ctx24));
    CHECK_EQ(sr_context_arena_peak(ctx24) - first_peak, (size_t)W * BAND * 2);
    CHECK(memcmp(want.image, got24.image, W * H * 2) == 0);
    sr_destroy_context(ctx24);
    free(got24.image);
    free(got.image);
    free(want.image);
    free(arena);
    sr_destroy_mesh(heap, &pot);
    sr_destroy_context(heap);
}

/* ---- the vertex window: an indexed draw from an arena equals the same
 * primitives drawn from de-indexed arrays (one vertex per use, which the
 * front end transforms as it goes, without a window). */

enum { WW = 96, WH = 72 };

/* A draw of `prim` over the teapot's vertices in the order idx[0 .. n):
 * indexed, or with the vertices copied out in that order. */
static sr_result draw_mesh(sr_context *ctx, sr_framebuffer *fb, const sr_state *st,
                           sr_primitive prim, const sr_mesh *pot, const uint32_t *idx, size_t n,
                           bool indexed, float *flat_pos, float *flat_nrm)
{
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 2.2f, 6.5f }, (sr_vec3){ 0, 0.6f, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.8f, (float)WW / WH, 1, 20, false);
    sr_draw_desc d = { .primitive = prim, .view = &view, .projection = &proj };
    if (indexed) {
        d.positions = pot->positions;
        d.normals = pot->normals;
        d.vertex_count = pot->vertex_count;
        d.indices = idx;
        d.index_type = SR_INDEX_U32;
        d.index_count = n;
    } else {
        for (size_t i = 0; i < n; i++) {
            memcpy(&flat_pos[3 * i], &pot->positions[3 * (size_t)idx[i]], 3 * sizeof(float));
            memcpy(&flat_nrm[3 * i], &pot->normals[3 * (size_t)idx[i]], 3 * sizeof(float));
        }
        d.positions = flat_pos;
        d.normals = flat_nrm;
        d.vertex_count = n;
    }
    return sr_draw(ctx, fb, st, &d);
}

/* The pixels of the scene: every primitive kind and three shading models
 * over the vertices in the order idx[0 .. n). */
static sr_result window_scene(sr_context *ctx, const sr_mesh *pot, const uint32_t *idx, size_t n,
                              bool indexed, float *flat_pos, float *flat_nrm, uint8_t *pixels)
{
    sr_framebuffer *fb = NULL;
    sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = WW, .height = WH }, &fb);
    if (r != SR_OK) {
        return r;
    }
    static const sr_primitive prims[] = { SR_PRIM_TRIANGLES, SR_PRIM_TRIANGLE_STRIP,
                                          SR_PRIM_TRIANGLE_FAN, SR_PRIM_LINES, SR_PRIM_LINE_STRIP,
                                          SR_PRIM_LINE_LOOP, SR_PRIM_POINTS };
    static const sr_shading shadings[] = { SR_SHADING_PHONG, SR_SHADING_FLAT, SR_SHADING_GOURAUD };
    for (size_t k = 0; k < sizeof prims / sizeof prims[0] && r == SR_OK; k++) {
        sr_state st = { .shading = shadings[k % 3], .provoking = k % 2 ? SR_PROVOKING_LAST : SR_PROVOKING_DEFAULT,
                        .point_size = 3, .blend = { .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                                    .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA },
                        .material = { .diffuse = { 0.85f, 0.5f, 0.25f }, .specular = { 0.5f, 0.5f, 0.5f },
                                      .opacity = 0.6f },
                        .lights = { { .type = SR_LIGHT_DIRECTIONAL, .vector = { -0.5f, -1, -0.7f } } } };
        r = sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.12f, 0.3f, 1 } });
        /* A fan of the whole list would be one shape over and over: a
         * fan of its first 300. */
        size_t count = prims[k] == SR_PRIM_TRIANGLE_FAN && n > 300 ? 300 : n;
        if (r == SR_OK) {
            r = draw_mesh(ctx, fb, &st, prims[k], pot, idx, count, indexed, flat_pos, flat_nrm);
        }
        if (r == SR_OK) {
            r = sr_read_pixels(ctx, fb, 0, 0, WW, WH, pixels + k * WW * WH * 4, WW * 4);
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    return r;
}

SR_TEST(a_vertex_window_draws_what_the_whole_mesh_draws)
{
    sr_context *heap = NULL, *ctx = NULL;
    sr_mesh pot = { 0 };
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &heap) == SR_OK);
    REQUIRE(sr_make_teapot(heap, 8, &pot) == SR_OK);
    size_t n = 3 * pot.triangle_count, size = 1024 * 1024, image = 7 * WW * WH * 4;
    uint32_t *order = malloc(n * sizeof *order), *perm = malloc(pot.vertex_count * sizeof *perm);
    float *flat_pos = malloc(n * 3 * sizeof(float)), *flat_nrm = malloc(n * 3 * sizeof(float));
    uint8_t *want = malloc(image), *got = malloc(image);
    void *arena = malloc(size);
    REQUIRE(order && perm && flat_pos && flat_nrm && want && got && arena);
    REQUIRE(sr_make_context(&(sr_context_desc){ .arena = arena, .arena_size = size,
                                                .batch_primitives = SR_BATCH_MIN }, &ctx) == SR_OK);
    /* The mesh's own order (the window slides along it), then its
     * vertices renumbered at random (nearly every primitive's vertices
     * lie too far apart for one window). */
    uint64_t seed = 12345;
    for (size_t v = 0; v < pot.vertex_count; v++) {
        perm[v] = (uint32_t)v;
    }
    for (size_t v = pot.vertex_count - 1; v > 0; v--) {
        seed = seed * 6364136223846793005u + 1442695040888963407u;
        size_t j = (size_t)(seed >> 33) % (v + 1);
        uint32_t t = perm[v];
        perm[v] = perm[j];
        perm[j] = t;
    }
    float *pos = malloc(pot.vertex_count * 3 * sizeof(float));
    float *nrm = malloc(pot.vertex_count * 3 * sizeof(float));
    REQUIRE(pos && nrm);
    sr_mesh shuffled = pot;
    shuffled.positions = pos;
    shuffled.normals = nrm;
    for (size_t v = 0; v < pot.vertex_count; v++) {
        memcpy(&pos[3 * perm[v]], &pot.positions[3 * v], 3 * sizeof(float));
        memcpy(&nrm[3 * perm[v]], &pot.normals[3 * v], 3 * sizeof(float));
    }
    for (int shuffle = 0; shuffle < 2; shuffle++) {
        const sr_mesh *m = shuffle ? &shuffled : &pot;
        for (size_t i = 0; i < n; i++) {
            order[i] = shuffle ? perm[pot.indices[i]] : pot.indices[i];
        }
        CHECK_EQ(window_scene(heap, m, order, n, false, flat_pos, flat_nrm, want), SR_OK);
        CHECK_EQ(window_scene(ctx, m, order, n, true, flat_pos, flat_nrm, got), SR_OK);
        CHECK(memcmp(want, got, image) == 0);
        /* Something was drawn in each. */
        for (size_t k = 0; k < 7; k++) {
            CHECK(memcmp(want + k * WW * WH * 4, want + k * WW * WH * 4 + 4, WW * WH * 4 - 4) != 0);
        }
    }
    sr_destroy_context(ctx);
    free(arena);
    free(pos);
    free(nrm);
    free(order);
    free(perm);
    free(flat_pos);
    free(flat_nrm);
    free(want);
    free(got);
    sr_destroy_mesh(heap, &pot);
    sr_destroy_context(heap);
}

SR_TEST(an_exhausted_arena_fails_cleanly)
{
    sr_context *heap = NULL, *ctx = NULL;
    sr_mesh pot = { 0 };
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &heap) == SR_OK);
    REQUIRE(sr_make_teapot(heap, 8, &pot) == SR_OK);
    /* Room for the draw scratch and a band of a few rows, not for a
     * whole-frame band (its color and D16 depth alone take 450 KiB). */
    enum { SIZE = 384 * 1024 };
    uint8_t *arena = malloc(SIZE);
    frame f = { .pot = &pot, .image = malloc(W * H * 4), .bpp = 4 };
    REQUIRE(arena && f.image);
    /* Too small for the context itself. */
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .arena = arena, .arena_size = 100 }, &ctx),
             SR_OUT_OF_MEMORY);
    CHECK(ctx == NULL);
    /* An unaligned start. */
    REQUIRE(sr_make_context(&(sr_context_desc){ .arena = arena + 3, .arena_size = SIZE - 3,
                                                .batch_primitives = SR_BATCH_MIN }, &ctx) == SR_OK);
    CHECK_EQ(render(ctx, &f, H, SR_PIXEL_RGBA8), SR_OUT_OF_MEMORY);
    /* What the failure freed serves the next frame. */
    CHECK_EQ(render(ctx, &f, 4, SR_PIXEL_RGBA8), SR_OK);
    sr_destroy_context(ctx);
    free(f.image);
    free(arena);
    sr_destroy_mesh(heap, &pot);
    sr_destroy_context(heap);
}

SR_TEST(an_arena_excludes_an_allocator_and_threads)
{
    static uint8_t arena[256 * 1024];
    sr_context *ctx = NULL;
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .arena = arena, .arena_size = sizeof arena,
                                                 .threads = 2 }, &ctx), SR_INVALID_ARG);
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .arena_size = sizeof arena }, &ctx),
             SR_INVALID_ARG);
    CHECK(ctx == NULL);
    REQUIRE(sr_make_context(&(sr_context_desc){ .arena = arena, .arena_size = sizeof arena,
                                                .threads = 1 }, &ctx) == SR_OK);
    CHECK(sr_context_arena_peak(ctx) <= sizeof arena);
    sr_destroy_context(ctx);
}
