/* test_encode.c - sr_encode_png and sr_encode_jpeg hand a write function
 * exactly the bytes sr_write_png and sr_write_jpeg put in a file, in
 * pieces; a write function that fails makes the call fail cleanly, with
 * every block it took released. */
#include "failing_alloc.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A growing buffer that refuses everything from byte `fail_after` on. */
typedef struct sink {
    uint8_t *data;
    size_t size, cap;
    size_t fail_after;     /* SIZE_MAX: never */
    int calls;
} sink;

static bool sink_write(void *user, const void *data, size_t size)
{
    sink *s = user;
    s->calls++;
    if (s->size + size > s->fail_after) {
        return false;
    }
    if (s->size + size > s->cap) {
        size_t cap = s->cap ? s->cap : 4096;
        while (cap < s->size + size) {
            cap *= 2;
        }
        uint8_t *p = realloc(s->data, cap);
        if (!p) {
            return false;
        }
        s->data = p;
        s->cap = cap;
    }
    memcpy(s->data + s->size, data, size);
    s->size += size;
    return true;
}

/* A picture with both smooth parts and noise, in rows of a wider stride. */
static uint8_t *test_image(int w, int h, size_t stride)
{
    uint8_t *p = malloc(stride * (size_t)h);
    sr_rng rng = { 0xe7c0deULL };
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            uint8_t *q = p + (size_t)y * stride + 4 * (size_t)x;
            q[0] = (uint8_t)(x * 255 / w);
            q[1] = (uint8_t)(y * 255 / h);
            q[2] = x > w / 2 ? (uint8_t)sr_rng_next(&rng) : 40;
            q[3] = (uint8_t)(255 - x % 7);
        }
    }
    return p;
}

enum { W = 700, H = 530 };
#define STRIDE ((size_t)W * 4 + 12)

SR_TEST(encoded_png_bytes_equal_the_written_file)
{
    uint8_t *img = test_image(W, H, STRIDE);
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 3 }, &ctx) == SR_OK);
    const sr_png_write_desc descs[] = {
        { 0 }, { .compression_level = -1 }, { .compression_level = 6, .channels = SR_PNG_RGB },
        { .context = ctx },
    };
    for (size_t i = 0; i < sizeof descs / sizeof descs[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/encode_%zu.png", sr_test_out_dir(), i);
        sr_io_error err;
        CHECK_EQ(sr_write_png(path, W, H, img, STRIDE, &descs[i], &err), SR_OK);
        sink s = { .fail_after = SIZE_MAX };
        CHECK_EQ(sr_encode_png(sink_write, &s, W, H, img, STRIDE, &descs[i], &err), SR_OK);
        size_t n = 0;
        uint8_t *file = sr_test_read_file(path, &n);
        REQUIRE(file);
        CHECK(n > 1000);
        CHECK_EQ(s.size, n);
        CHECK(s.size == n && memcmp(s.data, file, n) == 0);
        /* And it decodes to the picture. */
        int w, h;
        uint8_t *px = NULL;
        CHECK_EQ(sr_decode_png("mem", s.data, s.size, &w, &h, &px, &err), SR_OK);
        CHECK(px && w == W && h == H &&
              px[4 * (W * 10 + 10) + 1] == img[10 * STRIDE + 4 * 10 + 1]);
        free(px);
        free(file);
        free(s.data);
    }
    sr_destroy_context(ctx);
    free(img);
}

SR_TEST(png_write_function_failure_fails_cleanly_at_any_byte)
{
    uint8_t *img = test_image(W, H, STRIDE);
    /* The whole size first, then failures at the first byte, inside the
     * first piece, at a piece boundary and near the end. */
    sink whole = { .fail_after = SIZE_MAX };
    sr_io_error err;
    REQUIRE(sr_encode_png(sink_write, &whole, W, H, img, STRIDE, NULL, &err) == SR_OK);
    CHECK(whole.calls > 1); /* pieces, not one block */
    const size_t cuts[] = { 0, 1, 100, 65536, whole.size / 2, whole.size - 1 };
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        failing f = { .fail_at = -1 };
        sink s = { .fail_after = cuts[i] };
        sr_png_write_desc desc = { .allocator = { fail_alloc, fail_free, &f } };
        CHECK_EQ(sr_encode_png(sink_write, &s, W, H, img, STRIDE, &desc, &err), SR_IO_ERROR);
        CHECK_STR_CONTAINS(err.message, "<memory>: the write function failed");
        CHECK(f.count > 0);
        CHECK_EQ(f.live, 0);
        CHECK(s.size <= cuts[i]);
        free(s.data);
    }
    free(whole.data);
    free(img);
}

