/* test_jpeg.c - io stage: sr_read_jpeg, sr_decode_jpeg, sr_write_jpeg,
 * sr_read_image, sr_decode_image and sr_decode_png (src/io/jpeg.c,
 * image.c, png.c).  The JPEGs are written here with
 * libjpeg's own encoder from pixels the test chose, so the decoded pixels
 * are checked against those, within the error the encoding's quality
 * allows; damaged files must come back as an error with a message and
 * nothing partial, never as a picture with a gray band. */
#include "sr_test.h"
#include "softrast_io.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef SR_HAVE_JPEG_TEST
#include "jpeg_encode.h"
#endif

#define FAILF(...) sr_test_fail(__FILE__, __LINE__, __VA_ARGS__)

#ifdef SR_HAVE_JPEG_TEST

static char *out_path(const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/jpeg_%s", sr_test_out_dir(), name);
    return buf;
}

static bool write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    bool ok = fwrite(data, 1, n, f) == n;
    return (fclose(f) == 0) && ok;
}

/* A smooth test picture: gradients across and down, a diagonal in blue. */
static uint8_t channel_at(int x, int y, int c, int w, int h)
{
    int v = c == 0 ? 255 * x / (w - 1) : c == 1 ? 255 * y / (h - 1) : 255 * (x + y) / (w + h - 2);
    return (uint8_t)v;
}

typedef enum sample_kind { RGB_444, RGB_420_PROGRESSIVE, GRAY, CMYK_ADOBE } sample_kind;

/* Encode the test picture (w x h) with libjpeg into a malloc'd buffer.
 * CMYK is written as Adobe does, inks inverted: C' = R, M' = G, Y' = B
 * and K' = `k_inv`, which should read back as (R, G, B) k_inv / 255. */
static uint8_t *encode(sample_kind kind, int w, int h, int quality, int k_inv, size_t *size)
{
    int comps = kind == GRAY ? 1 : kind == CMYK_ADOBE ? 4 : 3;
    uint8_t *px = malloc((size_t)comps * w * h);
    if (!px) {
        return NULL;
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            uint8_t *p = px + (size_t)comps * ((size_t)y * w + x);
            for (int ch = 0; ch < comps && ch < 3; ch++) {
                p[ch] = channel_at(x, y, ch, w, h);
            }
            if (kind == CMYK_ADOBE) {
                p[3] = (uint8_t)k_inv;
            }
        }
    }
    jpeg_encoding e = { kind == GRAY ? JCS_GRAYSCALE : kind == CMYK_ADOBE ? JCS_CMYK : JCS_RGB,
                        quality, kind == RGB_420_PROGRESSIVE, kind == RGB_444 };
    uint8_t *jpg = jpeg_encode(px, w, h, e, size);
    free(px);
    return jpg;
}

/* The largest difference of a decoded channel from `expect(x, y, c)`. */
static int max_error(const uint8_t *px, int w, int h, sample_kind kind, int k_inv)
{
    int worst = 0;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * w + x);
            for (int c = 0; c < 3; c++) {
                int want = kind == GRAY ? channel_at(x, y, 0, w, h) : channel_at(x, y, c, w, h);
                if (kind == CMYK_ADOBE) {
                    want = (want * k_inv + 127) / 255;
                }
                int d = abs((int)p[c] - want);
                worst = d > worst ? d : worst;
            }
            if (p[3] != 255) {
                return 1000; /* alpha must be opaque */
            }
        }
    }
    return worst;
}

