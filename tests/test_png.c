/* test_png.c - io stage: sr_write_png (src/io/png_write.c) and sr_read_png
 * (src/io/png.c).  Round trips must be bit-exact; the file must be a valid
 * PNG by its own checksums and the same bytes for any number of threads;
 * a failed write must leave no file, no
 * temporary and no damage to an existing image; every malformed input must
 * come back as a result code with a "FILE: what" message. */
#include "sr_test.h"
#include "softrast_io.h"

#include <png.h>
#include <zlib.h>

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- helpers ------------------------------------------------------------ */

/* A fresh, empty directory of the test's own under the output dir. */
static const char *test_dir(const char *name)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/png_%s", sr_test_out_dir(), name);
    mkdir(path, 0777);
    DIR *d = opendir(path);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) {
                continue;
            }
            char p[2048];
            snprintf(p, sizeof p, "%s/%s", path, e->d_name);
            if (unlink(p) != 0) {
                rmdir(p);
            }
        }
        closedir(d);
    }
    return path;
}

/* Files limited to 8 KiB (RLIMIT_FSIZE) with SIGXFSZ ignored, so that a
 * longer write fails with EFBIG as on a full disk, until file_limit_end. */
typedef struct file_limit {
    struct rlimit old;
    void (*old_handler)(int);
} file_limit;

static bool file_limit_begin(file_limit *l)
{
    if (getrlimit(RLIMIT_FSIZE, &l->old) != 0) {
        return false;
    }
    struct rlimit lim = l->old;
    lim.rlim_cur = 8192;
    l->old_handler = signal(SIGXFSZ, SIG_IGN); /* EFBIG instead of death */
    if (setrlimit(RLIMIT_FSIZE, &lim) != 0) {
        signal(SIGXFSZ, l->old_handler);
        return false;
    }
    return true;
}

static void file_limit_end(const file_limit *l)
{
    setrlimit(RLIMIT_FSIZE, &l->old);
    signal(SIGXFSZ, l->old_handler);
}

static int count_entries(const char *dir, bool hidden_only)
{
    DIR *d = opendir(dir);
    if (!d) {
        return -1;
    }
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) {
            continue;
        }
        if (!hidden_only || e->d_name[0] == '.') {
            n++;
        }
    }
    closedir(d);
    return n;
}

static bool write_bytes(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    bool ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

static uint8_t *random_image(sr_rng *rng, int h, size_t stride)
{
    uint8_t *p = malloc(stride * (size_t)h);
    for (size_t i = 0; i < stride * (size_t)h; i++) {
        p[i] = (uint8_t)sr_rng_next(rng);
    }
    return p;
}

static bool exists(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0;
}

/* ---- round trips -------------------------------------------------------- */

SR_TEST(png_rgba_round_trip_is_exact)
{
    const char *dir = test_dir("rgba");
    sr_rng rng = { 0x5eed0001u };
    static const int levels[] = { 0, -1, 1, 6, 9 };
    for (size_t l = 0; l < sizeof levels / sizeof levels[0]; l++) {
        int w = sr_rng_int(&rng, 1, 97), h = sr_rng_int(&rng, 1, 61);
        size_t stride = 4 * (size_t)w + (size_t)sr_rng_int(&rng, 0, 3) * 4 + (l & 1);
        uint8_t *img = random_image(&rng, h, stride);
        char path[1200];
        snprintf(path, sizeof path, "%s/level%d.png", dir, levels[l]);
        sr_io_error err;
        sr_result r = sr_write_png(path, w, h, img, stride,
                                   &(sr_png_write_desc){ .compression_level = levels[l] }, &err);
        CHECK_EQ(r, SR_OK);
        int rw = 0, rh = 0;
        uint8_t *back = NULL;
        r = sr_read_png(path, NULL, &rw, &rh, &back, &err);
        REQUIRE(r == SR_OK);
        CHECK_EQ(rw, w);
        CHECK_EQ(rh, h);
        int diff = 0;
        for (int y = 0; y < h; y++) {
            diff += memcmp(back + 4 * (size_t)w * y, img + stride * y, 4 * (size_t)w) != 0;
        }
        CHECK_EQ(diff, 0);
        free(back);
        free(img);
    }
    CHECK_EQ(count_entries(dir, true), 0);
}

SR_TEST(png_no_alpha_round_trip_keeps_rgb_and_reads_opaque)
{
    const char *dir = test_dir("rgb");
    sr_rng rng = { 0x5eed0002u };
    int w = 53, h = 29;
    size_t stride = 4 * (size_t)w + 8;
    uint8_t *img = random_image(&rng, h, stride);
    char path[1200];
    snprintf(path, sizeof path, "%s/rgb.png", dir);
    sr_io_error err;
    CHECK_EQ(sr_write_png(path, w, h, img, stride, &(sr_png_write_desc){ .channels = SR_PNG_RGB }, &err),
             SR_OK);
    int rw, rh;
    uint8_t *back = NULL;
    REQUIRE(sr_read_png(path, NULL, &rw, &rh, &back, &err) == SR_OK);
    REQUIRE(rw == w && rh == h);
    int bad = 0;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const uint8_t *a = img + stride * y + 4 * x;
            const uint8_t *b = back + 4 * ((size_t)w * y + x);
            bad += a[0] != b[0] || a[1] != b[1] || a[2] != b[2] || b[3] != 255;
        }
    }
    CHECK_EQ(bad, 0);
    /* And the file really is RGB: color type 2 in IHDR (byte 25). */
    size_t n = 0;
    uint8_t *bytes = sr_test_read_file(path, &n);
    REQUIRE(bytes && n > 26);
    CHECK_EQ(bytes[25], 2);
    free(bytes);
    free(back);
    free(img);
}

