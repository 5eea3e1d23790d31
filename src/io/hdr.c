/* hdr.c - io: Radiance RGBE pictures (.hdr, .pic) to linear float RGB.
 * sr_decode_hdr consumes the file's bytes (header, resolution line, then
 * new-style run-length or flat scanlines) and produces malloc'd floats,
 * three a pixel, top row first.  Reentrant: no state outside the call.
 *
 * A pixel is a shared exponent and three 8-bit mantissas (r, g, b, e).
 * Values are converted as Greg Ward's Radiance does (colr_color in its
 * color.c): e == 0 is black, otherwise (m + 0.5) * 2^(e - 136), the centre
 * of the interval the encoder rounded into.  That value is exact in a float
 * for every byte combination, so the conversion loses nothing.
 */
#include "io/io_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* New-style run-length scanlines carry their width in 15 bits and exist
 * only for widths 8..32767; other widths are always flat. */
#define RLE_MIN_WIDTH 8
#define RLE_MAX_WIDTH 32767
#define RUN_MAX       127       /* the longest run one (code, value) pair codes */

typedef struct hdr_in {
    const char *name;
    const uint8_t *d;
    size_t size;
    size_t pos;
    sr_io_error *err;
} hdr_in;

/* The next header line, without its '\n' (and trailing blanks), or false
 * when no '\n' ends it. */
static bool next_line(hdr_in *in, const char **line, size_t *len)
{
    const uint8_t *start = in->d + in->pos;
    const uint8_t *nl = memchr(start, '\n', in->size - in->pos);
    if (!nl) {
        return false;
    }
    size_t n = (size_t)(nl - start);
    in->pos += n + 1;
    while (n > 0 && (start[n - 1] == '\r' || start[n - 1] == ' ' || start[n - 1] == '\t')) {
        n--;
    }
    *line = (const char *)start;
    *len = n;
    return true;
}

static bool line_is(const char *line, size_t len, const char *word)
{
    return len == strlen(word) && memcmp(line, word, len) == 0;
}

/* The header: the magic line, variables up to a blank line.  FORMAT must be
 * RGBE when given; EXPOSURE and the rest only describe the picture (the
 * pixel values are used as stored), so they are skipped. */
static sr_result read_header(hdr_in *in)
{
    const char *line;
    size_t len;
    if (in->size == 0) {
        return sr__io_fail(in->err, SR_BAD_FORMAT, in->name, 0, "empty file, not a Radiance HDR");
    }
    if (!next_line(in, &line, &len) ||
        !(line_is(line, len, "#?RADIANCE") || line_is(line, len, "#?RGBE"))) {
        return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, 0,
                              "not a Radiance HDR file (the first line is not #?RADIANCE "
                              "or #?RGBE)");
    }
    for (;;) {
        size_t at = in->pos;
        if (!next_line(in, &line, &len)) {
            return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                                  "truncated header (no blank line ends it)");
        }
        if (len == 0) {
            return SR_OK;
        }
        if (len >= 7 && memcmp(line, "FORMAT=", 7) == 0) {
            if (line_is(line + 7, len - 7, "32-bit_rle_rgbe")) {
                continue;
            }
            if (line_is(line + 7, len - 7, "32-bit_rle_xyze")) {
                return sr__io_fail_at(in->err, SR_UNSUPPORTED, in->name, at,
                                      "XYZE pixels are not supported, only "
                                      "FORMAT=32-bit_rle_rgbe");
            }
            return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                                  "unknown FORMAT=%.*s (expected 32-bit_rle_rgbe)",
                                  (int)(len - 7 > 40 ? 40 : len - 7), line + 7);
        }
    }
}

/* One "[+-][XY] N" field of the resolution line at *s; false when malformed
 * or N has more than 9 digits (far past any limit). */
static bool resolution_field(const char **s, const char *end, char *sign, char *axis, long *n)
{
    const char *p = *s;
    if (end - p < 4 || (p[0] != '+' && p[0] != '-') || (p[1] != 'X' && p[1] != 'Y') ||
        p[2] != ' ') {
        return false;
    }
    *sign = p[0];
    *axis = p[1];
    p += 3;
    long v = 0;
    int digits = 0;
    while (p < end && *p >= '0' && *p <= '9' && digits < 10) {
        v = v * 10 + (*p - '0');
        p++;
        digits++;
    }
    if (digits == 0 || digits > 9) {
        return false;
    }
    *n = v;
    *s = p;
    return true;
}

