/*
 * test_ply.c - tests for the PLY reader (src/io/ply.c).
 * Every file is written by the test itself with the small writer below, in
 * ASCII and both binary byte orders, so each case states exactly which
 * bytes the reader sees and where an error must be reported.
 */
#include "io/readers.h"
#include "softrast_io.h"
#include "sr_test.h"
#include "wbuf.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* The reader under test, whatever the file is named. */
static const sr_load_desc ply_desc = { .format = SR_FORMAT_PLY };

/* ---- a tiny PLY writer -------------------------------------------------- */

typedef enum wfmt { W_ASCII, W_LE, W_BE } wfmt;

static const char *const format_name[] = { "ascii", "binary_little_endian",
                                           "binary_big_endian" };


static const struct {
    const char *name;
    int size;
    bool is_float;
} wtypes[] = {
    { "char", 1, false },   { "uchar", 1, false },  { "short", 2, false },
    { "ushort", 2, false }, { "int", 4, false },    { "uint", 4, false },
    { "float", 4, true },   { "double", 8, true },  { "int8", 1, false },
    { "uint8", 1, false },  { "int16", 2, false },  { "uint16", 2, false },
    { "int32", 4, false },  { "uint32", 4, false }, { "float32", 4, true },
    { "float64", 8, true },
};
#define WTYPE_COUNT (sizeof wtypes / sizeof wtypes[0])

static int wtype(const char *name)
{
    for (size_t i = 0; i < WTYPE_COUNT; i++) {
        if (strcmp(wtypes[i].name, name) == 0) {
            return (int)i;
        }
    }
    abort(); /* a typo in the test */
}

/* One value of the named type; ASCII values end with a space. */
static void put(wbuf *b, wfmt f, const char *type, double v)
{
    int t = wtype(type);
    if (f == W_ASCII) {
        if (wtypes[t].is_float) {
            wb_printf(b, "%.9g ", v);
        } else {
            wb_printf(b, "%lld ", (long long)v);
        }
        return;
    }
    uint64_t bits;
    int n = wtypes[t].size;
    if (wtypes[t].is_float && n == 4) {
        float fl = (float)v;
        uint32_t b32;
        memcpy(&b32, &fl, 4);
        bits = b32;
    } else if (wtypes[t].is_float) {
        memcpy(&bits, &v, 8);
    } else {
        bits = (uint64_t)(long long)v; /* two's complement, low bytes used */
    }
    uint8_t out[8];
    for (int i = 0; i < n; i++) {
        int shift = 8 * (f == W_LE ? i : n - 1 - i);
        out[i] = (uint8_t)(bits >> shift);
    }
    wb_put(b, out, (size_t)n);
}

static void end_row(wbuf *b, wfmt f)
{
    if (f == W_ASCII) {
        wb_put(b, "\n", 1);
    }
}

static void put_list(wbuf *b, wfmt f, const char *count_type, const char *item_type,
                     const int *items, int n)
{
    put(b, f, count_type, n);
    for (int i = 0; i < n; i++) {
        put(b, f, item_type, items[i]);
    }
}

/* ---- the unit cube, as quads, counter-clockwise seen from outside ------- */

static const int cube_quads[6][4] = {
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 },
    { 2, 6, 7, 3 }, { 0, 2, 3, 1 }, { 4, 5, 7, 6 },
};

static double corner(int i, int axis)
{
    return (i >> axis) & 1;
}

typedef struct cube_opts {
    wfmt fmt;
    const char *coord_type;  /* NULL -> float */
    const char *count_type;  /* NULL -> uchar */
    const char *index_type;  /* NULL -> int */
    bool extras;             /* normals, uchar colors, texcoords */
    bool scrambled;          /* other property and element order, unknown elements */
} cube_opts;

