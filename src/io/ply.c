/*
 * ply.c - io stage: the PLY (Stanford polygon file) model reader.
 * Consumes a whole file in memory: ASCII, binary little- or big-endian.
 * Produces an sr_mesh of triangles (polygons fan-split, strips unrolled).
 * No shared state: any thread may call it.
 *
 * A PLY file is a text header that declares elements (a name and a count)
 * and their properties (a scalar type, or a list of a count type and an
 * item type), then the data of each element in header order.  We read
 * `vertex` (x y z, normals, colors, texcoords), `face` and `tristrips`, and
 * step over everything else.  The data must end with the last element
 * (ASCII: but for whitespace): anything after it is an error, not dropped.
 */
#include "io/io_util.h"
#include "io/number.h"
#include "io/readers.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- types and roles ---------------------------------------------------- */

typedef enum ply_type {
    T_NONE = 0,
    T_INT8,
    T_UINT8,
    T_INT16,
    T_UINT16,
    T_INT32,
    T_UINT32,
    T_FLOAT32,
    T_FLOAT64,
} ply_type;

static const struct {
    const char *name;
    ply_type type;
} type_names[] = {
    /* The original 1994 names, then the sized names later writers use. */
    { "char", T_INT8 },     { "uchar", T_UINT8 },   { "short", T_INT16 },
    { "ushort", T_UINT16 }, { "int", T_INT32 },     { "uint", T_UINT32 },
    { "float", T_FLOAT32 }, { "double", T_FLOAT64 },
    { "int8", T_INT8 },     { "uint8", T_UINT8 },   { "int16", T_INT16 },
    { "uint16", T_UINT16 }, { "int32", T_INT32 },   { "uint32", T_UINT32 },
    { "float32", T_FLOAT32 }, { "float64", T_FLOAT64 },
};

static const size_t type_size[] = { 0, 1, 1, 2, 2, 4, 4, 4, 8 };
static const char *const type_label[] = {
    "none", "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64",
};
static const double type_min[] = { 0, -128.0, 0, -32768.0, 0, -2147483648.0, 0, 0, 0 };
static const double type_max[] = { 0, 127.0, 255.0, 32767.0, 65535.0, 2147483647.0,
                                   4294967295.0, 0, 0 };

static bool is_integer_type(ply_type t)
{
    return t >= T_INT8 && t <= T_UINT32;
}

/* Full intensity of an integer color channel: the unsigned maximum of its
 * width, whether or not the writer declared the type signed. */
static double color_max(ply_type t)
{
    return type_size[t] == 1 ? 255.0 : type_size[t] == 2 ? 65535.0 : 4294967295.0;
}

/* What a property feeds.  Vertex attributes index vertex_values[]. */
enum {
    R_SKIP = 0,
    R_X, R_Y, R_Z,
    R_NX, R_NY, R_NZ,
    R_RED, R_GREEN, R_BLUE, R_ALPHA,
    R_U, R_V,
    R_INDICES,
    ROLE_COUNT
};

static const struct {
    const char *name;
    int role;
} vertex_names[] = {
    { "x", R_X },         { "y", R_Y },         { "z", R_Z },
    { "nx", R_NX },       { "ny", R_NY },       { "nz", R_NZ },
    { "red", R_RED },     { "green", R_GREEN }, { "blue", R_BLUE },
    { "alpha", R_ALPHA },
    { "diffuse_red", R_RED }, { "diffuse_green", R_GREEN }, { "diffuse_blue", R_BLUE },
    { "u", R_U },         { "v", R_V },
    { "s", R_U },         { "t", R_V },
    { "texture_u", R_U }, { "texture_v", R_V },
    { "texture_s", R_U }, { "texture_t", R_V },
};

typedef enum elem_kind { K_OTHER = 0, K_VERTEX, K_FACE, K_STRIPS } elem_kind;
typedef enum ply_format { F_NONE = 0, F_ASCII, F_LE, F_BE } ply_format;

#define NAME_MAX_LEN 64 /* element and property names, with the NUL */

typedef struct ply_prop {
    ply_type type;        /* the scalar's type, or a list's item type */
    ply_type count_type;  /* T_NONE for a scalar */
    int role;
    float scale;          /* colors: integer -> [0, 1]; 1 otherwise */
    long line;            /* header line, for messages */
} ply_prop;

typedef struct ply_elem {
    char name[NAME_MAX_LEN];
    unsigned long long count;
    elem_kind kind;
    long line;
    ply_prop *props;
    size_t prop_count, prop_cap;
} ply_elem;

