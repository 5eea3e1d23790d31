/*
 * obj.c - model input (src/io): the Wavefront OBJ reader and its MTL files.
 * Consumes OBJ text from memory (sr_parse_obj) or a file plus the MTL files
 * it names (sr__load_obj); produces an sr_mesh holding one de-indexed vertex
 * array and counter-clockwise triangles.  No global state: any thread.
 *
 * What is read, and the choices made where OBJ leaves room:
 *  - `v x y z`, `v x y z w` (w only weights rational curves: read, checked,
 *    ignored) and `v x y z r g b` (the common vertex color extension);
 *    `vt u [v [w]]`; `vn x y z`; `f` (and the old `fo`) with corners v,
 *    v/vt, v//vn or v/vt/vn, indices from 1 or negative (relative).  An
 *    index must refer to data defined earlier in the file, as the format
 *    says.  `o g s l p vp` and unknown statements are skipped.
 *  - `mtllib` (files only) and `usemtl`: MTL `newmtl`, `Kd` and `map_Kd`;
 *    `Ks`, `Ns`, `d`, `Tr`, `Pm`, `Pr`, `map_Bump`/`bump` (a height map,
 *    its `-bm` scale) and `norm` (a normal map) for sr_mesh_part.material.
 *  - '#' starts a comment where a token could start.  CR LF, tabs and a
 *    UTF-8 byte order mark are fine; a backslash ending a line that is not
 *    a comment joins it with the next.
 *  - The text must be UTF-8 with no NUL byte.  Comments may hold any byte
 *    but NUL, because old exporters write Latin-1 names there; anywhere else
 *    a byte that is not UTF-8 means a binary or damaged file: an error.
 *  - Output: each distinct (v, vt, vn, material color) corner becomes one
 *    vertex, numbered in order of first use; unreferenced vertices are
 *    dropped.  normals only when every corner has a vn (else NULL: the
 *    caller computes them); texcoords when any corner has a vt ((0, 0) for
 *    the others); colors when any corner has a vertex color or an active
 *    material with Kd.  A vertex color wins over Kd; corners with neither
 *    are white.  Alpha is 1.
 */
#define _DEFAULT_SOURCE 1   /* populate.h */
#include "io/readers.h"
#include "io/io_util.h"
#include "io/number.h"

#include "geometry/newell.h"
#include "populate.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NO_INDEX UINT32_MAX

/* How many distinct MTL files one OBJ may pull in; more is surely a
 * mistake, and each costs a file read. */
#define MAX_MTL_FILES 64

/* One polygon corner: 0-based indices into v, vt, vn and the usemtl list,
 * NO_INDEX when absent.  When the mesh is built, `m` is rewritten to the
 * material whose Kd colors the corner (NO_INDEX for none). */
typedef struct corner {
    uint32_t v, vt, vn, m;
} corner;

/* The de-indexing map: each distinct corner tuple becomes one output
 * vertex.  Tuples live in `keys` in order of first use; `slots` is an
 * open-addressing table of key index + 1 (0: empty), kept at most half
 * full so probes stay short. */
typedef struct vertex_map {
    corner *keys;
    size_t n, cap;
    uint32_t *slots;
    size_t slot_cap;
} vertex_map;

/* A corner of the polygon being read: its position and its output vertex. */
typedef struct poly_corner {
    uint32_t v, key;
} poly_corner;

/* A string in the parser's arena: offsets stay valid when it grows. */
typedef struct str_ref {
    size_t off, len;
} str_ref;

typedef struct material {
    str_ref name;
    str_ref map_kd;     /* resolved path; len 0 when none */
    float kd[3];
    bool has_kd;
    str_ref bump;       /* map_Bump, bump or norm: resolved path; len 0 when none */
    sr_mesh_material look;  /* Ks, Ns, d/Tr, Pm, Pr and the bump map's kind and scale
                             * (look.bump_path stays NULL: the part gets its copy) */
} material;

/* Hands out logical lines: CR stripped, continuations joined, bytes
 * checked.  Shared by the OBJ and MTL parsers. */
typedef struct line_reader {
    const char *p, *end;
    const char *name;   /* for messages */
    sr_io_error *err;
    long line;          /* first physical line of the current logical line */
    long next_line;
    char *join;         /* holds lines joined by a backslash */
    size_t join_cap;
    bool plain;         /* the whole input is plain ASCII: skip the checks per line */
} line_reader;

typedef struct obj_parser {
    const char *name;
    sr_io_error *err;
    const char *dir;    /* OBJ path whose first dir_len bytes are its folder; NULL: no file access */
    size_t dir_len;

    float *v;           /* 3 per vertex */
    size_t nv, v_cap;
    uint32_t *vplain;   /* per vertex: its key with no vt, vn or usemtl, or NO_INDEX */
    size_t vplain_cap;
    float *vc;          /* 4 per vertex, a = 0 when it has no color; NULL until a color appears */
    size_t vc_cap;
    float *vt;          /* 2 per texture coordinate */
    size_t nvt, vt_cap;
    float *vn;          /* 3 per normal */
    size_t nvn, vn_cap;

    vertex_map map;     /* distinct corners seen so far */
    uint32_t *indices;  /* 3 per triangle, file order: indices into map.keys */
    size_t nindices, indices_cap;

    /* Scratch for the polygon on the current line and its triangulation. */
    poly_corner *poly;
    size_t poly_cap;
    double *scratch;    /* one block holding the four arrays below */
    size_t scratch_cap; /* in polygon corners */
    double *pxy;        /* 2 per corner, projected */
    uint32_t *prev, *next;  /* the corners not yet clipped, as a ring */
    long long ear_budget; /* point-in-triangle tests left for ear clipping */

    char *arena;        /* names and paths, each followed by a NUL */
    size_t arena_len, arena_cap;
    str_ref *uses;      /* usemtl names in order of appearance */
    size_t nuses, uses_cap;
    uint32_t cur_use;
    material *mats;
    size_t nmats, mats_cap;
    str_ref mtl_loaded[MAX_MTL_FILES];
    size_t nmtl_loaded;
    const sr_load_desc *desc;   /* its file_read hears of each MTL file read; may be NULL */

} obj_parser;

/* ---- small helpers ------------------------------------------------------ */

static bool is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

static bool is_digit(char c)
{
    return (unsigned)(c - '0') < 10u;
}

/* Make room for `need` elements of `size` bytes in the array at *(T **)pp,
 * doubling so that pushes stay amortized O(1).  Counts come from the data
 * actually read, never from a header, and every product is checked. */
static bool reserve(void *pp, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap) {
        return true;
    }
    size_t n = *cap ? *cap : 16;
    while (n < need) {
        if (n > SIZE_MAX / 2) {
            return false;
        }
        n *= 2;
    }
    size_t bytes;
    if (!sr__mul_ok(n, size, &bytes)) {
        return false;
    }
    void *p;
    memcpy(&p, pp, sizeof p);
    void *np = realloc(p, bytes);
    if (!np) {
        return false;
    }
    /* The new part is written next, element by element: its pages in one
     * go rather than one fault each (the bunny's arrays reach megabytes). */
    size_t old_bytes = *cap * size;
    sr__populate((char *)np + old_bytes, bytes - old_bytes);
    memcpy(pp, &np, sizeof np);
    *cap = n;
    return true;
}

/* malloc for an output array written whole at once (sr__populate). */
static void *malloc_written(size_t bytes)
{
    void *p = malloc(bytes);
    sr__populate(p, bytes);
    return p;
}

/* The next whitespace-separated token of [*s, e), or false at the end of
 * the line or at a comment. */
static bool next_token(const char **s, const char *e, const char **ts, const char **te)
{
    const char *p = *s;
    while (p < e && is_space(*p)) {
        p++;
    }
    if (p == e || *p == '#') {
        *s = e;
        return false;
    }
    *ts = p;
    while (p < e && !is_space(*p)) {
        p++;
    }
    *te = p;
    *s = p;
    return true;
}

/* The rest of a line as one name (usemtl, newmtl, mtllib, map_Kd): names
 * may hold spaces, so only surrounding blanks and a trailing comment go. */
