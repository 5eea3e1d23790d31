/* test_arena.c - a context inside a fixed arena (sr_context_desc.arena):
 * it draws what a context with malloc draws, reports its high-water mark,
 * fails cleanly with SR_OUT_OF_MEMORY when the arena runs out and reuses
 * what it frees. */
#include "sr_test.h"
#include "softrast.h"
#include "pipeline.h"

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

static sr_result render(sr_context *ctx, frame *f, int band_rows, sr_pixel_format format)
{
    return sr_render_bands(ctx, &(sr_bands_desc){
        .width = W, .height = H, .band_rows = band_rows, .depth_format = SR_DEPTH_D16,
        .format = format, .draw = draw_teapot, .output = keep_band, .user = f });
}

SR_TEST(teapot_in_bands_from_an_arena_is_the_malloc_frame)
{
    sr_context *heap = NULL, *ctx = NULL;
    sr_mesh pot = { 0 };
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &heap) == SR_OK);
    /* The mesh lives outside the arena: the budget is the working memory. */
    REQUIRE(sr_make_teapot(heap, 8, &pot) == SR_OK);
    size_t size = 1024 * 1024;
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
#ifdef SR_EMBEDDED
    /* The profile's budget: 64 KiB besides what scales with the mesh, its
     * post-transform vertices (each with room for every varying). */
    size_t per_vertex = sizeof(sr_vertex_post) + SR_MAX_VARYINGS * sizeof(float);
    printf("besides %zu bytes per vertex: %zu bytes\n", per_vertex, peak - pot.vertex_count * per_vertex);
    CHECK(peak <= 64 * 1024 + pot.vertex_count * per_vertex);
#endif
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
    free(got.image);
    free(want.image);
    free(arena);
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
     * whole-frame band (its color and depth alone take 600 KiB); the
     * embedded profile's scratch is the smaller (SR_EMBEDDED). */
#ifdef SR_EMBEDDED
    enum { SIZE = 512 * 1024 };
#else
    enum { SIZE = 1024 * 1024 };
#endif
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
