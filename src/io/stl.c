/*
 * stl.c - io stage: the STL (stereolithography) model reader.
 * Consumes a whole file in memory, ASCII or binary (told apart by the
 * binary size rule and by content, since binary headers may say "solid").
 * Produces an indexed sr_mesh: identical corners welded into one vertex,
 * winding as in the file, normals NULL.  No shared state: any thread.
 *
 * STL stores three separate corners per triangle and a facet normal.  We
 * weld corners so that callers can compute smooth normals, and drop the
 * facet normals, which writers often leave zero or get wrong.
 */
#include "io/byteorder.h"
#include "io/io_util.h"
#include "io/number.h"
#include "io/readers.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define STL_HEADER_BYTES   80
#define STL_PREFIX_BYTES   84  /* header + uint32 triangle count */
#define STL_TRIANGLE_BYTES 50  /* normal, 3 corners (12 floats), uint16 attribute */

/* ---- welding ------------------------------------------------------------ */

/* Open-addressing hash table from a position's exact float bits to its
 * vertex index.  Exact bits, not a tolerance: STL writers emit the same
 * corner with the same bits each time, and an epsilon would merge
 * vertices that the model keeps apart. */
typedef struct welder {
    float *positions;
    size_t count, cap;     /* vertices */
    uint32_t *slots;       /* vertex index + 1; 0 = empty */
    size_t slot_count;     /* power of two */
} welder;