/* ---- the writer's container and bands ------------------------------------ */

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Checks a file sr_write_png wrote without libpng: the signature, every
 * chunk's CRC, IHDR, one zlib stream over the IDATs (zlib's inflate checks
 * its Adler-32), then undoes the filters and compares with the image.
 * Returns the number of IDAT chunks, or -1 at the first thing wrong. */
static int check_png_by_hand(const uint8_t *f, size_t n, int w, int h, const uint8_t *img,
                             size_t stride, int channels)
{
    static const uint8_t sig[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
    if (n < 8 || memcmp(f, sig, 8) != 0) {
        return -1;
    }
    size_t row = 1 + (size_t)channels * (size_t)w, raw_size = row * (size_t)h;
    uint8_t *z = malloc(n), *raw = malloc(raw_size);
    size_t zn = 0, at = 8;
    int idats = 0;
    bool ok = z && raw, ended = false;
    while (ok && !ended && at + 12 <= n) {
        uint32_t len = get32(f + at);
        const uint8_t *type = f + at + 4, *data = f + at + 8;
        ok = at + 12 + (size_t)len <= n &&
             crc32(0L, type, 4 + len) == get32(data + len);
        if (ok && memcmp(type, "IHDR", 4) == 0) {
            ok = len == 13 && get32(data) == (uint32_t)w && get32(data + 4) == (uint32_t)h &&
                 data[8] == 8 && data[9] == (channels == 4 ? 6 : 2) && !data[10] && !data[11] &&
                 !data[12];
        } else if (ok && memcmp(type, "IDAT", 4) == 0) {
            memcpy(z + zn, data, len);
            zn += len;
            idats++;
        }
        ended = ok && memcmp(type, "IEND", 4) == 0;
        at += 12 + (size_t)len;
    }
    uLongf got = (uLongf)raw_size;
    ok = ok && ended && at == n && uncompress(raw, &got, z, (uLong)zn) == Z_OK &&
         got == raw_size;
    for (int y = 0; ok && y < h; y++) {
        const uint8_t *r = raw + row * (size_t)y, *up = y ? r - row : NULL;
        ok = r[0] == 0 || (r[0] == 2 && up);          /* NONE, or UP below row 0 */
        for (int x = 0; ok && x < w; x++) {
            for (int c = 0; c < channels; c++) {
                size_t i = 1 + (size_t)channels * (size_t)x + (size_t)c;
                uint8_t v = (uint8_t)(r[i] + (r[0] == 2 ? img[stride * (size_t)(y - 1) + 4 * (size_t)x + (size_t)c] : 0));
                ok = v == img[stride * (size_t)y + 4 * (size_t)x + (size_t)c];
            }
        }
    }
    free(z);
    free(raw);
    return ok ? idats : -1;
}

/* Smooth gradients with noise in a disc over a flat background, like a
 * render: runs, small differences and random bytes. */
static uint8_t *render_like_image(int w, int h, size_t stride, uint32_t seed)
{
    sr_rng rng = { seed };
    uint8_t *p = malloc(stride * (size_t)h);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            uint8_t *q = p + stride * (size_t)y + 4 * (size_t)x;
            long dx = x - w / 2, dy = y - h / 2;
            bool in = dx * dx + dy * dy < (long)w * w / 9;
            q[0] = in ? (uint8_t)(x + (sr_rng_next(&rng) & 3)) : 29;
            q[1] = in ? (uint8_t)(y * 3) : 34;
            q[2] = in ? (uint8_t)sr_rng_next(&rng) : 48;
            q[3] = in ? 255 : (uint8_t)(x & 1 ? 255 : 0);
        }
    }
    return p;
}