/* Returns the header's length in *header_bytes (where the data begins). */
static wbuf write_cube(const cube_opts *o, size_t *header_bytes)
{
    const char *ct = o->coord_type ? o->coord_type : "float";
    const char *lt = o->count_type ? o->count_type : "uchar";
    const char *it = o->index_type ? o->index_type : "int";
    wfmt f = o->fmt;
    wbuf b = { 0 };
    wb_printf(&b, "ply\nformat %s 1.0\ncomment written by test_ply.c\n", format_name[f]);
    if (o->scrambled) {
        wb_printf(&b, "element material 2\nproperty list uchar float diffuse\n"
                      "property uchar id\n");
        wb_printf(&b, "element face 6\nproperty uchar flags\n"
                      "property list %s %s vertex_indices\n"
                      "property list uint8 float texcoord\n", lt, it);
        wb_printf(&b, "element vertex 8\nproperty %s z\nproperty float confidence\n"
                      "property list ushort int16 neighbours\nproperty %s x\n"
                      "property %s y\n", ct, ct, ct);
        wb_printf(&b, "obj_info unused\nelement edge 3\nproperty int vertex1\n"
                      "property int vertex2\n");
    } else {
        wb_printf(&b, "element vertex 8\nproperty %s x\nproperty %s y\nproperty %s z\n",
                  ct, ct, ct);
        if (o->extras) {
            wb_printf(&b, "property float nx\nproperty float ny\nproperty float nz\n"
                          "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                          "property uchar alpha\nproperty float u\nproperty float v\n");
        }
        wb_printf(&b, "element face 6\nproperty list %s %s vertex_indices\n", lt, it);
    }
    wb_printf(&b, "end_header\n");
    *header_bytes = b.n;

    if (o->scrambled) {
        static const int diffuse[] = { 1, 2, 3 };
        put_list(&b, f, "uchar", "float", diffuse, 3);
        put(&b, f, "uchar", 7);
        end_row(&b, f);
        put_list(&b, f, "uchar", "float", diffuse, 0);
        put(&b, f, "uchar", 8);
        end_row(&b, f);
        for (int q = 0; q < 6; q++) {
            static const int uv[8] = { 0, 0, 1, 0, 1, 1, 0, 1 };
            put(&b, f, "uchar", q);
            put_list(&b, f, lt, it, cube_quads[q], 4);
            put_list(&b, f, "uint8", "float", uv, 8);
            end_row(&b, f);
        }
        for (int v = 0; v < 8; v++) {
            static const int nb[] = { -1, 5, 300 };
            put(&b, f, ct, corner(v, 2));
            put(&b, f, "float", 0.5);
            put_list(&b, f, "ushort", "int16", nb, v % 3);
            put(&b, f, ct, corner(v, 0));
            put(&b, f, ct, corner(v, 1));
            end_row(&b, f);
        }
        for (int e = 0; e < 3; e++) {
            put(&b, f, "int", e);
            put(&b, f, "int", e + 1);
            end_row(&b, f);
        }
        return b;
    }
    for (int v = 0; v < 8; v++) {
        for (int a = 0; a < 3; a++) {
            put(&b, f, ct, corner(v, a));
        }
        if (o->extras) {
            for (int a = 0; a < 3; a++) {
                put(&b, f, "float", corner(v, a) * 2 - 1);
            }
            put(&b, f, "uchar", v * 30);
            put(&b, f, "uchar", 255);
            put(&b, f, "uchar", 0);
            put(&b, f, "uchar", 51);
            put(&b, f, "float", v * 0.125);
            put(&b, f, "float", 1 - v * 0.125);
        }
        end_row(&b, f);
    }
    for (int q = 0; q < 6; q++) {
        put_list(&b, f, lt, it, cube_quads[q], 4);
        end_row(&b, f);
    }
    return b;
}

/* ---- checks ------------------------------------------------------------- */

static bool mesh_is_zero(const sr_mesh *m)
{
    static const sr_mesh zero;
    return memcmp(m, &zero, sizeof zero) == 0;
}

static double triangle_area_and_facing(const sr_mesh *m, size_t t, const double center[3],
                                       double *facing)
{
    const float *p[3];
    for (int k = 0; k < 3; k++) {
        p[k] = m->positions + 3 * (size_t)m->indices[3 * t + (size_t)k];
    }
    double e1[3], e2[3], n[3], c[3];
    for (int a = 0; a < 3; a++) {
        e1[a] = p[1][a] - p[0][a];
        e2[a] = p[2][a] - p[0][a];
        c[a] = (p[0][a] + p[1][a] + p[2][a]) / 3.0 - center[a];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    *facing = n[0] * c[0] + n[1] * c[1] + n[2] * c[2];
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* A closed unit cube: 8 corners, 12 triangles, every one facing out, total
 * area 6 (so no face is missing or doubled). */
static void check_cube(const sr_mesh *m)
{
    CHECK_EQ(m->vertex_count, 8);
    CHECK_EQ(m->triangle_count, 12);
    if (m->vertex_count != 8 || m->triangle_count != 12) {
        return;
    }
    for (int v = 0; v < 8; v++) {
        for (int a = 0; a < 3; a++) {
            CHECK_EQ(m->positions[3 * v + a], corner(v, a));
        }
    }
    const double center[3] = { 0.5, 0.5, 0.5 };
    double area = 0;
    for (size_t t = 0; t < 12; t++) {
        double facing;
        area += triangle_area_and_facing(m, t, center, &facing);
        CHECK(facing > 0);
    }
    CHECK_NEAR(area, 6.0, 1e-9);
}

static sr_result parse(const wbuf *b, size_t size, sr_mesh *m, sr_io_error *err)
{
    memset(err, 0, sizeof *err);
    return sr_parse_ply(sr_test_ctx(), "t.ply", b->p, size, m, err);
}

/* ---- well-formed files -------------------------------------------------- */

SR_TEST(ply_reads_every_scalar_type_in_every_format)
{
    for (int f = W_ASCII; f <= W_BE; f++) {
        for (size_t t = 0; t < WTYPE_COUNT; t++) {
            /* Integer types also serve as list count and index types;
             * coordinates 0 and 1 fit every type. */
            bool is_int = !wtypes[t].is_float;
            cube_opts o = { .fmt = (wfmt)f, .coord_type = wtypes[t].name,
                            .count_type = is_int ? wtypes[t].name : NULL,
                            .index_type = is_int ? wtypes[t].name : NULL };
            size_t hb;
            wbuf b = write_cube(&o, &hb);
            sr_mesh m;
            sr_io_error err;
            sr_result r = parse(&b, b.n, &m, &err);
            if (r != SR_OK) {
                printf("  %s %s: %s\n", format_name[f], wtypes[t].name, err.message);
            }
            CHECK_EQ(r, SR_OK);
            check_cube(&m);
            CHECK(m.normals == NULL && m.colors == NULL && m.texcoords == NULL);
            sr_destroy_mesh(sr_test_ctx(), &m);
            free(b.p);
        }
    }
}

SR_TEST(ply_reads_normals_colors_and_texcoords)
{
    for (int f = W_ASCII; f <= W_BE; f++) {
        size_t hb;
        wbuf b = write_cube(&(cube_opts){ .fmt = (wfmt)f, .extras = true }, &hb);
        sr_mesh m;
        sr_io_error err;
        CHECK_EQ(parse(&b, b.n, &m, &err), SR_OK);
        check_cube(&m);
        REQUIRE(m.normals && m.colors && m.texcoords);
        for (int v = 0; v < 8; v++) {
            for (int a = 0; a < 3; a++) {
                CHECK_EQ(m.normals[3 * v + a], corner(v, a) * 2 - 1);
            }
            /* uchar colors are scaled to [0, 1]. */
            CHECK_NEAR(m.colors[4 * v + 0], v * 30 / 255.0, 1e-6);
            CHECK_EQ(m.colors[4 * v + 1], 1.0f);
            CHECK_EQ(m.colors[4 * v + 2], 0.0f);
            CHECK_NEAR(m.colors[4 * v + 3], 0.2, 1e-6);
            CHECK_EQ(m.texcoords[2 * v + 0], v * 0.125f);
            CHECK_EQ(m.texcoords[2 * v + 1], 1 - v * 0.125f);
        }
        sr_destroy_mesh(sr_test_ctx(), &m);
        free(b.p);
    }
}

SR_TEST(ply_float_colors_are_kept_and_alpha_defaults_to_one)
{
    const char *text =
        "ply\nformat ascii 1.0\n"
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "property float red\nproperty float green\nproperty float blue\n"
        "property float s\nproperty float t\n"
        "element face 1\nproperty list uchar uint vertex_index\nend_header\n"
        "0 0 0 0.25 0.5 0.75 0 1\n1 0 0 1 1 1 1 1\n0 1 0 0 0 0 0 0\n3 0 1 2\n";
    sr_mesh m;
    sr_io_error err;
    REQUIRE(sr_parse_ply(sr_test_ctx(), "c.ply", (const uint8_t *)text, strlen(text), &m, &err) == SR_OK);
    REQUIRE(m.colors && m.texcoords);
    CHECK_EQ(m.colors[0], 0.25f);
    CHECK_EQ(m.colors[1], 0.5f);
    CHECK_EQ(m.colors[2], 0.75f);
    CHECK_EQ(m.colors[3], 1.0f);
    CHECK_EQ(m.texcoords[1], 1.0f); /* s/t taken as u/v */
    CHECK_EQ(m.triangle_count, 1);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(ply_handles_any_property_and_element_order_and_skips_unknowns)
{
    for (int f = W_ASCII; f <= W_BE; f++) {
        static const char *const index_types[] = { "int", "uint16", "uint8", "int32" };
        for (int it = 0; it < 4; it++) {
            size_t hb;
            cube_opts o = { .fmt = (wfmt)f, .scrambled = true, .index_type = index_types[it],
                            .count_type = it & 1 ? "int" : "uchar" };
            wbuf b = write_cube(&o, &hb);
            sr_mesh m;
            sr_io_error err;
            sr_result r = parse(&b, b.n, &m, &err);
            if (r != SR_OK) {
                printf("  %s: %s\n", format_name[f], err.message);
            }
            CHECK_EQ(r, SR_OK);
            check_cube(&m);
            sr_destroy_mesh(sr_test_ctx(), &m);
            free(b.p);
        }
    }
}

SR_TEST(ply_crlf_header_and_extra_whitespace)
{
    const char *text =
        "ply\r\nformat ascii 1.0\r\n\r\nelement vertex 3\r\nproperty  float\tx\r\n"
        "property float y\r\nproperty float z\r\n"
        "element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
        "  0 0 0\r\n1 0 0\r\n\r\n0 1 0\r\n3   0 1 2\r\n";
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_parse_ply(sr_test_ctx(), "c.ply", (const uint8_t *)text, strlen(text), &m, &err), SR_OK);
    CHECK_EQ(m.triangle_count, 1);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(ply_polygons_are_fan_triangulated)
{
    /* A regular hexagon (4 triangles) and a quad (2), in the z = 0 plane. */
    wbuf b = { 0 };
    wb_printf(&b, "ply\nformat binary_big_endian 1.0\nelement vertex 10\n"
                  "property double x\nproperty double y\nproperty double z\n"
                  "element face 2\nproperty list int uint vertex_indices\nend_header\n");
    for (int i = 0; i < 6; i++) {
        put(&b, W_BE, "double", cos(i * 3.14159265358979323846 / 3));
        put(&b, W_BE, "double", sin(i * 3.14159265358979323846 / 3));
        put(&b, W_BE, "double", 0);
    }
    static const double quad[4][2] = { { 2, 0 }, { 3, 0 }, { 3, 1 }, { 2, 1 } };
    for (int i = 0; i < 4; i++) {
        put(&b, W_BE, "double", quad[i][0]);
        put(&b, W_BE, "double", quad[i][1]);
        put(&b, W_BE, "double", 0);
    }
    put_list(&b, W_BE, "int", "uint", (const int[]){ 0, 1, 2, 3, 4, 5 }, 6);
    put_list(&b, W_BE, "int", "uint", (const int[]){ 6, 7, 8, 9 }, 4);
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse(&b, b.n, &m, &err) == SR_OK);
    CHECK_EQ(m.triangle_count, 6);
    double area = 0;
    const double below[3] = { 0, 0, -1 };
    for (size_t t = 0; t < m.triangle_count; t++) {
        double facing;
        area += triangle_area_and_facing(&m, t, below, &facing);
        CHECK(facing > 0); /* counter-clockwise seen from +z */
    }
    CHECK_NEAR(area, 3 * sqrt(3) / 2 + 1, 1e-6);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(b.p);
}

/* A 3 x 1 strip of quads in z = 0: bottom row 0..3 at y = 0, top row 4..7. */
static wbuf write_strips(wfmt f, const char *index_type, const int *items, int n)
{
    wbuf b = { 0 };
    wb_printf(&b, "ply\nformat %s 1.0\nelement vertex 8\nproperty float x\n"
                  "property float y\nproperty float z\nelement tristrips 1\n"
                  "property list int %s vertex_indices\nend_header\n",
              format_name[f], index_type);
    for (int v = 0; v < 8; v++) {
        put(&b, f, "float", v & 3);
        put(&b, f, "float", v >> 2);
        put(&b, f, "float", 0);
        end_row(&b, f);
    }
    put_list(&b, f, "int", index_type, items, n);
    end_row(&b, f);
    return b;
}

static void check_strip_mesh(const sr_mesh *m)
{
    CHECK_EQ(m->triangle_count, 6);
    double area = 0;
    const double below[3] = { 1.5, 0.5, -1 };
    for (size_t t = 0; t < m->triangle_count; t++) {
        double facing;
        double a = triangle_area_and_facing(m, t, below, &facing);
        CHECK(a > 0);        /* the degenerate stitches were dropped */
        CHECK(facing > 0);   /* odd triangles were flipped back */
        area += a;
    }
    CHECK_NEAR(area, 3.0, 1e-9);
}

SR_TEST(ply_tristrips_with_restarts_and_degenerate_stitches)
{
    static const int restarted[] = { 4, 0, 5, 1, -1, 5, 1, 6, 2, 7, 3 };
    static const int stitched[] = { 4, 0, 5, 1, 1, 5, 5, 1, 6, 2, 7, 3 };
    for (int f = W_ASCII; f <= W_BE; f++) {
        sr_mesh m;
        sr_io_error err;
        wbuf b = write_strips((wfmt)f, "int", restarted, 11);
        CHECK_EQ(parse(&b, b.n, &m, &err), SR_OK);
        check_strip_mesh(&m);
        sr_destroy_mesh(sr_test_ctx(), &m);
        free(b.p);

        b = write_strips((wfmt)f, "int", stitched, 12);
        CHECK_EQ(parse(&b, b.n, &m, &err), SR_OK);
        check_strip_mesh(&m);
        sr_destroy_mesh(sr_test_ctx(), &m);
        free(b.p);
    }
    /* In an unsigned index type the restart is -1 written as all ones. */
    static const int restarted_u32[] = { 4, 0, 5, 1, -1, 5, 1, 6, 2, 7, 3 };
    sr_mesh m;
    sr_io_error err;
    wbuf b = write_strips(W_LE, "uint", restarted_u32, 11);
    CHECK_EQ(parse(&b, b.n, &m, &err), SR_OK);
    check_strip_mesh(&m);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(b.p);
}

SR_TEST(ply_load_from_file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/ply_cube.ply", sr_test_out_dir());
    size_t hb;
    wbuf b = write_cube(&(cube_opts){ .fmt = W_LE, .extras = true }, &hb);
    FILE *f = fopen(path, "wb");
    REQUIRE(f);
    fwrite(b.p, 1, b.n, f);
    fclose(f);
    free(b.p);
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), path, &ply_desc, &m, &err), SR_OK);
    check_cube(&m);
    sr_destroy_mesh(sr_test_ctx(), &m);
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), "/nonexistent/x.ply", &ply_desc, &m, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "/nonexistent/x.ply: cannot open");
    CHECK(mesh_is_zero(&m));
}