static uint64_t hash_position(const uint32_t bits[3])
{
    uint64_t h = bits[0] * 0x9E3779B97F4A7C15ull;
    h ^= (bits[1] + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= (bits[2] + 0x165667B19E3779F9ull) * 0x27D4EB2F165667C5ull;
    return h ^ (h >> 29);
}

static void position_bits(const float *p, uint32_t bits[3])
{
    for (int k = 0; k < 3; k++) {
        /* -0 and +0 are the same point; adding +0 turns -0 into +0. */
        float f = p[k] + 0.0f;
        memcpy(&bits[k], &f, sizeof f);
    }
}

static bool welder_rehash(welder *w, size_t slot_count)
{
    uint32_t *slots = calloc(slot_count, sizeof *slots);
    if (!slots) {
        return false;
    }
    for (size_t i = 0; i < w->count; i++) {
        uint32_t bits[3];
        position_bits(w->positions + 3 * i, bits);
        size_t s = (size_t)hash_position(bits) & (slot_count - 1);
        while (slots[s]) {
            s = (s + 1) & (slot_count - 1);
        }
        slots[s] = (uint32_t)i + 1;
    }
    free(w->slots);
    w->slots = slots;
    w->slot_count = slot_count;
    return true;
}

/* Room for `n` vertices without further growth; n <= SR_IO_MAX_VERTICES. */
static bool welder_reserve(welder *w, size_t n)
{
    if (n > w->cap) {
        float *p = realloc(w->positions, n * 3 * sizeof *p);
        if (!p) {
            return false;
        }
        w->positions = p;
        w->cap = n;
    }
    /* Keep the table at most half full so probes stay short. */
    size_t slots = w->slot_count ? w->slot_count : 64;
    while (slots < 2 * n) {
        slots *= 2;
    }
    return slots == w->slot_count || welder_rehash(w, slots);
}

/* The index of position p, adding it if new. */
static sr_result welder_add(welder *w, const float *p, uint32_t *index)
{
    uint32_t bits[3];
    position_bits(p, bits);
    if (w->slot_count) {
        size_t s = (size_t)hash_position(bits) & (w->slot_count - 1);
        while (w->slots[s]) {
            uint32_t other[3];
            position_bits(w->positions + 3 * (size_t)(w->slots[s] - 1), other);
            if (memcmp(bits, other, sizeof bits) == 0) {
                *index = w->slots[s] - 1;
                return SR_OK;
            }
            s = (s + 1) & (w->slot_count - 1);
        }
    }
    if (w->count >= SR_IO_MAX_VERTICES) {
        return SR_TOO_LARGE;
    }
    if (w->count + 1 > w->cap || 2 * (w->count + 1) > w->slot_count) {
        size_t want = w->cap ? 2 * w->cap : 1024;
        if (want > SR_IO_MAX_VERTICES) {
            want = SR_IO_MAX_VERTICES;
        }
        if (want < w->count + 1) {
            want = w->count + 1;
        }
        if (!welder_reserve(w, want)) {
            return SR_OUT_OF_MEMORY;
        }
    }
    /* Reserve may have rehashed: find the empty slot afresh. */
    size_t s = (size_t)hash_position(bits) & (w->slot_count - 1);
    while (w->slots[s]) {
        s = (s + 1) & (w->slot_count - 1);
    }
    memcpy(w->positions + 3 * w->count, p, 3 * sizeof(float));
    w->slots[s] = (uint32_t)w->count + 1;
    *index = (uint32_t)w->count++;
    return SR_OK;
}

/* The growing output: welded vertices plus triangles. */
typedef struct stl_builder {
    welder weld;
    uint32_t *indices;
    size_t triangle_count, index_cap;
} stl_builder;

static void builder_free(stl_builder *b)
{
    free(b->weld.positions);
    free(b->weld.slots);
    free(b->indices);
    memset(b, 0, sizeof *b);
}

static sr_result builder_triangle(stl_builder *b, const uint32_t tri[3])
{
    if (b->triangle_count >= SR_IO_MAX_TRIANGLES) {
        return SR_TOO_LARGE;
    }
    if (3 * b->triangle_count + 3 > b->index_cap) {
        size_t cap = b->index_cap ? 2 * b->index_cap : 3 * 1024;
        uint32_t *idx = realloc(b->indices, cap * sizeof *idx);
        if (!idx) {
            return SR_OUT_OF_MEMORY;
        }
        b->indices = idx;
        b->index_cap = cap;
    }
    memcpy(b->indices + 3 * b->triangle_count++, tri, 3 * sizeof *tri);
    return SR_OK;
}

/* Hand the builder's arrays to *out, trimmed to size. */
static void builder_finish(stl_builder *b, sr_mesh *out)
{
    float *p = realloc(b->weld.positions, b->weld.count * 3 * sizeof *p);
    uint32_t *idx = realloc(b->indices, b->triangle_count * 3 * sizeof *idx);
    out->positions = p ? p : b->weld.positions;
    out->indices = idx ? idx : b->indices;
    out->vertex_count = b->weld.count;
    out->triangle_count = b->triangle_count;
    free(b->weld.slots);
    memset(b, 0, sizeof *b);
}

static const char *result_what(sr_result r)
{
    return r == SR_TOO_LARGE ? "more vertices or triangles than the reader's limit"
                             : "out of memory";
}

/* ---- binary ------------------------------------------------------------- */

static bool binary_size_matches(const uint8_t *data, size_t size)
{
    if (size < STL_PREFIX_BYTES) {
        return false;
    }
    uint64_t count = sr__le32(data + STL_HEADER_BYTES);
    return STL_PREFIX_BYTES + STL_TRIANGLE_BYTES * count == (uint64_t)size;
}

static sr_result parse_binary(const char *name, const uint8_t *data, size_t size,
                              sr_mesh *out, sr_io_error *err)
{
    if (size < STL_PREFIX_BYTES) {
        return sr__io_fail(err, SR_BAD_FORMAT, name, 0,
                           "not an STL file (%zu bytes: too short for a binary STL's "
                           "84-byte header, and no 'solid' at the start)", size);
    }
    uint32_t count = sr__le32(data + STL_HEADER_BYTES);
    uint64_t expected = STL_PREFIX_BYTES + STL_TRIANGLE_BYTES * (uint64_t)count;
    if (expected != (uint64_t)size) {
        return sr__io_fail_at(err, SR_BAD_FORMAT, name, STL_HEADER_BYTES,
                              "binary STL declares %lu triangles, which take %llu bytes, "
                              "but the file has %zu bytes (%s)", (unsigned long)count,
                              (unsigned long long)expected, size,
                              expected > size ? "truncated" : "trailing data");
    }
    if (count == 0) {
        return sr__io_fail(err, SR_BAD_FORMAT, name, 0, "contains no faces");
    }
    if (count > SR_IO_MAX_TRIANGLES) {
        return sr__io_fail_at(err, SR_TOO_LARGE, name, STL_HEADER_BYTES,
                              "%lu triangles exceed the limit of %zu",
                              (unsigned long)count, (size_t)SR_IO_MAX_TRIANGLES);
    }

    stl_builder b = { 0 };
    /* Closed meshes have about half as many vertices as triangles; start
     * there and let the welder grow if the model is a triangle soup. */
    size_t guess = count / 2 + 16;
    if (guess > SR_IO_MAX_VERTICES) {
        guess = SR_IO_MAX_VERTICES;
    }
    b.indices = malloc((size_t)count * 3 * sizeof *b.indices);
    b.index_cap = (size_t)count * 3;
    if (!b.indices || !welder_reserve(&b.weld, guess)) {
        builder_free(&b);
        return sr__io_fail(err, SR_OUT_OF_MEMORY, name, 0, "out of memory for %lu triangles",
                           (unsigned long)count);
    }
    for (size_t t = 0; t < count; t++) {
        /* The facet normal (the first 12 bytes) and the attribute word
         * (the last 2) are not used. */
        const uint8_t *rec = data + STL_PREFIX_BYTES + t * STL_TRIANGLE_BYTES;
        uint32_t tri[3];
        for (int k = 0; k < 3; k++) {
            const uint8_t *c = rec + 12 + 12 * k;
            float p[3] = { sr__le_float(c), sr__le_float(c + 4), sr__le_float(c + 8) };
            for (int a = 0; a < 3; a++) {
                if (!isfinite(p[a])) {
                    builder_free(&b);
                    return sr__io_fail_at(err, SR_BAD_FORMAT, name,
                                          (unsigned long long)(c + 4 * a - data),
                                          "triangle %zu: vertex coordinate is not finite", t);
                }
            }
            sr_result res = welder_add(&b.weld, p, &tri[k]);
            if (res != SR_OK) {
                builder_free(&b);
                return sr__io_fail_at(err, res, name, (unsigned long long)(c - data),
                                      "triangle %zu: %s", t, result_what(res));
            }
        }
        sr_result res = builder_triangle(&b, tri);
        if (res != SR_OK) {
            builder_free(&b);
            return sr__io_fail_at(err, res, name, (unsigned long long)(rec - data),
                                  "triangle %zu: %s", t, result_what(res));
        }
    }
    builder_finish(&b, out);
    return SR_OK;
}

/* ---- ASCII -------------------------------------------------------------- */

typedef struct stl_lexer {
    const char *name;
    const uint8_t *data;
    size_t size, pos;
    long line;          /* line of the word last returned */
    long next_line;     /* line `pos` is on */
    char word[64];      /* the word, NUL-terminated, cut at 63 bytes */
    size_t word_len;    /* full length, even when cut */
    sr_io_error *err;
} stl_lexer;

static bool is_space(uint8_t c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* Next whitespace-separated word; false at the end of the data. */
static bool lex_word(stl_lexer *lx)
{
    while (lx->pos < lx->size && is_space(lx->data[lx->pos])) {
        if (lx->data[lx->pos] == '\n') {
            lx->next_line++;
        }
        lx->pos++;
    }
    if (lx->pos == lx->size) {
        /* Leave `line` on the last word: "end of file" is reported
         * where the text stops, not on the empty line after it. */
        lx->word[0] = 0;
        lx->word_len = 0;
        return false;
    }
    lx->line = lx->next_line;
    size_t start = lx->pos;
    while (lx->pos < lx->size && !is_space(lx->data[lx->pos])) {
        lx->pos++;
    }
    lx->word_len = lx->pos - start;
    size_t n = lx->word_len < sizeof lx->word ? lx->word_len : sizeof lx->word - 1;
    memcpy(lx->word, lx->data + start, n);
    lx->word[n] = 0;
    return true;
}

/* Skip the rest of the current line (solid and endsolid names). */
static void lex_skip_line(stl_lexer *lx)
{
    while (lx->pos < lx->size && lx->data[lx->pos] != '\n') {
        lx->pos++;
    }
}

/* Keywords are compared ignoring case: some CAD exporters shout. */
static bool word_is(const stl_lexer *lx, const char *kw)
{
    return lx->word_len == strlen(kw) && strcasecmp(lx->word, kw) == 0;
}

static sr_result expect(stl_lexer *lx, const char *kw)
{
    if (!lex_word(lx)) {
        return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                           "unexpected end of file, expected '%s'", kw);
    }
    if (!word_is(lx, kw)) {
        return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                           "expected '%s', found '%s'", kw, lx->word);
    }
    return SR_OK;
}

