/*
 * test_stl.c - tests for the STL reader (src/io/stl.c).
 * The files are written here: a unit cube as 12 triangles in ASCII and in
 * binary (also with a header that begins with "solid"), then broken in
 * the ways real files are broken.
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
static const sr_load_desc stl_desc = { .format = SR_FORMAT_STL };


static void wb_u32(wbuf *b, uint32_t v)
{
    uint8_t le[4] = { (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24) };
    wb_put(b, le, 4);
}

static void wb_f32(wbuf *b, float f)
{
    uint32_t bits;
    memcpy(&bits, &f, 4);
    wb_u32(b, bits);
}

/* The unit cube's 12 triangles, counter-clockwise from outside. */
static const int cube_tris[12][3] = {
    { 0, 4, 6 }, { 0, 6, 2 }, { 1, 3, 7 }, { 1, 7, 5 }, { 0, 1, 5 }, { 0, 5, 4 },
    { 2, 6, 7 }, { 2, 7, 3 }, { 0, 2, 3 }, { 0, 3, 1 }, { 4, 5, 7 }, { 4, 7, 6 },
};

static float corner(int i, int axis)
{
    return (float)((i >> axis) & 1);
}

static wbuf ascii_cube(void)
{
    wbuf b = { 0 };
    wb_printf(&b, "solid cube made by test_stl.c\n");
    for (int t = 0; t < 12; t++) {
        wb_printf(&b, "  facet normal 0 0 0\n    outer loop\n");
        for (int k = 0; k < 3; k++) {
            int v = cube_tris[t][k];
            wb_printf(&b, "      vertex %g %g %g\n", corner(v, 0), corner(v, 1), corner(v, 2));
        }
        wb_printf(&b, "    endloop\n  endfacet\n");
    }
    wb_printf(&b, "endsolid cube\n");
    return b;
}

static wbuf binary_cube(const char *header)
{
    wbuf b = { 0 };
    char h[80] = { 0 };
    memcpy(h, header, strlen(header));
    wb_put(&b, h, 80);
    wb_u32(&b, 12);
    for (int t = 0; t < 12; t++) {
        for (int k = 0; k < 3; k++) {
            wb_f32(&b, 0.0f); /* facet normal, not used */
        }
        for (int k = 0; k < 3; k++) {
            int v = cube_tris[t][k];
            wb_f32(&b, corner(v, 0));
            wb_f32(&b, corner(v, 1));
            wb_f32(&b, corner(v, 2));
        }
        wb_put(&b, "\0\0", 2);
    }
    return b;
}

static bool mesh_is_zero(const sr_mesh *m)
{
    static const sr_mesh zero;
    return memcmp(m, &zero, sizeof zero) == 0;
}

