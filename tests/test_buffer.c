/* test_buffer.c - vertex buffers (sr_make_buffer): the copy is exact and
 * independent of the source, its arguments are validated, a failed
 * allocation leaks nothing, and drawing from buffers writes the same bytes
 * as drawing from the application's own arrays - with a buffer large
 * enough (over 4 MiB) to take the default allocator's huge-page path. */
#include "failing_alloc.h"
#include "sr_test.h"
#include "softrast.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

SR_TEST(a_buffer_is_an_exact_copy_that_its_source_no_longer_touches)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    uint8_t src[1000];
    for (int i = 0; i < 1000; i++) {
        src[i] = (uint8_t)(i * 37 + 11);
    }
    sr_buffer *b = NULL;
    REQUIRE(sr_make_buffer(ctx, src, sizeof src, &b) == SR_OK);
    CHECK_EQ(sr_buffer_size(b), sizeof src);
    uint8_t *data = sr_buffer_data(b);
    REQUIRE(data);
    CHECK(memcmp(data, src, sizeof src) == 0);
    CHECK_EQ((uintptr_t)data % 64, 0);   /* the default allocator's alignment */
    src[5] ^= 0xff;
    CHECK_EQ(data[5], (uint8_t)(5 * 37 + 11));
    sr_destroy_buffer(ctx, b);

    /* No source: zeroes. */
    REQUIRE(sr_make_buffer(ctx, NULL, 4096, &b) == SR_OK);
    data = sr_buffer_data(b);
    bool zero = true;
    for (int i = 0; i < 4096; i++) {
        zero &= data[i] == 0;
    }
    CHECK(zero);
    sr_destroy_buffer(ctx, b);

    /* NULL buffers answer as empty; destroying one is a no-op. */
    CHECK(sr_buffer_data(NULL) == NULL);
    CHECK_EQ(sr_buffer_size(NULL), 0);
    sr_destroy_buffer(ctx, NULL);
    sr_destroy_context(ctx);
}

SR_TEST(an_update_writes_its_range_and_nothing_else)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    uint8_t src[64], patch[10];
    for (int i = 0; i < 64; i++) {
        src[i] = (uint8_t)i;
    }
    memset(patch, 0xee, sizeof patch);
    sr_buffer *b = NULL;
    REQUIRE(sr_make_buffer(ctx, src, sizeof src, &b) == SR_OK);
    CHECK_EQ(sr_buffer_update(ctx, b, 50, patch, 10), SR_OK);
    const uint8_t *d = sr_buffer_data(b);
    for (int i = 0; i < 64; i++) {
        CHECK_EQ(d[i], i >= 50 && i < 60 ? 0xee : i);
    }
    /* The range must lie inside the buffer; nothing is written otherwise. */
    CHECK_EQ(sr_buffer_update(ctx, b, 55, patch, 10), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "run past the buffer's 64");
    CHECK_EQ(sr_buffer_update(ctx, b, 65, patch, 0), SR_INVALID_ARG);
    CHECK_EQ(sr_buffer_update(ctx, b, (size_t)-1, patch, 2), SR_INVALID_ARG);
    CHECK_EQ(d[60], 60);
    CHECK_EQ(sr_buffer_update(ctx, b, 0, NULL, 4), SR_INVALID_ARG);
    CHECK_EQ(sr_buffer_update(ctx, NULL, 0, patch, 4), SR_INVALID_ARG);
    CHECK_EQ(sr_buffer_update(NULL, b, 0, patch, 4), SR_INVALID_ARG);
    CHECK_EQ(sr_buffer_update(ctx, b, 64, NULL, 0), SR_OK);   /* an empty range at the end */
    CHECK_EQ(d[0], 0);
    /* The source may lie in the buffer: bytes move as memmove moves them. */
    CHECK_EQ(sr_buffer_update(ctx, b, 4, d, 32), SR_OK);
    for (int i = 0; i < 36; i++) {
        CHECK_EQ(d[i], i < 4 ? i : i - 4);
    }
    CHECK_EQ(sr_buffer_update(ctx, b, 0, d + 8, 16), SR_OK);
    for (int i = 0; i < 16; i++) {
        CHECK_EQ(d[i], i + 4);
    }
    sr_destroy_buffer(ctx, b);
    sr_destroy_context(ctx);
}

