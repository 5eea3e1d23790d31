/* test_draw_alloc.c - a draw whose allocations are refused, one at a time,
 * on two threads: it returns SR_OUT_OF_MEMORY with a message or, where a
 * store is only an optimization (the copy of a scattered chunk in tile
 * order, parallel/bin.c), goes on without it and draws the same bytes.
 * Either way nothing leaks and the context's next draw is exact. */
#include "sr_test.h"
#include "softrast.h"
#include "raster/fixed.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* failing_alloc.h's allocator, safe for the front-end workers that grow
 * their chunks' stores while the caller does too. */
typedef struct failing_mt {
    atomic_long count;   /* allocations so far */
    atomic_long fail_at; /* this one fails; -1: none */
    atomic_long live;    /* blocks not yet freed */
    atomic_long failed;  /* allocations refused */
} failing_mt;

static void *mt_alloc(size_t size, void *user)
{
    failing_mt *f = user;
    if (atomic_fetch_add(&f->count, 1) == atomic_load(&f->fail_at)) {
        atomic_fetch_add(&f->failed, 1);
        return NULL;
    }
    void *p = malloc(size);
    if (p) {
        atomic_fetch_add(&f->live, 1);
    }
    return p;
}

static void mt_free(void *ptr, void *user)
{
    failing_mt *f = user;
    if (ptr) {
        atomic_fetch_sub(&f->live, 1);
        free(ptr);
    }
}

/* 10 x 6 tiles: two random primitives in a row mostly start over a tile
 * apart, which makes a chunk scattered (parallel/bin.c). */
enum { W = 10 * SR_TILE_SIZE, H = 6 * SR_TILE_SIZE, N = 6000 };

/* Tiny triangles all over the image, in random order and depth: their
 * chunks are scattered and mostly in one tile, so two threads copy them
 * in tile order. */
static void tiny_triangles(float *pos, float *col)
{
    uint64_t s = 0x5eed;
    for (int i = 0; i < 9 * N + 12 * N; i++) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        float u = (float)(s >> 40) / (float)(1 << 24);
        if (i < 9 * N) {
            int v = i / 3 % 3, axis = i % 3;
            float *corner = &pos[(i / 9) * 9 + axis];
            pos[i] = axis == 2 ? u * 1.8f - 0.9f
                     : v == 0  ? u * 2.0f - 1.0f
                               : *corner + (u - 0.5f) * 16.0f / (axis == 0 ? W : H);
        } else {
            col[i - 9 * N] = u;
        }
    }
}

static sr_result draw(sr_context *ctx, sr_framebuffer *fb, const float *pos, const float *col)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
    return sr_draw(ctx, fb, &(sr_state){ .shading = SR_SHADING_UNLIT, .depth_func = SR_LESS },
                   &(sr_draw_desc){ .positions = pos, .vertex_count = 3 * N, .colors = col });
}

SR_TEST(a_refused_allocation_in_a_draw_fails_cleanly_or_draws_the_same_bytes)
{
    float *pos = malloc(sizeof(float) * 9 * N), *col = malloc(sizeof(float) * 12 * N);
    uint8_t *want = malloc(W * H * 4);
    REQUIRE(pos && col && want);
    tiny_triangles(pos, col);
    {
        sr_context *ctx;
        sr_framebuffer *fb;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H },
                                    &fb) == SR_OK);
        REQUIRE(draw(ctx, fb, pos, col) == SR_OK);
        memcpy(want, sr_framebuffer_pixels(fb), W * H * 4);
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
    }
    int refused_ok = 0, refused_oom = 0;
    for (long k = 0; k < 1000; k++) {
        failing_mt f;
        atomic_init(&f.count, 0);
        atomic_init(&f.fail_at, -1);
        atomic_init(&f.live, 0);
        atomic_init(&f.failed, 0);
        sr_context *ctx;
        sr_framebuffer *fb;
        REQUIRE(sr_make_context(&(sr_context_desc){ .allocator = { mt_alloc, mt_free, &f },
                                                    .threads = 2 },
                                &ctx) == SR_OK);
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H },
                                    &fb) == SR_OK);
        atomic_store(&f.count, 0);
        atomic_store(&f.fail_at, k); /* the k-th allocation of the draw */
        sr_result r = draw(ctx, fb, pos, col);
        atomic_store(&f.fail_at, -1);
        bool refused = atomic_load(&f.failed) > 0;
        if (r == SR_OK) {
            CHECK(memcmp(want, sr_framebuffer_pixels(fb), W * H * 4) == 0);
            refused_ok += refused;
        } else {
            CHECK_EQ(r, SR_OUT_OF_MEMORY);
            CHECK(refused);
            CHECK_STR_CONTAINS(sr_context_error(ctx), "out of memory");
            refused_oom++;
        }
        /* The context draws exactly again. */
        CHECK_EQ(draw(ctx, fb, pos, col), SR_OK);
        CHECK(memcmp(want, sr_framebuffer_pixels(fb), W * H * 4) == 0);
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
        CHECK_EQ(atomic_load(&f.live), 0);
        if (!refused) {
            break; /* every allocation of the draw has been refused in turn */
        }
    }
    /* Some refusals end the draw, and the tile-order copies' only make it
     * go without them. */
    CHECK(refused_oom > 0);
    CHECK(refused_ok > 0);
    printf("  refused allocations: %d gave out of memory, %d drew the same bytes\n", refused_oom,
           refused_ok);
    free(pos);
    free(col);
    free(want);
}