typedef struct ply_reader {
    const char *name;
    const uint8_t *data;
    size_t size;
    size_t pos;
    ply_format format;
    long line;               /* ASCII: the line `pos` is on */
    sr_io_error *err;

    ply_elem *elems;
    size_t elem_count, elem_cap;

    /* Where the value just read started, so that a value found wrong after
     * reading it (an index out of range) is reported where it is. */
    size_t value_pos;
    long value_line;

    unsigned long long vertex_count;
    bool has_normals, has_colors, has_texcoords;

    sr_mesh mesh;            /* being built; freed on failure */
    size_t index_cap;
} ply_reader;

/* ---- messages ----------------------------------------------------------- */

/* A problem in the data: line of the file for ASCII, byte offset of the
 * offending value for binary. */
__attribute__((format(printf, 3, 4)))
static sr_result data_fail(ply_reader *r, sr_result code, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (r->format == F_ASCII) {
        return sr__io_fail(r->err, code, r->name, r->value_line, "%s", msg);
    }
    return sr__io_fail_at(r->err, code, r->name, (unsigned long long)r->value_pos, "%s", msg);
}

/* ---- header ------------------------------------------------------------- */

typedef struct token {
    const char *s;
    size_t n;
} token;

static bool tok_is(token t, const char *word)
{
    size_t n = strlen(word);
    return t.n == n && memcmp(t.s, word, n) == 0;
}

static ply_type parse_type(token t)
{
    for (size_t i = 0; i < sizeof type_names / sizeof type_names[0]; i++) {
        if (tok_is(t, type_names[i].name)) {
            return type_names[i].type;
        }
    }
    return T_NONE;
}

/* Split one header line into words; returns how many (at most `max`,
 * with the rest counted but not stored). */
static size_t split_words(const char *s, size_t n, token *out, size_t max)
{
    size_t count = 0, i = 0;
    while (i < n) {
        while (i < n && (s[i] == ' ' || s[i] == '\t')) {
            i++;
        }
        if (i == n) {
            break;
        }
        size_t start = i;
        while (i < n && s[i] != ' ' && s[i] != '\t') {
            i++;
        }
        if (count < max) {
            out[count] = (token){ s + start, i - start };
        }
        count++;
    }
    return count;
}

static sr_result add_element(ply_reader *r, token name, token count_tok)
{
    if (name.n >= NAME_MAX_LEN) {
        return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                           "element name is longer than %d characters", NAME_MAX_LEN - 1);
    }
    /* Plain decimal digits only: strtoull would take "-1" as 2^64 - 1. */
    unsigned long long count = 0;
    if (count_tok.n == 0) {
        return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line, "element count missing");
    }
    for (size_t i = 0; i < count_tok.n; i++) {
        char c = count_tok.s[i];
        if (c < '0' || c > '9') {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "element count '%.*s' is not a non-negative integer",
                               (int)(count_tok.n > 40 ? 40 : count_tok.n), count_tok.s);
        }
        if (count > (ULLONG_MAX - 9) / 10) {
            return sr__io_fail(r->err, SR_TOO_LARGE, r->name, r->line,
                               "element count '%.*s' is too large",
                               (int)(count_tok.n > 40 ? 40 : count_tok.n), count_tok.s);
        }
        count = count * 10 + (unsigned long long)(c - '0');
    }
    if (r->elem_count == r->elem_cap) {
        size_t cap = r->elem_cap ? 2 * r->elem_cap : 8;
        ply_elem *e = realloc(r->elems, cap * sizeof *e);
        if (!e) {
            return sr__io_fail(r->err, SR_OUT_OF_MEMORY, r->name, 0, "out of memory");
        }
        r->elems = e;
        r->elem_cap = cap;
    }
    ply_elem *e = &r->elems[r->elem_count++];
    memset(e, 0, sizeof *e);
    memcpy(e->name, name.s, name.n);
    e->name[name.n] = 0;
    e->count = count;
    e->line = r->line;
    return SR_OK;
}