/* The orientation of the scanlines in the file, as output rows and columns. */
typedef struct hdr_layout {
    int width, height;
    bool bottom_up;     /* "+Y": the first scanline is the bottom row */
    bool right_left;    /* "-X": each scanline runs right to left */
} hdr_layout;

static sr_result read_resolution(hdr_in *in, hdr_layout *lay)
{
    size_t at = in->pos;
    const char *line;
    size_t len;
    if (!next_line(in, &line, &len)) {
        return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                              "truncated: no resolution line (such as \"-Y 512 +X 1024\")");
    }
    const char *s = line, *end = line + len;
    char sign1, axis1, sign2, axis2;
    long n1, n2;
    if (!resolution_field(&s, end, &sign1, &axis1, &n1) || s >= end || *s != ' ' ||
        (s++, !resolution_field(&s, end, &sign2, &axis2, &n2)) || s != end) {
        return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                              "bad resolution line \"%.*s\" (expected such as \"-Y 512 +X 1024\")",
                              (int)(len > 40 ? 40 : len), line);
    }
    if (axis1 == axis2) {
        return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                              "bad resolution line: %c given twice", axis1);
    }
    if (axis1 == 'X') {
        return sr__io_fail_at(in->err, SR_UNSUPPORTED, in->name, at,
                              "column-ordered pictures (X before Y in the resolution line) "
                              "are not supported");
    }
    if (n1 < 1 || n2 < 1) {
        return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                              "picture is %ldx%ld, it has no pixels", n2, n1);
    }
    if (n1 > SR_HDR_MAX_SIDE || n2 > SR_HDR_MAX_SIDE ||
        (size_t)n1 * (size_t)n2 > SR_HDR_MAX_PIXELS) {
        return sr__io_fail_at(in->err, SR_TOO_LARGE, in->name, at,
                              "picture is %ldx%ld, beyond the limits (%d a side, %zu pixels)",
                              n2, n1, SR_HDR_MAX_SIDE, (size_t)SR_HDR_MAX_PIXELS);
    }
    lay->height = (int)n1;
    lay->width = (int)n2;
    lay->bottom_up = sign1 == '+';
    lay->right_left = sign2 == '-';
    return SR_OK;
}

/* The fewest bytes a scanline of this width can take: the run-length form
 * when the width allows it (four channels of RUN_MAX-pixel runs), else flat. */
static size_t min_scanline_bytes(int w)
{
    if (w >= RLE_MIN_WIDTH && w <= RLE_MAX_WIDTH) {
        return 4 + 4 * 2 * (((size_t)w + RUN_MAX - 1) / RUN_MAX);
    }
    return 4 * (size_t)w;
}

/* One new-style run-length scanline (after its 4-byte header) into rgbe:
 * each channel in turn as runs (code > 128: code - 128 copies of the next
 * byte) and literals (code 1..128: that many bytes). */
static sr_result read_rle_scanline(hdr_in *in, int y, int w, uint8_t *rgbe)
{
    for (int c = 0; c < 4; c++) {
        int x = 0;
        while (x < w) {
            size_t at = in->pos;
            if (at >= in->size) {
                return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                                      "truncated in scanline %d (channel %d, pixel %d)", y, c,
                                      x);
            }
            unsigned code = in->d[in->pos++];
            bool run = code > 128;
            int n = (int)(run ? code - 128 : code);
            if (n == 0) {
                return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                                      "scanline %d: a literal of 0 bytes", y);
            }
            if (n > w - x) {
                return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, at,
                                      "scanline %d: a %s of %d bytes overflows the scanline "
                                      "(%d pixels left in channel %d)",
                                      y, run ? "run" : "literal", n, w - x, c);
            }
            size_t need = run ? 1 : (size_t)n;
            if (in->size - in->pos < need) {
                return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, in->pos,
                                      "truncated in scanline %d (channel %d, pixel %d)", y, c,
                                      x);
            }
            for (int i = 0; i < n; i++) {
                rgbe[4 * (x + i) + c] = in->d[in->pos + (run ? 0 : (size_t)i)];
            }
            in->pos += need;
            x += n;
        }
    }
    return SR_OK;
}

/* One flat scanline: w pixels of 4 bytes.  A (1, 1, 1, n) pixel is an old
 * style run in Radiance's reader; those files are refused, not misread. */
