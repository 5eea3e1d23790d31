/*
 * test_obj.c - tests for the OBJ reader (src/io/obj.c): face forms, polygon
 * triangulation, colors from vertices and MTL files, every error with its
 * line, the number parser against strtof, and the shared models checked
 * against an independent scan of their text.
 */
#include "io/readers.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

/* The reader under test, whatever the file is named. */
static const sr_load_desc obj_desc = { .format = SR_FORMAT_OBJ };

/* ---- helpers ---------------------------------------------------------------- */

/* Parse `n` bytes from an exact-size heap copy, so that the sanitizers
 * catch any read past the end (the data is not NUL-terminated). */
static sr_result parse_mem(const char *name, const char *data, size_t n, sr_mesh *m,
                           sr_io_error *err)
{
    char *copy = calloc(n ? n : 1, 1);
    memcpy(copy, data, n);
    sr_result r = sr_parse_obj(sr_test_ctx(), name, copy, n, m, err);
    free(copy);
    return r;
}

static sr_result parse_str(const char *text, sr_mesh *m, sr_io_error *err)
{
    return parse_mem("t.obj", text, strlen(text), m, err);
}

static bool mesh_is_zero(const sr_mesh *m)
{
    static const sr_mesh zero;
    return memcmp(m, &zero, sizeof zero) == 0;
}

/* Parse and expect failure with `code`, a message containing `where` and
 * `what`, and *out left zeroed.  Prints what it got when it differs. */
static bool fails_with_len(const char *text, size_t n, sr_result code,
                           const char *where, const char *what)
{
    sr_mesh m;
    sr_io_error err = { { 0 } };
    memset(&m, 0x5a, sizeof m);
    sr_result r = parse_mem("t.obj", text, n, &m, &err);
    bool ok = r == code && strstr(err.message, where) && strstr(err.message, what) &&
              mesh_is_zero(&m);
    if (!ok) {
        fprintf(stderr, "  got %s \"%s\" (mesh %s); wanted %s with \"%s\" and \"%s\"\n",
                sr_result_name(r), err.message, mesh_is_zero(&m) ? "zeroed" : "NOT zeroed",
                sr_result_name(code), where, what);
    }
    if (r == SR_OK) {
        sr_destroy_mesh(sr_test_ctx(), &m);
    }
    return ok;
}

static bool fails_with(const char *text, const char *where, const char *what)
{
    return fails_with_len(text, strlen(text), SR_BAD_FORMAT, where, what);
}

typedef struct dvec { double x, y, z; } dvec;

static dvec vpos(const sr_mesh *m, uint32_t i)
{
    const float *p = m->positions + 3 * (size_t)i;
    return (dvec){ p[0], p[1], p[2] };
}