static sr_result add_property(ply_reader *r, const token *w, size_t words)
{
    if (r->elem_count == 0) {
        return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                           "property declared before any element");
    }
    ply_prop p = { .line = r->line, .scale = 1.0f };
    token name;
    if (words >= 2 && tok_is(w[1], "list")) {
        if (words != 5) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
        }
        p.count_type = parse_type(w[2]);
        p.type = parse_type(w[3]);
        token bad = p.count_type == T_NONE ? w[2] : w[3];
        if (p.count_type == T_NONE || p.type == T_NONE) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "unknown type '%.*s'", (int)(bad.n > 40 ? 40 : bad.n), bad.s);
        }
        if (!is_integer_type(p.count_type)) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "list count type must be an integer type, not %s",
                               type_label[p.count_type]);
        }
        name = w[4];
    } else {
        if (words != 3) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "expected 'property TYPE NAME'");
        }
        p.type = parse_type(w[1]);
        if (p.type == T_NONE) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line, "unknown type '%.*s'",
                               (int)(w[1].n > 40 ? 40 : w[1].n), w[1].s);
        }
        name = w[2];
    }

    ply_elem *e = &r->elems[r->elem_count - 1];
    /* Roles are decided here, from the element's name, because the element
     * line comes first; a second x or u is read but not used. */
    bool is_vertex = strcmp(e->name, "vertex") == 0;
    bool is_face = strcmp(e->name, "face") == 0;
    bool is_strips = strcmp(e->name, "tristrips") == 0;
    if (is_vertex) {
        for (size_t i = 0; i < sizeof vertex_names / sizeof vertex_names[0]; i++) {
            if (tok_is(name, vertex_names[i].name)) {
                p.role = vertex_names[i].role;
                break;
            }
        }
        for (size_t i = 0; p.role != R_SKIP && i < e->prop_count; i++) {
            if (e->props[i].role == p.role) {
                p.role = R_SKIP;
            }
        }
        if (p.role != R_SKIP && p.count_type != T_NONE) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "vertex property '%.*s' must be a scalar, not a list",
                               (int)name.n, name.s);
        }
        if (p.role >= R_RED && p.role <= R_ALPHA && is_integer_type(p.type)) {
            /* 8-bit colors are the common case (0..255); wider integer
             * types are scaled by their own maximum the same way. */
            p.scale = (float)(1.0 / color_max(p.type));
        }
    } else if ((is_face && (tok_is(name, "vertex_indices") || tok_is(name, "vertex_index"))) ||
               (is_strips && tok_is(name, "vertex_indices"))) {
        if (p.count_type == T_NONE) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "'%.*s' must be a list property", (int)name.n, name.s);
        }
        if (!is_integer_type(p.type)) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "vertex indices must have an integer type, not %s",
                               type_label[p.type]);
        }
        for (size_t i = 0; i < e->prop_count; i++) {
            if (e->props[i].role == R_INDICES) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                                   "element '%s' has two vertex index lists", e->name);
            }
        }
        p.role = R_INDICES;
    }

    if (e->prop_count == e->prop_cap) {
        size_t cap = e->prop_cap ? 2 * e->prop_cap : 8;
        ply_prop *props = realloc(e->props, cap * sizeof *props);
        if (!props) {
            return sr__io_fail(r->err, SR_OUT_OF_MEMORY, r->name, 0, "out of memory");
        }
        e->props = props;
        e->prop_cap = cap;
    }
    e->props[e->prop_count++] = p;
    return SR_OK;
}

/* The header is text whatever the data format; `r->line` counts its lines
 * so that messages about it, and about ASCII data, give file lines. */
static sr_result parse_header(ply_reader *r)
{
    bool seen_end = false;
    r->pos = 0;
    r->line = 0;
    while (!seen_end) {
        const char *s = (const char *)r->data + r->pos;
        const void *nl = memchr(s, '\n', r->size - r->pos);
        if (!nl) {
            if (r->line == 0) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, 0,
                                   "not a PLY file (the first line must be 'ply')");
            }
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line + 1,
                               "file ends inside the header (no 'end_header')");
        }
        size_t n = (size_t)((const char *)nl - s);
        r->pos += n + 1;
        r->line++;
        /* Tolerate CRLF headers; the data after end_header is not touched. */
        if (n > 0 && s[n - 1] == '\r') {
            n--;
        }
        /* The header is text: a NUL would end a quoted word early, and the
         * message quote a word that looks right ("count '3' is not..."). */
        if (memchr(s, 0, n)) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "a NUL byte in the header (a PLY header is text)");
        }
        token w[6];
        size_t words = split_words(s, n, w, 6);
        if (r->line == 1) {
            if (words != 1 || !tok_is(w[0], "ply")) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, 0,
                                   "not a PLY file (the first line must be 'ply')");
            }
            continue;
        }
        if (words == 0 || tok_is(w[0], "comment") || tok_is(w[0], "obj_info")) {
            continue;
        }
        sr_result res = SR_OK;
        if (tok_is(w[0], "format")) {
            if (r->format != F_NONE) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                                   "second 'format' line");
            }
            if (words != 3) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                                   "expected 'format KIND 1.0'");
            }
            if (tok_is(w[1], "ascii")) {
                r->format = F_ASCII;
            } else if (tok_is(w[1], "binary_little_endian")) {
                r->format = F_LE;
            } else if (tok_is(w[1], "binary_big_endian")) {
                r->format = F_BE;
            } else {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                                   "unknown format '%.*s' (expected ascii, "
                                   "binary_little_endian or binary_big_endian)",
                                   (int)(w[1].n > 40 ? 40 : w[1].n), w[1].s);
            }
            if (!tok_is(w[2], "1.0") && !tok_is(w[2], "1")) {
                return sr__io_fail(r->err, SR_UNSUPPORTED, r->name, r->line,
                                   "PLY version '%.*s' is not supported (only 1.0)",
                                   (int)(w[2].n > 40 ? 40 : w[2].n), w[2].s);
            }
        } else if (tok_is(w[0], "element")) {
            if (words != 3) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                                   "expected 'element NAME COUNT'");
            }
            res = add_element(r, w[1], w[2]);
        } else if (tok_is(w[0], "property")) {
            res = add_property(r, w, words > 6 ? 6 : words);
            if (res == SR_OK && words > 6) {
                res = sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                                  "too many words in a property line");
            }
        } else if (tok_is(w[0], "end_header")) {
            if (words != 1) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                                   "unexpected words after 'end_header'");
            }
            seen_end = true;
        } else {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "unknown header keyword '%.*s'",
                               (int)(w[0].n > 40 ? 40 : w[0].n), w[0].s);
        }
        if (res != SR_OK) {
            return res;
        }
    }
    if (r->format == F_NONE) {
        return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                           "header has no 'format' line");
    }
    return SR_OK;
}