/* ---- malformed files ---------------------------------------------------- */

/* Parse `text`, expect `code`, a message containing `needle`, and a zeroed
 * mesh. */
static void expect_error(const char *text, size_t size, sr_result code, const char *needle)
{
    sr_mesh m;
    memset(&m, 0xAB, sizeof m); /* must come back zeroed */
    sr_io_error err = { { 0 } };
    sr_result r = sr_parse_ply(sr_test_ctx(), "bad.ply", (const uint8_t *)text, size, &m, &err);
    CHECK_EQ(r, code);
    CHECK_STR_CONTAINS(err.message, needle);
    CHECK(mesh_is_zero(&m));
    if (r == SR_OK) {
        sr_destroy_mesh(sr_test_ctx(), &m);
    }
}

#define TRI_HEADER                                                          \
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"           \
    "property float y\nproperty float z\nelement face 1\n"                  \
    "property list uchar int vertex_indices\nend_header\n"

SR_TEST(ply_truncated_binary_reports_the_byte)
{
    for (int f = W_LE; f <= W_BE; f++) {
        /* Each vertex carries a list of 20 floats, which the header's size
         * check can only count as its length byte: a file cut inside the
         * vertices passes that check and is caught value by value. */
        wbuf b = { 0 };
        wb_printf(&b, "ply\nformat %s 1.0\nelement vertex 8\nproperty float x\n"
                      "property float y\nproperty float z\n"
                      "property list uchar float junk\nelement face 6\n"
                      "property list uchar int vertex_indices\nend_header\n",
                  format_name[f]);
        size_t hb = b.n;
        static const int junk[20];
        for (int v = 0; v < 8; v++) {
            for (int a = 0; a < 3; a++) {
                put(&b, (wfmt)f, "float", corner(v, a));
            }
            put_list(&b, (wfmt)f, "uchar", "float", junk, 20);
        }
        size_t faces = b.n;
        for (int q = 0; q < 6; q++) {
            put_list(&b, (wfmt)f, "uchar", "int", cube_quads[q], 4);
        }
        sr_mesh m;
        sr_io_error err;
        REQUIRE(parse(&b, b.n, &m, &err) == SR_OK);
        check_cube(&m);
        sr_destroy_mesh(sr_test_ctx(), &m);

        /* Vertex 3 starts at 3 * (12 + 1 + 80) bytes; cut 2 bytes into its x. */
        char want[128];
        snprintf(want, sizeof want, "bad.ply: byte %zu: file ends inside vertex 3 (of 8)",
                 hb + 3 * 93);
        expect_error((const char *)b.p, hb + 3 * 93 + 2, SR_BAD_FORMAT, want);
        /* Cut in the middle of the last face's list (17 bytes a face): the
         * list's length byte is where the missing data was promised. */
        snprintf(want, sizeof want, "bad.ply: byte %zu: face 5: a list of 4 values runs past",
                 faces + 5 * 17);
        expect_error((const char *)b.p, faces + 5 * 17 + 1 + 7, SR_BAD_FORMAT, want);
        free(b.p);
    }

    /* So much missing that the declared counts cannot fit: refused from
     * the header, naming the element's line. */
    size_t hb;
    wbuf b = write_cube(&(cube_opts){ .fmt = W_LE }, &hb);
    expect_error((const char *)b.p, hb + 38, SR_BAD_FORMAT,
                 "bad.ply:4: element 'vertex' declares 8 entries, more than the 38 bytes");
    free(b.p);
}