static dvec dsub(dvec a, dvec b) { return (dvec){ a.x - b.x, a.y - b.y, a.z - b.z }; }
static double ddot(dvec a, dvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static dvec dcross(dvec a, dvec b)
{
    return (dvec){ a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}

/* Twice-area vector of triangle t (its normal times 2 * area). */
static dvec tri_cross(const sr_mesh *m, size_t t)
{
    const uint32_t *ix = m->indices + 3 * t;
    dvec a = vpos(m, ix[0]), b = vpos(m, ix[1]), c = vpos(m, ix[2]);
    return dcross(dsub(b, a), dsub(c, a));
}

/* Every index in range. */
static bool indices_valid(const sr_mesh *m)
{
    for (size_t i = 0; i < 3 * m->triangle_count; i++) {
        if (m->indices[i] >= m->vertex_count) {
            return false;
        }
    }
    return true;
}

/* Write a polygon given as 2D points (x, y) mapped into 3D by the rows of
 * `basis` (origin, u axis, v axis) as an OBJ with one face. */
static char *polygon_obj(const double (*pts)[2], int n, const double basis[3][3])
{
    size_t cap = 64 + (size_t)n * 96;
    char *s = malloc(cap);
    size_t len = 0;
    for (int i = 0; i < n; i++) {
        double p[3];
        for (int k = 0; k < 3; k++) {
            p[k] = basis[0][k] + pts[i][0] * basis[1][k] + pts[i][1] * basis[2][k];
        }
        len += (size_t)snprintf(s + len, cap - len, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
    }
    len += (size_t)snprintf(s + len, cap - len, "f");
    for (int i = 0; i < n; i++) {
        len += (size_t)snprintf(s + len, cap - len, " %d", i + 1);
    }
    snprintf(s + len, cap - len, "\n");
    return s;
}

static double shoelace(const double (*pts)[2], int n)
{
    double a = 0;
    for (int i = 0; i < n; i++) {
        const double *p = pts[i], *q = pts[(i + 1) % n];
        a += p[0] * q[1] - q[0] * p[1];
    }
    return a / 2;
}

/* Triangulate pts (counter-clockwise in the u, v plane of `basis`) and
 * check: n - 2 triangles, none inverted against the plane normal u x v,
 * and their areas sum to the polygon's (which an overlap or a triangle
 * outside the polygon would break). */
static void check_polygon(const double (*pts)[2], int n, const double basis[3][3], bool reversed)
{
    double (*p)[2] = malloc((size_t)n * sizeof *p);
    for (int i = 0; i < n; i++) {
        int j = reversed ? n - 1 - i : i;
        p[i][0] = pts[j][0];
        p[i][1] = pts[j][1];
    }
    char *text = polygon_obj((const double (*)[2])p, n, basis);
    sr_mesh m;
    sr_io_error err;
    sr_result r = parse_str(text, &m, &err);
    CHECK_EQ(r, SR_OK);
    if (r == SR_OK) {
        dvec u = { basis[1][0], basis[1][1], basis[1][2] };
        dvec v = { basis[2][0], basis[2][1], basis[2][2] };
        dvec normal = dcross(u, v);
        double scale = sqrt(ddot(normal, normal));
        if (reversed) {
            normal = (dvec){ -normal.x, -normal.y, -normal.z };
        }
        CHECK_EQ(m.triangle_count, (size_t)n - 2);
        CHECK(indices_valid(&m));
        double area = 0;
        int inverted = 0;
        for (size_t t = 0; t < m.triangle_count; t++) {
            dvec c = tri_cross(&m, t);
            area += sqrt(ddot(c, c)) / 2;
            if (ddot(c, normal) <= 0) {
                inverted++;
            }
        }
        double want = fabs(shoelace(pts, n)) * scale;
        CHECK_EQ(inverted, 0);
        CHECK_NEAR(area, want, 1e-4 * want);
        sr_destroy_mesh(sr_test_ctx(), &m);
    }
    free(text);
    free(p);
}

static const double basis_xy[3][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
/* A tilted plane, away from the origin, with no axis-aligned projection. */
static const double basis_tilted[3][3] = {
    { 10, -3, 7 }, { 0.6, 0.64, 0.48 }, { -0.8, 0.48, 0.36 },
};

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    REQUIRE(f != NULL);
    fputs(text, f);
    fclose(f);
}

static char *join_path(const char *dir, const char *rel)
{
    size_t n = strlen(dir) + strlen(rel) + 2;
    char *s = malloc(n);
    if (!s) {
        abort();
    }
    snprintf(s, n, "%s/%s", dir, rel);
    return s;
}

/* A bad token quoted in the message keeps no control byte: an escape
 * sequence in a file would otherwise reach the terminal. */
SR_TEST(obj_error_messages_hold_no_control_bytes)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/obj_escape.obj", sr_test_out_dir());
    write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 \x1b[2J\x1b[31mRED\x7f\nf 1 2 3\n");
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), path, NULL, &m, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "obj_escape.obj:3:");
    for (const char *c = err.message; *c; c++) {
        unsigned char b = (unsigned char)*c;
        CHECK(b >= 0x20 && b != 0x7f);
    }
    if (sr_test_failed_now()) {
        fprintf(stderr, "  message: \"%s\"\n", err.message);
    }
}

/* ---- face forms and indices ------------------------------------------------ */

SR_TEST(obj_face_with_positions_only)
{
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &m, &err) == SR_OK);
    CHECK_EQ(m.vertex_count, 3);
    CHECK_EQ(m.triangle_count, 1);
    CHECK(m.normals == NULL);
    CHECK(m.texcoords == NULL);
    CHECK(m.colors == NULL);
    CHECK(m.texture_path == NULL);
    CHECK_EQ(m.positions[3], 1.0f);
    CHECK_EQ(m.positions[7], 1.0f);
    CHECK(tri_cross(&m, 0).z > 0);   /* the file's counter-clockwise winding kept */
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(obj_face_with_texcoords)
{
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25 0.5\nvt 0.75 0.125 0\nvt 1\n"
                      "f 1/1 2/2 3/3\n", &m, &err) == SR_OK);
    REQUIRE(m.texcoords != NULL);
    CHECK(m.normals == NULL);
    CHECK_EQ(m.vertex_count, 3);
    CHECK_EQ(m.texcoords[0], 0.25f);
    CHECK_EQ(m.texcoords[1], 0.5f);
    CHECK_EQ(m.texcoords[2], 0.75f);
    CHECK_EQ(m.texcoords[3], 0.125f);
    CHECK_EQ(m.texcoords[4], 1.0f);     /* "vt u": v defaults to 0 */
    CHECK_EQ(m.texcoords[5], 0.0f);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(obj_face_with_normals)
{
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0\n"
                      "f 1//1 2//1 3//2\n", &m, &err) == SR_OK);
    REQUIRE(m.normals != NULL);
    CHECK(m.texcoords == NULL);
    CHECK_EQ(m.normals[2], 1.0f);
    CHECK_EQ(m.normals[5], 1.0f);
    CHECK_EQ(m.normals[7], 1.0f);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(obj_face_with_all_three_and_shared_corners)
{
    sr_mesh m;
    sr_io_error err;
    /* A quad as two triangles: corners 1 and 3 have the same tuple in both
     * and are shared; corner 4 differs only in its vt and is split. */
    REQUIRE(parse_str("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\nvn 0 0 1\n"
                      "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\nf 4/5/1 1/1/1 3/3/1\n",
                      &m, &err) == SR_OK);
    CHECK_EQ(m.triangle_count, 3);
    CHECK_EQ(m.vertex_count, 5);
    CHECK(m.normals != NULL && m.texcoords != NULL);
    CHECK_EQ(m.indices[3], m.indices[0]);
    CHECK_EQ(m.indices[4], m.indices[2]);
    CHECK(m.indices[5] != m.indices[6]);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(obj_mixed_corner_forms_in_one_face)
{
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nvn 0 0 1\n"
                      "f 1/1/1 2//1 3/1/1\n", &m, &err) == SR_OK);
    REQUIRE(m.texcoords != NULL);
    CHECK(m.normals != NULL);
    CHECK_EQ(m.texcoords[2], 0.0f);    /* the corner without vt gets (0, 0) */
    CHECK_EQ(m.texcoords[3], 0.0f);
    CHECK_EQ(m.texcoords[4], 0.5f);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(obj_partial_normals_are_dropped_and_corners_merged)
{
    sr_mesh m;
    sr_io_error err;
    /* One face has normals, one has not: normals go (the caller computes
     * them), and v1 and v3, used by both faces, become one vertex each. */
    REQUIRE(parse_str("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                      "f 1//1 2//1 3//1\nf 1 3 4\n", &m, &err) == SR_OK);
    CHECK(m.normals == NULL);
    CHECK_EQ(m.vertex_count, 4);
    CHECK_EQ(m.indices[3], m.indices[0]);
    CHECK_EQ(m.indices[4], m.indices[2]);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(obj_negative_indices_are_relative)
{
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
                      "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n"
                      "v 1 1 0\n"
                      "f -3 -1 -2\n", &m, &err) == SR_OK);
    CHECK_EQ(m.triangle_count, 2);
    CHECK(m.normals == NULL);           /* the second face has none */
    dvec a = vpos(&m, m.indices[3]), b = vpos(&m, m.indices[4]), c = vpos(&m, m.indices[5]);
    CHECK(a.x == 1 && a.y == 0);        /* -3 after four vertices: v2 */
    CHECK(b.x == 1 && b.y == 1);        /* -1: v4 */
    CHECK(c.x == 0 && c.y == 1);        /* -2: v3 */
    sr_destroy_mesh(sr_test_ctx(), &m);
}

/* ---- polygons ------------------------------------------------------------------ */

SR_TEST(obj_quad_becomes_two_triangles)
{
    static const double quad[4][2] = { { 0, 0 }, { 2, 0 }, { 2, 1 }, { 0, 1 } };
    check_polygon(quad, 4, basis_xy, false);
    check_polygon(quad, 4, basis_tilted, false);
    check_polygon(quad, 4, basis_tilted, true);
}

SR_TEST(obj_concave_l_shape_is_ear_clipped)
{
    /* Starts at a corner that cannot see the whole polygon, so a fan from
     * the first corner would invert a triangle. */
    static const double l_shape[6][2] = {
        { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 }, { 0, 0 },
    };
    check_polygon(l_shape, 6, basis_xy, false);
    check_polygon(l_shape, 6, basis_xy, true);
    check_polygon(l_shape, 6, basis_tilted, false);
    check_polygon(l_shape, 6, basis_tilted, true);
}

SR_TEST(obj_concave_arrow_is_ear_clipped)
{
    static const double arrow[7][2] = {
        { 4, 1 }, { 2, 3 }, { 2, 2 }, { 0, 2 }, { 0, 0 }, { 2, 0 }, { 2, -1 },
    };
    check_polygon(arrow, 7, basis_xy, false);
    check_polygon(arrow, 7, basis_tilted, true);
    /* A chevron: the reflex corner is the first one. */
    static const double chevron[4][2] = { { 1, 1 }, { 0, 2 }, { 1, 0 }, { 2, 2 } };
    check_polygon(chevron, 4, basis_xy, false);
    check_polygon(chevron, 4, basis_tilted, true);
}

SR_TEST(obj_large_star_polygon_is_ear_clipped)
{
    enum { N = 400 };
    static double star[N][2];
    for (int i = 0; i < N; i++) {
        double a = 2 * 3.14159265358979 * i / N, r = i % 2 ? 1.0 : 3.0;
        star[i][0] = r * cos(a);
        star[i][1] = r * sin(a);
    }
    check_polygon((const double (*)[2])star, N, basis_xy, false);
    check_polygon((const double (*)[2])star, N, basis_tilted, true);
}

SR_TEST(obj_degenerate_polygons_terminate)
{
    static const char *cases[] = {
        /* all corners on one line */
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nv 4 0 0\nf 1 2 3 4 5\n",
        /* all at one point */
        "v 1 1 1\nv 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3 4\n",
        /* a repeated corner */
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 2 3 4\n",
        /* a bow tie (self-intersecting) */
        "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n",
        /* a pentagram: every turn the same way, winding twice */
        "v 0 1 0\nv 0.588 -0.809 0\nv -0.951 0.309 0\nv 0.951 0.309 0\nv -0.588 -0.809 0\n"
        "f 1 2 3 4 5\n",
        /* a self-overlapping spiral (concave, no simple triangulation) */
        "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 1 4 0\nv 1 1 0\nv 3 1 0\nv 3 3 0\nv 2 3 0\nv 2 -1 0\n"
        "f 1 2 3 4 5 6 7 8 9\n",
    };
    static const size_t tris[] = { 3, 2, 3, 2, 3, 7 };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sr_mesh m;
        sr_io_error err;
        sr_result r = parse_str(cases[i], &m, &err);
        CHECK_EQ(r, SR_OK);
        if (r == SR_OK) {
            CHECK_EQ(m.triangle_count, tris[i]);
            CHECK(indices_valid(&m));
            sr_destroy_mesh(sr_test_ctx(), &m);
        }
    }
}