/* Welded: 8 vertices, 12 triangles, all facing out, area 6. */
static void check_cube(const sr_mesh *m)
{
    CHECK_EQ(m->vertex_count, 8);
    CHECK_EQ(m->triangle_count, 12);
    CHECK(m->normals == NULL);
    if (m->vertex_count != 8 || m->triangle_count != 12) {
        return;
    }
    double area = 0;
    for (size_t t = 0; t < 12; t++) {
        const float *p[3];
        for (int k = 0; k < 3; k++) {
            REQUIRE(m->indices[3 * t + (size_t)k] < 8);
            p[k] = m->positions + 3 * (size_t)m->indices[3 * t + (size_t)k];
        }
        /* Same corners, same order as written. */
        for (int k = 0; k < 3; k++) {
            for (int a = 0; a < 3; a++) {
                CHECK_EQ(p[k][a], corner(cube_tris[t][k], a));
            }
        }
        double e1[3], e2[3], n[3], c[3];
        for (int a = 0; a < 3; a++) {
            e1[a] = p[1][a] - p[0][a];
            e2[a] = p[2][a] - p[0][a];
            c[a] = (p[0][a] + p[1][a] + p[2][a]) / 3.0 - 0.5;
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        CHECK(n[0] * c[0] + n[1] * c[1] + n[2] * c[2] > 0);
        area += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    CHECK_NEAR(area, 6.0, 1e-9);
}

static sr_result parse(const uint8_t *data, size_t n, sr_mesh *m, sr_io_error *err)
{
    memset(err, 0, sizeof *err);
    return sr_parse_stl(sr_test_ctx(), "t.stl", data, n, m, err);
}

static void expect_error(const uint8_t *data, size_t n, sr_result code, const char *needle)
{
    sr_mesh m;
    memset(&m, 0xAB, sizeof m);
    sr_io_error err;
    sr_result r = parse(data, n, &m, &err);
    CHECK_EQ(r, code);
    CHECK_STR_CONTAINS(err.message, needle);
    CHECK(mesh_is_zero(&m));
    if (r == SR_OK) {
        sr_destroy_mesh(sr_test_ctx(), &m);
    }
}

static void expect_text_error(const char *text, const char *needle)
{
    expect_error((const uint8_t *)text, strlen(text), SR_BAD_FORMAT, needle);
}

/* ---- well-formed files -------------------------------------------------- */

SR_TEST(stl_ascii_cube_is_welded)
{
    wbuf b = ascii_cube();
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(parse(b.p, b.n, &m, &err), SR_OK);
    check_cube(&m);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(b.p);
}

SR_TEST(stl_binary_cube_is_welded)
{
    wbuf b = binary_cube("binary cube");
    CHECK_EQ(b.n, 84 + 12 * 50);
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(parse(b.p, b.n, &m, &err), SR_OK);
    check_cube(&m);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(b.p);
}

SR_TEST(stl_binary_with_solid_header_is_binary)
{
    /* Many exporters start the 80-byte header with "solid"; the size rule
     * tells the formats apart. */
    wbuf b = binary_cube("solid cube exported by a CAD tool");
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(parse(b.p, b.n, &m, &err), SR_OK);
    check_cube(&m);
    sr_destroy_mesh(sr_test_ctx(), &m);
    /* Truncated, it no longer meets the size rule, but the zero bytes
     * still mark it binary: the message is about sizes, not syntax. */
    expect_error(b.p, b.n - 7, SR_BAD_FORMAT, "t.stl: byte 80: binary STL declares 12 triangles");
    free(b.p);
}

/* "NAME: byte N: reason" keeps its offset and reason whatever the name's
 * length; the name gives way from the left, keeping its tail. */
SR_TEST(stl_byte_offsets_survive_long_names)
{
    static const char reason[] = ": byte 80: binary STL declares 12 triangles, which take 684 "
                                 "bytes, but the file has 683 bytes (truncated)";
    wbuf b = binary_cube("binary");
    for (size_t dirs = 7; dirs <= 12; dirs += 5) {
        char name[1024];
        size_t n = 0;
        for (size_t i = 0; i < dirs; i++) {
            n += (size_t)snprintf(name + n, sizeof name - n, "/%02zu%048d", i, 0);
        }
        snprintf(name + n, sizeof name - n, "/cube.stl");
        sr_mesh m;
        sr_io_error err;
        CHECK_EQ(sr_parse_stl(sr_test_ctx(), name, b.p, b.n - 1, &m, &err), SR_BAD_FORMAT);
        CHECK(mesh_is_zero(&m));
        size_t len = strlen(err.message), rlen = strlen(reason);
        CHECK(len > rlen && strcmp(err.message + len - rlen, reason) == 0);
        CHECK_STR_CONTAINS(err.message, "/cube.stl: byte 80: ");
        CHECK(strncmp(err.message, strlen(name) + rlen < sizeof err.message ? name : "...", 3) == 0);
        if (sr_test_failed_now()) {
            fprintf(stderr, "  %zu-character name: \"%s\"\n", strlen(name), err.message);
        }
    }
    free(b.p);
}

SR_TEST(stl_minus_zero_welds_with_zero)
{
    wbuf b = { 0 };
    wb_printf(&b, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                  "vertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
                  "vertex 1 0 0\nvertex 1 1 0\nvertex -0 1 -0\nendloop\nendfacet\n"
                  "endsolid s\n");
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse(b.p, b.n, &m, &err) == SR_OK);
    CHECK_EQ(m.vertex_count, 4);
    CHECK_EQ(m.triangle_count, 2);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(b.p);
}

SR_TEST(stl_ascii_tolerates_case_crlf_and_several_solids)
{
    const char *text =
        "SOLID upper\r\n FACET NORMAL 0 0 1\r\n  OUTER LOOP\r\n   VERTEX 0 0 0\r\n"
        "   VERTEX 1 0 0\r\n   VERTEX 0 1 0\r\n  ENDLOOP\r\n ENDFACET\r\nENDSOLID upper\r\n"
        "solid second\nfacet normal nan nan nan\nouter loop\nvertex 0 0 1\nvertex 1 0 1\n"
        "vertex 1e0 1.0E0 1\nvertex 0 1 1\nendloop\nendfacet\nendsolid";
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(parse((const uint8_t *)text, strlen(text), &m, &err), SR_OK);
    /* The second solid's facet is a quad, fanned into two triangles. */
    CHECK_EQ(m.triangle_count, 3);
    CHECK_EQ(m.vertex_count, 7);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(stl_large_binary_soup_welds_exactly)
{
    /* A grid of n x n squares as a triangle soup: (n+1)^2 shared corners.
     * Enough vertices to make the weld table grow several times. */
    const int n = 120;
    wbuf b = { 0 };
    char h[80] = "solid grid";
    wb_put(&b, h, 80);
    wb_u32(&b, (uint32_t)(2 * n * n));
    sr_rng rng = { 12345 };
    float z[121][121];
    for (int i = 0; i <= n; i++) {
        for (int j = 0; j <= n; j++) {
            z[i][j] = (float)sr_rng_range(&rng, -1, 1);
        }
    }
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            const int c[2][3][2] = { { { i, j }, { i + 1, j }, { i + 1, j + 1 } },
                                     { { i, j }, { i + 1, j + 1 }, { i, j + 1 } } };
            for (int t = 0; t < 2; t++) {
                wb_f32(&b, 0);
                wb_f32(&b, 0);
                wb_f32(&b, 0);
                for (int k = 0; k < 3; k++) {
                    wb_f32(&b, (float)c[t][k][0]);
                    wb_f32(&b, (float)c[t][k][1]);
                    wb_f32(&b, z[c[t][k][0]][c[t][k][1]]);
                }
                wb_put(&b, "\0\0", 2);
            }
        }
    }
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse(b.p, b.n, &m, &err) == SR_OK);
    CHECK_EQ(m.vertex_count, (n + 1) * (n + 1));
    CHECK_EQ(m.triangle_count, 2 * n * n);
    for (size_t t = 0; t < m.triangle_count; t++) {
        const uint32_t *tri = m.indices + 3 * t;
        CHECK(tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]);
    }
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(b.p);
}