SR_TEST(ply_every_truncation_fails_cleanly)
{
    for (int f = W_ASCII; f <= W_BE; f++) {
        size_t hb;
        wbuf b = write_cube(&(cube_opts){ .fmt = (wfmt)f, .scrambled = true }, &hb);
        for (size_t n = 0; n < b.n; n++) {
            /* ASCII may end without the last separators; the last value
             * must be complete. */
            if (f == W_ASCII && n >= b.n - 2) {
                continue;
            }
            uint8_t *copy = malloc(n ? n : 1); /* ASan sees any overread */
            memcpy(copy, b.p, n);
            sr_mesh m;
            sr_io_error err;
            sr_result r = sr_parse_ply(sr_test_ctx(), "cut.ply", copy, n, &m, &err);
            if (r == SR_OK) {
                printf("  %s: truncated to %zu of %zu bytes and still read\n",
                       format_name[f], n, b.n);
                sr_destroy_mesh(sr_test_ctx(), &m);
            }
            CHECK(r != SR_OK);
            CHECK(mesh_is_zero(&m));
            free(copy);
        }
        free(b.p);
    }
}

SR_TEST(ply_random_corruption_never_crashes)
{
    sr_rng rng = { 0x9E3779B97F4A7C15ull };
    for (int f = W_ASCII; f <= W_BE; f++) {
        size_t hb;
        wbuf b = write_cube(&(cube_opts){ .fmt = (wfmt)f, .scrambled = true }, &hb);
        for (int trial = 0; trial < 2000; trial++) {
            uint8_t *copy = malloc(b.n);
            memcpy(copy, b.p, b.n);
            int flips = sr_rng_int(&rng, 1, 4);
            for (int k = 0; k < flips; k++) {
                copy[sr_rng_int(&rng, 0, (int)b.n - 1)] = (uint8_t)sr_rng_int(&rng, 0, 255);
            }
            sr_mesh m;
            sr_io_error err;
            sr_result r = sr_parse_ply(sr_test_ctx(), "x.ply", copy, b.n, &m, &err);
            if (r == SR_OK) {
                for (size_t i = 0; i < 3 * m.triangle_count; i++) {
                    CHECK(m.indices[i] < m.vertex_count);
                }
                sr_destroy_mesh(sr_test_ctx(), &m);
            } else {
                CHECK(mesh_is_zero(&m));
                CHECK(err.message[0] != 0);
            }
            free(copy);
        }
        free(b.p);
    }
}