/* ---- colors and materials --------------------------------------------------- */

SR_TEST(obj_vertex_colors)
{
    sr_mesh m;
    sr_io_error err;
    REQUIRE(parse_str("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 1 1 0\n"
                      "f 1 2 3\nf 2 4 3\n", &m, &err) == SR_OK);
    REQUIRE(m.colors != NULL);
    const float *c0 = m.colors + 4 * m.indices[0];
    const float *c1 = m.colors + 4 * m.indices[1];
    const float *c4 = m.colors + 4 * m.indices[4];  /* v4 has no color: white */
    CHECK(c0[0] == 1 && c0[1] == 0 && c0[2] == 0 && c0[3] == 1);
    CHECK(c1[0] == 0 && c1[1] == 1 && c1[2] == 0 && c1[3] == 1);
    CHECK(c4[0] == 1 && c4[1] == 1 && c4[2] == 1 && c4[3] == 1);
    sr_destroy_mesh(sr_test_ctx(), &m);

    /* "v x y z w" carries no color. */
    REQUIRE(parse_str("v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n", &m, &err) == SR_OK);
    CHECK(m.colors == NULL);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

static const char scene_obj[] =
    "# a scene with materials\n"
    "mtllib mats/scene.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
    "f 1 2 3\n"             /* before any usemtl: white */
    "usemtl red\n"
    "f 1 3 4\n"
    "usemtl blue\n"
    "f 2 5 3\n"
    "usemtl nokd\n"
    "f 3 5 4\n"             /* a material without Kd: white */
    "usemtl missing\n"
    "f 1 2 4\n";            /* not in the MTL: white */

static const char scene_mtl[] =
    "# materials\n"
    "newmtl red\n"
    "Ka 0 0 0\n"
    "Kd 1 0 0\n"
    "map_Kd -s 1 1 1 -o 0 0 textures\\red.png\n"
    "newmtl blue\r\n"
    "\tKd 0 0 1\r\n"
    "map_Kd blue.png\n"
    "newmtl nokd\n"
    "Ns 10\n";

static bool color_is(const sr_mesh *m, uint32_t v, float r, float g, float b)
{
    const float *c = m->colors + 4 * (size_t)v;
    return c[0] == r && c[1] == g && c[2] == b && c[3] == 1.0f;
}

SR_TEST(obj_mtl_kd_colors_and_map_kd)
{
    char *dir = join_path(sr_test_out_dir(), "obj_mtl");
    char *mats = join_path(dir, "mats");
    mkdir(dir, 0777);
    mkdir(mats, 0777);
    char *obj = join_path(dir, "scene.obj");
    char *mtl = join_path(mats, "scene.mtl");
    write_file(obj, scene_obj);
    write_file(mtl, scene_mtl);

    sr_mesh m;
    sr_io_error err;
    sr_result r = sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err);
    CHECK_EQ(r, SR_OK);
    if (r == SR_OK) {
        REQUIRE(m.colors != NULL);
        CHECK_EQ(m.triangle_count, 5);
        /* Corners of differently colored faces are split, white ones shared
         * (see the face comments in scene_obj): 11 distinct vertices. */
        CHECK_EQ(m.vertex_count, 11);
        for (int k = 0; k < 3; k++) {
            CHECK(color_is(&m, m.indices[0 + k], 1, 1, 1));
            CHECK(color_is(&m, m.indices[3 + k], 1, 0, 0));
            CHECK(color_is(&m, m.indices[6 + k], 0, 0, 1));
            CHECK(color_is(&m, m.indices[9 + k], 1, 1, 1));
            CHECK(color_is(&m, m.indices[12 + k], 1, 1, 1));
        }
        CHECK_EQ(m.indices[12], m.indices[0]);     /* white v1 shared */
        /* The first used material's map_Kd, options skipped, backslash
         * turned into a slash, relative to the MTL's folder. */
        char *want = join_path(mats, "textures/red.png");
        REQUIRE(m.texture_path != NULL);
        CHECK_STR_CONTAINS(m.texture_path, want);
        CHECK_EQ(strlen(m.texture_path), strlen(want));
        /* The faces take different textures, so they come in parts: the
         * first face none, then red, blue, and the last two none - a
         * material without map_Kd but with an Ns of its own (so a part of
         * its own), and one the MTL does not define. */
        REQUIRE(m.parts != NULL);
        CHECK_EQ(m.part_count, 5);
        for (size_t i = 0; i < 5 && i < m.part_count; i++) {
            CHECK_EQ(m.parts[i].first_triangle, i);
            CHECK_EQ(m.parts[i].triangle_count, 1);
        }
        CHECK(m.parts[0].texture_path == NULL && m.parts[3].texture_path == NULL &&
              m.parts[4].texture_path == NULL);
        CHECK(m.parts[3].material.has_shininess && m.parts[3].material.shininess == 10.0f);
        CHECK(!m.parts[4].material.has_shininess);
        REQUIRE(m.parts[1].texture_path && m.parts[2].texture_path);
        CHECK(strcmp(m.parts[1].texture_path, m.texture_path) == 0);
        char *blue = join_path(mats, "blue.png");
        CHECK(strcmp(m.parts[2].texture_path, blue) == 0);
        free(blue);
        free(want);
        sr_destroy_mesh(sr_test_ctx(), &m);
        CHECK(m.parts == NULL && m.part_count == 0);
    } else {
        fprintf(stderr, "  %s\n", err.message);
    }

    /* From memory there is no folder: mtllib is ignored. */
    r = parse_str(scene_obj, &m, &err);
    CHECK_EQ(r, SR_OK);
    if (r == SR_OK) {
        CHECK(m.colors == NULL);
        CHECK(m.texture_path == NULL);
        CHECK_EQ(m.vertex_count, 5);   /* usemtl without colors splits nothing */
        sr_destroy_mesh(sr_test_ctx(), &m);
    }
    free(obj);
    free(mtl);
    free(mats);
    free(dir);
}

/* Parts follow the textures, not the materials: two materials naming the
 * same file make one part, and a model whose faces all take one texture
 * has no parts at all. */