SR_TEST(decoded_pixels_match_what_was_encoded)
{
    /* Error bounds from the quality: at 100 with full-resolution chroma a
     * smooth picture comes back within a few levels; subsampled chroma
     * blurs the colors of 2 x 2 blocks a little more. */
    struct {
        const char *label;
        sample_kind kind;
        int quality, k_inv, bound;
    } cases[] = {
        { "RGB 4:4:4 baseline", RGB_444, 100, 0, 3 },
        { "RGB 4:2:0 progressive", RGB_420_PROGRESSIVE, 95, 0, 8 },
        { "grayscale", GRAY, 100, 0, 2 },
        { "CMYK (Adobe, no black)", CMYK_ADOBE, 100, 255, 3 },
        { "CMYK (Adobe, half black)", CMYK_ADOBE, 100, 128, 3 },
    };
    const int w = 61, h = 37; /* not multiples of the 8 x 8 or 16 x 16 blocks */
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        size_t size;
        uint8_t *jpg = encode(cases[i].kind, w, h, cases[i].quality, cases[i].k_inv, &size);
        REQUIRE(jpg);
        int dw = -1, dh = -1;
        uint8_t *px = NULL;
        sr_io_error err;
        sr_result r = sr_decode_jpeg(cases[i].label, jpg, size, &dw, &dh, &px, &err);
        if (r != SR_OK) {
            FAILF("%s: %s", cases[i].label, err.message);
            free(jpg);
            continue;
        }
        CHECK_EQ(dw, w);
        CHECK_EQ(dh, h);
        int e = max_error(px, w, h, cases[i].kind, cases[i].k_inv);
        if (e > cases[i].bound) {
            FAILF("%s: a channel is %d levels off (bound %d)", cases[i].label, e, cases[i].bound);
        }
        /* From a file: the same pixels. */
        char path[1024];
        out_path("picture.jpg", path, sizeof path);
        REQUIRE(write_bytes(path, jpg, size));
        int fw, fh;
        uint8_t *fpx = NULL;
        REQUIRE(sr_read_jpeg(path, &fw, &fh, &fpx, &err) == SR_OK);
        CHECK(fw == w && fh == h && memcmp(fpx, px, 4 * (size_t)w * h) == 0);
        free(fpx);
        free(px);
        free(jpg);
    }
}

/* The bytes of a JPEG of the test picture, the tests' common input. */
static uint8_t *sample_jpeg(size_t *size)
{
    return encode(RGB_444, 160, 96, 90, 0, size); /* mostly entropy-coded data */
}

/* Every failure: the code, a message naming the input, no pixels, 0 x 0. */
static void expect_failure(const char *label, const uint8_t *data, size_t size, sr_result code,
                           const char *needle)
{
    int w = -1, h = -1;
    uint8_t *px = (uint8_t *)&w;
    sr_io_error err;
    sr_result r = sr_decode_jpeg("bad.jpg", data, size, &w, &h, &px, &err);
    if (r != code) {
        FAILF("%s: %s, expected %s (%s)", label, sr_result_name(r), sr_result_name(code),
              err.message);
    }
    CHECK(px == NULL && w == 0 && h == 0);
    if (strncmp(err.message, "bad.jpg: ", 9) != 0 || !strstr(err.message, needle) ||
        strchr(err.message, '\n')) {
        FAILF("%s: message \"%s\" is not \"bad.jpg: ...%s...\" on one line", label, err.message,
              needle);
    }
}