SR_TEST(ply_header_errors_name_the_line)
{
    const char *bad_type =
        "ply\nformat ascii 1.0\ncomment fine\nelement vertex 3\n"
        "property flot x\n";
    expect_error(bad_type, strlen(bad_type), SR_BAD_FORMAT, "bad.ply:5: unknown type 'flot'");

    const char *bad_keyword = "ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n";
    expect_error(bad_keyword, strlen(bad_keyword), SR_BAD_FORMAT,
                 "bad.ply:3: unknown header keyword 'elemnt'");

    const char *negative = "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n";
    expect_error(negative, strlen(negative), SR_BAD_FORMAT, "bad.ply:3: element count");

    const char *no_end = "ply\nformat ascii 1.0\nelement vertex 3\n";
    expect_error(no_end, strlen(no_end), SR_BAD_FORMAT, "bad.ply:4: file ends inside the header");

    const char *not_ply = "PLY\nformat ascii 1.0\n";
    expect_error(not_ply, strlen(not_ply), SR_BAD_FORMAT, "bad.ply: not a PLY file");
    expect_error("", 0, SR_BAD_FORMAT, "bad.ply: not a PLY file");

    const char *bad_format = "ply\nformat binary_middle_endian 1.0\nend_header\n";
    expect_error(bad_format, strlen(bad_format), SR_BAD_FORMAT, "bad.ply:2: unknown format");

    const char *no_xyz =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0\n";
    expect_error(no_xyz, strlen(no_xyz), SR_BAD_FORMAT, "bad.ply:3: element 'vertex' lacks");

    const char *no_faces =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n0 0 0\n";
    expect_error(no_faces, strlen(no_faces), SR_BAD_FORMAT, "bad.ply: contains no faces");

    const char *float_index =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar float vertex_indices\n";
    expect_error(float_index, strlen(float_index), SR_BAD_FORMAT,
                 "bad.ply:8: vertex indices must have an integer type");

    const char *scalar_indices =
        "ply\nformat ascii 1.0\nelement face 1\nproperty int vertex_indices\n";
    expect_error(scalar_indices, strlen(scalar_indices), SR_BAD_FORMAT,
                 "bad.ply:4: 'vertex_indices' must be a list property");

    /* A NUL in a header word used to cut the quoted word short: "element
     * count '3' is not a non-negative integer" for "3\0". */
    static const char nul_count[] = "ply\nformat ascii 1.0\nelement vertex 3\0\nend_header\n";
    expect_error(nul_count, sizeof nul_count - 1, SR_BAD_FORMAT,
                 "bad.ply:3: a NUL byte in the header");
    static const char nul_comment[] = "ply\nformat ascii 1.0\ncomment a\0b\nend_header\n";
    expect_error(nul_comment, sizeof nul_comment - 1, SR_BAD_FORMAT,
                 "bad.ply:3: a NUL byte in the header");
}