SR_TEST(buffer_arguments_are_validated)
{
    uint8_t src[16] = { 0 };
    sr_buffer *b = (sr_buffer *)src;   /* must come back NULL on failure */
    CHECK_EQ(sr_make_buffer(NULL, src, sizeof src, &b), SR_INVALID_ARG);
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    CHECK_EQ(sr_make_buffer(ctx, src, sizeof src, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "out is NULL");
    CHECK_EQ(sr_make_buffer(ctx, src, 0, &b), SR_INVALID_ARG);
    CHECK(b == NULL);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "bytes is 0");
    sr_destroy_context(ctx);

    /* Over the limit (SIZE_MAX included): refused before any allocation.
     * Where size_t has 32 bits the limit is SIZE_MAX and no size is over. */
    failing f = { 0, -1, 0, 0 };
    REQUIRE(sr_make_context(&(sr_context_desc){ .allocator = { fail_alloc, fail_free, &f },
                                                .threads = 1 },
                            &ctx) == SR_OK);
    long before = f.count;
    size_t huge[] = { SR_BUFFER_MAX + 1, SIZE_MAX };
    for (int i = 0; i < 2 && SR_BUFFER_MAX < SIZE_MAX; i++) {
        b = (sr_buffer *)src;
        CHECK_EQ(sr_make_buffer(ctx, NULL, huge[i], &b), SR_TOO_LARGE);
        CHECK(b == NULL);
        CHECK_STR_CONTAINS(sr_context_error(ctx), "exceeds the limit");
    }
    CHECK_EQ(f.count, before);
    /* A success clears the last error. */
    REQUIRE(sr_make_buffer(ctx, src, sizeof src, &b) == SR_OK);
    CHECK_EQ(sr_context_error(ctx)[0], 0);
    sr_destroy_buffer(ctx, b);
    sr_destroy_context(ctx);
}

SR_TEST(a_failed_buffer_allocation_reports_and_leaks_nothing)
{
    uint8_t src[256] = { 1, 2, 3 };
    for (long k = 0;; k++) {
        failing f = { 0, -1, 0, 0 };
        sr_context *ctx;
        REQUIRE(sr_make_context(&(sr_context_desc){ .allocator = { fail_alloc, fail_free, &f },
                                                    .threads = 1 },
                                &ctx) == SR_OK);
        long before = f.live;
        f.count = 0;
        f.fail_at = k;   /* the k-th allocation of sr_make_buffer */
        sr_buffer *b = NULL;
        sr_result r = sr_make_buffer(ctx, src, sizeof src, &b);
        if (f.failed == 0) {
            /* Every allocation of the call has been refused in turn. */
            CHECK_EQ(r, SR_OK);
            CHECK(k >= 2);
            sr_destroy_buffer(ctx, b);
            CHECK_EQ(f.live, before);
            sr_destroy_context(ctx);
            break;
        }
        CHECK_EQ(r, SR_OUT_OF_MEMORY);
        CHECK(b == NULL);
        CHECK_STR_CONTAINS(sr_context_error(ctx), "out of memory");
        CHECK_EQ(f.live, before);
        sr_destroy_context(ctx);
        CHECK_EQ(f.live, 0);
    }
}

enum { W = 97, H = 61, TRIS = 120000 };

/* Random small triangles over a W x H view with random depth and colors:
 * positions (4 floats) and colors (4 floats) per vertex, and indices that
 * draw the same triangles in reverse order. */
static void make_scene(float *pos, float *col, uint32_t *idx)
{
    sr_rng rng = { 0xb0ffe5ull };
    for (int t = 0; t < TRIS; t++) {
        double cx = sr_rng_range(&rng, -1.0, 1.0), cy = sr_rng_range(&rng, -1.0, 1.0);
        float z = (float)sr_rng_range(&rng, -0.9, 0.9);
        for (int k = 0; k < 3; k++) {
            float *p = &pos[(t * 3 + k) * 4], *c = &col[(t * 3 + k) * 4];
            p[0] = (float)(cx + sr_rng_range(&rng, -0.1, 0.1));
            p[1] = (float)(cy + sr_rng_range(&rng, -0.1, 0.1));
            p[2] = z;
            p[3] = 1.0f;
            for (int ch = 0; ch < 3; ch++) {
                c[ch] = (float)sr_rng_unit(&rng);
            }
            c[3] = 1.0f;
            idx[(TRIS - 1 - t) * 3 + k] = (uint32_t)(t * 3 + k);
        }
    }
}

