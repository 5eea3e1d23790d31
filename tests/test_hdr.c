/* test_hdr.c - the Radiance RGBE reader: pictures written here (flat and
 * run-length encoded by the encoder below) decode to the exact values
 * their bytes define, and every malformed input gets its message. */
#include "softrast_io.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct hbuf {
    uint8_t *d;
    size_t n, cap;
} hbuf;

static void put(hbuf *b, const void *p, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2 + 64;
        b->d = realloc(b->d, b->cap);
    }
    memcpy(b->d + b->n, p, n);
    b->n += n;
}

static void put_byte(hbuf *b, uint8_t v)
{
    put(b, &v, 1);
}

static void put_str(hbuf *b, const char *s)
{
    put(b, s, strlen(s));
}

/* Header and resolution line. */
static void put_header(hbuf *b, int w, int h)
{
    char res[64];
    put_str(b, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n");
    snprintf(res, sizeof res, "-Y %d +X %d\n", h, w);
    put_str(b, res);
}

/* One channel of a new-style scanline: runs of 3 or more equal bytes as
 * (128 + n, v), the rest as literals of at most 128 bytes. */
static void put_rle_channel(hbuf *b, const uint8_t *v, int w, int stride)
{
    int x = 0;
    while (x < w) {
        int run = 1;
        while (x + run < w && run < 127 && v[(x + run) * stride] == v[x * stride]) {
            run++;
        }
        if (run >= 3) {
            put_byte(b, (uint8_t)(128 + run));
            put_byte(b, v[x * stride]);
            x += run;
            continue;
        }
        /* A literal up to the next run of 3 (or 128 bytes). */
        int n = 0;
        while (x + n < w && n < 128) {
            if (x + n + 2 < w && v[(x + n) * stride] == v[(x + n + 1) * stride] &&
                v[(x + n) * stride] == v[(x + n + 2) * stride]) {
                break;
            }
            n++;
        }
        put_byte(b, (uint8_t)n);
        for (int i = 0; i < n; i++) {
            put_byte(b, v[(x + i) * stride]);
        }
        x += n;
    }
}

static void put_rle_scanline(hbuf *b, const uint8_t *rgbe, int w)
{
    put_byte(b, 2);
    put_byte(b, 2);
    put_byte(b, (uint8_t)(w >> 8));
    put_byte(b, (uint8_t)(w & 255));
    for (int c = 0; c < 4; c++) {
        put_rle_channel(b, rgbe + c, w, 4);
    }
}

/* A picture of w x h RGBE pixels with runs and noise; never (1, 1, 1, e)
 * nor starting (2, 2, ...) so that flat scanlines stay flat. */
static uint8_t *make_rgbe(int w, int h, unsigned seed)
{
    uint8_t *p = malloc(4 * (size_t)w * h);
    for (size_t i = 0; i < (size_t)w * h; i++) {
        seed = seed * 1103515245u + 12345u;
        unsigned r = seed >> 8;
        bool plain = (i / 7) % 3 == 0; /* stretches of equal pixels make runs */
        p[4 * i + 0] = plain ? 200 : (uint8_t)(r & 255);
        p[4 * i + 1] = plain ? 17 : (uint8_t)((r >> 8) & 255);
        p[4 * i + 2] = plain ? 3 : (uint8_t)((r >> 16) & 255);
        p[4 * i + 3] = plain ? 128 : (uint8_t)(r % 7 == 0 ? 0 : 100 + (r >> 4) % 80);
        if (p[4 * i] < 3) {
            p[4 * i] = 3;
        }
    }
    return p;
}

static float ref_value(uint8_t m, uint8_t e)
{
    return e == 0 ? 0.0f : (float)ldexp(m + 0.5, e - 136);
}

static sr_result decode(const hbuf *b, int *w, int *h, float **px, sr_io_error *err)
{
    return sr_decode_hdr("t.hdr", b->d, b->n, w, h, px, err);
}

/* Decoded pixel (x, y) of picture rgbe (file order) equals its reference. */
static void check_pixels(const float *px, const uint8_t *rgbe, int w, int h, bool bottom_up,
                         bool right_left)
{
    int bad = 0;
    for (int s = 0; s < h && bad < 5; s++) {
        for (int i = 0; i < w && bad < 5; i++) {
            const uint8_t *p = rgbe + 4 * ((size_t)s * w + i);
            int y = bottom_up ? h - 1 - s : s, x = right_left ? w - 1 - i : i;
            const float *q = px + 3 * ((size_t)y * w + x);
            for (int c = 0; c < 3; c++) {
                if (q[c] != ref_value(p[c], p[3])) {
                    sr_test_fail(__FILE__, __LINE__, "pixel %d,%d channel %d: %.9g != %.9g",
                                 x, y, c, q[c], ref_value(p[c], p[3]));
                    bad++;
                }
            }
        }
    }
}

SR_TEST(conversion_is_radiance_colr_color)
{
    /* One pixel a row of a 1-wide picture (always flat): the exponent's
     * extremes and mantissas at both ends. */
    const uint8_t px[][4] = { { 0, 0, 0, 0 },     { 255, 255, 255, 0 },  { 128, 64, 0, 128 },
                              { 0, 1, 255, 1 },   { 255, 254, 2, 255 }, { 2, 3, 4, 136 } };
    int n = (int)(sizeof px / sizeof px[0]);
    hbuf b = { 0 };
    put_header(&b, 1, n);
    put(&b, px, sizeof px);
    int w, h;
    float *out;
    sr_io_error err;
    REQUIRE(decode(&b, &w, &h, &out, &err) == SR_OK);
    CHECK_EQ(w, 1);
    CHECK_EQ(h, n);
    check_pixels(out, &px[0][0], 1, n, false, false);
    /* Spelled out: (128 + 0.5) / 2^8 = 0.501953125, and 0.5 * 2^0 = 0.5 for
     * a zero mantissa under e = 136. */
    CHECK(out[3 * 2] == 0.501953125f);
    CHECK(out[3 * 5] == 2.5f);
    CHECK(out[0] == 0.0f && out[3] == 0.0f);
    free(out);
    free(b.d);
}

SR_TEST(flat_and_rle_decode_to_the_encoded_values)
{
    /* Widths below, at and above the run-length range's ends. */
    const int widths[] = { 1, 7, 8, 9, 127, 128, 300 };
    for (int k = 0; k < (int)(sizeof widths / sizeof widths[0]); k++) {
        int w = widths[k], h = 5;
        uint8_t *rgbe = make_rgbe(w, h, (unsigned)k + 1);
        for (int rle = 0; rle < 2; rle++) {
            if (rle && w < 8) {
                continue;
            }
            hbuf b = { 0 };
            put_header(&b, w, h);
            for (int s = 0; s < h; s++) {
                /* Mixed: odd scanlines flat when encoding RLE. */
                if (rle && s % 2 == 0) {
                    put_rle_scanline(&b, rgbe + 4 * (size_t)s * w, w);
                } else {
                    put(&b, rgbe + 4 * (size_t)s * w, 4 * (size_t)w);
                }
            }
            int ow, oh;
            float *out;
            sr_io_error err;
            sr_result r = decode(&b, &ow, &oh, &out, &err);
            if (r != SR_OK) {
                sr_test_fail(__FILE__, __LINE__, "width %d rle %d: %s", w, rle, err.message);
                free(b.d);
                continue;
            }
            CHECK_EQ(ow, w);
            CHECK_EQ(oh, h);
            check_pixels(out, rgbe, w, h, false, false);
            free(out);
            free(b.d);
        }
        free(rgbe);
    }
}

/* A w x h RLE picture with the given resolution line. */
static hbuf rle_picture(const char *header, const uint8_t *rgbe, int w, int h)
{
    hbuf b = { 0 };
    put_str(&b, header);
    for (int s = 0; s < h; s++) {
        put_rle_scanline(&b, rgbe + 4 * (size_t)s * w, w);
    }
    return b;
}

SR_TEST(orientations_and_header_variants)
{
    int w = 10, h = 3;
    uint8_t *rgbe = make_rgbe(w, h, 99);
    struct {
        const char *header;
        bool bottom_up, right_left;
    } cases[] = {
        { "#?RADIANCE\n\n-Y 3 +X 10\n", false, false },
        { "#?RGBE\nEXPOSURE=4.0\n# a comment\nFORMAT=32-bit_rle_rgbe\n\n+Y 3 +X 10\n", true,
          false },
        { "#?RADIANCE\r\nFORMAT=32-bit_rle_rgbe \nSOFTWARE=x\n\n-Y 3 -X 10\n", false, true },
        { "#?RADIANCE\n\n+Y 3 -X 10\n", true, true },
    };
    for (int k = 0; k < 4; k++) {
        hbuf b = rle_picture(cases[k].header, rgbe, w, h);
        int ow, oh;
        float *out;
        sr_io_error err;
        sr_result r = decode(&b, &ow, &oh, &out, &err);
        if (r != SR_OK) {
            sr_test_fail(__FILE__, __LINE__, "case %d: %s", k, err.message);
        } else {
            check_pixels(out, rgbe, w, h, cases[k].bottom_up, cases[k].right_left);
            free(out);
        }
        free(b.d);
    }
    free(rgbe);
}

SR_TEST(read_from_a_file)
{
    int w = 16, h = 4;
    uint8_t *rgbe = make_rgbe(w, h, 7);
    hbuf b = rle_picture("#?RADIANCE\n\n-Y 4 +X 16\n", rgbe, w, h);
    char path[512];
    snprintf(path, sizeof path, "%s/hdr_read.hdr", sr_test_out_dir());
    FILE *f = fopen(path, "wb");
    REQUIRE(f);
    REQUIRE(fwrite(b.d, 1, b.n, f) == b.n);
    fclose(f);
    int ow, oh;
    float *out;
    sr_io_error err;
    REQUIRE(sr_read_hdr(path, &ow, &oh, &out, &err) == SR_OK);
    CHECK_EQ(ow, w);
    CHECK_EQ(oh, h);
    check_pixels(out, rgbe, w, h, false, false);
    free(out);
    CHECK(sr_read_hdr(sr_test_out_dir(), &ow, &oh, &out, &err) == SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "is a directory, not a Radiance HDR file");
    CHECK(out == NULL && ow == 0 && oh == 0);
    free(b.d);
    free(rgbe);
}

/* Decoding `bytes` fails with `code` and a message containing `text`,
 * leaving no pixels and a 0 x 0 size. */
static void check_error(int line, const uint8_t *bytes, size_t n, sr_result code,
                        const char *text)
{
    int w = -1, h = -1;
    float *out = (float *)&w;
    sr_io_error err;
    sr_result r = sr_decode_hdr("bad.hdr", bytes, n, &w, &h, &out, &err);
    if (r != code || !strstr(err.message, text) || out || w != 0 || h != 0) {
        sr_test_fail(__FILE__, line, "got %s \"%s\", expected %s \"%s\"", sr_result_name(r),
                     err.message, sr_result_name(code), text);
        if (r == SR_OK) {
            free(out);
        }
    }
}

static void check_error_str(int line, const char *s, sr_result code, const char *text)
{
    check_error(line, (const uint8_t *)s, strlen(s), code, text);
}

SR_TEST(malformed_headers)
{
    check_error_str(__LINE__, "", SR_BAD_FORMAT, "bad.hdr: empty file, not a Radiance HDR");
    check_error_str(__LINE__, "\x89PNG\r\n", SR_BAD_FORMAT,
                    "bad.hdr: byte 0: not a Radiance HDR file");
    check_error_str(__LINE__, "#?RADIANCE", SR_BAD_FORMAT, "byte 0: not a Radiance HDR file");
    check_error_str(__LINE__, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", SR_BAD_FORMAT,
                    "bad.hdr: byte 34: truncated header (no blank line ends it)");
    check_error_str(__LINE__, "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n", SR_UNSUPPORTED,
                    "byte 11: XYZE pixels are not supported");
    check_error_str(__LINE__, "#?RADIANCE\nFORMAT=16-bit\n\n-Y 1 +X 1\n", SR_BAD_FORMAT,
                    "byte 11: unknown FORMAT=16-bit");
    check_error_str(__LINE__, "#?RADIANCE\n\n", SR_BAD_FORMAT,
                    "byte 12: truncated: no resolution line");
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 2 +X\n", SR_BAD_FORMAT,
                    "byte 12: bad resolution line \"-Y 2 +X\"");
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 2  +X 3\n", SR_BAD_FORMAT,
                    "bad resolution line");
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 2 +X 3 4\n", SR_BAD_FORMAT,
                    "bad resolution line");
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 2 +Y 3\n", SR_BAD_FORMAT, "Y given twice");
    check_error_str(__LINE__, "#?RADIANCE\n\n+X 2 -Y 3\n", SR_UNSUPPORTED,
                    "column-ordered pictures");
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 0 +X 3\n", SR_BAD_FORMAT, "it has no pixels");
}