SR_TEST(ply_index_out_of_range)
{
    const char *text = TRI_HEADER "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n";
    expect_error(text, strlen(text), SR_BAD_FORMAT,
                 "bad.ply:13: face 0: vertex index 3 out of range (the file has 3 vertices)");
    const char *negative = TRI_HEADER "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n";
    expect_error(negative, strlen(negative), SR_BAD_FORMAT, "bad.ply:13: face 0: vertex index -1");

    /* Binary: the message points at the offending index's first byte. */
    wbuf b = { 0 };
    wb_printf(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                  "property float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n");
    size_t data = b.n;
    for (int i = 0; i < 9; i++) {
        put(&b, W_LE, "float", i == 3 || i == 7);
    }
    put_list(&b, W_LE, "uchar", "int", (const int[]){ 0, 1, 70000 }, 3);
    char want[128];
    snprintf(want, sizeof want, "bad.ply: byte %zu: face 0: vertex index 70000", data + 36 + 1 + 8);
    expect_error((const char *)b.p, b.n, SR_BAD_FORMAT, want);
    free(b.p);
}

SR_TEST(ply_face_with_fewer_than_three_vertices)
{
    const char *text = TRI_HEADER "0 0 0\n1 0 0\n0 1 0\n2 0 1\n";
    expect_error(text, strlen(text), SR_BAD_FORMAT, "bad.ply:13: face 0 has 2 vertices");
}