SR_TEST(png_writes_bands_that_make_one_valid_stream_the_same_for_any_thread_count)
{
    const char *dir = test_dir("bands");
    /* 700 x 500 RGBA: 2801-byte rows, 93 to a 256 KiB band, so 6 bands
     * (the last short); RGB (5 bands) and stored too; 30 x 20 is a single
     * band. */
    static const struct { int w, h, level; bool no_alpha; } cases[] = {
        { 700, 500, 0, false }, { 700, 500, 0, true }, { 700, 500, -1, false },
        { 700, 500, 6, true }, { 30, 20, 0, false },
    };
    sr_context *ctx[3];
    for (int t = 0; t < 3; t++) {
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = t + 1 }, &ctx[t]) == SR_OK);
    }
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        int w = cases[k].w, h = cases[k].h;
        size_t stride = 4 * (size_t)w + 12;
        uint8_t *img = render_like_image(w, h, stride, 0x5eed0100u + (uint32_t)k);
        /* One IDAT a band of 256 KiB of filtered rows. */
        int band_rows = (int)((256 * 1024) / (1 + (cases[k].no_alpha ? 3 : 4) * (size_t)w));
        int bands = (h + band_rows - 1) / band_rows;
        uint8_t *first = NULL;
        size_t first_n = 0;
        for (int t = -1; t < 3; t++) {   /* no context, then 1, 2 and 3 threads */
            char path[1200];
            snprintf(path, sizeof path, "%s/case%zu_t%d.png", dir, k, t + 1);
            sr_io_error err;
            CHECK_EQ(sr_write_png(path, w, h, img, stride,
                                  &(sr_png_write_desc){ .compression_level = cases[k].level,
                                                        .channels = cases[k].no_alpha ? SR_PNG_RGB : SR_PNG_RGBA,
                                                        .context = t < 0 ? NULL : ctx[t] },
                                  &err),
                     SR_OK);
            size_t n = 0;
            uint8_t *bytes = sr_test_read_file(path, &n);
            REQUIRE(bytes);
            int idats = check_png_by_hand(bytes, n, w, h, img, stride, cases[k].no_alpha ? 3 : 4);
            CHECK_EQ(idats, bands);
            if (!first) {
                first = bytes;
                first_n = n;
            } else {
                CHECK(n == first_n && memcmp(bytes, first, n) == 0);
                free(bytes);
            }
            int rw, rh;
            uint8_t *back = NULL;
            REQUIRE(sr_read_png(path, NULL, &rw, &rh, &back, &err) == SR_OK);
            int bad = 0;
            for (int y = 0; y < h; y++) {
                for (int x = 0; x < w; x++) {
                    const uint8_t *a = img + stride * (size_t)y + 4 * (size_t)x;
                    const uint8_t *b = back + 4 * ((size_t)w * (size_t)y + (size_t)x);
                    bad += memcmp(a, b, 3) != 0 || b[3] != (cases[k].no_alpha ? 255 : a[3]);
                }
            }
            CHECK_EQ(bad, 0);
            free(back);
        }
        free(first);
        free(img);
    }
    for (int t = 0; t < 3; t++) {
        sr_destroy_context(ctx[t]);
    }
    CHECK_EQ(count_entries(dir, true), 0);
}

/* Level 1 matches runs only (Z_RLE); levels 2-9 search further back and
 * find a pattern that repeats along the row, which UP does not remove. */