static void rest_of_line(const char *s, const char *e, const char **rs, const char **re)
{
    while (s < e && is_space(*s)) {
        s++;
    }
    const char *p = s;
    while (p < e && !(*p == '#' && (p == s || is_space(p[-1])))) {
        p++;
    }
    while (p > s && is_space(p[-1])) {
        p--;
    }
    *rs = s;
    *re = p;
}

static bool token_is(const char *s, size_t n, const char *word)
{
    return strlen(word) == n && memcmp(s, word, n) == 0;
}

/* Tokens quoted in messages are cut short so one line stays one line. */
static int quote_len(const char *s, const char *e)
{
    return e - s > 40 ? 40 : (int)(e - s);
}

/* ---- numbers ------------------------------------------------------------ */

/* A decimal integer with an optional sign; magnitudes beyond 2^40 saturate
 * (they are out of range anyway). */
static bool parse_int(const char *s, const char *e, long long *out)
{
    bool neg = false;
    if (s < e && (*s == '+' || *s == '-')) {
        neg = *s == '-';
        s++;
    }
    if (s == e) {
        return false;
    }
    long long x = 0;
    for (; s < e; s++) {
        if (!is_digit(*s)) {
            return false;
        }
        if (x < (1LL << 40)) {
            x = x * 10 + (*s - '0');
        }
    }
    *out = neg ? -x : x;
    return true;
}

/* ---- lines and text checks ------------------------------------------------ */

/* Length of the valid UTF-8 sequence at s (RFC 3629: no overlong forms, no
 * surrogates, nothing above U+10FFFF), or 0. */
static size_t utf8_len(const unsigned char *s, size_t n)
{
    unsigned c = s[0];
    unsigned lo = 0x80, hi = 0xBF;
    size_t len;
    if (c < 0x80) {
        return 1;
    } else if (c >= 0xC2 && c <= 0xDF) {
        len = 2;
    } else if (c == 0xE0) {
        len = 3;
        lo = 0xA0;
    } else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) {
        len = 3;
    } else if (c == 0xED) {
        len = 3;
        hi = 0x9F;
    } else if (c == 0xF0) {
        len = 4;
        lo = 0x90;
    } else if (c >= 0xF1 && c <= 0xF3) {
        len = 4;
    } else if (c == 0xF4) {
        len = 4;
        hi = 0x8F;
    } else {
        return 0;
    }
    if (n < len || s[1] < lo || s[1] > hi) {
        return 0;
    }
    for (size_t i = 2; i < len; i++) {
        if ((s[i] & 0xC0) != 0x80) {
            return 0;
        }
    }
    return len;
}

/* The policy in the file header: no NUL anywhere, UTF-8 outside comments. */
/* True when [s, s + n) holds no NUL and no byte >= 0x80.  Eight bytes at a
 * time: (w - 0x01..01) & ~w & 0x80..80 is non-zero exactly when some byte
 * of w is zero (a borrow can only start at a zero byte), and w & 0x80..80
 * catches the high bytes. */
static bool plain_ascii(const char *s, size_t n)
{
    const uint64_t ones = 0x0101010101010101ull, highs = 0x8080808080808080ull;
    uint64_t bad = 0;
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        uint64_t w;
        memcpy(&w, s + i, 8);
        bad |= (w | ((w - ones) & ~w)) & highs;
    }
    for (; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        bad |= (uint64_t)((c - 1) | c) & 0x80;
    }
    return bad == 0;
}

static sr_result check_text(const line_reader *r, const char *s, size_t n)
{
    if (r->plain || plain_ascii(s, n)) {
        return SR_OK;
    }
    const unsigned char *u = (const unsigned char *)s;
    bool token_start = true;
    for (size_t i = 0; i < n;) {
        if (u[i] == 0) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "NUL byte in column %zu: binary data, not OBJ text", i + 1);
        }
        if (token_start && u[i] == '#') {
            const unsigned char *nul = memchr(u + i, 0, n - i);
            if (nul) {
                return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                                   "NUL byte in column %zu: binary data, not OBJ text",
                                   (size_t)(nul - u) + 1);
            }
            return SR_OK;
        }
        size_t len = utf8_len(u + i, n - i);
        if (len == 0) {
            return sr__io_fail(r->err, SR_BAD_FORMAT, r->name, r->line,
                               "byte 0x%02x in column %zu is not UTF-8 text "
                               "(a binary or mis-encoded file?)", u[i], i + 1);
        }
        token_start = is_space(s[i]);
        i += len;
    }
    return SR_OK;
}

static void reader_init(line_reader *r, const char *name, const char *data, size_t size,
                        sr_io_error *err)
{
    memset(r, 0, sizeof *r);
    r->p = data;
    r->end = data + size;
    r->name = name;
    r->err = err;
    r->next_line = 1;
    /* A byte order mark would otherwise glue itself to the first keyword. */
    if (size >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) {
        r->p += 3;
    }
    r->plain = plain_ascii(r->p, (size_t)(r->end - r->p));
}

static void physical_line(line_reader *r, const char **a, const char **b)
{
    const char *s = r->p;
    const char *nl = memchr(s, '\n', (size_t)(r->end - s));
    const char *e = nl ? nl : r->end;
    r->p = nl ? nl + 1 : r->end;
    r->next_line++;
    if (e > s && e[-1] == '\r') {
        e--;
    }
    *a = s;
    *b = e;
}

static bool is_comment_line(const char *s, const char *e)
{
    while (s < e && is_space(*s)) {
        s++;
    }
    return s < e && *s == '#';
}

/* The next logical line in [*ls, *le); *eof at the end of the input. */
static sr_result read_line(line_reader *r, const char **ls, const char **le, bool *eof)
{
    if (r->p >= r->end) {
        *eof = true;
        return SR_OK;
    }
    *eof = false;
    r->line = r->next_line;
    const char *a, *b;
    physical_line(r, &a, &b);
    if (!(b > a && b[-1] == '\\') || is_comment_line(a, b)) {
        *ls = a;
        *le = b;
        return check_text(r, a, (size_t)(b - a));
    }
    size_t len = 0;
    for (;;) {
        bool more = b > a && b[-1] == '\\';
        size_t piece = (size_t)(b - a) - (more ? 1 : 0);
        if (!reserve(&r->join, &r->join_cap, len + piece + 1, 1)) {
            return sr__io_fail(r->err, SR_OUT_OF_MEMORY, r->name, r->line, "out of memory");
        }
        memcpy(r->join + len, a, piece);
        len += piece;
        if (!more || r->p >= r->end) {
            break;
        }
        r->join[len++] = ' ';   /* the backslash-newline separates tokens */
        physical_line(r, &a, &b);
    }
    *ls = r->join;
    *le = r->join + len;
    return check_text(r, r->join, len);
}

/* ---- parser state ---------------------------------------------------------- */

static sr_result oom(obj_parser *P, long line)
{
    return sr__io_fail(P->err, SR_OUT_OF_MEMORY, P->name, line, "out of memory");
}

static void parser_free(obj_parser *P)
{
    free(P->v);
    free(P->vplain);
    free(P->vc);
    free(P->vt);
    free(P->vn);
    free(P->map.keys);
    free(P->map.slots);
    free(P->indices);
    free(P->poly);
    free(P->scratch);
    free(P->arena);
    free(P->uses);
    free(P->mats);
}

/* Copy n bytes into the arena, NUL-terminated so paths can be opened. */
static bool arena_add(obj_parser *P, const char *s, size_t n, str_ref *out)
{
    if (n > SIZE_MAX - P->arena_len - 1 ||
        !reserve(&P->arena, &P->arena_cap, P->arena_len + n + 1, 1)) {
        return false;
    }
    out->off = P->arena_len;
    out->len = n;
    memcpy(P->arena + P->arena_len, s, n);
    P->arena[P->arena_len + n] = 0;
    P->arena_len += n + 1;
    return true;
}

/* dir (its first dir_len bytes) + rel, in the arena.  Backslashes become
 * slashes: Windows exporters write "textures\wood.png". */