SR_TEST(stl_load_from_file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/stl_cube.stl", sr_test_out_dir());
    wbuf b = binary_cube("solid");
    FILE *f = fopen(path, "wb");
    REQUIRE(f);
    fwrite(b.p, 1, b.n, f);
    fclose(f);
    free(b.p);
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), path, &stl_desc, &m, &err), SR_OK);
    check_cube(&m);
    sr_destroy_mesh(sr_test_ctx(), &m);
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), sr_test_out_dir(), &stl_desc, &m, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "is a directory");
    CHECK(mesh_is_zero(&m));
}

/* ---- malformed files ---------------------------------------------------- */

SR_TEST(stl_binary_size_must_match_the_count)
{
    wbuf b = binary_cube("binary");
    expect_error(b.p, b.n - 1, SR_BAD_FORMAT,
                 "t.stl: byte 80: binary STL declares 12 triangles, which take 684 bytes, "
                 "but the file has 683 bytes (truncated)");
    /* A count far beyond the file: refused before anything is allocated. */
    b.p[80] = 0xFF;
    b.p[81] = 0xFF;
    b.p[82] = 0xFF;
    b.p[83] = 0x7F;
    expect_error(b.p, b.n, SR_BAD_FORMAT, "t.stl: byte 80: binary STL declares 2147483647 triangles");
    b.p[80] = 11;
    b.p[81] = b.p[82] = b.p[83] = 0;
    expect_error(b.p, b.n, SR_BAD_FORMAT, "(trailing data)");
    expect_error(b.p, 50, SR_BAD_FORMAT, "t.stl: not an STL file (50 bytes");
    free(b.p);

    uint8_t empty[84] = { 0 };
    expect_error(empty, sizeof empty, SR_BAD_FORMAT, "t.stl: contains no faces");
}