SR_TEST(png_higher_levels_find_repeats_that_level_1_does_not)
{
    const char *dir = test_dir("levels");
    int w = 256, h = 64;
    sr_rng rng = { 0x5eed0200u };
    uint8_t tile[16 * 4];
    uint8_t *img = malloc(4 * (size_t)w * (size_t)h);
    for (int y = 0; y < h; y++) {
        for (size_t i = 0; i < sizeof tile; i++) {
            tile[i] = (uint8_t)sr_rng_next(&rng);   /* a new 16-pixel pattern every row */
        }
        for (int x = 0; x < w; x++) {
            memcpy(img + 4 * ((size_t)w * (size_t)y + (size_t)x), tile + 4 * (x % 16), 4);
        }
    }
    size_t size[10] = { 0 };
    for (int level = 1; level <= 9; level += 8) {
        char path[1200];
        snprintf(path, sizeof path, "%s/level%d.png", dir, level);
        sr_io_error err;
        REQUIRE(sr_write_png(path, w, h, img, 4 * (size_t)w,
                             &(sr_png_write_desc){ .compression_level = level }, &err) == SR_OK);
        uint8_t *bytes = sr_test_read_file(path, &size[level]);
        CHECK(check_png_by_hand(bytes, size[level], w, h, img, 4 * (size_t)w, 4) == 1);
        free(bytes);
    }
    /* 64 KiB of pixels: runs alone cannot shrink random patterns much,
     * while matches 64 bytes back leave one pattern a row. */
    CHECK(size[1] > 40000);
    CHECK(size[9] < 10000);
    free(img);
}

/* PNGs not written by us: every color type and depth comes back as RGBA8. */
static bool write_with_libpng(const char *path, int w, int h, int color_type, int depth,
                              int interlace, const uint8_t *rows_data, size_t rowbytes,
                              const png_color *palette, int palette_n,
                              const uint8_t *trns, int trns_n)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fclose(f);
        return false;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, color_type, interlace,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (palette) {
        png_set_PLTE(png, info, palette, palette_n);
    }
    if (trns) {
        png_set_tRNS(png, info, trns, trns_n, NULL);
    }
    png_write_info(png, info);
    int passes = png_set_interlace_handling(png);
    for (int p = 0; p < passes; p++) {
        for (int y = 0; y < h; y++) {
            png_write_row(png, rows_data + rowbytes * (size_t)y);
        }
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    return fclose(f) == 0;
}