static sr_result read_float(stl_lexer *lx, float *out)
{
    if (!lex_word(lx)) {
        return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                           "unexpected end of file, expected a number");
    }
    /* inf, nan and 1e39 come back as values; the caller decides. */
    if (lx->word_len >= sizeof lx->word ||
        sr__parse_float(lx->word, lx->word + lx->word_len, out) == SR_NUM_MALFORMED) {
        return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                           "expected a number, found '%s'", lx->word);
    }
    return SR_OK;
}

static sr_result read_facet(stl_lexer *lx, stl_builder *b)
{
    /* "facet" has been read.  "normal nx ny nz" is required by the format
     * but some writers drop it; its values are not used either way. */
    if (!lex_word(lx)) {
        return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                           "unexpected end of file inside a facet");
    }
    if (word_is(lx, "normal")) {
        float n;
        for (int k = 0; k < 3; k++) {
            sr_result res = read_float(lx, &n);
            if (res != SR_OK) {
                return res;
            }
        }
        if (!lex_word(lx)) {
            return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                               "unexpected end of file, expected 'outer'");
        }
    }
    if (!word_is(lx, "outer")) {
        return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                           "expected 'outer', found '%s'", lx->word);
    }
    sr_result res = expect(lx, "loop");
    if (res != SR_OK) {
        return res;
    }
    /* Three corners per the format; a longer loop is taken as a convex
     * polygon and fanned, rather than rejected. */
    uint32_t first = 0, prev = 0;
    int corners = 0;
    for (;;) {
        if (!lex_word(lx)) {
            return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                               "unexpected end of file, expected 'vertex' or 'endloop'");
        }
        if (word_is(lx, "endloop")) {
            break;
        }
        if (!word_is(lx, "vertex")) {
            return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                               "expected 'vertex' or 'endloop', found '%s'", lx->word);
        }
        float p[3];
        for (int k = 0; k < 3; k++) {
            res = read_float(lx, &p[k]);
            if (res != SR_OK) {
                return res;
            }
            if (!isfinite(p[k])) {
                /* 1e39 is a finite number, only not a float. */
                double v = 0;
                bool finite = sr__parse_double(lx->word, lx->word + lx->word_len, &v) !=
                              SR_NUM_NOT_FINITE;
                return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                                   finite ? "vertex coordinate '%s' is beyond float's range"
                                          : "vertex coordinate '%s' is not finite",
                                   lx->word);
            }
        }
        uint32_t index;
        res = welder_add(&b->weld, p, &index);
        if (res == SR_OK && corners >= 2) {
            res = builder_triangle(b, (uint32_t[3]){ first, prev, index });
        }
        if (res != SR_OK) {
            return sr__io_fail(lx->err, res, lx->name, lx->line, "%s", result_what(res));
        }
        if (corners == 0) {
            first = index;
        }
        prev = index;
        corners++;
    }
    if (corners < 3) {
        return sr__io_fail(lx->err, SR_BAD_FORMAT, lx->name, lx->line,
                           "facet has %d vertices; it needs 3", corners);
    }
    return expect(lx, "endfacet");
}