SR_TEST(obj_parts_follow_textures_not_materials)
{
    char *obj = join_path(sr_test_out_dir(), "obj_parts.obj");
    char *mtl = join_path(sr_test_out_dir(), "obj_parts.mtl");
    write_file(mtl, "newmtl a\nKd 1 0 0\nmap_Kd wood.png\n"
                    "newmtl b\nKd 0 1 0\nmap_Kd wood.png\n"
                    "newmtl c\nmap_Kd stone.png\n");
    write_file(obj, "mtllib obj_parts.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                    "usemtl a\nf 1 2 3\nusemtl b\nf 2 4 3\nf 1 2 4\n"
                    "usemtl c\nf 1 3 4\nusemtl a\nf 1 2 3\n");
    sr_mesh m;
    sr_io_error err;
    REQUIRE(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err) == SR_OK);
    REQUIRE(m.parts != NULL);
    CHECK_EQ(m.part_count, 3);          /* wood (a, b), stone (c), wood (a) */
    CHECK(m.part_count == 3 && m.parts[0].triangle_count == 3 && m.parts[1].first_triangle == 3 &&
          m.parts[1].triangle_count == 1 && m.parts[2].first_triangle == 4 &&
          m.parts[2].triangle_count == 1);
    CHECK(m.part_count == 3 && strstr(m.parts[1].texture_path, "stone.png") &&
          strstr(m.parts[2].texture_path, "wood.png"));
    sr_destroy_mesh(sr_test_ctx(), &m);

    write_file(obj, "mtllib obj_parts.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                    "usemtl a\nf 1 2 3\nusemtl b\nf 2 4 3\n");
    REQUIRE(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err) == SR_OK);
    CHECK(m.parts == NULL);
    CHECK_EQ(m.part_count, 0);
    REQUIRE(m.texture_path != NULL);
    CHECK(strstr(m.texture_path, "wood.png") != NULL);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(obj);
    free(mtl);
}

/* Ks, Ns, d, Tr, Pm, Pr and the bump maps reach sr_mesh_part.material;
 * a material saying them is a part of its own even when it is the only
 * one, and a malformed statement names its line. */
SR_TEST(obj_material_statements_reach_the_parts)
{
    char *obj = join_path(sr_test_out_dir(), "obj_looks.obj");
    char *mtl = join_path(sr_test_out_dir(), "obj_looks.mtl");
    write_file(mtl, "newmtl shiny\nKd 1 0 0\nKs 0.5 0.25 1\nNs 250\nd 0.4\n"
                    "map_Bump -bm 2.5 -clamp on bumps.png\n"
                    "newmtl metal\nKs 0.3\nTr 0.25\nPm 1\nPr 0.2\nnorm normals.png\n"
                    "newmtl plain\nKd 0 1 0\n");
    write_file(obj, "mtllib obj_looks.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                    "usemtl shiny\nf 1 2 3\nusemtl metal\nf 2 4 3\nusemtl plain\nf 1 2 4\n");
    sr_mesh m;
    sr_io_error err;
    REQUIRE(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err) == SR_OK);
    REQUIRE(m.part_count == 3);
    const sr_mesh_material *a = &m.parts[0].material, *b = &m.parts[1].material,
                           *c = &m.parts[2].material;
    CHECK(a->has_specular && a->specular[0] == 0.5f && a->specular[1] == 0.25f &&
          a->specular[2] == 1.0f);
    CHECK(a->has_shininess && a->shininess == 250.0f);
    CHECK(a->has_opacity && a->opacity == 0.4f);
    CHECK(!a->has_metallic && !a->has_roughness);
    CHECK(a->bump_path && strstr(a->bump_path, "bumps.png") && !a->bump_is_normal);
    CHECK_EQ(a->bump_scale, 2.5f);
    CHECK(b->has_specular && b->specular[0] == 0.3f && b->specular[2] == 0.3f);
    CHECK(b->has_opacity && b->opacity == 0.75f);
    CHECK(b->has_metallic && b->metallic == 1.0f && b->has_roughness && b->roughness == 0.2f);
    CHECK(b->bump_path && strstr(b->bump_path, "normals.png") && b->bump_is_normal);
    CHECK(!c->has_specular && !c->has_opacity && !c->bump_path);
    /* The copy sr_make_mesh makes carries the bump path too. */
    sr_mesh copy;
    REQUIRE(sr_make_mesh(sr_test_ctx(), &m, &copy) == SR_OK);
    CHECK(copy.parts[1].material.bump_path != m.parts[1].material.bump_path &&
          strcmp(copy.parts[1].material.bump_path, m.parts[1].material.bump_path) == 0);
    sr_destroy_mesh(sr_test_ctx(), &copy);
    sr_destroy_mesh(sr_test_ctx(), &m);

    write_file(obj, "mtllib obj_looks.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl shiny\nf 1 2 3\n");
    REQUIRE(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err) == SR_OK);
    CHECK(m.part_count == 1 && m.parts[0].triangle_count == 1 &&
          m.parts[0].material.has_shininess);
    sr_destroy_mesh(sr_test_ctx(), &m);

    write_file(mtl, "newmtl shiny\nNs 1 2\n");
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "obj_looks.mtl:2: 'Ns' takes one number");
    free(obj);
    free(mtl);
}

typedef struct files_heard {
    int count;
    char last[1024];
} files_heard;

static void hear_file(void *user, const char *path)
{
    files_heard *h = user;
    h->count++;
    snprintf(h->last, sizeof h->last, "%s", path);
}

/* sr_load_desc.file_read hears of each MTL file read, once, and of no
 * missing one: a program can then refuse to write over any of them. */
SR_TEST(load_reports_the_mtl_files_it_reads)
{
    char *obj = join_path(sr_test_out_dir(), "obj_heard.obj");
    char *mtl = join_path(sr_test_out_dir(), "obj_heard.mtl");
    write_file(mtl, "newmtl a\nKd 1 0 0\n");
    write_file(obj, "mtllib obj_heard.mtl\nmtllib obj_heard.mtl\nmtllib no_such.mtl\n"
                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    files_heard heard = { 0 };
    sr_mesh m;
    sr_io_error err;
    REQUIRE(sr_load_mesh(sr_test_ctx(), obj,
                         &(sr_load_desc){ .file_read = hear_file, .user = &heard }, &m,
                         &err) == SR_OK);
    CHECK_EQ(heard.count, 1);
    CHECK(strcmp(heard.last, mtl) == 0);
    sr_destroy_mesh(sr_test_ctx(), &m);
    /* Without a callback the same file loads the same. */
    REQUIRE(sr_load_mesh(sr_test_ctx(), obj, NULL, &m, &err) == SR_OK);
    CHECK_EQ(m.triangle_count, 1);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(obj);
    free(mtl);
}

SR_TEST(obj_vertex_color_wins_over_kd)
{
    char *obj = join_path(sr_test_out_dir(), "obj_vcol.obj");
    char *mtl = join_path(sr_test_out_dir(), "obj_vcol.mtl");
    write_file(mtl, "newmtl green\nKd 0 1 0\n");
    write_file(obj, "mtllib obj_vcol.mtl\nv 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\n"
                    "usemtl green\nf 1 2 3\n");
    sr_mesh m;
    sr_io_error err;
    REQUIRE(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err) == SR_OK);
    REQUIRE(m.colors != NULL);
    CHECK(color_is(&m, m.indices[0], 1, 0, 0));
    CHECK(color_is(&m, m.indices[1], 0, 1, 0));
    CHECK(m.texture_path == NULL);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(obj);
    free(mtl);
}

SR_TEST(obj_missing_mtl_is_ignored)
{
    char *obj = join_path(sr_test_out_dir(), "obj_nomtl.obj");
    write_file(obj, "mtllib no_such_file.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    sr_mesh m;
    sr_io_error err;
    REQUIRE(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err) == SR_OK);
    CHECK(m.colors == NULL);
    CHECK_EQ(m.triangle_count, 1);
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(obj);
}

SR_TEST(obj_bad_mtl_names_its_own_line)
{
    char *obj = join_path(sr_test_out_dir(), "obj_badmtl.obj");
    char *mtl = join_path(sr_test_out_dir(), "obj_badmtl.mtl");
    write_file(mtl, "newmtl a\nKd 1 0 0\n\nKd 0.5 nan 0\n");
    write_file(obj, "mtllib obj_badmtl.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "obj_badmtl.mtl:4:");
    CHECK_STR_CONTAINS(err.message, "not a finite number");
    CHECK(mesh_is_zero(&m));
    free(obj);
    free(mtl);
}

SR_TEST(obj_load_missing_file_is_an_io_error)
{
    char *obj = join_path(sr_test_out_dir(), "obj_does_not_exist.obj");
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), obj, &obj_desc, &m, &err), SR_IO_ERROR);
    CHECK(mesh_is_zero(&m));
    free(obj);
}