static bool arena_path(obj_parser *P, const char *dir, size_t dir_len,
                       const char *rel, size_t rel_len, str_ref *out)
{
    if (rel_len > 0 && (rel[0] == '/' || rel[0] == '\\')) {
        dir_len = 0;            /* absolute already */
    }
    if (rel_len > SIZE_MAX / 2 || dir_len > SIZE_MAX / 2 ||
        !arena_add(P, dir, dir_len, out)) {
        return false;
    }
    /* Extend the entry just added (it is the last one in the arena). */
    if (!reserve(&P->arena, &P->arena_cap, P->arena_len + rel_len, 1)) {
        return false;
    }
    char *d = P->arena + out->off + dir_len;
    for (size_t i = 0; i < rel_len; i++) {
        d[i] = rel[i] == '\\' ? '/' : rel[i];
    }
    d[rel_len] = 0;
    out->len = dir_len + rel_len;
    P->arena_len += rel_len;
    return true;
}

static const char *arena_str(const obj_parser *P, str_ref r)
{
    return P->arena + r.off;
}

static sr_result number_error(const char *name, sr_io_error *err, long line,
                              sr_num_status st, const char *s, const char *e)
{
    switch (st) {
    case SR_NUM_NOT_FINITE:
        return sr__io_fail(err, SR_BAD_FORMAT, name, line,
                           "'%.*s' is not a finite number", quote_len(s, e), s);
    case SR_NUM_OVERFLOW:
        return sr__io_fail(err, SR_BAD_FORMAT, name, line,
                           "number '%.*s' is too large for a float", quote_len(s, e), s);
    default:
        return sr__io_fail(err, SR_BAD_FORMAT, name, line,
                           "malformed number '%.*s'", quote_len(s, e), s);
    }
}

/* Read up to `max` numbers from the rest of a line into vals; *count says
 * how many there were (max + 1 means too many). */
static sr_result read_numbers(const char *name, sr_io_error *err, long line,
                              const char *s, const char *e, float *vals, int max, int *count)
{
    const char *ts, *te;
    int k = 0;
    while (next_token(&s, e, &ts, &te)) {
        if (k == max) {
            *count = max + 1;
            return SR_OK;
        }
        sr_num_status st = sr__parse_float(ts, te, &vals[k]);
        if (st != SR_NUM_OK) {
            return number_error(name, err, line, st, ts, te);
        }
        k++;
    }
    *count = k;
    return SR_OK;
}

/* ---- MTL ----------------------------------------------------------------- */

/* map_Kd options that come before the file name, with their argument
 * counts; -o, -s and -t take one to three numbers. */
static int map_option_args(const char *s, size_t n)
{
    static const char *const one[] = {
        "-blendu", "-blendv", "-cc", "-clamp", "-imfchan", "-texres", "-bm", "-boost", "-type",
    };
    for (size_t i = 0; i < sizeof one / sizeof one[0]; i++) {
        if (token_is(s, n, one[i])) {
            return 1;
        }
    }
    if (token_is(s, n, "-mm")) {
        return 2;
    }
    if (token_is(s, n, "-o") || token_is(s, n, "-s") || token_is(s, n, "-t")) {
        return 3;
    }
    return -1;
}

/* A map statement's file name after its options, resolved against the
 * MTL's folder into *file; *bm (when not NULL) takes a -bm value.  False
 * when out of memory. */
static bool map_file(obj_parser *P, const char *path, size_t path_dir_len, const char *s,
                     const char *e, str_ref *file, float *bm)
{
    const char *q = s, *a, *b;
    const char *name_start = e;
    while (next_token(&q, e, &a, &b)) {
        int args = *a == '-' ? map_option_args(a, (size_t)(b - a)) : -1;
        if (args < 0) {
            name_start = a;
            break;
        }
        bool is_bm = token_is(a, (size_t)(b - a), "-bm");
        for (int i = 0; i < args; i++) {
            const char *q2 = q, *a2, *b2;
            float value;
            if (!next_token(&q2, e, &a2, &b2)) {
                break;
            }
            bool number = sr__parse_float(a2, b2, &value) == SR_NUM_OK;
            /* -o/-s/-t take "u [v [w]]": stop at the first non-number. */
            if (args == 3 && !number) {
                break;
            }
            if (is_bm && bm && number && isfinite(value)) {
                *bm = value;
            }
            q = q2;
        }
    }
    const char *ns, *ne;
    rest_of_line(name_start, e, &ns, &ne);
    return ne <= ns || arena_path(P, path, path_dir_len, ns, (size_t)(ne - ns), file);
}

/* Ks r g b (or one gray), Ns, d, Tr, Pm, Pr: the numbers after the
 * keyword ts..te into look.  Ks's spectral and xyz forms are ignored, as
 * Kd's are; d's "-halo" option is skipped. */
static sr_result parse_look(const char *path, sr_io_error *err, long line, const char *ts,
                            const char *te, const char *s, const char *e, sr_mesh_material *look)
{
    size_t kl = (size_t)(te - ts);
    bool ks = token_is(ts, kl, "Ks");
    const char *q = s, *a, *b;
    if (next_token(&q, e, &a, &b)) {
        size_t al = (size_t)(b - a);
        if (ks && (token_is(a, al, "spectral") || token_is(a, al, "xyz"))) {
            return SR_OK;
        }
        if (token_is(ts, kl, "d") && token_is(a, al, "-halo")) {
            s = q;
        }
    }
    float c[3];
    int n = 0;
    sr_result res = read_numbers(path, err, line, s, e, c, 3, &n);
    if (res != SR_OK) {
        return res;
    }
    if (ks ? n != 1 && n != 3 : n != 1) {
        return sr__io_fail(err, SR_BAD_FORMAT, path, line, "'%.*s' takes %s, found %s%d numbers",
                           (int)kl, ts, ks ? "r g b (or one gray value)" : "one number",
                           n > 3 ? "more than " : "", n > 3 ? 3 : n);
    }
    if (ks) {
        look->has_specular = true;
        look->specular[0] = c[0];
        look->specular[1] = n == 3 ? c[1] : c[0];
        look->specular[2] = n == 3 ? c[2] : c[0];
    } else if (token_is(ts, kl, "Ns")) {
        look->has_shininess = true;
        look->shininess = c[0];
    } else if (token_is(ts, kl, "d") || token_is(ts, kl, "Tr")) {
        /* Tr is 1 - d (some writers use one, some the other). */
        look->has_opacity = true;
        look->opacity = token_is(ts, kl, "d") ? c[0] : 1.0f - c[0];
    } else if (token_is(ts, kl, "Pm")) {
        look->has_metallic = true;
        look->metallic = c[0];
    } else {
        look->has_roughness = true;
        look->roughness = c[0];
    }
    return SR_OK;
}

static sr_result parse_mtl(obj_parser *P, const char *path, size_t path_dir_len,
                           const char *data, size_t size)
{
    line_reader r;
    reader_init(&r, path, data, size, P->err);
    size_t cur = SIZE_MAX;      /* material being defined */
    sr_result res = SR_OK;
    for (;;) {
        const char *s, *e, *ts, *te;
        bool eof;
        res = read_line(&r, &s, &e, &eof);
        if (res != SR_OK || eof) {
            break;
        }
        if (!next_token(&s, e, &ts, &te)) {
            continue;
        }
        size_t kl = (size_t)(te - ts);
        if (token_is(ts, kl, "newmtl")) {
            const char *ns, *ne;
            rest_of_line(s, e, &ns, &ne);
            if (!reserve(&P->mats, &P->mats_cap, P->nmats + 1, sizeof *P->mats)) {
                res = oom(P, 0);
                break;
            }
            material *mt = &P->mats[P->nmats];
            memset(mt, 0, sizeof *mt);
            if (!arena_add(P, ns, (size_t)(ne - ns), &mt->name)) {
                res = oom(P, 0);
                break;
            }
            cur = P->nmats++;
        } else if (token_is(ts, kl, "Kd") && cur != SIZE_MAX) {
            const char *q = s, *a, *b;
            /* "Kd spectral file.rfl" and "Kd xyz x y z" are not RGB: ignored. */
            if (next_token(&q, e, &a, &b) &&
                (token_is(a, (size_t)(b - a), "spectral") || token_is(a, (size_t)(b - a), "xyz"))) {
                continue;
            }
            float c[3];
            int n = 0;
            res = read_numbers(path, P->err, r.line, s, e, c, 3, &n);
            if (res != SR_OK) {
                break;
            }
            if (n != 1 && n != 3) {
                res = sr__io_fail(P->err, SR_BAD_FORMAT, path, r.line,
                                  "'Kd' takes r g b (or one gray value), found %s%d numbers",
                                  n > 3 ? "more than " : "", n > 3 ? 3 : n);
                break;
            }
            material *mt = &P->mats[cur];
            mt->kd[0] = c[0];
            mt->kd[1] = n == 3 ? c[1] : c[0];
            mt->kd[2] = n == 3 ? c[2] : c[0];
            mt->has_kd = true;
        } else if (token_is(ts, kl, "map_Kd") && cur != SIZE_MAX && P->mats[cur].map_kd.len == 0) {
            if (!map_file(P, path, path_dir_len, s, e, &P->mats[cur].map_kd, NULL)) {
                res = oom(P, 0);
                break;
            }
        } else if ((token_is(ts, kl, "map_Bump") || token_is(ts, kl, "bump") ||
                    token_is(ts, kl, "norm")) && cur != SIZE_MAX && P->mats[cur].bump.len == 0) {
            material *mt = &P->mats[cur];
            if (!map_file(P, path, path_dir_len, s, e, &mt->bump, &mt->look.bump_scale)) {
                res = oom(P, 0);
                break;
            }
            mt->look.bump_is_normal = token_is(ts, kl, "norm");
        } else if (cur != SIZE_MAX && (token_is(ts, kl, "Ks") || token_is(ts, kl, "Ns") ||
                                       token_is(ts, kl, "d") || token_is(ts, kl, "Tr") ||
                                       token_is(ts, kl, "Pm") || token_is(ts, kl, "Pr"))) {
            res = parse_look(path, P->err, r.line, ts, te, s, e, &P->mats[cur].look);
            if (res != SR_OK) {
                break;
            }
        }
    }
    free(r.join);
    return res;
}