SR_TEST(ply_counts_larger_than_the_file_are_refused_before_allocating)
{
    const char *big =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1000000\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n0123456789";
    expect_error(big, strlen(big), SR_BAD_FORMAT,
                 "bad.ply:3: element 'vertex' declares 1000000 entries");

    /* Faces are counted too: each needs at least its list count byte. */
    const char *faces =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 999999\nproperty list uchar int vertex_indices\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    expect_error(faces, strlen(faces), SR_BAD_FORMAT, "bad.ply:7: element 'face' declares 999999");

    /* Beyond the documented limit: refused as too large, whatever the size. */
    const char *huge =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty uchar x\n"
        "property uchar y\nproperty uchar z\nend_header\n";
    expect_error(huge, strlen(huge), SR_TOO_LARGE, "bad.ply:3: 4000000000 vertices exceed");

    const char *overflow =
        "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nend_header\n";
    expect_error(overflow, strlen(overflow), SR_TOO_LARGE, "bad.ply:3:");

    /* A list length the rest of the file cannot hold. */
    wbuf b = { 0 };
    wb_printf(&b, "ply\nformat binary_big_endian 1.0\nelement vertex 3\n"
                  "property float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uint int vertex_indices\nend_header\n");
    size_t data = b.n;
    for (int i = 0; i < 9; i++) {
        put(&b, W_BE, "float", i == 3 || i == 7);
    }
    put(&b, W_BE, "uint", 4000000000.0);
    put(&b, W_BE, "int", 0);
    char want[128];
    snprintf(want, sizeof want,
             "bad.ply: byte %zu: face 0: a list of 4000000000 values runs past", data + 36);
    expect_error((const char *)b.p, b.n, SR_BAD_FORMAT, want);
    free(b.p);
}