/* ---- text handling ------------------------------------------------------------- */

SR_TEST(obj_comments_crlf_tabs_continuations_and_skipped_statements)
{
    static const char text[] =
        "\xEF\xBB\xBF# exported by something \xe9 (Latin-1 in a comment is fine)\r\n"
        "mtllib none.mtl\r\n"
        "o thing\r\n"
        "g group one\r\n"
        "s 1\r\n"
        "v\t0 0 0   # trailing comment\r\n"
        "v 1 \\\r\n"
        "  0 0\r\n"
        "v 0 1 0\r\n"
        "vp 0.5\r\n"
        "l 1 2\r\n"
        "p 3\r\n"
        "curv 0 1 1 2\r\n"
        "\r\n"
        "   \t\r\n"
        "usemtl x\r\n"
        "f 1\t2 \\\n 3\r\n"
        "  f 1 3 2";        /* no final newline */
    sr_mesh m;
    sr_io_error err;
    sr_result r = parse_str(text, &m, &err);
    CHECK_EQ(r, SR_OK);
    if (r != SR_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return;
    }
    CHECK_EQ(m.triangle_count, 2);
    CHECK_EQ(m.vertex_count, 3);
    CHECK_EQ(m.positions[3], 1.0f);
    sr_destroy_mesh(sr_test_ctx(), &m);

    /* Line numbers count physical lines, continuations included. */
    CHECK(fails_with("v 0 0 \\\n0\nv 1 0 0\r\nv 0 1 0\nf 1 2 5\n", "t.obj:5:", "vertex index 5"));
}

/* ---- errors -------------------------------------------------------------------- */

#define TRI "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

SR_TEST(obj_index_errors_name_the_line)
{
    CHECK(fails_with(TRI "f 1 2 4\n", "t.obj:4:", "vertex index 4"));
    CHECK(fails_with(TRI "f 1 2 4\n", "t.obj:4:", "out of range"));
    CHECK(fails_with(TRI "# note\nf 0 1 2\n", "t.obj:5:", "index 0"));
    CHECK(fails_with(TRI "f -4 -1 -2\n", "t.obj:4:", "vertex index -4"));
    CHECK(fails_with(TRI "vt 0 0\nf 1/1 2/2 3/1\n", "t.obj:5:", "texture coordinate index 2"));
    CHECK(fails_with(TRI "vn 0 0 1\nf 1//1 2//1 3//2\n", "t.obj:5:", "normal index 2"));
    CHECK(fails_with(TRI "f 1//1 2//1 3//1\n", "t.obj:4:", "normal index 1"));
    CHECK(fails_with(TRI "f 1 2 99999999999999999999\n", "t.obj:4:", "out of range"));
    /* Forward references: the data must come first. */
    CHECK(fails_with("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", "t.obj:3:", "vertex index 3"));
}

/* `dir` (under the output dir) made `levels` folders of 50 characters
 * deeper; the new path in buf. */
static bool make_deep_dir(const char *name, int levels, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%s/%s", sr_test_out_dir(), name);
    mkdir(buf, 0777);
    for (int i = 0; i < levels; i++) {
        n += snprintf(buf + n, size - (size_t)n, "/%02d%048d", i, 0);
        if ((size_t)n >= size || (mkdir(buf, 0777) != 0 && errno != EEXIST)) {
            return false;
        }
    }
    return true;
}

/* The line number and the reason outlive any path length: a long name gives
 * way from the left, keeping its tail (the file's own name). */
SR_TEST(obj_errors_in_long_paths_keep_the_line_and_the_reason)
{
    static const char text[] = TRI "f 0 1 2\n";
    static const char reason[] = ":4: index 0 in face vertex '0': OBJ indices start at 1";
    sr_mesh m;
    sr_io_error err;
    /* 7 folders: over 400 characters, which fit in the message whole;
     * 12: about 650, which do not. */
    for (int levels = 7; levels <= 12; levels += 5) {
        char dir[1024], path[1100];
        REQUIRE(make_deep_dir("long_paths", levels, dir, sizeof dir));
        snprintf(path, sizeof path, "%s/long_path_model.obj", dir);
        REQUIRE(strlen(path) > 400);
        write_file(path, text);
        CHECK_EQ(sr_load_mesh(sr_test_ctx(), path, NULL, &m, &err), SR_BAD_FORMAT);
        CHECK(mesh_is_zero(&m));
        size_t len = strlen(err.message), rlen = strlen(reason);
        /* The message ends with the whole reason, right after the name's tail. */
        CHECK(len > rlen && strcmp(err.message + len - rlen, reason) == 0);
        CHECK_STR_CONTAINS(err.message, "/long_path_model.obj:4: index 0");
        if (strlen(path) + rlen < sizeof err.message) {
            CHECK(strncmp(err.message, path, strlen(path)) == 0);
            CHECK_EQ(len, strlen(path) + rlen);
        } else {
            CHECK(strncmp(err.message, "...", 3) == 0);
            CHECK_EQ(len, sizeof err.message - 1);   /* the tail fills what is left */
            CHECK(strncmp(err.message + 3, path + strlen(path) - (len - 3 - rlen),
                          len - 3 - rlen) == 0);
        }
        if (sr_test_failed_now()) {
            fprintf(stderr, "  %zu-character path: \"%s\"\n", strlen(path), err.message);
        }
    }
}

SR_TEST(obj_nonfinite_and_overflowing_numbers_are_refused)
{
    CHECK(fails_with("v 0 0 0\nv nan 0 0\n", "t.obj:2:", "'nan' is not a finite number"));
    CHECK(fails_with("v 0 0 0\nv 0 -inf 0\n", "t.obj:2:", "not a finite number"));
    CHECK(fails_with("v 0 0 Infinity\n", "t.obj:1:", "not a finite number"));
    CHECK(fails_with("v 0 0 NaN\n", "t.obj:1:", "not a finite number"));
    CHECK(fails_with("\n\nv 1e999 0 0\n", "t.obj:3:", "'1e999' is too large"));
    CHECK(fails_with("v 0 3.5e38 0\n", "t.obj:1:", "too large for a float"));
    CHECK(fails_with(TRI "vn 0 0 1e39\n", "t.obj:4:", "too large"));
    CHECK(fails_with(TRI "vt nan 0\n", "t.obj:4:", "not a finite number"));
    CHECK(fails_with(TRI "v 0 0 0 1 nan 0\n", "t.obj:4:", "not a finite number"));
}

SR_TEST(obj_malformed_numbers_and_statements_are_refused)
{
    static const char *bad[] = {
        "1.2.3", "1,5", "abc", "1e", "1e+", "-", "+", ".", "0x10", "--1", "1ee2", "1e2.5", "1f",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[128];
        snprintf(text, sizeof text, "v 0 0 0\nv 0 %s 0\n", bad[i]);
        char what[64];
        snprintf(what, sizeof what, "malformed number '%s'", bad[i]);
        CHECK(fails_with(text, "t.obj:2:", what));
    }
    CHECK(fails_with("v 1 2\n", "t.obj:1:", "'v' takes"));
    CHECK(fails_with("v 1 2 3 4 5\n", "t.obj:1:", "found 5 numbers"));
    CHECK(fails_with("v 1 2 3 4 5 6 7\n", "t.obj:1:", "more than 6"));
    CHECK(fails_with("vn 1 2\n", "t.obj:1:", "'vn' takes"));
    CHECK(fails_with("vt\n", "t.obj:1:", "'vt' takes"));
    CHECK(fails_with(TRI "f 1/x 2 3\n", "t.obj:4:", "malformed face vertex '1/x'"));
    CHECK(fails_with(TRI "f 1/1/1/1 2 3\n", "t.obj:4:", "malformed face vertex"));
    CHECK(fails_with(TRI "f a b c\n", "t.obj:4:", "malformed face vertex 'a'"));
    CHECK(fails_with(TRI "f 1 2 3#c\n", "t.obj:4:", "malformed face vertex '3#c'"));
}