static sr_result parse_ascii(const char *name, const uint8_t *data, size_t size,
                             sr_mesh *out, sr_io_error *err)
{
    stl_lexer lx = { .name = name, .data = data, .size = size, .line = 1,
                     .next_line = 1, .err = err };
    stl_builder b = { 0 };
    sr_result res = expect(&lx, "solid");
    /* Some tools concatenate several solids into one file; read them all. */
    while (res == SR_OK) {
        lex_skip_line(&lx); /* the solid's name */
        for (;;) {
            if (!lex_word(&lx)) {
                res = sr__io_fail(err, SR_BAD_FORMAT, name, lx.line,
                                  "unexpected end of file, expected 'endsolid'");
                break;
            }
            if (word_is(&lx, "endsolid")) {
                lex_skip_line(&lx);
                break;
            }
            if (!word_is(&lx, "facet")) {
                res = sr__io_fail(err, SR_BAD_FORMAT, name, lx.line,
                                  "expected 'facet' or 'endsolid', found '%s'", lx.word);
                break;
            }
            res = read_facet(&lx, &b);
            if (res != SR_OK) {
                break;
            }
        }
        if (res != SR_OK || !lex_word(&lx)) {
            break; /* an error, or the end of the file after endsolid */
        }
        if (!word_is(&lx, "solid")) {
            res = sr__io_fail(err, SR_BAD_FORMAT, name, lx.line,
                              "expected 'solid' or the end of the file after 'endsolid', "
                              "found '%s'", lx.word);
        }
    }
    if (res == SR_OK && b.triangle_count == 0) {
        res = sr__io_fail(err, SR_BAD_FORMAT, name, 0, "contains no faces");
    }
    if (res != SR_OK) {
        builder_free(&b);
        return res;
    }
    builder_finish(&b, out);
    return SR_OK;
}