SR_TEST(png_read_expands_gray_palette_16bit_and_interlaced)
{
    const char *dir = test_dir("formats");
    char path[1200];
    sr_io_error err;
    int w, h;
    uint8_t *px;

    /* 8-bit gray */
    {
        uint8_t rows[3 * 2] = { 0, 100, 255, 7, 8, 9 };
        snprintf(path, sizeof path, "%s/gray8.png", dir);
        REQUIRE(write_with_libpng(path, 3, 2, PNG_COLOR_TYPE_GRAY, 8, PNG_INTERLACE_NONE,
                                  rows, 3, NULL, 0, NULL, 0));
        REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
        CHECK(w == 3 && h == 2);
        CHECK(px[4] == 100 && px[5] == 100 && px[6] == 100 && px[7] == 255);
        CHECK(px[4 * 5 + 0] == 9 && px[4 * 5 + 3] == 255);
        free(px);
    }
    /* 1-bit gray: 0 -> 0, 1 -> 255 */
    {
        uint8_t rows[1] = { 0xA0 }; /* 1 0 1 */
        snprintf(path, sizeof path, "%s/gray1.png", dir);
        REQUIRE(write_with_libpng(path, 3, 1, PNG_COLOR_TYPE_GRAY, 1, PNG_INTERLACE_NONE,
                                  rows, 1, NULL, 0, NULL, 0));
        REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
        CHECK(px[0] == 255 && px[4] == 0 && px[8] == 255 && px[11] == 255);
        free(px);
    }
    /* gray + alpha */
    {
        uint8_t rows[4] = { 10, 20, 30, 40 };
        snprintf(path, sizeof path, "%s/graya.png", dir);
        REQUIRE(write_with_libpng(path, 2, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 8, PNG_INTERLACE_NONE,
                                  rows, 4, NULL, 0, NULL, 0));
        REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
        CHECK(px[0] == 10 && px[1] == 10 && px[2] == 10 && px[3] == 20);
        CHECK(px[4] == 30 && px[7] == 40);
        free(px);
    }
    /* palette with transparency */
    {
        png_color pal[3] = { { 255, 0, 0 }, { 0, 255, 0 }, { 1, 2, 3 } };
        uint8_t trns[2] = { 0, 128 };
        uint8_t rows[3] = { 2, 1, 0 };
        snprintf(path, sizeof path, "%s/palette.png", dir);
        REQUIRE(write_with_libpng(path, 3, 1, PNG_COLOR_TYPE_PALETTE, 8, PNG_INTERLACE_NONE,
                                  rows, 3, pal, 3, trns, 2));
        REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
        CHECK(px[0] == 1 && px[1] == 2 && px[2] == 3 && px[3] == 255);
        CHECK(px[4] == 0 && px[5] == 255 && px[6] == 0 && px[7] == 128);
        CHECK(px[8] == 255 && px[9] == 0 && px[10] == 0 && px[11] == 0);
        free(px);
    }
    /* 16-bit RGBA keeps the high byte */
    {
        uint8_t rows[8] = { 0x12, 0x34, 0x56, 0x78, 0x9A, 0xBC, 0xDE, 0xF0 };
        snprintf(path, sizeof path, "%s/rgba16.png", dir);
        REQUIRE(write_with_libpng(path, 1, 1, PNG_COLOR_TYPE_RGB_ALPHA, 16, PNG_INTERLACE_NONE,
                                  rows, 8, NULL, 0, NULL, 0));
        REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
        CHECK(px[0] == 0x12 && px[1] == 0x56 && px[2] == 0x9A && px[3] == 0xDE);
        free(px);
    }
    /* Adam7-interlaced RGB */
    {
        sr_rng rng = { 77 };
        enum { W = 13, H = 11 };
        uint8_t rows[W * H * 3];
        for (size_t i = 0; i < sizeof rows; i++) {
            rows[i] = (uint8_t)sr_rng_next(&rng);
        }
        snprintf(path, sizeof path, "%s/adam7.png", dir);
        REQUIRE(write_with_libpng(path, W, H, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_ADAM7,
                                  rows, W * 3, NULL, 0, NULL, 0));
        REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
        REQUIRE(w == W && h == H);
        int bad = 0;
        for (int i = 0; i < W * H; i++) {
            bad += px[4 * i] != rows[3 * i] || px[4 * i + 1] != rows[3 * i + 1] ||
                   px[4 * i + 2] != rows[3 * i + 2] || px[4 * i + 3] != 255;
        }
        CHECK_EQ(bad, 0);
        free(px);
    }
}

/* ---- atomic writing ----------------------------------------------------- */