SR_TEST(obj_faces_with_fewer_than_three_vertices_are_refused)
{
    CHECK(fails_with(TRI "f 1 2\n", "t.obj:4:", "face has 2 vertices"));
    CHECK(fails_with(TRI "\nf\n", "t.obj:5:", "face has 0 vertices"));
    CHECK(fails_with(TRI "f 1 # 2 3\n", "t.obj:4:", "at least 3"));
}

SR_TEST(obj_binary_junk_is_refused)
{
    static const char nul[] = "v 0 0 0\nv 1 0 0\nv 0 1\0 0\nf 1 2 3\n";
    CHECK(fails_with_len(nul, sizeof nul - 1, SR_BAD_FORMAT, "t.obj:3:", "NUL byte"));
    static const char nul_comment[] = TRI "# \0\nf 1 2 3\n";
    CHECK(fails_with_len(nul_comment, sizeof nul_comment - 1, SR_BAD_FORMAT, "t.obj:4:", "NUL byte"));
    CHECK(fails_with(TRI "g caf\xe9\nf 1 2 3\n", "t.obj:4:", "not UTF-8"));
    CHECK(fails_with(TRI "f 1 2 3\n\x89PNG\n", "t.obj:5:", "byte 0x89"));
    CHECK(fails_with("v 0 0 0\xC0\xAF\n", "t.obj:1:", "not UTF-8"));       /* overlong */
    CHECK(fails_with("g \xED\xA0\x80\n", "t.obj:1:", "not UTF-8"));         /* surrogate */
    /* Valid UTF-8 in names is fine, and so is anything but NUL in comments. */
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(parse_str("g caf\xc3\xa9 \xe2\x9c\x93\n# \xff\xfe\n" TRI "f 1 2 3 # \xe9t\xe9\n",
                       &m, &err), SR_OK);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(obj_files_without_faces_are_refused)
{
    CHECK(fails_with("", "t.obj: ", "file is empty"));
    CHECK(fails_with("\n \r\n\t\n", "t.obj: ", "file is empty"));
    CHECK(fails_with("# only a comment\n", "t.obj: contains no faces", ""));
    CHECK(fails_with(TRI "l 1 2 3\n", "t.obj: contains no faces", ""));
    /* an SVG (or any markup) named .obj: its unknown lines are all skipped */
    CHECK(fails_with("\n <svg xmlns='http://www.w3.org/2000/svg'>\n</svg>\n",
                     "t.obj: contains no faces: it starts with '<'", "not an OBJ file"));
    sr_io_error err;
    sr_mesh m;
    CHECK_EQ(parse_str(TRI, &m, &err), SR_BAD_FORMAT);
    CHECK(strcmp(err.message, "t.obj: contains no faces") == 0);
    CHECK_EQ(parse_str("", &m, &err), SR_BAD_FORMAT);
    CHECK(strcmp(err.message, "t.obj: file is empty") == 0);
}

SR_TEST(obj_null_arguments)
{
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_parse_obj(sr_test_ctx(), "t.obj", NULL, 5, &m, &err), SR_INVALID_ARG);
    CHECK(mesh_is_zero(&m));
    CHECK_EQ(sr_parse_obj(sr_test_ctx(), "t.obj", "f", 1, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_parse_obj(sr_test_ctx(), "t.obj", NULL, 0, &m, &err), SR_BAD_FORMAT);   /* empty */
    CHECK_EQ(sr_parse_obj(sr_test_ctx(), NULL, TRI "f 1 2 3\n", sizeof TRI "f 1 2 3\n" - 1, &m, NULL), SR_OK);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

/* ---- robustness ------------------------------------------------------------------ */

static const char messy_obj[] =
    "# messy\r\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n"
    "f 1/1/1 2/2/1 3/3/1 4/1/1\nf -5 -3 \\\n -2\n"
    "usemtl a\nf 1 2 5 3 4\nf 5 4 3 2\n";

SR_TEST(obj_every_truncation_parses_or_fails_cleanly)
{
    size_t n = sizeof messy_obj - 1;
    for (size_t len = 0; len <= n; len++) {
        sr_mesh m;
        sr_io_error err;
        sr_result r = parse_mem("t.obj", messy_obj, len, &m, &err);
        if (r == SR_OK) {
            CHECK(indices_valid(&m));
            sr_destroy_mesh(sr_test_ctx(), &m);
        } else {
            CHECK_EQ(r, SR_BAD_FORMAT);
            CHECK(mesh_is_zero(&m));
        }
    }
}

SR_TEST(obj_random_corruption_never_crashes)
{
    sr_rng rng = { 0x0b1ec7ULL };
    size_t n = sizeof messy_obj - 1;
    char *buf = malloc(n);
    static const char alphabet[] = "0123456789-+./ \n\r\t#\\eEfvtn\x80\xff";
    for (int iter = 0; iter < 3000; iter++) {
        memcpy(buf, messy_obj, n);
        int flips = sr_rng_int(&rng, 1, 4);
        for (int k = 0; k < flips; k++) {
            buf[sr_rng_int(&rng, 0, (int)n - 1)] =
                alphabet[sr_rng_int(&rng, 0, (int)sizeof alphabet - 2)];
        }
        sr_mesh m;
        sr_io_error err;
        sr_result r = parse_mem("t.obj", buf, n, &m, &err);
        if (r == SR_OK) {
            CHECK(indices_valid(&m));
            sr_destroy_mesh(sr_test_ctx(), &m);
        } else {
            CHECK(r == SR_BAD_FORMAT);
            CHECK(mesh_is_zero(&m));
        }
    }
    free(buf);
}

/* Fault injection, as SQLite does it: replace malloc for this executable,
 * fail the k-th allocation for k = 0, 1, ... and check the result and that
 * nothing leaked.  glibc lets a program replace malloc; the sanitizers
 * replace it themselves, so there the test is skipped. */
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define OBJ_NO_FAULT_INJECTION 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define OBJ_NO_FAULT_INJECTION 1
#endif

#if defined(__GLIBC__) && !defined(OBJ_NO_FAULT_INJECTION)
extern void *__libc_malloc(size_t size);
extern void *__libc_calloc(size_t n, size_t size);
extern void *__libc_realloc(void *p, size_t size);
extern void __libc_free(void *p);

static long fault_countdown = -1;   /* allocations to let through; -1: never fail */
static long live_blocks;
static bool tracking;

static bool inject_failure(void)
{
    if (fault_countdown < 0) {
        return false;
    }
    return fault_countdown-- == 0;
}

void *malloc(size_t size)
{
    if (inject_failure()) {
        return NULL;
    }
    void *p = __libc_malloc(size);
    live_blocks += p && tracking;
    return p;
}

void *calloc(size_t n, size_t size)
{
    if (inject_failure()) {
        return NULL;
    }
    void *p = __libc_calloc(n, size);
    live_blocks += p && tracking;
    return p;
}

void *realloc(void *old, size_t size)
{
    if (inject_failure()) {
        return NULL;
    }
    void *p = __libc_realloc(old, size);
    live_blocks += p && !old && tracking;
    return p;
}

void free(void *p)
{
    live_blocks -= p && tracking;
    __libc_free(p);
}

/* The mesh's context allocates through the replaced malloc too, so its
 * blocks are counted and fail in turn like the reader's. */
static sr_context *fault_ctx;

static void *fault_alloc(size_t size, void *user)
{
    (void)user;
    return malloc(size);
}

static void fault_free(void *p, void *user)
{
    (void)user;
    free(p);
}

static void run_fault_injection(const char *what, sr_result (*run)(sr_mesh *, sr_io_error *),
                                bool file)
{
    int failures = 0;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1,
                                                .allocator = { .alloc = fault_alloc, .free = fault_free } },
                            &fault_ctx) == SR_OK);
    for (long k = 0; k < 100000; k++) {
        sr_mesh m;
        sr_io_error err;
        tracking = true;
        live_blocks = 0;
        fault_countdown = k;
        sr_result r = run(&m, &err);
        bool injected = fault_countdown < 0;
        fault_countdown = -1;
        bool zero = mesh_is_zero(&m);
        sr_destroy_mesh(fault_ctx, &m);
        long leaked = live_blocks;
        tracking = false;
        if (!injected) {
            CHECK_EQ(r, SR_OK);       /* every allocation succeeded */
            break;
        }
        /* A failed MTL read is ignored (colors are optional), so a run
         * may still succeed; when fopen itself runs out of memory, the file
         * cannot be opened. */
        if (r != SR_OK && r != SR_OUT_OF_MEMORY && !(file && r == SR_IO_ERROR)) {
            sr_test_fail(__FILE__, __LINE__, "%s: allocation %ld failed: got %s \"%s\"",
                         what, k, sr_result_name(r), err.message);
        }
        if (r == SR_OUT_OF_MEMORY) {
            failures++;
            CHECK(zero);
            CHECK_STR_CONTAINS(err.message, "out of memory");
        }
        if (leaked != 0) {
            sr_test_fail(__FILE__, __LINE__, "%s: allocation %ld failed: %ld blocks leaked",
                         what, k, leaked);
        }
    }
    CHECK(failures > 3);
    sr_destroy_context(fault_ctx);
}