SR_TEST(ply_nan_and_inf_coordinates_are_refused)
{
    const char *text = TRI_HEADER "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n";
    expect_error(text, strlen(text), SR_BAD_FORMAT, "bad.ply:11: vertex 1: y is not finite");
    const char *inf = TRI_HEADER "0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n";
    expect_error(inf, strlen(inf), SR_BAD_FORMAT, "bad.ply:12: vertex 2: z is not finite");
    const char *overflow = TRI_HEADER "0 0 0\n1 0 0\n1e39 1 0\n3 0 1 2\n";
    expect_error(overflow, strlen(overflow), SR_BAD_FORMAT, "bad.ply:12: vertex 2: '1e39' is beyond float32's range");

    wbuf b = { 0 };
    wb_printf(&b, "ply\nformat binary_big_endian 1.0\nelement vertex 3\n"
                  "property float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n");
    size_t data = b.n;
    for (int i = 0; i < 9; i++) {
        put(&b, W_BE, "float", i == 5 ? NAN : (i == 3 || i == 7));
    }
    put_list(&b, W_BE, "uchar", "int", (const int[]){ 0, 1, 2 }, 3);
    char want[128];
    snprintf(want, sizeof want, "bad.ply: byte %zu: vertex 1: z is not finite", data + 20);
    expect_error((const char *)b.p, b.n, SR_BAD_FORMAT, want);
    free(b.p);

    /* A double beyond float's range is finite, only not a float. */
    wbuf d = { 0 };
    wb_printf(&d, "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                  "property double x\nproperty double y\nproperty double z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n");
    data = d.n;
    for (int i = 0; i < 9; i++) {
        put(&d, W_LE, "double", i == 6 ? 3.5e38 : (i == 3 || i == 7));
    }
    put_list(&d, W_LE, "uchar", "int", (const int[]){ 0, 1, 2 }, 3);
    snprintf(want, sizeof want, "bad.ply: byte %zu: vertex 2: x is beyond float's range",
             data + 48);
    expect_error((const char *)d.p, d.n, SR_BAD_FORMAT, want);
    free(d.p);
}

SR_TEST(ply_ascii_value_errors_name_the_line)
{
    const char *word = TRI_HEADER "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n";
    expect_error(word, strlen(word), SR_BAD_FORMAT, "bad.ply:11: vertex 1: 'zero' is not a valid");
    const char *range = TRI_HEADER "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n";
    expect_error(range, strlen(range), SR_BAD_FORMAT, "bad.ply:13: face 0: '300' is not a valid uint8");
    const char *short_file = TRI_HEADER "0.0000000 0 0\n1.0000000 0 0\n0 1\n";
    expect_error(short_file, strlen(short_file), SR_BAD_FORMAT,
                 "bad.ply:12: file ends inside vertex 2");
    const char *no_data = TRI_HEADER;
    expect_error(no_data, strlen(no_data), SR_BAD_FORMAT, "bad.ply:3: element 'vertex' declares 3");
}

/* Data after the last element means the header's counts are wrong: one face
 * declared and three written used to give one face, the others dropped
 * without a word.  ASCII may end in whitespace only; binary in nothing,
 * as binary STL. */
SR_TEST(ply_data_after_the_last_element_is_refused)
{
    const char *faces = TRI_HEADER "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n\n3 1 2 0\n";
    expect_error(faces, strlen(faces), SR_BAD_FORMAT,
                 "bad.ply:14: data after the last element (the header declares "
                 "'element face 1' on line 7)");
    const char *junk = TRI_HEADER "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n  junk\n";
    expect_error(junk, strlen(junk), SR_BAD_FORMAT, "bad.ply:15: data after the last element");
    const char *same_line = TRI_HEADER "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n";
    expect_error(same_line, strlen(same_line), SR_BAD_FORMAT,
                 "bad.ply:13: data after the last element");

    const char *spaces = TRI_HEADER "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n \t\r\n\n";
    sr_mesh m;
    sr_io_error err = { { 0 } };
    CHECK_EQ(sr_parse_ply(sr_test_ctx(), "ok.ply", (const uint8_t *)spaces, strlen(spaces), &m, &err), SR_OK);
    CHECK_EQ(m.triangle_count, 1);
    sr_destroy_mesh(sr_test_ctx(), &m);

    for (int f = W_LE; f <= W_BE; f++) {
        size_t hb;
        wbuf b = write_cube(&(cube_opts){ .fmt = (wfmt)f }, &hb);
        size_t end = b.n;
        REQUIRE(parse(&b, b.n, &m, &err) == SR_OK);
        check_cube(&m);
        sr_destroy_mesh(sr_test_ctx(), &m);

        /* A seventh face where the header declares six (line 8). */
        put_list(&b, (wfmt)f, "uchar", "int", cube_quads[0], 4);
        char want[200];
        snprintf(want, sizeof want, "bad.ply: byte %zu: 17 bytes after the last element "
                 "(the header declares 'element face 6' on line 8)", end);
        expect_error((const char *)b.p, b.n, SR_BAD_FORMAT, want);
        /* Even a single newline. */
        b.p[end] = '\n';
        snprintf(want, sizeof want, "bad.ply: byte %zu: 1 byte after the last element", end);
        expect_error((const char *)b.p, end + 1, SR_BAD_FORMAT, want);
        free(b.p);
    }
}

SR_TEST(ply_null_arguments)
{
    sr_io_error err;
    CHECK_EQ(sr_parse_ply(sr_test_ctx(), "x", (const uint8_t *)"ply\n", 4, NULL, &err), SR_INVALID_ARG);
    sr_mesh m;
    CHECK_EQ(sr_parse_ply(sr_test_ctx(), "x", NULL, 10, &m, &err), SR_INVALID_ARG);
    CHECK(mesh_is_zero(&m));
    CHECK_EQ(sr_parse_ply(sr_test_ctx(), NULL, NULL, 0, &m, NULL), SR_BAD_FORMAT); /* no err: no crash */
}