static sr_result read_flat_scanline(hdr_in *in, int y, int w, uint8_t *rgbe)
{
    if (in->size - in->pos < 4 * (size_t)w) {
        return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, in->pos,
                              "truncated in scanline %d (%zu bytes left, a flat scanline "
                              "needs %zu)", y, in->size - in->pos, 4 * (size_t)w);
    }
    const uint8_t *p = in->d + in->pos;
    for (int x = 0; x < w; x++) {
        if (p[4 * x] == 1 && p[4 * x + 1] == 1 && p[4 * x + 2] == 1) {
            return sr__io_fail_at(in->err, SR_UNSUPPORTED, in->name, in->pos + 4 * (size_t)x,
                                  "scanline %d: old-style run-length encoding is not supported",
                                  y);
        }
    }
    memcpy(rgbe, p, 4 * (size_t)w);
    in->pos += 4 * (size_t)w;
    return SR_OK;
}

static sr_result read_scanline(hdr_in *in, int y, int w, uint8_t *rgbe)
{
    const uint8_t *p = in->d + in->pos;
    if (w >= RLE_MIN_WIDTH && w <= RLE_MAX_WIDTH && in->size - in->pos >= 4 && p[0] == 2 &&
        p[1] == 2 && !(p[2] & 0x80)) {
        int lw = p[2] << 8 | p[3];
        if (lw != w) {
            return sr__io_fail_at(in->err, SR_BAD_FORMAT, in->name, in->pos,
                                  "scanline %d says it is %d pixels wide, the picture is %d", y,
                                  lw, w);
        }
        in->pos += 4;
        return read_rle_scanline(in, y, w, rgbe);
    }
    return read_flat_scanline(in, y, w, rgbe);
}

/* Radiance's colr_color: exact, see the top of the file. */
static float rgbe_component(uint8_t m, uint8_t e)
{
    return e == 0 ? 0.0f : ldexpf((float)(2 * m + 1), (int)e - 137);
}

sr_result sr_decode_hdr(const char *name, const uint8_t *data, size_t size, int *width,
                        int *height, float **pixels, sr_io_error *err)
{
    sr__image_outputs_clear(width, height, NULL, err);
    if (pixels) {
        *pixels = NULL;
    }
    if (!name) {
        name = "<memory>";
    }
    if (!width || !height || !pixels || (!data && size > 0)) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "width, height, pixels and data must not be NULL");
    }
    hdr_in in = { .name = name, .d = data, .size = size, .err = err };
    hdr_layout lay = { 0 };
    sr_result r = read_header(&in);
    if (r == SR_OK) {
        r = read_resolution(&in, &lay);
    }
    if (r != SR_OK) {
        return r;
    }
    int w = lay.width, h = lay.height;
    /* Enough bytes for h of the smallest scanlines, before allocating: a
     * short file claiming a large picture fails here, not after. */
    size_t need = (size_t)h * min_scanline_bytes(w);
    if (in.size - in.pos < need) {
        return sr__io_fail_at(err, SR_BAD_FORMAT, name, in.pos,
                              "truncated: %d scanlines of %d pixels need at least %zu bytes, "
                              "%zu remain", h, w, need, in.size - in.pos);
    }
    float *out = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
    uint8_t *rgbe = malloc(4 * (size_t)w);
    if (!out || !rgbe) {
        free(out);
        free(rgbe);
        return sr__io_fail(err, SR_OUT_OF_MEMORY, name, 0, "out of memory for a %dx%d picture",
                           w, h);
    }
    for (int s = 0; s < h; s++) {
        r = read_scanline(&in, s, w, rgbe);
        if (r != SR_OK) {
            free(out);
            free(rgbe);
            return r;
        }
        float *row = out + (size_t)(lay.bottom_up ? h - 1 - s : s) * (size_t)w * 3;
        for (int x = 0; x < w; x++) {
            const uint8_t *p = rgbe + 4 * x;
            float *q = row + 3 * (size_t)(lay.right_left ? w - 1 - x : x);
            for (int c = 0; c < 3; c++) {
                q[c] = rgbe_component(p[c], p[3]);
            }
        }
    }
    free(rgbe);
    *width = w;
    *height = h;
    *pixels = out;
    return SR_OK;
}

sr_result sr_read_hdr(const char *path, int *width, int *height, float **pixels,
                      sr_io_error *err)
{
    sr__image_outputs_clear(width, height, NULL, err);
    if (pixels) {
        *pixels = NULL;
    }
    if (!path || !path[0]) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    char *data;
    size_t size;
    sr_result r = sr__read_file_as(path, "a Radiance HDR file", &data, &size, err);
    if (r != SR_OK) {
        return r;
    }
    r = sr_decode_hdr(path, (const uint8_t *)data, size, width, height, pixels, err);
    sr__free_file(data, size);
    return r;
}
