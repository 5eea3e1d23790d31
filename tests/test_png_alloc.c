/* test_png_alloc.c - io stage: sr_write_png (src/io/png_write.c) survives
 * each of its allocations failing in turn - the temporary file's name, its
 * buffers, and every block zlib asks for through
 * sr_png_write_desc.allocator.  Each failing run must return
 * SR_OUT_OF_MEMORY with a message, free every block it took, remove its
 * temporary file and leave the image it was to replace byte for byte as
 * it was; the first run that fails nothing must write the right image.
 * The reader (sr_read_png) is held to the same at the end. */
#include "sr_test.h"
#include "failing_alloc.h"
#include "softrast_io.h"

#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A fresh, empty directory of the test's own under the output dir. */
static const char *test_dir(const char *name)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/png_alloc_%s", sr_test_out_dir(), name);
    mkdir(sr_test_out_dir(), 0777);
    mkdir(path, 0777);
    DIR *d = opendir(path);
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL) {
        if (e->d_name[0] != '.' || (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))) {
            char p[2048];
            snprintf(p, sizeof p, "%s/%s", path, e->d_name);
            unlink(p);
        }
    }
    if (d) {
        closedir(d);
    }
    return path;
}

static int count_entries(const char *dir)
{
    int n = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL) {
        n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    }
    if (d) {
        closedir(d);
    }
    return n;
}

static long read_all(const char *path, char *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        return -1;
    }
    long n = (long)fread(buf, 1, cap, f);
    fclose(f);
    return n;
}

/* An image that compresses to several zlib blocks' worth of calls. */
static uint8_t *test_image(int w, int h)
{
    uint8_t *px = malloc((size_t)w * h * 4);
    for (int i = 0; i < w * h * 4; i++) {
        px[i] = (uint8_t)(i * 7 + (i >> 9) * 13);
    }
    return px;
}

static void every_allocation_fails_cleanly(bool existing, bool no_alpha, int level,
                                           sr_context *ctx, int w, int h)
{
    const char *dir = test_dir(existing ? "existing" : "new");
    char target[1100];
    snprintf(target, sizeof target, "%s/image.png", dir);
    static const char old[] = "the image that was here before";
    if (existing) {
        FILE *f = fopen(target, "wb");
        REQUIRE(f);
        fwrite(old, 1, sizeof old - 1, f);
        fclose(f);
    }
    uint8_t *px = test_image(w, h);
    long failures = 0;
    for (long fail_at = 0;; fail_at++) {
        failing f = { .fail_at = fail_at };
        sr_io_error err;
        sr_result r = sr_write_png(target, w, h, px, (size_t)w * 4,
                                   &(sr_png_write_desc){
                                       .compression_level = level, .channels = no_alpha ? SR_PNG_RGB : SR_PNG_RGBA,
                                       .allocator = { fail_alloc, fail_free, &f },
                                       .context = ctx },
                                   &err);
        CHECK_EQ(f.live, 0);
        if (f.failed == 0) {
            /* Nothing failed: the run must have succeeded. */
            CHECK_EQ(r, SR_OK);
            CHECK(fail_at > 5); /* the temp name, the buffers, zlib's */
            printf("  %s %dx%d image, level %d, %d threads: each of %ld allocations failed in "
                   "turn\n", existing ? "existing" : "new", w, h, level,
                   ctx ? sr_context_threads(ctx) : 1, fail_at);
            break;
        }
        failures++;
        CHECK_EQ(r, SR_OUT_OF_MEMORY);
        CHECK_STR_CONTAINS(err.message, "image.png: ");
        CHECK_STR_CONTAINS(err.message, "out of memory");
        /* The directory as it was: the old image untouched, no temporary. */
        CHECK_EQ(count_entries(dir), existing ? 1 : 0);
        if (existing) {
            char buf[256];
            long n = read_all(target, buf, sizeof buf);
            CHECK_EQ(n, (long)sizeof old - 1);
            CHECK(n == (long)sizeof old - 1 && memcmp(buf, old, sizeof old - 1) == 0);
        }
        if (sr_test_failed_now() || fail_at > 10000) {
            break;
        }
    }
    CHECK(failures > 5);
    /* The image finally written reads back exactly. */
    int rw = 0, rh = 0;
    uint8_t *back = NULL;
    sr_io_error err;
    REQUIRE(sr_read_png(target, NULL, &rw, &rh, &back, &err) == SR_OK);
    CHECK_EQ(rw, w);
    CHECK_EQ(rh, h);
    int bad = 0;
    for (int i = 0; i < w * h; i++) {
        for (int c = 0; c < 4; c++) {
            uint8_t want = c == 3 && no_alpha ? 255 : px[i * 4 + c];
            bad += back[i * 4 + c] != want;
        }
    }
    CHECK_EQ(bad, 0);
    CHECK_EQ(count_entries(dir), 1);
    free(back);
    free(px);
}