/* The scene drawn from the given arrays, indexed or not, on 2 threads;
 * the pixels copied to out. */
static void draw(sr_context *ctx, sr_framebuffer *fb, const float *pos, const float *col,
                 const uint32_t *idx, uint32_t *out)
{
    sr_state st = { .depth_func = SR_LESS, .cull = SR_CULL_NONE, .shading = SR_SHADING_UNLIT };
    CHECK_EQ(sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1.0f }),
             SR_OK);
    CHECK_EQ(sr_draw(ctx, fb, &st,
                     &(sr_draw_desc){ .positions = pos, .position_size = 4, .colors = col,
                                      .vertex_count = 3 * TRIS, .indices = idx,
                                      .index_type = idx ? SR_INDEX_U32 : SR_INDEX_NONE,
                                      .index_count = idx ? 3 * TRIS : 0 }),
             SR_OK);
    memcpy(out, sr_framebuffer_pixels(fb), sizeof(uint32_t) * W * H);
}

SR_TEST(drawing_from_buffers_writes_the_bytes_the_arrays_write)
{
    size_t vbytes = sizeof(float) * 4 * 3 * TRIS;   /* 5.8 MB: the huge-page path */
    float *pos = malloc(vbytes), *col = malloc(vbytes);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * TRIS);
    uint32_t *a = malloc(sizeof(uint32_t) * W * H), *b = malloc(sizeof(uint32_t) * W * H);
    REQUIRE(pos && col && idx && a && b);
    make_scene(pos, col, idx);
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                             .depth_format = SR_DEPTH_D24 },
                                &fb) == SR_OK);
    sr_buffer *bp, *bc, *bi;
    REQUIRE(sr_make_buffer(ctx, pos, vbytes, &bp) == SR_OK);
    REQUIRE(sr_make_buffer(ctx, col, vbytes, &bc) == SR_OK);
    REQUIRE(sr_make_buffer(ctx, idx, sizeof(uint32_t) * 3 * TRIS, &bi) == SR_OK);

    for (int indexed = 0; indexed < 2; indexed++) {
        draw(ctx, fb, pos, col, indexed ? idx : NULL, a);
        draw(ctx, fb, sr_buffer_data(bp), sr_buffer_data(bc), indexed ? sr_buffer_data(bi) : NULL,
             b);
        CHECK(memcmp(a, b, sizeof(uint32_t) * W * H) == 0);
    }
    /* The picture is not empty, and it depends on the colors. */
    int lit = 0;
    for (int i = 0; i < W * H; i++) {
        lit += (a[i] & 0xffffff) != 0;
    }
    CHECK(lit > W * H / 2);

    /* Writes through sr_buffer_data and sr_buffer_update reach the next
     * draw. */
    for (size_t i = 0; i < (size_t)3 * TRIS; i++) {
        col[i * 4 + 0] = 1.0f - col[i * 4 + 0];
    }
    memcpy(sr_buffer_data(bc), col, vbytes / 2);
    CHECK_EQ(sr_buffer_update(ctx, bc, vbytes / 2, (const char *)col + vbytes / 2, vbytes / 2),
             SR_OK);
    draw(ctx, fb, pos, col, NULL, a);
    draw(ctx, fb, sr_buffer_data(bp), sr_buffer_data(bc), NULL, b);
    CHECK(memcmp(a, b, sizeof(uint32_t) * W * H) == 0);

    sr_destroy_buffer(ctx, bp);
    sr_destroy_buffer(ctx, bc);
    sr_destroy_buffer(ctx, bi);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    free(pos);
    free(col);
    free(idx);
    free(a);
    free(b);
}