/* Give each element its kind, check what the mesh needs is there, and
 * check every declared count against the bytes that follow the header, so
 * that nothing is allocated from a count the file cannot back. */
static sr_result check_elements(ply_reader *r)
{
    const ply_elem *vertex = NULL;
    bool has_faces = false;
    size_t remaining = r->size - r->pos;
    unsigned long long needed = 0;

    for (size_t i = 0; i < r->elem_count; i++) {
        ply_elem *e = &r->elems[i];
        for (size_t j = 0; j < i; j++) {
            if (strcmp(r->elems[j].name, e->name) == 0) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, e->line,
                                   "element '%s' is declared twice", e->name);
            }
        }
        int roles = 0;
        for (size_t j = 0; j < e->prop_count; j++) {
            roles |= 1 << e->props[j].role;
        }
        if (strcmp(e->name, "vertex") == 0) {
            e->kind = K_VERTEX;
            vertex = e;
            int xyz = (1 << R_X) | (1 << R_Y) | (1 << R_Z);
            if ((roles & xyz) != xyz) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, e->line,
                                   "element 'vertex' lacks one of the properties x, y, z");
            }
            int nxyz = (1 << R_NX) | (1 << R_NY) | (1 << R_NZ);
            int rgb = (1 << R_RED) | (1 << R_GREEN) | (1 << R_BLUE);
            int uv = (1 << R_U) | (1 << R_V);
            /* Half a normal or color is ignored rather than guessed at. */
            r->has_normals = (roles & nxyz) == nxyz;
            r->has_colors = (roles & rgb) == rgb;
            r->has_texcoords = (roles & uv) == uv;
            if (e->count > SR_IO_MAX_VERTICES) {
                return sr__io_fail(r->err, SR_TOO_LARGE, r->name, e->line,
                                   "%llu vertices exceed the limit of %zu",
                                   e->count, (size_t)SR_IO_MAX_VERTICES);
            }
        } else if (strcmp(e->name, "face") == 0 || strcmp(e->name, "tristrips") == 0) {
            e->kind = e->name[0] == 'f' ? K_FACE : K_STRIPS;
            if (!(roles & (1 << R_INDICES))) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, e->line,
                                   "element '%s' has no vertex_indices list", e->name);
            }
            /* Every face yields at least one triangle. */
            if (e->kind == K_FACE && e->count > SR_IO_MAX_TRIANGLES) {
                return sr__io_fail(r->err, SR_TOO_LARGE, r->name, e->line,
                                   "%llu faces exceed the limit of %zu triangles",
                                   e->count, (size_t)SR_IO_MAX_TRIANGLES);
            }
            has_faces |= e->count > 0;
        }

        /* Least bytes one entry can take: binary, each scalar's size and
         * each list's count (lists may be empty); ASCII, one character and
         * one separator per value. */
        unsigned long long least = 0;
        for (size_t j = 0; j < e->prop_count; j++) {
            const ply_prop *p = &e->props[j];
            if (r->format == F_ASCII) {
                least += 2;
            } else {
                least += type_size[p->count_type != T_NONE ? p->count_type : p->type];
            }
        }
        unsigned long long bytes;
        if (__builtin_mul_overflow(least, e->count, &bytes) ||
            __builtin_add_overflow(needed, bytes, &needed) ||
            needed > (unsigned long long)remaining + (r->format == F_ASCII ? 1 : 0)) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, e->line,
                               "element '%s' declares %llu entries, more than the %zu "
                               "bytes after the header can hold",
                               e->name, e->count, remaining);
        }
    }
    if (!vertex) {
        return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                           "header declares no 'vertex' element");
    }
    if (!has_faces) {
        return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, 0, "contains no faces");
    }
    r->vertex_count = vertex->count;
    return SR_OK;
}

/* ---- data --------------------------------------------------------------- */

static uint64_t load_bytes(const uint8_t *p, size_t n, bool big_endian)
{
    uint64_t v = 0;
    for (size_t i = 0; i < n; i++) {
        size_t k = big_endian ? i : n - 1 - i;
        v = (v << 8) | p[k];
    }
    return v;
}