SR_TEST(png_write_into_missing_directory_fails_and_creates_nothing)
{
    const char *dir = test_dir("missing");
    char missing[1200], path[1300];
    snprintf(missing, sizeof missing, "%s/no_such_dir", dir);
    snprintf(path, sizeof path, "%s/out.png", missing);
    uint8_t px[16] = { 0 };
    sr_io_error err;
    CHECK_EQ(sr_write_png(path, 2, 2, px, 8, NULL, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, path);
    CHECK_STR_CONTAINS(err.message, "No such file or directory");
    CHECK(!exists(missing));
    CHECK_EQ(count_entries(dir, false), 0);
}

SR_TEST(png_write_through_a_file_as_directory_fails_and_creates_nothing)
{
    const char *dir = test_dir("notdir");
    char file[1200], path[1300];
    snprintf(file, sizeof file, "%s/plain_file", dir);
    REQUIRE(write_bytes(file, "x", 1));
    snprintf(path, sizeof path, "%s/out.png", file);
    uint8_t px[16] = { 0 };
    sr_io_error err;
    CHECK_EQ(sr_write_png(path, 2, 2, px, 8, NULL, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, path);
    CHECK_EQ(count_entries(dir, false), 1); /* just plain_file */
    size_t n = 0;
    uint8_t *b = sr_test_read_file(file, &n);
    CHECK(b && n == 1 && b[0] == 'x');
    free(b);
}

SR_TEST(png_target_that_is_a_directory_is_refused)
{
    const char *dir = test_dir("dirtarget");
    char target[1200];
    snprintf(target, sizeof target, "%s/image.png", dir);
    REQUIRE(mkdir(target, 0777) == 0);
    uint8_t px[16] = { 0 };
    sr_io_error err;
    CHECK_EQ(sr_write_png(target, 2, 2, px, 8, NULL, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, target);
    CHECK_STR_CONTAINS(err.message, "directory");
    struct stat st;
    CHECK(stat(target, &st) == 0 && S_ISDIR(st.st_mode));
    CHECK_EQ(count_entries(dir, false), 1);
    /* A name ending in '/' is a directory too, even when it does not exist. */
    char slash[1300];
    snprintf(slash, sizeof slash, "%s/new_dir/", dir);
    CHECK_EQ(sr_write_png(slash, 2, 2, px, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "directory");
    CHECK_EQ(count_entries(dir, false), 1);
    rmdir(target);
}

/* A write that fails halfway -- the file size limit cuts it off, the way a
 * full disk would -- leaves the existing image byte-identical and no
 * temporary file behind. */
SR_TEST(png_failed_write_leaves_existing_file_untouched)
{
    const char *dir = test_dir("atomic");
    char path[1200];
    snprintf(path, sizeof path, "%s/keep.png", dir);
    sr_rng rng = { 0x5eed0003u };
    uint8_t small[4 * 4 * 4];
    for (size_t i = 0; i < sizeof small; i++) {
        small[i] = (uint8_t)sr_rng_next(&rng);
    }
    sr_io_error err;
    REQUIRE(sr_write_png(path, 4, 4, small, 16, NULL, &err) == SR_OK);
    size_t before_n = 0;
    uint8_t *before = sr_test_read_file(path, &before_n);
    REQUIRE(before != NULL);

    /* Noise does not compress: 256x256 RGBA is ~256 KiB, far past 8 KiB. */
    int w = 256, h = 256;
    uint8_t *noise = random_image(&rng, h, 4 * (size_t)w);
    file_limit lim;
    REQUIRE(file_limit_begin(&lim));
    sr_result r = sr_write_png(path, w, h, noise, 4 * (size_t)w, NULL, &err);
    file_limit_end(&lim);

    CHECK_EQ(r, SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, path);
    CHECK_STR_CONTAINS(err.message, "write failed");
    size_t after_n = 0;
    uint8_t *after = sr_test_read_file(path, &after_n);
    REQUIRE(after != NULL);
    CHECK_EQ(after_n, before_n);
    CHECK(after_n == before_n && memcmp(before, after, before_n) == 0);
    CHECK_EQ(count_entries(dir, true), 0);
    CHECK_EQ(count_entries(dir, false), 1);
    free(before);
    free(after);
    free(noise);
}

SR_TEST(png_successful_write_replaces_and_keeps_permissions)
{
    const char *dir = test_dir("replace");
    char path[1200];
    snprintf(path, sizeof path, "%s/img.png", dir);
    uint8_t a[16] = { 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16 };
    uint8_t b[16] = { 16, 15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1 };
    sr_io_error err;

    /* A new file gets what fopen would have given it, not mkstemp's 0600. */
    mode_t mask = umask(022);
    umask(mask);
    REQUIRE(sr_write_png(path, 2, 2, a, 8, NULL, &err) == SR_OK);
    struct stat st;
    REQUIRE(stat(path, &st) == 0);
    CHECK_EQ(st.st_mode & 0777, 0666 & ~mask);

    REQUIRE(chmod(path, 0640) == 0);
    REQUIRE(sr_write_png(path, 2, 2, b, 8, NULL, &err) == SR_OK);
    REQUIRE(stat(path, &st) == 0);
    CHECK_EQ(st.st_mode & 0777, 0640);
    int w, h;
    uint8_t *px;
    REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
    CHECK(memcmp(px, b, 16) == 0);
    free(px);

    /* Through a symbolic link: the file it names is replaced, the link stays. */
    char link_path[1300];
    snprintf(link_path, sizeof link_path, "%s/link.png", dir);
    REQUIRE(symlink("img.png", link_path) == 0);
    REQUIRE(sr_write_png(link_path, 2, 2, a, 8, NULL, &err) == SR_OK);
    REQUIRE(lstat(link_path, &st) == 0);
    CHECK(S_ISLNK(st.st_mode));
    REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
    CHECK(memcmp(px, a, 16) == 0);
    free(px);
    CHECK_EQ(count_entries(dir, true), 0);
    CHECK_EQ(count_entries(dir, false), 2);
}

/* sr_write_file, the atomic writer under sr_write_png, for bytes encoded
 * elsewhere: whole files in place, an existing one kept when the write
 * fails half-way, no temporary left either way. */
SR_TEST(write_file_replaces_whole_or_not_at_all)
{
    const char *dir = test_dir("write_file");
    char path[1200];
    snprintf(path, sizeof path, "%s/anim.webp", dir);
    const char first[] = "RIFF first", second[] = "RIFF the second, longer";
    sr_io_error err;
    REQUIRE(sr_write_file(path, first, sizeof first, &err) == SR_OK);
    CHECK_EQ(err.message[0], '\0');
    REQUIRE(sr_write_file(path, second, sizeof second, &err) == SR_OK);
    size_t n = 0;
    uint8_t *got = sr_test_read_file(path, &n);
    CHECK(got && n == sizeof second && memcmp(got, second, n) == 0);
    free(got);

    /* Past RLIMIT_FSIZE the write fails (EFBIG, as on a full disk). */
    size_t big_n = 64 * 1024;
    uint8_t *big = calloc(1, big_n);
    REQUIRE(big != NULL);
    file_limit lim;
    REQUIRE(file_limit_begin(&lim));
    sr_result r = sr_write_file(path, big, big_n, &err);
    file_limit_end(&lim);
    free(big);
    CHECK_EQ(r, SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, path);
    CHECK_STR_CONTAINS(err.message, "write failed");
    got = sr_test_read_file(path, &n);
    CHECK(got && n == sizeof second && memcmp(got, second, n) == 0);
    free(got);

    /* Nothing to write is an empty file. */
    char empty[1300];
    snprintf(empty, sizeof empty, "%s/empty", dir);
    CHECK_EQ(sr_write_file(empty, NULL, 0, &err), SR_OK);
    struct stat st;
    CHECK(stat(empty, &st) == 0 && st.st_size == 0);
    CHECK_EQ(count_entries(dir, true), 0);
    CHECK_EQ(count_entries(dir, false), 2);
}

SR_TEST(write_file_rejects_invalid_arguments)
{
    const char *dir = test_dir("write_file_args");
    char path[1200];
    snprintf(path, sizeof path, "%s/x.bin", dir);
    sr_io_error err;
    CHECK_EQ(sr_write_file(NULL, "x", 1, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_file("", "x", 1, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_file(path, NULL, 1, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "data is NULL");
    CHECK_EQ(sr_write_file(dir, "x", 1, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "is a directory");
    CHECK_EQ(sr_write_file(path, NULL, 1, NULL), SR_INVALID_ARG);   /* err may be NULL */
    CHECK_EQ(count_entries(dir, false), 0);
}

SR_TEST(png_write_rejects_invalid_arguments)
{
    const char *dir = test_dir("args");
    char path[1200];
    snprintf(path, sizeof path, "%s/x.png", dir);
    uint8_t px[64] = { 0 };
    sr_io_error err;
    CHECK_EQ(sr_write_png(NULL, 2, 2, px, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_png("", 2, 2, px, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_png(path, 2, 2, NULL, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_png(path, 0, 2, px, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_png(path, 2, -1, px, 8, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_png(path, 65536, 1, px, 4 * 65536, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_png(path, 1, 65536, px, 4, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_write_png(path, 2, 2, px, 7, NULL, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "stride");
    CHECK_EQ(sr_write_png(path, 2, 2, px, 8, &(sr_png_write_desc){ .compression_level = 10 }, &err),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "compression_level");
    CHECK_EQ(sr_write_png(path, 2, 2, px, 8, &(sr_png_write_desc){ .compression_level = -2 }, &err),
             SR_INVALID_ARG);
    /* A NULL error pointer is allowed. */
    CHECK_EQ(sr_write_png(path, 0, 0, px, 8, NULL, NULL), SR_INVALID_ARG);
    CHECK_EQ(count_entries(dir, false), 0);
}

/* ---- bad input files ---------------------------------------------------- */

SR_TEST(png_read_reports_missing_corrupt_and_truncated_files)
{
    const char *dir = test_dir("corrupt");
    char good[1200], path[1300];
    snprintf(good, sizeof good, "%s/good.png", dir);
    sr_rng rng = { 0x5eed0004u };
    int w = 40, h = 30;
    uint8_t *img = random_image(&rng, h, 4 * (size_t)w);
    sr_io_error err;
    REQUIRE(sr_write_png(good, w, h, img, 4 * (size_t)w, NULL, &err) == SR_OK);
    size_t n = 0;
    uint8_t *bytes = sr_test_read_file(good, &n);
    REQUIRE(bytes && n > 200);
    int rw = -1, rh = -1;
    uint8_t *px = (uint8_t *)1;

    /* missing */
    snprintf(path, sizeof path, "%s/absent.png", dir);
    CHECK_EQ(sr_read_png(path, NULL, &rw, &rh, &px, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, path);
    CHECK_STR_CONTAINS(err.message, "No such file");
    CHECK(px == NULL && rw == 0 && rh == 0);

    /* a directory */
    CHECK_EQ(sr_read_png(dir, NULL, &rw, &rh, &px, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "directory");

    /* empty, and not a PNG at all */
    snprintf(path, sizeof path, "%s/empty.png", dir);
    REQUIRE(write_bytes(path, "", 0));
    CHECK_EQ(sr_read_png(path, NULL, &rw, &rh, &px, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, path);
    snprintf(path, sizeof path, "%s/text.png", dir);
    REQUIRE(write_bytes(path, "this is not an image\n", 21));
    CHECK_EQ(sr_read_png(path, NULL, &rw, &rh, &px, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "not a PNG");

    /* a flipped bit inside the compressed data: IDAT's CRC no longer matches */
    snprintf(path, sizeof path, "%s/flipped.png", dir);
    bytes[n / 2] ^= 0x10;
    REQUIRE(write_bytes(path, bytes, n));
    bytes[n / 2] ^= 0x10;
    CHECK_EQ(sr_read_png(path, NULL, &rw, &rh, &px, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, path);
    CHECK_STR_CONTAINS(err.message, "corrupt PNG");
    CHECK(px == NULL);

    /* a bad IHDR (width 0), with its CRC left as it was */
    snprintf(path, sizeof path, "%s/ihdr.png", dir);
    uint8_t saved[4];
    memcpy(saved, bytes + 16, 4);
    memset(bytes + 16, 0, 4);
    REQUIRE(write_bytes(path, bytes, n));
    memcpy(bytes + 16, saved, 4);
    CHECK_EQ(sr_read_png(path, NULL, &rw, &rh, &px, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, path);

    /* cut off in the middle of the image data, and just before IEND */
    size_t cuts[2] = { n / 2, n - 12 };
    for (int c = 0; c < 2; c++) {
        snprintf(path, sizeof path, "%s/cut%d.png", dir, c);
        REQUIRE(write_bytes(path, bytes, cuts[c]));
        CHECK_EQ(sr_read_png(path, NULL, &rw, &rh, &px, &err), SR_BAD_FORMAT);
        CHECK_STR_CONTAINS(err.message, path);
        CHECK_STR_CONTAINS(err.message, "truncated");
        CHECK(px == NULL);
    }

    /* NULL outputs */
    CHECK_EQ(sr_read_png(good, NULL, NULL, &rh, &px, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_read_png(NULL, NULL, &rw, &rh, &px, &err), SR_INVALID_ARG);
    free(bytes);
    free(img);
}

SR_TEST(png_read_refuses_images_over_16384)
{
    const char *dir = test_dir("huge");
    char path[1200];
    snprintf(path, sizeof path, "%s/wide.png", dir);
    /* 16385 x 1 gray: a few KiB on disk, one pixel over the limit. */
    enum { W = 16385 };
    uint8_t *row = calloc(W, 1);
    REQUIRE(row != NULL);
    REQUIRE(write_with_libpng(path, W, 1, PNG_COLOR_TYPE_GRAY, 8, PNG_INTERLACE_NONE,
                              row, W, NULL, 0, NULL, 0));
    free(row);
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    CHECK_EQ(sr_read_png(path, NULL, &w, &h, &px, &err), SR_TOO_LARGE);
    CHECK_STR_CONTAINS(err.message, path);
    CHECK_STR_CONTAINS(err.message, "16385x1");
    CHECK(px == NULL);

    /* 16384 is still fine. */
    snprintf(path, sizeof path, "%s/edge.png", dir);
    row = calloc(W, 1);
    REQUIRE(write_with_libpng(path, W - 1, 1, PNG_COLOR_TYPE_GRAY, 8, PNG_INTERLACE_NONE,
                              row, W - 1, NULL, 0, NULL, 0));
    free(row);
    CHECK_EQ(sr_read_png(path, NULL, &w, &h, &px, &err), SR_OK);
    CHECK(w == W - 1 && h == 1);
    free(px);
}