SR_TEST(stl_binary_nan_is_refused_at_its_byte)
{
    wbuf b = binary_cube("binary");
    /* Triangle 2, corner 1, y: 84 + 2*50 + 12 + 12 + 4; a quiet NaN,
     * little-endian as binary STL stores it. */
    size_t at = 84 + 2 * 50 + 12 + 12 + 4;
    static const uint8_t nan_le[4] = { 0x00, 0x00, 0xC0, 0x7F };
    memcpy(b.p + at, nan_le, 4);
    char want[96];
    snprintf(want, sizeof want, "t.stl: byte %zu: triangle 2: vertex coordinate is not finite", at);
    expect_error(b.p, b.n, SR_BAD_FORMAT, want);
    free(b.p);
}

SR_TEST(stl_ascii_syntax_errors_name_the_line)
{
    expect_text_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                      "vertex 0 1\nendloop\n",
                      "t.stl:7: expected a number, found 'endloop'");
    expect_text_error("solid x\nfacet normal 0 0 1\nouter lop\n",
                      "t.stl:3: expected 'loop', found 'lop'");
    expect_text_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                      "endloop\nendfacet\nendsolid\n",
                      "t.stl:6: facet has 2 vertices; it needs 3");
    expect_text_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                      "vertex 0 1 0\nendloop\nendfacet\n",
                      "t.stl:8: unexpected end of file, expected 'endsolid'");
    expect_text_error("solid x\n\n\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                      "vertex 0 1 0\nendloop\nendfacet\nfacet\n outer loop\n  vertex 1 1 inf\n",
                      "t.stl:13: vertex coordinate 'inf' is not finite");
    expect_text_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e39 0 0\n",
                      "t.stl:5: vertex coordinate '1e39' is beyond float's range");
    expect_text_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                      "vertex 0 1 0\nendloop\nendfacet\nface\n",
                      "t.stl:9: expected 'facet' or 'endsolid', found 'face'");
    expect_text_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                      "vertex 0 1 0\nendloop\nendfacet\nendsolid x\ngarbage\n",
                      "t.stl:10: expected 'solid' or the end of the file after 'endsolid'");
    expect_text_error("solid empty\nendsolid empty\n", "t.stl: contains no faces");
}

SR_TEST(stl_every_truncation_fails_cleanly)
{
    for (int kind = 0; kind < 2; kind++) {
        wbuf b = kind ? binary_cube("solid x") : ascii_cube();
        /* ASCII may lose "cube\n" after endsolid and still be whole. */
        size_t whole = kind ? b.n : b.n - strlen(" cube\n");
        for (size_t n = 0; n < whole; n++) {
            uint8_t *copy = malloc(n ? n : 1);
            memcpy(copy, b.p, n);
            sr_mesh m;
            sr_io_error err;
            sr_result r = sr_parse_stl(sr_test_ctx(), "cut.stl", copy, n, &m, &err);
            CHECK(r != SR_OK);
            CHECK(mesh_is_zero(&m));
            if (r == SR_OK) {
                sr_destroy_mesh(sr_test_ctx(), &m);
            }
            free(copy);
        }
        free(b.p);
    }
}

SR_TEST(stl_random_corruption_never_crashes)
{
    sr_rng rng = { 0xC0FFEEull };
    for (int kind = 0; kind < 2; kind++) {
        wbuf b = kind ? binary_cube("solid x") : ascii_cube();
        for (int trial = 0; trial < 3000; trial++) {
            uint8_t *copy = malloc(b.n);
            memcpy(copy, b.p, b.n);
            int flips = sr_rng_int(&rng, 1, 4);
            for (int k = 0; k < flips; k++) {
                copy[sr_rng_int(&rng, 0, (int)b.n - 1)] = (uint8_t)sr_rng_int(&rng, 0, 255);
            }
            sr_mesh m;
            sr_io_error err;
            if (sr_parse_stl(sr_test_ctx(), "x.stl", copy, b.n, &m, &err) == SR_OK) {
                for (size_t i = 0; i < 3 * m.triangle_count; i++) {
                    CHECK(m.indices[i] < m.vertex_count);
                }
                sr_destroy_mesh(sr_test_ctx(), &m);
            } else {
                CHECK(mesh_is_zero(&m));
            }
            free(copy);
        }
        free(b.p);
    }
}