/* ---- entry points ------------------------------------------------------- */

static bool starts_with_solid(const uint8_t *data, size_t size)
{
    size_t i = 0;
    while (i < size && is_space(data[i])) {
        i++;
    }
    return size - i >= 5 && strncasecmp((const char *)data + i, "solid", 5) == 0 &&
           (size - i == 5 || is_space(data[i + 5]));
}

/* Binary if the size rule holds, even when the 80-byte header begins with
 * "solid" (many exporters write that).  Otherwise ASCII when it begins
 * with "solid" and is text: a NUL or control byte means a binary file
 * whose size is wrong, which deserves a binary size message rather than
 * a confusing ASCII syntax error. */
static bool looks_binary(const uint8_t *data, size_t size)
{
    if (binary_size_matches(data, size)) {
        return true;
    }
    if (!starts_with_solid(data, size)) {
        return true;
    }
    for (size_t i = 0; i < size; i++) {
        uint8_t c = data[i];
        if (c < 0x20 && !is_space(c)) {
            return true;
        }
    }
    return false;
}

sr_result sr__parse_stl(const char *name, const uint8_t *data, size_t size,
                        sr_mesh *out, sr_io_error *err)
{
    if (!name) {
        name = "<input>";
    }
    if (!out) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0, "no output mesh given");
    }
    memset(out, 0, sizeof *out);
    if (!data && size > 0) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0, "no data given");
    }
    if (!data) {
        data = (const uint8_t *)"";
    }
    if (looks_binary(data, size)) {
        return parse_binary(name, data, size, out, err);
    }
    return parse_ascii(name, data, size, out, err);
}

sr_result sr__load_stl(const char *path, sr_mesh *out, sr_io_error *err)
{
    return sr__load_file_with(path, sr__parse_stl, out, err);
}