SR_TEST(encoders_check_their_arguments)
{
    uint8_t px[16] = { 0 };
    sr_io_error err;
    sink s = { .fail_after = SIZE_MAX };
    CHECK_EQ(sr_encode_png(NULL, &s, 2, 2, px, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "<memory>: no write function given");
    CHECK_EQ(sr_encode_png(sink_write, &s, 0, 2, px, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_encode_png(sink_write, &s, 2, 2, NULL, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_encode_png(sink_write, &s, 2, 2, px, 4, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_encode_png(sink_write, &s, 2, 2, px, 8,
                           &(sr_png_write_desc){ .compression_level = 10 }, &err),
             SR_INVALID_ARG);
    CHECK_EQ(s.calls, 0);
    if (sr_io_have_jpeg()) {
        CHECK_EQ(sr_encode_jpeg(NULL, &s, 2, 2, px, 8, NULL, &err), SR_INVALID_ARG);
        CHECK_EQ(sr_encode_jpeg(sink_write, &s, 2, 2, px, 8,
                                &(sr_jpeg_write_desc){ .quality = 101 }, &err),
                 SR_INVALID_ARG);
        CHECK_STR_CONTAINS(err.message, "<memory>: sr_jpeg_write_desc.quality 101");
        CHECK_EQ(s.calls, 0);
    }
    /* A stride that wraps the address space (row 1 at px - 1) describes no
     * buffer: refused before a byte is read. */
    CHECK_EQ(sr_encode_png(sink_write, &s, 2, 2, px, SIZE_MAX, NULL, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "<memory>: 2 rows of stride");
    /* A span past PTRDIFF_MAX is no object either, wrapped or not. */
    CHECK_EQ(sr_encode_png(sink_write, &s, 2, 2, px, SIZE_MAX / 2, NULL, &err), SR_INVALID_ARG);
    if (sr_io_have_jpeg()) {
        CHECK_EQ(sr_encode_jpeg(sink_write, &s, 2, 2, px, SIZE_MAX, NULL, &err), SR_INVALID_ARG);
        CHECK_STR_CONTAINS(err.message, "<memory>: 2 rows of stride");
    }
    CHECK_EQ(s.calls, 0);
    /* err may be NULL. */
    CHECK_EQ(sr_encode_png(sink_write, &(sink){ .fail_after = 0 }, 2, 2, px, 8, NULL, NULL),
             SR_IO_ERROR);
}

SR_TEST(encoded_jpeg_bytes_equal_the_written_file)
{
    uint8_t *img = test_image(W, H, STRIDE);
    sr_io_error err;
    sink s = { .fail_after = SIZE_MAX };
    if (!sr_io_have_jpeg()) {
        CHECK_EQ(sr_encode_jpeg(sink_write, &s, W, H, img, STRIDE, NULL, &err), SR_UNSUPPORTED);
        free(img);
        SKIP("this build has no libjpeg");
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/encode.jpg", sr_test_out_dir());
    sr_jpeg_write_desc desc = { .quality = 75 };
    CHECK_EQ(sr_write_jpeg(path, W, H, img, STRIDE, &desc, &err), SR_OK);
    CHECK_EQ(sr_encode_jpeg(sink_write, &s, W, H, img, STRIDE, &desc, &err), SR_OK);
    size_t n = 0;
    uint8_t *file = sr_test_read_file(path, &n);
    REQUIRE(file);
    CHECK(n > 1000);
    CHECK(s.size == n && memcmp(s.data, file, n) == 0);
    free(file);
    free(s.data);
    /* A refusing write function: SR_IO_ERROR, and nothing leaks (ASan). */
    sink refuse = { .fail_after = 0 };
    CHECK_EQ(sr_encode_jpeg(sink_write, &refuse, W, H, img, STRIDE, &desc, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "<memory>: the write function failed");
    CHECK_EQ(refuse.calls, 1);
    free(img);
}