/* Load one MTL file named `rel` relative to the OBJ's folder.  *found says
 * whether it could be read; a missing file is not an error. */
static sr_result load_mtl(obj_parser *P, const char *rel, size_t rel_len, bool *found)
{
    *found = false;
    str_ref path;
    if (!arena_path(P, P->dir, P->dir_len, rel, rel_len, &path)) {
        return oom(P, 0);
    }
    for (size_t i = 0; i < P->nmtl_loaded; i++) {
        str_ref o = P->mtl_loaded[i];
        if (o.len == path.len && memcmp(arena_str(P, o), arena_str(P, path), o.len) == 0) {
            *found = true;      /* read already; its materials are in place */
            return SR_OK;
        }
    }
    if (P->nmtl_loaded == MAX_MTL_FILES) {
        return SR_OK;
    }
    /* Copy the path out: parsing the MTL grows the arena and may move it. */
    char *p = malloc(path.len + 1);
    if (!p) {
        return oom(P, 0);
    }
    memcpy(p, arena_str(P, path), path.len + 1);
    char *data;
    size_t size;
    sr_io_error ignored;
    sr_result res = sr__read_file(p, &data, &size, &ignored);
    if (res == SR_OUT_OF_MEMORY) {
        free(p);
        return oom(P, 0);
    }
    if (res != SR_OK) {
        free(p);
        return SR_OK;           /* missing or unreadable MTL: colors are optional */
    }
    *found = true;
    P->mtl_loaded[P->nmtl_loaded++] = path;
    if (P->desc && P->desc->file_read) {
        P->desc->file_read(P->desc->user, p);
    }
    const char *slash = strrchr(p, '/');
    size_t dir_len = slash ? (size_t)(slash - p) + 1 : 0;
    res = parse_mtl(P, p, dir_len, data, size);
    sr__free_file(data, size);
    free(p);
    return res;
}

/* mtllib names one or more files.  Names may hold spaces, so the whole rest
 * of the line is tried first, then each token. */
static sr_result handle_mtllib(obj_parser *P, const char *s, const char *e)
{
    const char *rs, *re;
    rest_of_line(s, e, &rs, &re);
    if (rs == re) {
        return SR_OK;
    }
    bool found;
    sr_result res = load_mtl(P, rs, (size_t)(re - rs), &found);
    if (res != SR_OK || found) {
        return res;
    }
    const char *ts, *te;
    const char *q = rs;
    while (next_token(&q, re, &ts, &te)) {
        if (ts == rs && te == re) {
            break;              /* a single token: tried above */
        }
        res = load_mtl(P, ts, (size_t)(te - ts), &found);
        if (res != SR_OK) {
            return res;
        }
    }
    return SR_OK;
}

/* ---- de-indexing -------------------------------------------------------- */