SR_TEST(damaged_jpegs_are_errors_not_pictures)
{
    size_t size;
    uint8_t *jpg = sample_jpeg(&size);
    REQUIRE(jpg && size > 2000);
    /* Cut anywhere after the header: libjpeg alone would return the
     * missing rows gray with a warning. */
    expect_failure("truncated at half", jpg, size / 2, SR_BAD_FORMAT, "corrupt JPEG");
    expect_failure("truncated before the end marker", jpg, size - 2, SR_BAD_FORMAT,
                   "corrupt JPEG");
    expect_failure("only the header's start", jpg, 20, SR_BAD_FORMAT, "corrupt JPEG");
    expect_failure("empty", jpg, 0, SR_BAD_FORMAT, "empty file");
    static const uint8_t text[] = "just some text, no image here";
    expect_failure("not a JPEG", text, sizeof text - 1, SR_BAD_FORMAT, "not a JPEG file");

    /* A frame header claiming 20000 x 20000: refused before anything
     * that size is allocated. */
    uint8_t *big = malloc(size);
    REQUIRE(big);
    memcpy(big, jpg, size);
    size_t sof = 0;
    for (size_t i = 2; i + 9 < size; i++) {
        if (big[i] == 0xFF && big[i + 1] == 0xC0) {
            sof = i;
            break;
        }
    }
    REQUIRE(sof != 0);
    big[sof + 5] = 20000 >> 8; /* height */
    big[sof + 6] = 20000 & 0xFF;
    big[sof + 7] = 20000 >> 8; /* width */
    big[sof + 8] = 20000 & 0xFF;
    expect_failure("20000 x 20000", big, size, SR_TOO_LARGE, "larger than the 16384x16384 limit");
    free(big);

    /* 16000 x 16000 is within the limit, but a progressive image keeps
     * every coefficient while it decodes: 768 MB here, refused before
     * libjpeg takes it. */
    size_t psize;
    uint8_t *prog = encode(RGB_420_PROGRESSIVE, 32, 32, 90, 0, &psize);
    REQUIRE(prog);
    sof = 0;
    for (size_t i = 2; i + 9 < psize; i++) {
        if (prog[i] == 0xFF && prog[i + 1] == 0xC2) {
            sof = i;
            break;
        }
    }
    REQUIRE(sof != 0);
    prog[sof + 5] = 16000 >> 8;
    prog[sof + 6] = 16000 & 0xFF;
    prog[sof + 7] = 16000 >> 8;
    prog[sof + 8] = 16000 & 0xFF;
    expect_failure("progressive 16000 x 16000", prog, psize, SR_TOO_LARGE,
                   "more than 512 MiB of working memory");
    free(prog);

    int w, h;
    uint8_t *px;
    sr_io_error err;
    CHECK_EQ(sr_decode_jpeg("x", jpg, size, NULL, &h, &px, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_decode_jpeg("x", NULL, 10, &w, &h, &px, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_read_jpeg(NULL, &w, &h, &px, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_read_jpeg("", &w, &h, &px, &err), SR_INVALID_ARG);
    free(jpg);
}

/* Random damage (fixed seed): every result is a picture of the right size
 * or an error with a message and no pixels.  Under the sanitizers (CI)
 * this also checks that the error path frees what it took. */
SR_TEST(randomly_damaged_jpegs_decode_or_fail_cleanly)
{
    size_t size;
    uint8_t *jpg = sample_jpeg(&size);
    REQUIRE(jpg);
    uint8_t *bad = malloc(size);
    REQUIRE(bad);
    uint32_t s = 12345;
    int ok = 0, failed = 0;
    for (int round = 0; round < 600; round++) {
        memcpy(bad, jpg, size);
        int flips = 1 + round % 4;
        for (int k = 0; k < flips; k++) {
            s = s * 1664525u + 1013904223u;
            size_t at = 2 + (s >> 8) % (size - 2);
            s = s * 1664525u + 1013904223u;
            bad[at] ^= (uint8_t)(1u << (s >> 29));
        }
        int w = -1, h = -1;
        uint8_t *px = NULL;
        sr_io_error err;
        sr_result r = sr_decode_jpeg("m.jpg", bad, size, &w, &h, &px, &err);
        if (r == SR_OK) {
            ok++;
            if (!px || w <= 0 || h <= 0 || w > 16384 || h > 16384) {
                FAILF("round %d: success without a picture (%dx%d)", round, w, h);
            }
        } else {
            failed++;
            if (px || w != 0 || h != 0 || strncmp(err.message, "m.jpg: ", 7) != 0) {
                FAILF("round %d: failure left %dx%d, pixels %p, message \"%s\"", round, w, h,
                      (void *)px, err.message);
            }
        }
        free(px);
    }
    /* Both outcomes occur: flipped bits in the entropy-coded data often
     * decode to other valid codes, and in the headers they fail. */
    CHECK(ok > 0);
    CHECK(failed > 0);
    free(bad);
    free(jpg);
}

SR_TEST(read_image_goes_by_content_not_name)
{
    size_t size;
    uint8_t *jpg = sample_jpeg(&size);
    REQUIRE(jpg);
    char as_png[1024], as_jpg[1024], text[1024];
    out_path("really_a_jpeg.png", as_png, sizeof as_png);
    out_path("really_a_png.jpg", as_jpg, sizeof as_jpg);
    out_path("text.jpg", text, sizeof text);
    REQUIRE(write_bytes(as_png, jpg, size));
    const uint8_t rgba[8] = { 1, 2, 3, 255, 200, 100, 50, 128 };
    sr_io_error err;
    REQUIRE(sr_write_png(as_jpg, 2, 1, rgba, 8, NULL, &err) == SR_OK);
    REQUIRE(write_bytes(text, "hello", 5));

    int w, h, jw, jh;
    uint8_t *px = NULL, *jpx = NULL;
    REQUIRE(sr_read_image(as_png, &w, &h, &px, &err) == SR_OK);
    REQUIRE(sr_decode_jpeg("x", jpg, size, &jw, &jh, &jpx, &err) == SR_OK);
    CHECK(w == jw && h == jh && memcmp(px, jpx, 4 * (size_t)w * h) == 0);
    free(px);
    free(jpx);
    REQUIRE(sr_read_image(as_jpg, &w, &h, &px, &err) == SR_OK);
    CHECK(w == 2 && h == 1 && memcmp(px, rgba, 8) == 0);
    free(px);

    /* From memory: the same pixels as from the files. */
    uint8_t png[4096];
    FILE *f = fopen(as_jpg, "rb");
    REQUIRE(f);
    size_t pn = fread(png, 1, sizeof png, f);
    fclose(f);
    REQUIRE(pn > 10 && pn < sizeof png);
    REQUIRE(sr_decode_image("mem.png", png, pn, &w, &h, &px, &err) == SR_OK);
    CHECK(w == 2 && h == 1 && memcmp(px, rgba, 8) == 0);
    free(px);
    REQUIRE(sr_decode_png("mem.png", png, pn, &w, &h, &px, &err) == SR_OK);
    CHECK(w == 2 && h == 1 && memcmp(px, rgba, 8) == 0);
    free(px);
    REQUIRE(sr_decode_image("mem.jpg", jpg, size, &w, &h, &px, &err) == SR_OK);
    REQUIRE(sr_decode_jpeg("x", jpg, size, &jw, &jh, &jpx, &err) == SR_OK);
    CHECK(w == jw && h == jh && memcmp(px, jpx, 4 * (size_t)w * h) == 0);
    free(px);
    free(jpx);
    /* A PNG cut short in memory is an error like one cut short on disk. */
    CHECK_EQ(sr_decode_png("cut.png", png, pn - 10, &w, &h, &px, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "cut.png: truncated PNG");
    CHECK(px == NULL && w == 0 && h == 0);
    CHECK_EQ(sr_decode_png("none.png", png, 0, &w, &h, &px, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "none.png: empty file, not a PNG");
    CHECK_EQ(sr_decode_image("t.txt", (const uint8_t *)"hello", 5, &w, &h, &px, &err),
             SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "t.txt: neither a PNG, a JPEG nor a WebP");

    CHECK_EQ(sr_read_image(text, &w, &h, &px, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "neither a PNG, a JPEG nor a WebP");
    CHECK(px == NULL);
    /* sr_read_jpeg itself checks the content too. */
    CHECK_EQ(sr_read_jpeg(as_jpg, &w, &h, &px, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "not a JPEG file");
    /* Directories are refused by name, as for every reader. */
    CHECK_EQ(sr_read_jpeg(sr_test_out_dir(), &w, &h, &px, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "is a directory, not a JPEG file");
    CHECK_EQ(sr_read_image(sr_test_out_dir(), &w, &h, &px, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "is a directory, not an image file");
    free(jpg);
}

/* sr_write_jpeg: what it writes reads back close to the pixels given
 * (alpha dropped), it replaces an existing file whole, and bad arguments
 * or an unwritable place leave nothing behind. */
SR_TEST(written_jpegs_read_back_and_failures_leave_nothing)
{
    const int w = 64, h = 40;
    uint8_t *rgba = malloc(4 * (size_t)w * h);
    REQUIRE(rgba);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            uint8_t *p = rgba + 4 * ((size_t)y * w + x);
            for (int c = 0; c < 3; c++) {
                p[c] = channel_at(x, y, c, w, h);
            }
            p[3] = (uint8_t)(x * 4); /* dropped */
        }
    }
    char path[1024], missing[1100];
    out_path("written.jpg", path, sizeof path);
    snprintf(missing, sizeof missing, "%s/no/such/dir/x.jpg", sr_test_out_dir());
    REQUIRE(write_bytes(path, "old", 3));
    sr_io_error err;
    REQUIRE(sr_write_jpeg(path, w, h, rgba, 4 * (size_t)w,
                          &(sr_jpeg_write_desc){ .quality = 100 }, &err) == SR_OK);
    int rw, rh;
    uint8_t *back = NULL;
    REQUIRE(sr_read_jpeg(path, &rw, &rh, &back, &err) == SR_OK);
    CHECK(rw == w && rh == h);
    /* Quality 100, but libjpeg's default 4:2:0 chroma: a few levels. */
    int worst = max_error(back, w, h, RGB_420_PROGRESSIVE, 0);
    if (worst > 8) {
        FAILF("a channel is %d levels off", worst);
    }
    free(back);

    struct {
        const char *label, *path;
        const uint8_t *px;
        int w, h;
        size_t stride;
        int quality;
        sr_result code;
        const char *needle;
    } bad[] = {
        { "no path", NULL, rgba, w, h, 4 * (size_t)w, 0, SR_INVALID_ARG, "no file name" },
        { "no pixels", path, NULL, w, h, 4 * (size_t)w, 0, SR_INVALID_ARG, "rgba is NULL" },
        { "zero width", path, rgba, 0, h, 4 * (size_t)w, 0, SR_INVALID_ARG, "outside 1..65500" },
        { "short stride", path, rgba, w, h, 4 * (size_t)w - 1, 0, SR_INVALID_ARG, "row stride" },
        { "quality 101", path, rgba, w, h, 4 * (size_t)w, 101, SR_INVALID_ARG, "quality 101" },
        { "no directory", missing, rgba, w, h, 4 * (size_t)w, 0, SR_IO_ERROR,
          "cannot create a file in" },
        { "a directory", sr_test_out_dir(), rgba, w, h, 4 * (size_t)w, 0, SR_IO_ERROR,
          "is a directory" },
    };
    size_t before_len;
    FILE *f = fopen(path, "rb");
    REQUIRE(f);
    uint8_t before[65536];
    before_len = fread(before, 1, sizeof before, f);
    fclose(f);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sr_result r = sr_write_jpeg(bad[i].path, bad[i].w, bad[i].h, bad[i].px, bad[i].stride,
                                    &(sr_jpeg_write_desc){ .quality = bad[i].quality }, &err);
        if (r != bad[i].code || !strstr(err.message, bad[i].needle)) {
            FAILF("%s: %s \"%s\"", bad[i].label, sr_result_name(r), err.message);
        }
    }
    /* The file the failed calls named is as the good one left it. */
    f = fopen(path, "rb");
    REQUIRE(f);
    uint8_t after[65536];
    size_t after_len = fread(after, 1, sizeof after, f);
    fclose(f);
    CHECK(after_len == before_len && memcmp(after, before, before_len) == 0);
    free(rgba);
}

#else

SR_TEST(decoded_pixels_match_what_was_encoded)
{
    CHECK(!sr_io_have_jpeg());
    int w, h;
    uint8_t *px;
    sr_io_error err;
    CHECK_EQ(sr_decode_jpeg("x.jpg", (const uint8_t *)"\xFF\xD8\xFF", 3, &w, &h, &px, &err),
             SR_UNSUPPORTED);
    CHECK_STR_CONTAINS(err.message, "install libjpeg-dev");
    SKIP("this build reads no JPEG (libjpeg-dev was not found)");
}

#endif