static sr_result run_messy(sr_mesh *m, sr_io_error *err)
{
    /* Polygons, ear clipping, usemtl, continuation, vertex colors. */
    static const char text[] =
        "v 2 0 0 1 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\nvt 0 0\nvn 0 0 1\n"
        "usemtl a\nf 1/1/1 2/1/1 3/1/1 4/1/1 5/1/1 6/1/1\nusemtl b\nf 1 2 \\\n 3\n";
    return sr_parse_obj(fault_ctx, "t.obj", text, sizeof text - 1, m, err);
}

static const char *fault_obj_path;

static sr_result run_scene(sr_mesh *m, sr_io_error *err)
{
    return sr_load_mesh(fault_ctx, fault_obj_path, &obj_desc, m, err);
}

SR_TEST(obj_every_allocation_failure_is_reported_cleanly)
{
    run_fault_injection("memory", run_messy, false);
    char *dir = join_path(sr_test_out_dir(), "obj_mtl");
    char *mats = join_path(dir, "mats");
    mkdir(dir, 0777);
    mkdir(mats, 0777);
    char *obj = join_path(dir, "scene.obj");
    char *mtl = join_path(mats, "scene.mtl");
    write_file(obj, scene_obj);
    write_file(mtl, scene_mtl);
    fault_obj_path = obj;
    run_fault_injection("file", run_scene, true);
    free(obj);
    free(mtl);
    free(mats);
    free(dir);
}
#else
SR_TEST(obj_every_allocation_failure_is_reported_cleanly)
{
    SKIP("needs glibc's replaceable malloc, and no AddressSanitizer");
}
#endif

/* ---- the number parser ----------------------------------------------------------- */

/* Distance in ulps between two finite floats of any signs. */
static long long ulp_distance(float a, float b)
{
    int32_t ia, ib;
    memcpy(&ia, &a, 4);
    memcpy(&ib, &b, 4);
    long long oa = ia < 0 ? -(long long)(ia & 0x7fffffff) : ia;
    long long ob = ib < 0 ? -(long long)(ib & 0x7fffffff) : ib;
    return oa > ob ? oa - ob : ob - oa;
}

/* One random decimal in one of the forms exporters write. */
static void random_decimal(sr_rng *rng, char *out, size_t cap)
{
    double mag = pow(10.0, sr_rng_range(rng, -8, 8));
    double x = sr_rng_range(rng, -1, 1) * mag;
    switch (sr_rng_int(rng, 0, 6)) {
    case 0:     /* "%f"-style, as MeshLab and Blender write */
        snprintf(out, cap, "%.*f", sr_rng_int(rng, 0, 9), x);
        break;
    case 1:     /* shortest-ish significant digits */
        snprintf(out, cap, "%.*g", sr_rng_int(rng, 1, 9), x);
        break;
    case 2:     /* full double precision: more digits than the fast path */
        snprintf(out, cap, "%.17g", x);
        break;
    case 3:     /* exponents across the float range, denormals included */
        snprintf(out, cap, "%.*e", sr_rng_int(rng, 0, 12),
                 sr_rng_range(rng, -9.99, 9.99) * pow(10.0, sr_rng_int(rng, -45, 37)));
        break;
    case 4:     /* integers */
        snprintf(out, cap, "%d", sr_rng_int(rng, -100000, 100000));
        break;
    case 5:     /* long exact expansions: past 19 significant digits */
        snprintf(out, cap, "%.30f", x);
        break;
    default: {  /* '+' signs, leading dots, capital E */
        char tmp[48];
        snprintf(tmp, sizeof tmp, "%.*E", sr_rng_int(rng, 0, 8), fabs(x));
        if (tmp[0] == '0' && tmp[1] == '.') {
            snprintf(out, cap, "+%s", tmp + 1);
        } else {
            snprintf(out, cap, "+%s", tmp);
        }
        break;
    }
    }
}