static uint64_t hash_corner(const corner *k)
{
    uint64_t h = ((uint64_t)k->v << 32 | k->vt) ^
                 (((uint64_t)k->vn << 32 | k->m) * 0x9E3779B97F4A7C15ull);
    h ^= h >> 33;                               /* murmur3 finalizer */
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

typedef enum map_status {
    MAP_OK,
    MAP_OOM,
    MAP_FULL,           /* SR_IO_MAX_VERTICES reached */
} map_status;

/* Add tuple k, known to be new, to m's keys without entering it in the
 * table: for tuples only ever looked up some other way. */
static map_status map_append(vertex_map *m, const corner *k, uint32_t *out)
{
    if (m->n >= SR_IO_MAX_VERTICES) {
        return MAP_FULL;
    }
    if (m->n == m->cap && !reserve(&m->keys, &m->cap, m->n + 1, sizeof *m->keys)) {
        return MAP_OOM;
    }
    m->keys[m->n] = *k;
    *out = (uint32_t)m->n++;
    return MAP_OK;
}

/* The index of tuple k in m, added if new. */
static map_status map_find_or_add(vertex_map *m, const corner *k, uint32_t *out)
{
    if (2 * (m->n + 1) > m->slot_cap) {
        /* Rehash into at least twice the slots (n <= 2^28 keeps this in
         * range).  Keys added by map_append are not in the table yet, so
         * n can be far beyond the old capacity: grow until the table is at
         * most half full, or the probe loops below would never find an
         * empty slot. */
        size_t ncap = m->slot_cap ? 2 * m->slot_cap : 1024;
        while (2 * (m->n + 1) > ncap) {
            ncap *= 2;
        }
        uint32_t *ns = calloc(ncap, sizeof *ns);
        if (!ns) {
            return MAP_OOM;
        }
        for (size_t j = 0; j < m->n; j++) {
            size_t g = (size_t)hash_corner(&m->keys[j]) & (ncap - 1);
            while (ns[g] != 0) {
                g = (g + 1) & (ncap - 1);
            }
            ns[g] = (uint32_t)(j + 1);
        }
        free(m->slots);
        m->slots = ns;
        m->slot_cap = ncap;
    }
    size_t mask = m->slot_cap - 1;
    size_t h = (size_t)hash_corner(k) & mask;
    for (; m->slots[h] != 0; h = (h + 1) & mask) {
        const corner *o = &m->keys[m->slots[h] - 1];
        if (o->v == k->v && o->vt == k->vt && o->vn == k->vn && o->m == k->m) {
            *out = m->slots[h] - 1;
            return MAP_OK;
        }
    }
    if (m->n >= SR_IO_MAX_VERTICES) {
        return MAP_FULL;
    }
    if (m->n == m->cap && !reserve(&m->keys, &m->cap, m->n + 1, sizeof *m->keys)) {
        return MAP_OOM;
    }
    m->keys[m->n] = *k;
    m->slots[h] = (uint32_t)(m->n + 1);
    *out = (uint32_t)m->n++;
    return MAP_OK;
}

static sr_result map_status_result(obj_parser *P, long line, map_status st)
{
    if (st == MAP_OOM) {
        return oom(P, line);
    }
    if (st == MAP_FULL) {
        return sr__io_fail(P->err, SR_TOO_LARGE, P->name, line,
                           "more than %zu distinct vertices", (size_t)SR_IO_MAX_VERTICES);
    }
    return SR_OK;
}

/* ---- statements ------------------------------------------------------------ */

static sr_result handle_v(obj_parser *P, long line, const char *s, const char *e)
{
    float c[7];
    int n = 0;
    sr_result res = read_numbers(P->name, P->err, line, s, e, c, 6, &n);
    if (res != SR_OK) {
        return res;
    }
    if (n != 3 && n != 4 && n != 6) {
        return sr__io_fail(P->err, SR_BAD_FORMAT, P->name, line,
                           "'v' takes x y z, x y z w or x y z r g b; found %s%d numbers",
                           n > 6 ? "more than " : "", n > 6 ? 6 : n);
    }
    if (P->nv >= SR_IO_MAX_VERTICES) {
        return sr__io_fail(P->err, SR_TOO_LARGE, P->name, line,
                           "more than %zu vertices", (size_t)SR_IO_MAX_VERTICES);
    }
    if ((P->nv == P->v_cap && !reserve(&P->v, &P->v_cap, P->nv + 1, 3 * sizeof(float))) ||
        (P->nv == P->vplain_cap &&
         !reserve(&P->vplain, &P->vplain_cap, P->nv + 1, sizeof *P->vplain))) {
        return oom(P, line);
    }
    P->vplain[P->nv] = NO_INDEX;
    float *p = P->v + 3 * P->nv;
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
    if (n == 6 || P->vc) {
        /* The color array appears with the first colored vertex; the
         * vertices before it are marked colorless (alpha 0). */
        size_t first_new = P->vc ? P->nv : 0;
        if (!reserve(&P->vc, &P->vc_cap, P->nv + 1, 4 * sizeof(float))) {
            return oom(P, line);
        }
        for (size_t i = first_new; i <= P->nv; i++) {
            float *q = P->vc + 4 * i;
            q[0] = q[1] = q[2] = 1.0f;
            q[3] = 0.0f;
        }
        if (n == 6) {
            float *q = P->vc + 4 * P->nv;
            q[0] = c[3];
            q[1] = c[4];
            q[2] = c[5];
            q[3] = 1.0f;
        }
    }
    P->nv++;
    return SR_OK;
}

static sr_result handle_vt(obj_parser *P, long line, const char *s, const char *e)
{
    float c[4];
    int n = 0;
    sr_result res = read_numbers(P->name, P->err, line, s, e, c, 3, &n);
    if (res != SR_OK) {
        return res;
    }
    if (n < 1 || n > 3) {
        return sr__io_fail(P->err, SR_BAD_FORMAT, P->name, line,
                           "'vt' takes u [v [w]]; found %s%d numbers",
                           n > 3 ? "more than " : "", n > 3 ? 3 : n);
    }
    if (P->nvt >= SR_IO_MAX_VERTICES) {
        return sr__io_fail(P->err, SR_TOO_LARGE, P->name, line,
                           "more than %zu texture coordinates", (size_t)SR_IO_MAX_VERTICES);
    }
    if (P->nvt == P->vt_cap && !reserve(&P->vt, &P->vt_cap, P->nvt + 1, 2 * sizeof(float))) {
        return oom(P, line);
    }
    P->vt[2 * P->nvt] = c[0];
    P->vt[2 * P->nvt + 1] = n > 1 ? c[1] : 0.0f;
    P->nvt++;
    return SR_OK;
}

static sr_result handle_vn(obj_parser *P, long line, const char *s, const char *e)
{
    float c[4];
    int n = 0;
    sr_result res = read_numbers(P->name, P->err, line, s, e, c, 3, &n);
    if (res != SR_OK) {
        return res;
    }
    if (n != 3) {
        return sr__io_fail(P->err, SR_BAD_FORMAT, P->name, line,
                           "'vn' takes x y z; found %s%d numbers",
                           n > 3 ? "more than " : "", n > 3 ? 3 : n);
    }
    if (P->nvn >= SR_IO_MAX_VERTICES) {
        return sr__io_fail(P->err, SR_TOO_LARGE, P->name, line,
                           "more than %zu normals", (size_t)SR_IO_MAX_VERTICES);
    }
    if (P->nvn == P->vn_cap && !reserve(&P->vn, &P->vn_cap, P->nvn + 1, 3 * sizeof(float))) {
        return oom(P, line);
    }
    memcpy(P->vn + 3 * P->nvn, c, 3 * sizeof(float));
    P->nvn++;
    return SR_OK;
}

static sr_result handle_usemtl(obj_parser *P, long line, const char *s, const char *e)
{
    const char *rs, *re;
    rest_of_line(s, e, &rs, &re);
    size_t n = (size_t)(re - rs);
    if (n == 0) {
        P->cur_use = NO_INDEX;
        return SR_OK;
    }
    /* Files switch back and forth; a repeat of the current name is free. */
    if (P->cur_use != NO_INDEX) {
        str_ref c = P->uses[P->cur_use];
        if (c.len == n && memcmp(arena_str(P, c), rs, n) == 0) {
            return SR_OK;
        }
    }
    if (P->nuses >= NO_INDEX - 1) {
        return sr__io_fail(P->err, SR_TOO_LARGE, P->name, line, "too many usemtl statements");
    }
    if (!reserve(&P->uses, &P->uses_cap, P->nuses + 1, sizeof *P->uses) ||
        !arena_add(P, rs, n, &P->uses[P->nuses])) {
        return oom(P, line);
    }
    P->cur_use = (uint32_t)P->nuses++;
    return SR_OK;
}

/* Turn a 1-based or negative OBJ index into a 0-based one below `count`. */
static sr_result resolve_index(obj_parser *P, long line, long long idx, size_t count,
                               const char *what, const char *plural,
                               const char *ts, const char *te, uint32_t *out)
{
    if (idx == 0) {
        return sr__io_fail(P->err, SR_BAD_FORMAT, P->name, line,
                           "index 0 in face vertex '%.*s': OBJ indices start at 1",
                           quote_len(ts, te), ts);
    }
    long long i = idx > 0 ? idx - 1 : (long long)count + idx;
    if (i < 0 || i >= (long long)count) {
        return sr__io_fail(P->err, SR_BAD_FORMAT, P->name, line,
                           "%s index %lld in '%.*s' is out of range: %zu %s defined before this line",
                           what, idx, quote_len(ts, te), ts, count, plural);
    }
    *out = (uint32_t)i;
    return SR_OK;
}

static sr_result parse_corner(obj_parser *P, long line, const char *ts, const char *te, corner *c)
{
    /* Up to three '/'-separated fields; empty fields are absent. */
    const char *f[3], *fe[3];
    int nf = 0;
    const char *q = ts;
    for (;;) {
        const char *sl = memchr(q, '/', (size_t)(te - q));
        if (nf == 3) {
            nf = 4;
            break;
        }
        f[nf] = q;
        fe[nf] = sl ? sl : te;
        nf++;
        if (!sl) {
            break;
        }
        q = sl + 1;
    }
    long long idx[3] = { 0, 0, 0 };
    bool ok = nf <= 3 && parse_int(f[0], fe[0], &idx[0]);
    for (int i = 1; ok && i < nf; i++) {
        ok = fe[i] == f[i] || parse_int(f[i], fe[i], &idx[i]);
    }
    if (!ok) {
        return sr__io_fail(P->err, SR_BAD_FORMAT, P->name, line,
                           "malformed face vertex '%.*s' (expected v, v/vt, v//vn or v/vt/vn)",
                           quote_len(ts, te), ts);
    }
    c->vt = c->vn = NO_INDEX;
    c->m = P->cur_use;
    sr_result res = resolve_index(P, line, idx[0], P->nv, "vertex", "vertices", ts, te, &c->v);
    if (res == SR_OK && nf > 1 && fe[1] > f[1]) {
        res = resolve_index(P, line, idx[1], P->nvt, "texture coordinate",
                            "texture coordinates", ts, te, &c->vt);
    }
    if (res == SR_OK && nf > 2 && fe[2] > f[2]) {
        res = resolve_index(P, line, idx[2], P->nvn, "normal", "normals", ts, te, &c->vn);
    }
    return res;
}

static void emit(obj_parser *P, uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t *o = P->indices + P->nindices;
    o[0] = P->poly[a].key;
    o[1] = P->poly[b].key;
    o[2] = P->poly[c].key;
    P->nindices += 3;
}

/* Triangles over the corners still linked from s, as a fan around s, in
 * polygon order so the winding is kept. */
static void fan_rest(obj_parser *P, uint32_t s)
{
    uint32_t a = P->next[s];
    while (P->next[a] != s) {
        emit(P, s, a, P->next[a]);
        a = P->next[a];
    }
}

/* Is corner b, between a and c, an ear of the remaining polygon (projected,
 * counter-clockwise): convex, with no other remaining corner inside or on
 * the triangle?  Corners at the same position as a, b or c don't block it
 * (polygons with holes bridged by a doubled edge have those). */
static bool is_ear(obj_parser *P, uint32_t a, uint32_t b, uint32_t c)
{
    /* Each call is charged too, so laps over reflex corners are bounded. */
    P->ear_budget--;
    const double *xy = P->pxy;
    double ax = xy[2 * a], ay = xy[2 * a + 1];
    double bx = xy[2 * b], by = xy[2 * b + 1];
    double cx = xy[2 * c], cy = xy[2 * c + 1];
    if (!((bx - ax) * (cy - by) - (by - ay) * (cx - bx) > 0)) {
        return false;
    }
    for (uint32_t j = P->next[c]; j != a; j = P->next[j]) {
        if (--P->ear_budget < 0) {
            return false;
        }
        double px = xy[2 * j], py = xy[2 * j + 1];
        if ((px == ax && py == ay) || (px == bx && py == by) || (px == cx && py == cy)) {
            continue;
        }
        if ((bx - ax) * (py - ay) - (by - ay) * (px - ax) >= 0 &&
            (cx - bx) * (py - by) - (cy - by) * (px - bx) >= 0 &&
            (ax - cx) * (py - cy) - (ay - cy) * (px - cx) >= 0) {
            return false;
        }
    }
    return true;
}

/* Split the n-corner polygon in P->poly (n > 3) into n - 2 triangles that
 * keep its winding.  Room for them is reserved by the caller. */
static sr_result triangulate(obj_parser *P, long line, size_t n)
{
    /* Per corner: xyz and xy as doubles, then prev and next; the doubles
     * come first so every array stays aligned. */
    if (!reserve(&P->scratch, &P->scratch_cap, n, 5 * sizeof(double) + 2 * sizeof(uint32_t))) {
        return oom(P, line);
    }
    double *p = P->scratch;
    P->pxy = p + 3 * n;
    P->prev = (uint32_t *)(P->pxy + 2 * n);
    P->next = P->prev + n;
    /* Positions relative to the first corner: large coordinates with small
     * polygons would otherwise lose the digits that matter. */
    const float *o = P->v + 3 * (size_t)P->poly[0].v;
    for (size_t i = 0; i < n; i++) {
        const float *q = P->v + 3 * (size_t)P->poly[i].v;
        p[3 * i] = (double)q[0] - o[0];
        p[3 * i + 1] = (double)q[1] - o[1];
        p[3 * i + 2] = (double)q[2] - o[2];
    }
    /* The polygon's normal by Newell's method: the sum over edges of
     * (y_i - y_j)(z_i + z_j) etc. is twice the area projected on each axis
     * plane, so it is robust for non-planar and partly collinear polygons
     * and points to the side from which the corners run counter-clockwise. */
    double nn[3] = { 0, 0, 0 };
    for (size_t i = 0; i < n; i++) {
        sr__newell_add(nn, p + 3 * i, p + 3 * ((i + 1) % n));
    }
    const double nx = nn[0], ny = nn[1], nz = nn[2];
    /* Convex when no corner turns against the Newell normal.  A zero normal
     * (degenerate polygon) passes too: any split of it is as good. */
    bool convex = true;
    for (size_t i = 0; i < n && convex; i++) {
        const double *a = p + 3 * ((i + n - 1) % n), *b = p + 3 * i, *c = p + 3 * ((i + 1) % n);
        double e1x = b[0] - a[0], e1y = b[1] - a[1], e1z = b[2] - a[2];
        double e2x = c[0] - b[0], e2y = c[1] - b[1], e2z = c[2] - b[2];
        double tx = e1y * e2z - e1z * e2y;
        double ty = e1z * e2x - e1x * e2z;
        double tz = e1x * e2y - e1y * e2x;
        convex = tx * nx + ty * ny + tz * nz >= 0;
    }
    for (size_t i = 0; i < n; i++) {
        P->prev[i] = (uint32_t)(i == 0 ? n - 1 : i - 1);
        P->next[i] = (uint32_t)(i + 1 == n ? 0 : i + 1);
    }
    if (convex || P->ear_budget <= 0) {
        fan_rest(P, 0);
        return SR_OK;
    }
    /* Ear clipping in 2D: drop the normal's largest axis and order the other
     * two so the polygon runs counter-clockwise (positive area) in them. */
    double ax = fabs(nx), ay = fabs(ny), az = fabs(nz);
    int u, w;
    if (az >= ax && az >= ay) {
        u = nz > 0 ? 0 : 1;
        w = nz > 0 ? 1 : 0;
    } else if (ax >= ay) {
        u = nx > 0 ? 1 : 2;
        w = nx > 0 ? 2 : 1;
    } else {
        u = ny > 0 ? 2 : 0;
        w = ny > 0 ? 0 : 2;
    }
    for (size_t i = 0; i < n; i++) {
        P->pxy[2 * i] = p[3 * i + u];
        P->pxy[2 * i + 1] = p[3 * i + w];
    }
    size_t m = n;
    uint32_t i = 0;
    size_t misses = 0;
    while (m > 3) {
        uint32_t a = P->prev[i], c = P->next[i];
        if (is_ear(P, a, i, c)) {
            emit(P, a, i, c);
            P->next[a] = c;
            P->prev[c] = a;
            m--;
            misses = 0;
            i = c;
            continue;
        }
        i = c;
        /* A full lap without an ear (self-intersecting or degenerate
         * input) or an exhausted budget: a fan still terminates and still
         * covers the polygon. */
        if (++misses >= m || P->ear_budget < 0) {
            fan_rest(P, i);
            return SR_OK;
        }
    }
    emit(P, P->prev[i], i, P->next[i]);
    return SR_OK;
}

static sr_result handle_f(obj_parser *P, long line, const char *s, const char *e)
{
    const char *ts, *te;
    size_t n = 0;
    while (next_token(&s, e, &ts, &te)) {
        if (n == P->poly_cap && !reserve(&P->poly, &P->poly_cap, n + 1, sizeof *P->poly)) {
            return oom(P, line);
        }
        corner c;
        sr_result res = parse_corner(P, line, ts, te, &c);
        if (res != SR_OK) {
            return res;
        }
        P->poly[n].v = c.v;
        /* Corners with a position only (most scanned meshes) find their key
         * by vertex index: one look into a small array instead of a hash
         * probe and a key compare, which dominated parsing the bunny. */
        map_status st = MAP_OK;
        if (c.vt == NO_INDEX && c.vn == NO_INDEX && c.m == NO_INDEX) {
            uint32_t *slot = &P->vplain[c.v];
            if (*slot == NO_INDEX) {
                st = map_append(&P->map, &c, slot);
            }
            P->poly[n].key = *slot;
        } else {
            st = map_find_or_add(&P->map, &c, &P->poly[n].key);
        }
        res = map_status_result(P, line, st);
        if (res != SR_OK) {
            return res;
        }
        n++;
    }
    if (n < 3) {
        return sr__io_fail(P->err, SR_BAD_FORMAT, P->name, line,
                           "face has %zu vertices; at least 3 are needed", n);
    }
    size_t tris = P->nindices / 3;
    if (n - 2 > SR_IO_MAX_TRIANGLES - tris) {
        return sr__io_fail(P->err, SR_TOO_LARGE, P->name, line,
                           "more than %zu triangles", (size_t)SR_IO_MAX_TRIANGLES);
    }
    size_t need = P->nindices + 3 * (n - 2);
    if (need > P->indices_cap &&
        !reserve(&P->indices, &P->indices_cap, need, sizeof *P->indices)) {
        return oom(P, line);
    }
    if (n == 3) {
        emit(P, 0, 1, 2);
        return SR_OK;
    }
    return triangulate(P, line, n);
}

/* ---- building the mesh ------------------------------------------------------ */

static uint64_t hash_bytes(const char *s, size_t n)
{
    uint64_t h = 1469598103934665603ull;        /* FNV-1a */
    for (size_t i = 0; i < n; i++) {
        h = (h ^ (unsigned char)s[i]) * 1099511628211ull;
    }
    return h;
}

static size_t pow2_at_least(size_t n)
{
    size_t c = 16;
    while (c < n && c <= SIZE_MAX / 2) {
        c *= 2;
    }
    return c;
}

/* Whether a material says more than Kd and map_Kd: its runs are then
 * parts of their own, carrying it. */
static bool has_look(const material *m)
{
    const sr_mesh_material *l = &m->look;
    return l->has_specular || l->has_shininess || l->has_opacity || l->has_metallic ||
           l->has_roughness || m->bump.len > 0;
}

/* Map each usemtl entry to the material that colors it (first definition
 * of a name wins) and pick the texture: the map_Kd of the first material
 * used, else the first map_Kd of any loaded material. */
static sr_result resolve_materials(obj_parser *P, uint32_t *use_kd, uint32_t *use_tex,
                                   str_ref *texture)
{
    texture->len = 0;
    for (size_t u = 0; u < P->nuses; u++) {
        use_kd[u] = NO_INDEX;
        use_tex[u] = NO_INDEX;
    }
    if (P->nmats == 0) {
        return SR_OK;
    }
    size_t cap = pow2_at_least(2 * P->nmats);
    uint32_t *table = calloc(cap, sizeof *table);  /* material index + 1, 0: empty */
    if (!table) {
        return oom(P, 0);
    }
    for (size_t i = 0; i < P->nmats; i++) {
        str_ref nm = P->mats[i].name;
        size_t h = (size_t)hash_bytes(arena_str(P, nm), nm.len) & (cap - 1);
        for (;; h = (h + 1) & (cap - 1)) {
            if (table[h] == 0) {
                table[h] = (uint32_t)i + 1;
                break;
            }
            str_ref o = P->mats[table[h] - 1].name;
            if (o.len == nm.len && memcmp(arena_str(P, o), arena_str(P, nm), nm.len) == 0) {
                break;          /* a later definition of the same name */
            }
        }
    }
    for (size_t u = 0; u < P->nuses; u++) {
        str_ref nm = P->uses[u];
        size_t h = (size_t)hash_bytes(arena_str(P, nm), nm.len) & (cap - 1);
        for (; table[h] != 0; h = (h + 1) & (cap - 1)) {
            const material *mt = &P->mats[table[h] - 1];
            if (mt->name.len == nm.len &&
                memcmp(arena_str(P, mt->name), arena_str(P, nm), nm.len) == 0) {
                if (mt->has_kd) {
                    use_kd[u] = table[h] - 1;
                }
                if (mt->map_kd.len > 0 || has_look(mt)) {
                    use_tex[u] = table[h] - 1;
                }
                if (mt->map_kd.len > 0 && texture->len == 0) {
                    *texture = mt->map_kd;
                }
                break;
            }
        }
    }
    free(table);
    for (size_t i = 0; i < P->nmats && texture->len == 0; i++) {
        *texture = P->mats[i].map_kd;
    }
    return SR_OK;
}

/* Whether materials a and b (indices, or NO_INDEX for none) draw alike:
 * the same resolved map_Kd path, or both none, and neither with more to
 * say (has_look). */
static bool same_texture(const obj_parser *P, uint32_t a, uint32_t b)
{
    if (a == b || a == NO_INDEX || b == NO_INDEX) {
        return a == b;   /* the common case, a run's next face, ends here */
    }
    if (has_look(&P->mats[a]) || has_look(&P->mats[b])) {
        return false;
    }
    str_ref x = P->mats[a].map_kd, y = P->mats[b].map_kd;
    return x.len == y.len && memcmp(arena_str(P, x), arena_str(P, y), x.len) == 0;
}

/* The texturing material of triangle t: its usemtl's (every corner of a
 * face carries the face's), read before build_mesh turns the corners'
 * usemtl indices into colors. */
static uint32_t triangle_texture(const obj_parser *P, const uint32_t *use_tex, size_t t)
{
    uint32_t use = P->map.keys[P->indices[3 * t]].m;
    return use == NO_INDEX ? NO_INDEX : use_tex[use];
}

/* sr_mesh.parts: the runs of triangles whose usemtl selects the same
 * texture (and the same material where it says more than Kd), when there
 * is more than one run or its material says more (else none: one
 * texture, or none, serves the whole mesh). */
/* A malloc'd copy of an arena string in *out; false when out of memory. */
static bool arena_copy(const obj_parser *P, str_ref str, char **out)
{
    *out = malloc(str.len + 1);
    if (*out) {
        memcpy(*out, arena_str(P, str), str.len + 1);
    }
    return *out != NULL;
}

static sr_result make_parts(obj_parser *P, const uint32_t *use_tex, sr_mesh *mesh)
{
    size_t tris = P->nindices / 3, runs = 0;
    for (size_t t = 0; t < tris; t++) {
        runs += t == 0 || !same_texture(P, triangle_texture(P, use_tex, t),
                                        triangle_texture(P, use_tex, t - 1));
    }
    uint32_t first = tris ? triangle_texture(P, use_tex, 0) : NO_INDEX;
    if (runs == 0 || (runs == 1 && (first == NO_INDEX || !has_look(&P->mats[first])))) {
        return SR_OK;
    }
    sr_mesh_part *parts = calloc(runs, sizeof *parts);
    if (!parts) {
        return oom(P, 0);
    }
    /* The mesh holds them from here: build_mesh frees what a failure leaves. */
    mesh->parts = parts;
    mesh->part_count = runs;
    size_t n = 0;
    for (size_t t = 0; t < tris; t++) {
        uint32_t tex = triangle_texture(P, use_tex, t);
        if (t > 0 && same_texture(P, tex, triangle_texture(P, use_tex, t - 1))) {
            parts[n - 1].triangle_count++;
            continue;
        }
        parts[n] = (sr_mesh_part){ .first_triangle = t, .triangle_count = 1 };
        n++;
        if (tex == NO_INDEX) {
            continue;
        }
        const material *mt = &P->mats[tex];
        parts[n - 1].material = mt->look;
        if ((mt->map_kd.len > 0 && !arena_copy(P, mt->map_kd, &parts[n - 1].texture_path)) ||
            (mt->bump.len > 0 && !arena_copy(P, mt->bump, &parts[n - 1].material.bump_path))) {
            return oom(P, 0);
        }
    }
    return SR_OK;
}

static sr_result build_mesh(obj_parser *P, sr_mesh *out)
{
    sr_mesh mesh = { 0 };
    vertex_map merged = { 0 };
    uint32_t *remap = NULL;
    str_ref texture;
    sr_result res;
    uint32_t *use_kd = malloc((P->nuses ? P->nuses : 1) * 2 * sizeof *use_kd);
    if (!use_kd) {
        return oom(P, 0);
    }
    uint32_t *use_tex = use_kd + (P->nuses ? P->nuses : 1);
    res = resolve_materials(P, use_kd, use_tex, &texture);
    if (res == SR_OK) {
        res = make_parts(P, use_tex, &mesh);
    }
    if (res != SR_OK) {
        goto done;
    }

    /* Which attributes the output carries (see the file header).  Every
     * corner is some key, so looking at the keys is enough. */
    corner *keys = P->map.keys;
    size_t nkeys = P->map.n;
    bool any_vn = false, all_vn = true, any_vt = false, any_color = false;
    for (size_t i = 0; i < nkeys; i++) {
        corner *c = &keys[i];
        any_vn |= c->vn != NO_INDEX;
        all_vn &= c->vn != NO_INDEX;
        any_vt |= c->vt != NO_INDEX;
        bool own = P->vc && P->vc[4 * (size_t)c->v + 3] > 0;
        c->m = own || c->m == NO_INDEX ? NO_INDEX : use_kd[c->m];
        any_color |= own || c->m != NO_INDEX;
    }
    bool use_vn = any_vn && all_vn;

    /* The keys were gathered with every field.  Dropping partial normals,
     * or going from usemtl statements to the colors they select, can make
     * keys equal: merge those so shared corners stay shared. */
    if ((any_vn && !use_vn) || P->nuses > 0) {
        remap = malloc(nkeys * sizeof *remap);
        if (!remap) {
            res = oom(P, 0);
            goto done;
        }
        for (size_t i = 0; i < nkeys; i++) {
            corner k = keys[i];
            if (!use_vn) {
                k.vn = NO_INDEX;
            }
            res = map_status_result(P, 0, map_find_or_add(&merged, &k, &remap[i]));
            if (res != SR_OK) {
                goto done;
            }
        }
        for (size_t i = 0; i < P->nindices; i++) {
            P->indices[i] = remap[P->indices[i]];
        }
        keys = merged.keys;
        nkeys = merged.n;
    }

    /* nkeys <= 2^28, so these products cannot overflow. */
    mesh.vertex_count = nkeys;
    mesh.triangle_count = P->nindices / 3;
    mesh.positions = malloc_written(nkeys * 3 * sizeof(float));
    mesh.normals = use_vn ? malloc_written(nkeys * 3 * sizeof(float)) : NULL;
    mesh.texcoords = any_vt ? malloc_written(nkeys * 2 * sizeof(float)) : NULL;
    mesh.colors = any_color ? malloc_written(nkeys * 4 * sizeof(float)) : NULL;
    if (texture.len > 0) {
        mesh.texture_path = malloc(texture.len + 1);
        if (mesh.texture_path) {
            memcpy(mesh.texture_path, arena_str(P, texture), texture.len + 1);
        }
    }
    if (!mesh.positions || (use_vn && !mesh.normals) || (any_vt && !mesh.texcoords) ||
        (any_color && !mesh.colors) || (texture.len > 0 && !mesh.texture_path)) {
        free(mesh.positions);
        free(mesh.normals);
        free(mesh.texcoords);
        free(mesh.colors);
        free(mesh.texture_path);
        res = oom(P, 0);
        goto done;
    }
    for (size_t i = 0; i < nkeys; i++) {
        const corner *k = &keys[i];
        memcpy(mesh.positions + 3 * i, P->v + 3 * (size_t)k->v, 3 * sizeof(float));
        if (use_vn) {
            memcpy(mesh.normals + 3 * i, P->vn + 3 * (size_t)k->vn, 3 * sizeof(float));
        }
        if (any_vt) {
            float *t = mesh.texcoords + 2 * i;
            if (k->vt != NO_INDEX) {
                t[0] = P->vt[2 * (size_t)k->vt];
                t[1] = P->vt[2 * (size_t)k->vt + 1];
            } else {
                t[0] = t[1] = 0.0f;
            }
        }
        if (any_color) {
            float *c = mesh.colors + 4 * i;
            const float *vc = P->vc ? P->vc + 4 * (size_t)k->v : NULL;
            if (vc && vc[3] > 0) {
                memcpy(c, vc, 3 * sizeof(float));
            } else if (k->m != NO_INDEX) {
                memcpy(c, P->mats[k->m].kd, 3 * sizeof(float));
            } else {
                c[0] = c[1] = c[2] = 1.0f;
            }
            c[3] = 1.0f;
        }
    }
    /* The index array moves into the mesh, trimmed of its growth slack. */
    mesh.indices = realloc(P->indices, P->nindices * sizeof *P->indices);
    if (!mesh.indices) {
        mesh.indices = P->indices;
    }
    P->indices = NULL;
    *out = mesh;
    mesh.parts = NULL;

done:
    for (size_t i = 0; mesh.parts && i < mesh.part_count; i++) {
        free(mesh.parts[i].texture_path);
        free(mesh.parts[i].material.bump_path);
    }
    free(mesh.parts);
    free(use_kd);
    free(remap);
    free(merged.keys);
    free(merged.slots);
    return res;
}

/* ---- entry points -------------------------------------------------------- */

/* Nothing but whitespace (and perhaps a byte order mark)? */
static bool is_blank(const char *s, size_t n)
{
    size_t i = n >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
    for (; i < n; i++) {
        if (!is_space(s[i]) && s[i] != '\n') {
            return false;
        }
    }
    return true;
}

/* Unknown statements are skipped, so markup under an .obj name reads as a
 * file of nothing: its first byte past blanks (and a BOM) says why. */
static bool starts_with_markup(const char *s, size_t n)
{
    size_t i = n >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
    while (i < n && (is_space(s[i]) || s[i] == '\n')) {
        i++;
    }
    return i < n && s[i] == '<';
}

static sr_result parse(const char *name, const char *data, size_t size,
                       const char *dir, size_t dir_len, const sr_load_desc *desc,
                       sr_mesh *out, sr_io_error *err)
{
    obj_parser P;
    memset(&P, 0, sizeof P);
    P.name = name;
    P.err = err;
    P.dir = dir;
    P.dir_len = dir_len;
    P.desc = desc;
    P.cur_use = NO_INDEX;
    /* Ear clipping costs up to n^3 point tests on hostile polygons.  A
     * budget in proportion to the input keeps the worst case linear in the
     * file size; honest files use a tiny fraction of it. */
    P.ear_budget = (1LL << 24) + 64LL * (long long)size;

    line_reader r;
    reader_init(&r, name, data, size, err);
    sr_result res = SR_OK;
    for (;;) {
        const char *s, *e, *ts, *te;
        bool eof;
        res = read_line(&r, &s, &e, &eof);
        if (res != SR_OK || eof) {
            break;
        }
        if (!next_token(&s, e, &ts, &te)) {
            continue;           /* blank or comment */
        }
        size_t kl = (size_t)(te - ts);
        long line = r.line;
        if (kl == 1 && ts[0] == 'v') {
            res = handle_v(&P, line, s, e);
        } else if (kl == 1 && ts[0] == 'f') {
            res = handle_f(&P, line, s, e);
        } else if (kl == 2 && ts[0] == 'v' && ts[1] == 't') {
            res = handle_vt(&P, line, s, e);
        } else if (kl == 2 && ts[0] == 'v' && ts[1] == 'n') {
            res = handle_vn(&P, line, s, e);
        } else if (token_is(ts, kl, "fo")) {
            res = handle_f(&P, line, s, e);
        } else if (token_is(ts, kl, "usemtl")) {
            res = handle_usemtl(&P, line, s, e);
        } else if (token_is(ts, kl, "mtllib")) {
            if (P.dir) {
                res = handle_mtllib(&P, s, e);
            }
        }
        /* Everything else (o, g, s, l, p, vp, curves, ...) is skipped. */
        if (res != SR_OK) {
            break;
        }
    }
    free(r.join);
    if (res == SR_OK && P.nindices == 0) {
        res = sr__io_fail(err, SR_BAD_FORMAT, name, 0, "%s",
                          is_blank(data, size) ? "file is empty"
                          : P.nv == 0 && starts_with_markup(data, size)
                              ? "contains no faces: it starts with '<', as XML, SVG and HTML "
                                "do; not an OBJ file"
                              : "contains no faces");
    }
    if (res == SR_OK) {
        res = build_mesh(&P, out);
    }
    parser_free(&P);
    return res;
}

sr_result sr__parse_obj(const char *name, const char *data, size_t size,
                        sr_mesh *out, sr_io_error *err)
{
    if (!name) {
        name = "<memory>";
    }
    if (!out || (!data && size > 0)) {
        if (out) {
            memset(out, 0, sizeof *out);
        }
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           out ? "data is NULL" : "no output mesh given");
    }
    memset(out, 0, sizeof *out);
    if (size > SR_IO_MAX_FILE_BYTES) {
        return sr__io_fail(err, SR_TOO_LARGE, name, 0,
                           "input is %zu bytes, larger than the %zu-byte limit",
                           size, (size_t)SR_IO_MAX_FILE_BYTES);
    }
    /* Memory has no folder to find MTL files in: mtllib is ignored. */
    return parse(name, data ? data : "", size, NULL, 0, NULL, out, err);
}

sr_result sr__load_obj(const char *path, const sr_load_desc *desc, sr_mesh *out,
                       sr_io_error *err)
{
    if (!out) {
        return sr__io_fail(err, SR_INVALID_ARG, path ? path : "<null>", 0, "no output mesh given");
    }
    memset(out, 0, sizeof *out);
    char *data;
    size_t size;
    sr_result res = sr__read_file(path, &data, &size, err);
    if (res != SR_OK) {
        return res;
    }
    const char *slash = strrchr(path, '/');
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    res = parse(path, data, size, path, dir_len, desc, out, err);
    sr__free_file(data, size);
    return res;
}