static double decode_binary(const uint8_t *p, ply_type t, bool big_endian)
{
    uint64_t bits = load_bytes(p, type_size[t], big_endian);
    switch (t) {
    case T_INT8:
        return (int8_t)(uint8_t)bits;
    case T_UINT8:
        return (uint8_t)bits;
    case T_INT16:
        return (int16_t)(uint16_t)bits;
    case T_UINT16:
        return (uint16_t)bits;
    case T_INT32:
        return (int32_t)(uint32_t)bits;
    case T_UINT32:
        return (uint32_t)bits;
    case T_FLOAT32: {
        uint32_t b32 = (uint32_t)bits;
        float f;
        memcpy(&f, &b32, sizeof f);
        return f;
    }
    case T_FLOAT64: {
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    case T_NONE:
        break;
    }
    return 0.0;
}

static bool is_space(uint8_t c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* Next whitespace-separated ASCII word; false at the end of the data. */
static bool next_word(ply_reader *r, token *out)
{
    while (r->pos < r->size && is_space(r->data[r->pos])) {
        if (r->data[r->pos] == '\n') {
            r->line++;
        }
        r->pos++;
    }
    r->value_pos = r->pos;
    if (r->pos == r->size) {
        /* value_line stays on the last word read: "file ends" is
         * reported where the text stops. */
        return false;
    }
    r->value_line = r->line;
    size_t start = r->pos;
    while (r->pos < r->size && !is_space(r->data[r->pos])) {
        r->pos++;
    }
    *out = (token){ (const char *)r->data + start, r->pos - start };
    return true;
}

/* Read one value of type t as a double (exact for every PLY integer). */
static sr_result read_value(ply_reader *r, const ply_elem *e, unsigned long long index,
                            ply_type t, double *out)
{
    if (r->format != F_ASCII) {
        size_t n = type_size[t];
        r->value_pos = r->pos;
        if (r->size - r->pos < n) {
            return data_fail(r, SR_BAD_FORMAT,
                             "file ends inside %s %llu (of %llu): needs %zu more bytes, has %zu",
                             e->name, index, e->count, n, r->size - r->pos);
        }
        *out = decode_binary(r->data + r->pos, t, r->format == F_BE);
        r->pos += n;
        return SR_OK;
    }

    token w;
    if (!next_word(r, &w)) {
        return data_fail(r, SR_BAD_FORMAT, "file ends inside %s %llu (of %llu)",
                         e->name, index, e->count);
    }
    char buf[64];
    if (w.n >= sizeof buf) {
        return data_fail(r, SR_BAD_FORMAT, "%s %llu: number too long", e->name, index);
    }
    memcpy(buf, w.s, w.n);
    buf[w.n] = 0;
    char *end;
    errno = 0;
    if (is_integer_type(t)) {
        long long v = strtoll(buf, &end, 10);
        if (end != buf + w.n || errno == ERANGE || (double)v < type_min[t] ||
            (double)v > type_max[t]) {
            return data_fail(r, SR_BAD_FORMAT, "%s %llu: '%s' is not a valid %s",
                             e->name, index, buf, type_label[t]);
        }
        *out = (double)v;
    } else {
        /* inf and nan are kept, and rejected where finiteness matters. */
        sr_num_status st;
        if (t == T_FLOAT32) {
            float f = 0;
            st = sr__parse_float(w.s, w.s + w.n, &f);
            *out = f;
        } else {
            st = sr__parse_double(w.s, w.s + w.n, out);
        }
        if (st == SR_NUM_MALFORMED) {
            return data_fail(r, SR_BAD_FORMAT, "%s %llu: '%s' is not a valid %s",
                             e->name, index, buf, type_label[t]);
        }
        if (st == SR_NUM_OVERFLOW) {
            /* Digits that overflowed (1e39 for a float, 1e999), not the
             * words inf or nan: say so rather than "not finite". */
            return data_fail(r, SR_BAD_FORMAT, "%s %llu: '%s' is beyond %s's range", e->name,
                             index, buf, type_label[t]);
        }
    }
    return SR_OK;
}

/* Step over `count` values of type t without interpreting them. */
static sr_result skip_values(ply_reader *r, const ply_elem *e, unsigned long long index,
                             ply_type t, unsigned long long count)
{
    if (r->format != F_ASCII) {
        unsigned long long bytes;
        r->value_pos = r->pos;
        if (__builtin_mul_overflow(count, (unsigned long long)type_size[t], &bytes) ||
            bytes > r->size - r->pos) {
            return data_fail(r, SR_BAD_FORMAT,
                             "file ends inside %s %llu (of %llu): a list of %llu values "
                             "runs past the end", e->name, index, e->count, count);
        }
        r->pos += (size_t)bytes;
        return SR_OK;
    }
    for (unsigned long long i = 0; i < count; i++) {
        token w;
        if (!next_word(r, &w)) {
            return data_fail(r, SR_BAD_FORMAT, "file ends inside %s %llu (of %llu)",
                             e->name, index, e->count);
        }
    }
    return SR_OK;
}

static sr_result read_list_count(ply_reader *r, const ply_elem *e, unsigned long long index,
                                 const ply_prop *p, unsigned long long *count)
{
    double v = 0.0;
    sr_result res = read_value(r, e, index, p->count_type, &v);
    if (res != SR_OK) {
        return res;
    }
    if (v < 0) {
        return data_fail(r, SR_BAD_FORMAT, "%s %llu: negative list length %.0f",
                         e->name, index, v);
    }
    *count = (unsigned long long)v;
    /* Each item takes at least a byte (binary) or two (ASCII); a length
     * the rest of the file cannot hold is reported here, not mid-list. */
    unsigned long long least = r->format == F_ASCII ? 1 : type_size[p->type];
    unsigned long long bytes;
    if (__builtin_mul_overflow(*count, least, &bytes) || bytes > r->size - r->pos) {
        return data_fail(r, SR_BAD_FORMAT,
                         "%s %llu: a list of %llu values runs past the end of the file",
                         e->name, index, *count);
    }
    return SR_OK;
}

static sr_result push_triangle(ply_reader *r, uint32_t a, uint32_t b, uint32_t c)
{
    sr_mesh *m = &r->mesh;
    if (m->triangle_count >= SR_IO_MAX_TRIANGLES) {
        return data_fail(r, SR_TOO_LARGE, "more than %zu triangles",
                         (size_t)SR_IO_MAX_TRIANGLES);
    }
    if (3 * m->triangle_count + 3 > r->index_cap) {
        size_t cap = r->index_cap ? 2 * r->index_cap : 3 * 1024;
        uint32_t *idx = realloc(m->indices, cap * sizeof *idx);
        if (!idx) {
            return data_fail(r, SR_OUT_OF_MEMORY, "out of memory for %zu triangles",
                             m->triangle_count + 1);
        }
        m->indices = idx;
        r->index_cap = cap;
    }
    uint32_t *t = m->indices + 3 * m->triangle_count++;
    t[0] = a;
    t[1] = b;
    t[2] = c;
    return SR_OK;
}

/* Read one vertex index; *restart is set for a strip restart marker, -1
 * (or all ones in an unsigned type, which is -1 written unsigned). */
static sr_result read_index(ply_reader *r, const ply_elem *e, unsigned long long index,
                            const ply_prop *p, uint32_t *out, bool *restart)
{
    double v = 0.0;
    sr_result res = read_value(r, e, index, p->type, &v);
    if (res != SR_OK) {
        return res;
    }
    *restart = false;
    if (e->kind == K_STRIPS && (v == -1.0 || (p->type == T_UINT32 && v == type_max[T_UINT32]))) {
        *restart = true;
        return SR_OK;
    }
    if (v < 0 || v >= (double)r->vertex_count) {
        return data_fail(r, SR_BAD_FORMAT,
                         "%s %llu: vertex index %.0f out of range (the file has %llu vertices)",
                         e->name, index, v, r->vertex_count);
    }
    *out = (uint32_t)v;
    return SR_OK;
}

/* A polygon of `count` corners, split into a fan around its first corner
 * (exact for convex polygons, which is what PLY writers emit). */
static sr_result read_face(ply_reader *r, const ply_elem *e, unsigned long long index,
                           const ply_prop *p)
{
    unsigned long long count;
    sr_result res = read_list_count(r, e, index, p, &count);
    if (res != SR_OK) {
        return res;
    }
    if (count < 3) {
        return data_fail(r, SR_BAD_FORMAT,
                         "face %llu has %llu vertices; a face needs at least 3", index, count);
    }
    uint32_t first = 0, prev = 0, cur = 0;
    bool restart;
    for (unsigned long long k = 0; k < count; k++) {
        res = read_index(r, e, index, p, &cur, &restart);
        if (res != SR_OK) {
            return res;
        }
        if (k == 0) {
            first = cur;
        } else if (k >= 2) {
            res = push_triangle(r, first, prev, cur);
            if (res != SR_OK) {
                return res;
            }
        }
        prev = cur;
    }
    return SR_OK;
}

/* A triangle strip with -1 restarts.  Triangle k of a run is (s[k],
 * s[k+1], s[k+2]) with the first two swapped for odd k, so every triangle
 * keeps the winding of the first; triangles with a repeated corner are the
 * writer's stitching between runs and are dropped. */
static sr_result read_strip(ply_reader *r, const ply_elem *e, unsigned long long index,
                            const ply_prop *p)
{
    unsigned long long count;
    sr_result res = read_list_count(r, e, index, p, &count);
    if (res != SR_OK) {
        return res;
    }
    uint32_t a = 0, b = 0, c = 0;
    unsigned long long run = 0; /* corners since the last restart */
    for (unsigned long long k = 0; k < count; k++) {
        bool restart;
        res = read_index(r, e, index, p, &c, &restart);
        if (res != SR_OK) {
            return res;
        }
        if (restart) {
            run = 0;
            continue;
        }
        if (run >= 2 && a != b && b != c && a != c) {
            bool odd = (run - 2) & 1;
            res = odd ? push_triangle(r, b, a, c) : push_triangle(r, a, b, c);
            if (res != SR_OK) {
                return res;
            }
        }
        a = b;
        b = c;
        run++;
    }
    return SR_OK;
}

static const char *const attribute_name[ROLE_COUNT] = {
    [R_X] = "x", [R_Y] = "y", [R_Z] = "z", [R_NX] = "nx", [R_NY] = "ny", [R_NZ] = "nz",
    [R_RED] = "red", [R_GREEN] = "green", [R_BLUE] = "blue", [R_ALPHA] = "alpha",
    [R_U] = "u", [R_V] = "v",
};

static sr_result read_vertex(ply_reader *r, const ply_elem *e, unsigned long long index)
{
    float v[ROLE_COUNT] = { 0 };
    v[R_ALPHA] = 1.0f; /* opaque unless the file says otherwise */
    for (size_t j = 0; j < e->prop_count; j++) {
        const ply_prop *p = &e->props[j];
        sr_result res;
        if (p->count_type != T_NONE) {
            unsigned long long count;
            res = read_list_count(r, e, index, p, &count);
            if (res == SR_OK) {
                res = skip_values(r, e, index, p->type, count);
            }
        } else {
            double d;
            res = read_value(r, e, index, p->type, &d);
            if (res == SR_OK && p->role != R_SKIP) {
                float f = (float)d * p->scale;
                /* A NaN or infinite attribute would poison bounds, normals
                 * and the rasterizer's fixed-point snap. */
                if (!isfinite(f)) {
                    return data_fail(r, SR_BAD_FORMAT,
                                     isfinite(d) ? "vertex %llu: %s is beyond float's range"
                                                 : "vertex %llu: %s is not finite",
                                     index, attribute_name[p->role]);
                }
                v[p->role] = f;
            }
        }
        if (res != SR_OK) {
            return res;
        }
    }
    sr_mesh *m = &r->mesh;
    size_t i = (size_t)index;
    m->positions[3 * i + 0] = v[R_X];
    m->positions[3 * i + 1] = v[R_Y];
    m->positions[3 * i + 2] = v[R_Z];
    if (m->normals) {
        m->normals[3 * i + 0] = v[R_NX];
        m->normals[3 * i + 1] = v[R_NY];
        m->normals[3 * i + 2] = v[R_NZ];
    }
    if (m->colors) {
        m->colors[4 * i + 0] = v[R_RED];
        m->colors[4 * i + 1] = v[R_GREEN];
        m->colors[4 * i + 2] = v[R_BLUE];
        m->colors[4 * i + 3] = v[R_ALPHA];
    }
    if (m->texcoords) {
        m->texcoords[2 * i + 0] = v[R_U];
        m->texcoords[2 * i + 1] = v[R_V];
    }
    return SR_OK;
}

static sr_result read_other(ply_reader *r, const ply_elem *e, unsigned long long index)
{
    for (size_t j = 0; j < e->prop_count; j++) {
        const ply_prop *p = &e->props[j];
        sr_result res;
        if (p->role == R_INDICES) {
            res = e->kind == K_FACE ? read_face(r, e, index, p) : read_strip(r, e, index, p);
        } else if (p->count_type != T_NONE) {
            unsigned long long count;
            res = read_list_count(r, e, index, p, &count);
            if (res == SR_OK) {
                res = skip_values(r, e, index, p->type, count);
            }
        } else {
            res = skip_values(r, e, index, p->type, 1);
        }
        if (res != SR_OK) {
            return res;
        }
    }
    return SR_OK;
}

static sr_result read_elements(ply_reader *r)
{
    for (size_t i = 0; i < r->elem_count; i++) {
        const ply_elem *e = &r->elems[i];
        if (e->prop_count == 0) {
            continue; /* nothing stored per entry, so nothing to read */
        }
        /* Binary elements we do not use and whose entries have a fixed
         * size are stepped over in one go.  check_elements() bounded the
         * product, but earlier lists may have used up the bytes it
         * counted on, so what is left is checked here. */
        if (e->kind == K_OTHER && r->format != F_ASCII) {
            size_t fixed = 0;
            bool has_list = false;
            for (size_t j = 0; j < e->prop_count; j++) {
                has_list |= e->props[j].count_type != T_NONE;
                fixed += type_size[e->props[j].type];
            }
            if (!has_list) {
                size_t left = r->size - r->pos;
                if (fixed * e->count > left) {
                    unsigned long long whole = left / fixed;
                    r->value_pos = r->pos + (size_t)whole * fixed;
                    return data_fail(r, SR_BAD_FORMAT, "file ends inside %s %llu (of %llu)",
                                     e->name, whole, e->count);
                }
                r->pos += fixed * (size_t)e->count;
                continue;
            }
        }
        for (unsigned long long k = 0; k < e->count; k++) {
            sr_result res = e->kind == K_VERTEX ? read_vertex(r, e, k) : read_other(r, e, k);
            if (res != SR_OK) {
                return res;
            }
        }
    }
    return SR_OK;
}

/* After the last element the file must end (ASCII: but for whitespace).
 * Anything more means the header's counts are wrong - most often too few
 * faces declared - and reading on would drop data without a word; binary
 * STL's trailing data is refused the same way. */
static sr_result check_trailing(ply_reader *r)
{
    token w;
    if (r->format == F_ASCII) {
        if (!next_word(r, &w)) {
            return SR_OK;
        }
        /* next_word left value_line on the stray word's line. */
    } else {
        if (r->pos == r->size) {
            return SR_OK;
        }
        r->value_pos = r->pos;
    }
    /* Name the header line of the last element: its count is the one to
     * check. */
    char declared[NAME_MAX_LEN + 64] = "no elements";
    if (r->elem_count > 0) {
        const ply_elem *e = &r->elems[r->elem_count - 1];
        snprintf(declared, sizeof declared, "'element %s %llu' on line %ld",
                 e->name, e->count, e->line);
    }
    if (r->format == F_ASCII) {
        return data_fail(r, SR_BAD_FORMAT, "data after the last element (the header declares %s)",
                         declared);
    }
    size_t extra = r->size - r->pos;
    return data_fail(r, SR_BAD_FORMAT, "%zu byte%s after the last element (the header declares %s)",
                     extra, extra == 1 ? "" : "s", declared);
}

static sr_result allocate_vertices(ply_reader *r)
{
    size_t n = (size_t)r->vertex_count;
    sr_mesh *m = &r->mesh;
    m->vertex_count = n;
    if (n == 0) {
        return SR_OK; /* any index will be out of range and say so */
    }
    /* n <= SR_IO_MAX_VERTICES, so these products cannot overflow. */
    m->positions = malloc(n * 3 * sizeof(float));
    m->normals = r->has_normals ? malloc(n * 3 * sizeof(float)) : NULL;
    m->colors = r->has_colors ? malloc(n * 4 * sizeof(float)) : NULL;
    m->texcoords = r->has_texcoords ? malloc(n * 2 * sizeof(float)) : NULL;
    if (!m->positions || (r->has_normals && !m->normals) || (r->has_colors && !m->colors) ||
        (r->has_texcoords && !m->texcoords)) {
        return sr__io_fail(r->err, SR_OUT_OF_MEMORY, r->name, 0,
                           "out of memory for %zu vertices", n);
    }
    return SR_OK;
}

static void free_reader(ply_reader *r)
{
    for (size_t i = 0; i < r->elem_count; i++) {
        free(r->elems[i].props);
    }
    free(r->elems);
    r->elems = NULL;
    r->elem_count = 0;
}

sr_result sr__parse_ply(const char *name, const uint8_t *data, size_t size,
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
    ply_reader r = { .name = name, .data = data, .size = size, .err = err };
    if (!data) {
        r.data = (const uint8_t *)"";
    }
    sr_result res = parse_header(&r);
    if (res == SR_OK) {
        res = check_elements(&r);
    }
    if (res == SR_OK) {
        res = allocate_vertices(&r);
    }
    if (res == SR_OK) {
        /* ASCII data starts on the line after end_header; an empty data
         * section is reported on the end_header line. */
        r.value_line = r.line;
        r.line++;
        res = read_elements(&r);
    }
    if (res == SR_OK) {
        res = check_trailing(&r);
    }
    if (res == SR_OK && r.mesh.triangle_count == 0) {
        res = sr__io_fail(err, SR_BAD_FORMAT, name, 0, "contains no faces");
    }
    free_reader(&r);
    if (res != SR_OK) {
        sr__free_malloc_mesh(&r.mesh);
        return res;
    }
    /* Give back the growth slack of the index array. */
    uint32_t *idx = realloc(r.mesh.indices, 3 * r.mesh.triangle_count * sizeof *idx);
    if (idx) {
        r.mesh.indices = idx;
    }
    *out = r.mesh;
    return SR_OK;
}

sr_result sr__load_ply(const char *path, sr_mesh *out, sr_io_error *err)
{
    return sr__load_file_with(path, sr__parse_ply, out, err);
}