SR_TEST(png_write_survives_every_allocation_failing_over_an_existing_image)
{
    every_allocation_fails_cleanly(true, false, 0, NULL, 97, 61);
}

SR_TEST(png_write_survives_every_allocation_failing_for_a_new_rgb_image_at_level_9)
{
    every_allocation_fails_cleanly(false, true, 9, NULL, 97, 61);
}

SR_TEST(png_write_survives_every_allocation_failing_when_storing)
{
    every_allocation_fails_cleanly(false, false, -1, NULL, 97, 61);
}

/* 400 x 300 RGBA is two bands of rows, compressed at once by two deflate
 * streams on a context's two threads: the allocations all happen before
 * the threads start, on the caller's. */
SR_TEST(png_write_survives_every_allocation_failing_with_two_bands_on_two_threads)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    every_allocation_fails_cleanly(true, false, 0, ctx, 400, 300);
    sr_destroy_context(ctx);
}

SR_TEST(png_write_rejects_half_an_allocator)
{
    const char *dir = test_dir("half");
    char target[1100];
    snprintf(target, sizeof target, "%s/image.png", dir);
    uint8_t px[16] = { 0 };
    failing f = { .fail_at = -1 };
    sr_io_error err;
    CHECK_EQ(sr_write_png(target, 2, 2, px, 8,
                          &(sr_png_write_desc){ .allocator = { fail_alloc, NULL, &f } }, &err),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "allocator");
    CHECK_EQ(f.count, 0);
    CHECK_EQ(count_entries(dir), 0);
}

/* The reader through sr_read_png with an allocator: each allocation failing in turn
 * gives SR_OUT_OF_MEMORY (or, where libpng treats a failed allocation as
 * optional, the right image), no pixels and no block left; pixels come
 * from the allocator and go back to it. */
static void every_read_allocation_fails_cleanly(bool no_alpha, int level)
{
    const char *dir = test_dir(no_alpha ? "read_rgb" : "read_rgba");
    char path[1100];
    snprintf(path, sizeof path, "%s/image.png", dir);
    const int w = 83, h = 45;
    uint8_t *px = test_image(w, h);
    sr_io_error err;
    REQUIRE(sr_write_png(path, w, h, px, (size_t)w * 4,
                         &(sr_png_write_desc){ .channels = no_alpha ? SR_PNG_RGB : SR_PNG_RGBA, .compression_level = level },
                         &err) == SR_OK);
    long oom = 0;
    for (long fail_at = 0;; fail_at++) {
        failing f = { .fail_at = fail_at };
        int rw = -1, rh = -1;
        uint8_t *back = (uint8_t *)"not touched";
        sr_result r = sr_read_png(path, &(sr_png_read_desc){
                                           .allocator = { fail_alloc, fail_free, &f } },
                                       &rw, &rh, &back, &err);
        if (r == SR_OK) {
            CHECK_EQ(rw, w);
            CHECK_EQ(rh, h);
            int bad = 0;
            for (int i = 0; back && i < w * h * 4; i++) {
                bad += back[i] != (no_alpha && i % 4 == 3 ? 255 : px[i]);
            }
            CHECK_EQ(bad, 0);
            fail_free(back, &f);
        } else {
            oom++;
            CHECK_EQ(r, SR_OUT_OF_MEMORY);
            CHECK_STR_CONTAINS(err.message, "image.png: ");
            CHECK_STR_CONTAINS(err.message, "out of memory");
            CHECK(back == NULL);
            CHECK_EQ(rw, 0);
        }
        CHECK_EQ(f.live, 0);
        if (f.failed == 0) {
            CHECK_EQ(r, SR_OK);
            printf("  read, %s: each of %ld allocations failed in turn (%ld gave "
                   "SR_OUT_OF_MEMORY)\n", no_alpha ? "RGB" : "RGBA", fail_at, oom);
            break;
        }
        if (sr_test_failed_now() || fail_at > 10000) {
            break;
        }
    }
    CHECK(oom > 3);
    free(px);
}

SR_TEST(png_read_survives_every_allocation_failing)
{
    every_read_allocation_fails_cleanly(false, 0);
    every_read_allocation_fails_cleanly(true, 9);
}