SR_TEST(obj_number_parser_matches_strtof)
{
    /* N numbers make N / 3 vertices, used by N / 9 faces in order. */
    enum { N = 60003, NV = N / 3 };
    /* Edge cases: ties decided by the 26th digit, subnormals, the ends of
     * the range; every number is correctly rounded (src/io/number.h). */
    static const char *fixed[] = {
        "0", "-0", "1", "0.1", "16777217", "16777219", "3.4028235e38", "-3.4028234e38",
        "1.17549435e-38", "1.1754942e-38", "1e-45", "1.4e-45", "7.1e-46", "7e-46", "1e-50",
        "0.000000000000000000000000000000000000000000001", "123456789012345678901234567890",
        "1.000000059604644775390625", "1.00000005960464477539062499",
        "9.999999e-5", ".5", "5.", "+.5e+1", "-0.0e-0",
        "00000000000000000000000012.5", "1e-400", "2.7182818284590452353602874713527",
        "1.000000059604644775390626",
    };
    const size_t nfixed = sizeof fixed / sizeof fixed[0];
    char (*strs)[64] = malloc(N * sizeof *strs);
    sr_rng rng = { 0x5eed0bULL };
    for (size_t i = 0; i < N; i++) {
        if (i < nfixed) {
            snprintf(strs[i], sizeof strs[i], "%s", fixed[i]);
        } else {
            random_decimal(&rng, strs[i], sizeof strs[i]);
        }
    }
    size_t cap = (size_t)N * 80 + 64, len = 0;
    char *text = malloc(cap);
    for (size_t i = 0; i < N; i += 3) {
        len += (size_t)snprintf(text + len, cap - len, "v %s %s %s\n", strs[i], strs[i + 1],
                                strs[i + 2]);
    }
    for (size_t i = 0; i < NV; i += 3) {
        len += (size_t)snprintf(text + len, cap - len, "f %zu %zu %zu\n", i + 1, i + 2, i + 3);
    }
    sr_mesh m;
    sr_io_error err;
    sr_result r = parse_mem("numbers.obj", text, len, &m, &err);
    CHECK_EQ(r, SR_OK);
    if (r == SR_OK) {
        /* Each vertex is first used in file order, so output i is v i and
         * positions[i] is number i. */
        REQUIRE(m.vertex_count == NV);
        long long worst = 0;
        size_t exact = 0;
        for (size_t i = 0; i < N; i++) {
            errno = 0;
            float want = strtof(strs[i], NULL);
            float got = m.positions[i];
            long long d = ulp_distance(got, want);
            exact += d == 0;
            if (d > worst) {
                worst = d;
            }
            if (d != 0) {
                sr_test_fail(__FILE__, __LINE__, "'%s': got %.9g, strtof %.9g (%lld ulp)",
                             strs[i], (double)got, (double)want, d);
            }
        }
        printf("  number parser: %zu of %d correctly rounded, worst %lld ulp\n",
               exact, N, worst);
        CHECK(worst <= 1);
        sr_destroy_mesh(sr_test_ctx(), &m);
    } else {
        fprintf(stderr, "  %s\n", err.message);
    }
    free(text);
    free(strs);
}

/* ---- the shared models ------------------------------------------------------------ */

/* What the test expects of a model, found by its own scan of the text:
 * triangles = sum over f lines of (corners - 2); the bounding box of the
 * vertices that faces use. */
typedef struct model_ref {
    size_t triangles;
    double lo[3], hi[3];
} model_ref;

static bool scan_model(const char *path, model_ref *ref)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        return false;
    }
    double *v = NULL;
    bool *used = NULL;
    size_t nv = 0, cap = 0;
    char *line = NULL;
    size_t line_cap = 0;
    memset(ref, 0, sizeof *ref);
    while (getline(&line, &line_cap, f) >= 0) {
        if (line[0] == 'v' && line[1] == ' ') {
            if (nv == cap) {
                cap = cap ? 2 * cap : 1024;
                v = realloc(v, cap * 3 * sizeof *v);
                used = realloc(used, cap * sizeof *used);
            }
            char *p = line + 2;
            for (int k = 0; k < 3; k++) {
                v[3 * nv + k] = strtod(p, &p);
            }
            used[nv++] = false;
        } else if (line[0] == 'f' && line[1] == ' ') {
            size_t corners = 0;
            for (char *tok = strtok(line + 2, " \t\r\n"); tok; tok = strtok(NULL, " \t\r\n")) {
                long idx = strtol(tok, NULL, 10);
                size_t i = idx < 0 ? nv + (size_t)idx : (size_t)idx - 1;
                if (i < nv) {
                    used[i] = true;
                }
                corners++;
            }
            ref->triangles += corners - 2;
        }
    }
    for (int k = 0; k < 3; k++) {
        ref->lo[k] = HUGE_VAL;
        ref->hi[k] = -HUGE_VAL;
    }
    for (size_t i = 0; i < nv; i++) {
        for (int k = 0; used[i] && k < 3; k++) {
            ref->lo[k] = fmin(ref->lo[k], v[3 * i + k]);
            ref->hi[k] = fmax(ref->hi[k], v[3 * i + k]);
        }
    }
    free(line);
    free(v);
    free(used);
    fclose(f);
    return true;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static void check_model(const char *file, size_t expect_triangles, bool texcoords, bool normals)
{
    const char *dir = sr_test_models_dir();
    if (!dir) {
        SKIP("no shared models folder (../shared/models or $SR_MODELS_DIR)");
    }
    char *path = join_path(dir, file);
    model_ref ref;
    if (!scan_model(path, &ref)) {
        free(path);
        SKIP("model file missing from the shared models folder");
    }
    sr_mesh m;
    sr_io_error err;
    double t0 = now_ms();
    sr_result r = sr_load_mesh(sr_test_ctx(), path, &obj_desc, &m, &err);
    double t1 = now_ms();
    CHECK_EQ(r, SR_OK);
    if (r != SR_OK) {
        fprintf(stderr, "  %s\n", err.message);
        free(path);
        return;
    }
    printf("  %s: %zu triangles, %zu vertices, loaded in %.1f ms\n",
           file, m.triangle_count, m.vertex_count, t1 - t0);
    CHECK_EQ(m.triangle_count, ref.triangles);
    if (expect_triangles) {
        CHECK_EQ(m.triangle_count, expect_triangles);
    }
    CHECK(indices_valid(&m));
    CHECK((m.texcoords != NULL) == texcoords);
    CHECK((m.normals != NULL) == normals);
    /* Comparisons rather than fmin/fmax (which skip a NaN the same way):
     * GCC 12 for aarch64 crashes vectorizing an fmin/fmax reduction. */
    double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (size_t i = 0; i < m.vertex_count; i++) {
        for (int k = 0; k < 3; k++) {
            double x = m.positions[3 * i + k];
            lo[k] = x < lo[k] ? x : lo[k];
            hi[k] = x > hi[k] ? x : hi[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        /* The mesh holds floats: equal to the double scan within rounding. */
        double tol = 1e-6 * fmax(fabs(ref.lo[k]), fabs(ref.hi[k]));
        CHECK_NEAR(lo[k], ref.lo[k], tol);
        CHECK_NEAR(hi[k], ref.hi[k], tol);
    }
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(path);
}

SR_TEST(obj_model_stanford_bunny)
{
    check_model("stanford-bunny.obj", 69451, false, false);
}

SR_TEST(obj_model_spot)
{
    check_model("spot.obj", 0, true, false);
}

SR_TEST(obj_model_teapot)
{
    check_model("teapot.obj", 0, false, false);
}

SR_TEST(obj_model_suzanne)
{
    check_model("suzanne.obj", 0, false, true);
}

SR_TEST(obj_model_cow)
{
    check_model("cow.obj", 0, false, false);
}

SR_TEST(obj_model_fandisk)
{
    check_model("fandisk.obj", 0, false, false);
}

/* Found by fuzz_obj (a timeout): faces with positions only enter their
 * vertices without the hash table, so the first face with a texture or
 * normal index rehashed n >> 1024 keys into 1024 slots and probed forever. */
SR_TEST(obj_many_plain_corners_then_a_textured_face)
{
    enum { N = 3000 };
    size_t cap = (size_t)N * 64 + 256, len = 0;
    char *text = malloc(cap);
    REQUIRE(text);
    for (int i = 0; i < N; i++) {
        len += (size_t)snprintf(text + len, cap - len, "v %d %d 0\n", i % 97, i / 97);
    }
    len += (size_t)snprintf(text + len, cap - len, "vt 0 0\n");
    for (int i = 0; i + 2 < N; i += 3) {
        len += (size_t)snprintf(text + len, cap - len, "f %d %d %d\n", i + 1, i + 2, i + 3);
    }
    len += (size_t)snprintf(text + len, cap - len, "f 1/1 2/1 3/1\n");
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(parse_mem("plain_then_textured.obj", text, len, &m, &err), SR_OK);
    CHECK_EQ(m.triangle_count, N / 3 + 1);
    CHECK_EQ(m.vertex_count, N + 3);
    CHECK(indices_valid(&m));
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(text);
}