SR_TEST(absurd_sizes_fail_before_allocating)
{
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 32769 +X 1\n", SR_TOO_LARGE,
                    "picture is 1x32769, beyond the limits");
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 32768 +X 32768\n", SR_TOO_LARGE,
                    "beyond the limits");
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 9999999999 +X 1\n", SR_BAD_FORMAT,
                    "bad resolution line");
    /* Within the limits but far more than the bytes can hold: refused by
     * the length check (no 1.5 GiB allocation for a 40-byte file). */
    check_error_str(__LINE__, "#?RADIANCE\n\n-Y 8192 +X 16384\n", SR_BAD_FORMAT,
                    "byte 29: truncated: 8192 scanlines of 16384 pixels need at least");
}

SR_TEST(malformed_scanlines)
{
    int w = 10, h = 2;
    uint8_t *rgbe = make_rgbe(w, h, 5);
    hbuf good = rle_picture("#?RADIANCE\n\n-Y 2 +X 10\n", rgbe, w, h);
    size_t start = strlen("#?RADIANCE\n\n-Y 2 +X 10\n");
    /* Every shorter prefix of the data fails as truncated. */
    for (size_t n = start; n < good.n; n++) {
        check_error(__LINE__, good.d, n, SR_BAD_FORMAT, "truncated");
    }
    uint8_t *b = malloc(good.n + 64);

    /* A run code whose length passes the scanline's end: channel 0 of
     * scanline 0 begins with the code byte at start + 4. */
    memcpy(b, good.d, good.n);
    b[start + 4] = 128 + 11;
    check_error(__LINE__, b, good.n, SR_BAD_FORMAT,
                "scanline 0: a run of 11 bytes overflows the scanline (10 pixels left in "
                "channel 0)");
    b[start + 4] = 11;
    check_error(__LINE__, b, good.n, SR_BAD_FORMAT, "a literal of 11 bytes overflows");
    b[start + 4] = 0;
    check_error(__LINE__, b, good.n, SR_BAD_FORMAT, "scanline 0: a literal of 0 bytes");
    char where[32];
    snprintf(where, sizeof where, "byte %zu: ", start + 4);
    check_error(__LINE__, b, good.n, SR_BAD_FORMAT, where);

    /* The scanline's own width disagrees with the picture's. */
    memcpy(b, good.d, good.n);
    b[start + 3] = 9;
    check_error(__LINE__, b, good.n, SR_BAD_FORMAT,
                "scanline 0 says it is 9 pixels wide, the picture is 10");

    /* Old-style runs: a flat scanline with a (1, 1, 1, n) pixel. */
    memcpy(b, "#?RADIANCE\n\n-Y 1 +X 2\n", 22);
    memcpy(b + 22, "\x10\x20\x30\x80\x01\x01\x01\x05", 8);
    check_error(__LINE__, b, 30, SR_UNSUPPORTED,
                "byte 26: scanline 0: old-style run-length encoding is not supported");

    /* A flat scanline that runs out after an RLE one used the margin. */
    hbuf mixed = { 0 };
    put_str(&mixed, "#?RADIANCE\n\n-Y 2 +X 10\n");
    put_rle_scanline(&mixed, rgbe, w);
    put(&mixed, rgbe + 4 * w, 4 * (size_t)w - 1);
    check_error(__LINE__, mixed.d, mixed.n, SR_BAD_FORMAT, "truncated in scanline 1");
    free(mixed.d);
    free(b);
    free(good.d);
    free(rgbe);
}

SR_TEST(null_arguments)
{
    int w, h;
    float *px;
    sr_io_error err;
    const uint8_t one = 0;
    CHECK(sr_decode_hdr(NULL, NULL, 1, &w, &h, &px, &err) == SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "<memory>: ");
    CHECK(sr_decode_hdr("x", &one, 1, NULL, &h, &px, &err) == SR_INVALID_ARG);
    CHECK(sr_decode_hdr("x", &one, 1, &w, &h, NULL, &err) == SR_INVALID_ARG);
    CHECK(sr_decode_hdr("x", &one, 1, &w, &h, &px, NULL) == SR_BAD_FORMAT);
    CHECK(sr_read_hdr(NULL, &w, &h, &px, &err) == SR_INVALID_ARG);
    CHECK(sr_read_hdr("", &w, &h, &px, &err) == SR_INVALID_ARG);
    CHECK(sr_read_hdr("/nonexistent/x.hdr", &w, &h, &px, &err) == SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "/nonexistent/x.hdr: cannot open");
}
