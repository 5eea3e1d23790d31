/*
 * test_mesh.c - tests for the mesh utilities (src/geometry/mesh.c) and for
 * sr_load_mesh's choice of reader (src/io/load.c, src/io/assimp.c): by
 * extension, by content, and through Assimp or its install hint.
 */
#include "gltf_write.h"
#include "softrast_io.h"
#include "sr_test.h"
#include "context.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- a cube mesh built in memory ---------------------------------------- */

/* Each face cut along a different diagonal than its neighbours would
 * suggest, so corners touch either one or two triangles of a face. */
static const uint32_t cube_tris[12][3] = {
    { 0, 4, 6 }, { 0, 6, 2 }, { 1, 3, 7 }, { 1, 7, 5 }, { 0, 1, 5 }, { 0, 5, 4 },
    { 2, 6, 7 }, { 2, 7, 3 }, { 0, 2, 3 }, { 0, 3, 1 }, { 4, 5, 7 }, { 4, 7, 6 },
};

static float corner(int i, int axis)
{
    return (float)((i >> axis) & 1);
}

/* Mesh memory on the test context, as sr_destroy_mesh frees it. */
static void *mesh_alloc(size_t bytes)
{
    return sr__calloc(sr_test_ctx(), 1, bytes);
}

/* A cube, as a reader would return it; extra_vertices are left at the
 * origin, used by no triangle. */
static sr_mesh make_cube(bool colors, bool texcoords, size_t extra_vertices)
{
    size_t n = 8 + extra_vertices;
    sr_mesh m = { .vertex_count = n, .triangle_count = 12 };
    m.positions = mesh_alloc(n * 3 * sizeof(float));
    m.indices = mesh_alloc(sizeof cube_tris);
    memcpy(m.indices, cube_tris, sizeof cube_tris);
    for (int v = 0; v < 8; v++) {
        for (int a = 0; a < 3; a++) {
            m.positions[3 * v + a] = corner(v, a);
        }
    }
    if (colors) {
        m.colors = mesh_alloc(n * 4 * sizeof(float));
        for (size_t i = 0; i < n * 4; i++) {
            m.colors[i] = (float)i;
        }
    }
    if (texcoords) {
        m.texcoords = mesh_alloc(n * 2 * sizeof(float));
        for (size_t i = 0; i < n * 2; i++) {
            m.texcoords[i] = (float)i * 0.5f;
        }
    }
    return m;
}

static bool mesh_is_zero(const sr_mesh *m)
{
    static const sr_mesh zero;
    return memcmp(m, &zero, sizeof zero) == 0;
}

/* ---- free and bounds ---------------------------------------------------- */

SR_TEST(mesh_free_is_null_safe_and_zeroes)
{
    sr_destroy_mesh(sr_test_ctx(), NULL);
    sr_mesh m = make_cube(true, true, 0);
    m.texture_path = mesh_alloc(8);
    memcpy(m.texture_path, "a.png", 6);
    sr_destroy_mesh(sr_test_ctx(), &m);
    CHECK(mesh_is_zero(&m));
    sr_destroy_mesh(sr_test_ctx(), &m); /* twice is harmless */
}

SR_TEST(mesh_bounds_of_random_points)
{
    sr_rng rng = { 42 };
    const size_t n = 1000;
    sr_mesh m = { .vertex_count = n };
    m.positions = mesh_alloc(n * 3 * sizeof(float));
    float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t i = 0; i < n * 3; i++) {
        float f = (float)sr_rng_range(&rng, -50, 20);
        m.positions[i] = f;
        lo[i % 3] = fminf(lo[i % 3], f);
        hi[i % 3] = fmaxf(hi[i % 3], f);
    }
    sr_vec3 mn, mx;
    REQUIRE(sr_mesh_bounds(&m, &mn, &mx));
    CHECK_EQ(mn.x, lo[0]);
    CHECK_EQ(mn.y, lo[1]);
    CHECK_EQ(mn.z, lo[2]);
    CHECK_EQ(mx.x, hi[0]);
    CHECK_EQ(mx.y, hi[1]);
    CHECK_EQ(mx.z, hi[2]);
    sr_destroy_mesh(sr_test_ctx(), &m);

    sr_mesh empty = { 0 };
    CHECK(!sr_mesh_bounds(&empty, &mn, &mx));
    CHECK(!sr_mesh_bounds(NULL, &mn, &mx));
}

/* ---- normals ------------------------------------------------------------ */

SR_TEST(smooth_normals_of_a_cube_point_along_the_diagonals)
{
    /* Angle weighting: each face meets a corner at 90 degrees, whether in
     * one triangle or split 45 + 45, so every corner gets exactly the
     * diagonal, (±1, ±1, ±1)/sqrt(3). */
    sr_mesh m = make_cube(false, false, 0);
    REQUIRE(sr_mesh_compute_normals(sr_test_ctx(), &m, SR_NORMALS_SMOOTH) == SR_OK);
    REQUIRE(m.normals != NULL);
    const double s = 1 / sqrt(3.0);
    for (int v = 0; v < 8; v++) {
        for (int a = 0; a < 3; a++) {
            CHECK_NEAR(m.normals[3 * v + a], (2 * corner(v, a) - 1) * s, 1e-6);
        }
    }
    /* Computing again replaces, not accumulates. */
    REQUIRE(sr_mesh_compute_normals(sr_test_ctx(), &m, SR_NORMALS_SMOOTH) == SR_OK);
    CHECK_NEAR(m.normals[21], s, 1e-6);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(smooth_normals_ignore_degenerate_faces_and_default_lonely_vertices)
{
    sr_mesh m = make_cube(false, false, 2);
    /* Vertex 8 sits at the origin like vertex 0 but belongs to no
     * triangle; vertex 9 only to a degenerate one (7, 7, 9). */
    uint32_t *idx = mesh_alloc(13 * 3 * sizeof *idx);
    REQUIRE(idx);
    memcpy(idx, m.indices, 12 * 3 * sizeof *idx);
    sr__free(sr_test_ctx(), m.indices);
    m.indices = idx;
    m.indices[36] = 7;
    m.indices[37] = 7;
    m.indices[38] = 9;
    m.triangle_count = 13;
    REQUIRE(sr_mesh_compute_normals(sr_test_ctx(), &m, SR_NORMALS_SMOOTH) == SR_OK);
    const double s = 1 / sqrt(3.0);
    CHECK_NEAR(m.normals[21], s, 1e-6); /* vertex 7 unchanged by the degenerate */
    CHECK_NEAR(m.normals[22], s, 1e-6);
    CHECK_NEAR(m.normals[23], s, 1e-6);
    for (int v = 8; v < 10; v++) {
        CHECK_EQ(m.normals[3 * v + 0], 0.0f);
        CHECK_EQ(m.normals[3 * v + 1], 0.0f);
        CHECK_EQ(m.normals[3 * v + 2], 1.0f);
    }
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(smooth_normals_are_unit_length_on_random_meshes)
{
    sr_rng rng = { 7 };
    const size_t nv = 200, nt = 600;
    sr_mesh m = { .vertex_count = nv, .triangle_count = nt };
    m.positions = mesh_alloc(nv * 3 * sizeof(float));
    m.indices = mesh_alloc(nt * 3 * sizeof(uint32_t));
    for (size_t i = 0; i < nv * 3; i++) {
        m.positions[i] = (float)sr_rng_range(&rng, -1, 1);
    }
    for (size_t i = 0; i < nt * 3; i++) {
        m.indices[i] = (uint32_t)sr_rng_int(&rng, 0, (int)nv - 1);
    }
    REQUIRE(sr_mesh_compute_normals(sr_test_ctx(), &m, SR_NORMALS_SMOOTH) == SR_OK);
    for (size_t v = 0; v < nv; v++) {
        const float *n = m.normals + 3 * v;
        CHECK_NEAR(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-5);
    }
    sr_destroy_mesh(sr_test_ctx(), &m);
}

/* The smooth normals of mesh m through sr_mesh_compute_normals on
 * contexts of 1, 2, 3 and 8 threads, against the single-threaded call:
 * the same bits (memcmp), and the mesh otherwise untouched. */
static void check_threaded_normals_match(const sr_mesh *src)
{
    sr_mesh ref = *src;
    ref.normals = NULL;
    REQUIRE(sr_mesh_compute_normals(sr_test_ctx(), &ref, SR_NORMALS_SMOOTH) == SR_OK);
    static const int threads[] = { 1, 2, 3, 8 };
    for (size_t k = 0; k < sizeof threads / sizeof threads[0]; k++) {
        sr_context *ctx = NULL;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads[k] }, &ctx) == SR_OK);
        sr_mesh m = *src;
        m.normals = NULL;
        CHECK_EQ(sr_mesh_compute_normals(ctx, &m, SR_NORMALS_SMOOTH), SR_OK);
        REQUIRE(m.normals);
        if (memcmp(m.normals, ref.normals, src->vertex_count * 3 * sizeof(float)) != 0) {
            sr_test_fail(__FILE__, __LINE__, "%d threads: normals differ from one thread's",
                         threads[k]);
        }
        CHECK(m.positions == src->positions && m.indices == src->indices &&
              m.vertex_count == src->vertex_count);
        sr__free(ctx, m.normals);
        sr_destroy_context(ctx);
    }
    sr__free(sr_test_ctx(), ref.normals);
}

/* Faces whose corners lie in different threads' ranges of vertices (the
 * indices are random), degenerate faces, unused vertices, and a vertex
 * shared by hundreds of faces: each vertex must sum the same terms in the
 * same order whatever thread owns it. */
SR_TEST(smooth_normals_on_threads_are_the_same_bits)
{
    sr_rng rng = { 0x7407 };
    for (int round = 0; round < 4; round++) {
        size_t nv = (size_t)sr_rng_int(&rng, 1, 3000), nt = (size_t)sr_rng_int(&rng, 0, 9000);
        sr_mesh m = { .vertex_count = nv, .triangle_count = nt };
        m.positions = mesh_alloc(nv * 3 * sizeof(float));
        m.indices = mesh_alloc((nt ? nt : 1) * 3 * sizeof(uint32_t));
        for (size_t i = 0; i < nv * 3; i++) {
            m.positions[i] = (float)sr_rng_range(&rng, -1, 1);
        }
        for (size_t i = 0; i < nt * 3; i++) {
            /* A fifth of the corners on the last vertex (in the last
             * thread's range: the order of its many terms shows); some
             * faces repeat a vertex. */
            m.indices[i] = sr_rng_int(&rng, 0, 4) == 0 ? (uint32_t)nv - 1
                                                        : (uint32_t)sr_rng_int(&rng, 0, (int)nv - 1);
        }
        check_threaded_normals_match(&m);
        sr_destroy_mesh(sr_test_ctx(), &m);
    }
    /* A hub whose faces come in pairs facing opposite ways (a, b then,
     * later, b, a): their terms cancel up to rounding, so the hub's normal
     * is the direction of the rounding errors, which depends on the order
     * of every term. */
    {
        size_t nv = 1201, pairs = 600;
        sr_mesh m = { .vertex_count = nv, .triangle_count = 2 * pairs };
        m.positions = mesh_alloc(nv * 3 * sizeof(float));
        m.indices = mesh_alloc(2 * pairs * 3 * sizeof(uint32_t));
        for (size_t i = 0; i < nv * 3; i++) {
            m.positions[i] = (float)sr_rng_range(&rng, -1, 1);
        }
        for (size_t p = 0; p < pairs; p++) {
            uint32_t a = (uint32_t)(2 * p), b = (uint32_t)(2 * p + 1), hub = (uint32_t)nv - 1;
            uint32_t *f = m.indices + 3 * p, *r = m.indices + 3 * (2 * pairs - 1 - p);
            f[0] = hub, f[1] = a, f[2] = b;
            r[0] = hub, r[1] = b, r[2] = a;
        }
        check_threaded_normals_match(&m);
        sr_destroy_mesh(sr_test_ctx(), &m);
    }
    const char *dir = sr_test_models_dir();
    if (dir) {
        char path[1024];
        snprintf(path, sizeof path, "%s/stanford-bunny.obj", dir);
        sr_mesh m;
        sr_io_error err;
        REQUIRE(sr_load_mesh(sr_test_ctx(), path, NULL, &m, &err) == SR_OK);
        check_threaded_normals_match(&m);
        sr_destroy_mesh(sr_test_ctx(), &m);
    } else {
        printf("  no shared models folder: the bunny part is skipped\n");
    }
}

SR_TEST(flat_normals_split_every_triangle)
{
    sr_mesh m = make_cube(true, true, 0);
    REQUIRE(sr_mesh_compute_normals(sr_test_ctx(), &m, SR_NORMALS_FLAT) == SR_OK);
    CHECK_EQ(m.vertex_count, 36);
    CHECK_EQ(m.triangle_count, 12);
    REQUIRE(m.normals && m.colors && m.texcoords);
    for (size_t t = 0; t < 12; t++) {
        for (int k = 0; k < 3; k++) {
            size_t v = 3 * t + (size_t)k;
            uint32_t src = cube_tris[t][k];
            CHECK_EQ(m.indices[v], v);
            for (int a = 0; a < 3; a++) {
                CHECK_EQ(m.positions[3 * v + (size_t)a], corner((int)src, a));
            }
            CHECK_EQ(m.colors[4 * v + 1], 4 * src + 1);
            CHECK_EQ(m.texcoords[2 * v + 1], (2 * src + 1) * 0.5f);
            /* The face normal is an axis, pointing away from the centre. */
            const float *n = m.normals + 3 * v;
            float c[3];
            for (int a = 0; a < 3; a++) {
                c[a] = (corner((int)cube_tris[t][0], a) + corner((int)cube_tris[t][1], a) +
                        corner((int)cube_tris[t][2], a)) / 3 - 0.5f;
            }
            CHECK_NEAR(fabsf(n[0]) + fabsf(n[1]) + fabsf(n[2]), 1.0, 1e-6);
            CHECK(n[0] * c[0] + n[1] * c[1] + n[2] * c[2] > 0);
        }
    }
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(compute_normals_validates_its_arguments)
{
    CHECK_EQ(sr_mesh_compute_normals(sr_test_ctx(), NULL, SR_NORMALS_SMOOTH), SR_INVALID_ARG);

    sr_mesh m = make_cube(false, false, 0);
    m.indices[17] = 8; /* one past the last vertex */
    sr_mesh before = m;
    CHECK_EQ(sr_mesh_compute_normals(sr_test_ctx(), &m, SR_NORMALS_SMOOTH), SR_INVALID_ARG);
    CHECK_EQ(sr_mesh_compute_normals(sr_test_ctx(), &m, SR_NORMALS_FLAT), SR_INVALID_ARG);
    CHECK(memcmp(&m, &before, sizeof m) == 0); /* untouched */
    m.indices[17] = 7;
    CHECK_EQ(sr_mesh_compute_normals(sr_test_ctx(), &m, (sr_normal_mode)99), SR_INVALID_ARG);

    sr_mesh no_positions = { .vertex_count = 3 };
    CHECK_EQ(sr_mesh_compute_normals(sr_test_ctx(), &no_positions, SR_NORMALS_SMOOTH), SR_INVALID_ARG);
    sr_mesh no_indices = { .vertex_count = 8, .positions = m.positions, .triangle_count = 1 };
    CHECK_EQ(sr_mesh_compute_normals(sr_test_ctx(), &no_indices, SR_NORMALS_SMOOTH), SR_INVALID_ARG);
    sr_destroy_mesh(sr_test_ctx(), &m);

    /* Empty meshes are fine: nothing to compute. */
    sr_mesh empty = { 0 };
    CHECK_EQ(sr_mesh_compute_normals(sr_test_ctx(), &empty, SR_NORMALS_SMOOTH), SR_OK);
    CHECK_EQ(sr_mesh_compute_normals(sr_test_ctx(), &empty, SR_NORMALS_FLAT), SR_OK);
    CHECK(mesh_is_zero(&empty));
}

/* ---- sr_load_mesh: choosing the reader ---------------------------------- */

static const char *out_path(const char *name)
{
    static char path[4][1024];
    static int slot;
    slot = (slot + 1) % 4;
    snprintf(path[slot], sizeof path[slot], "%s/%s", sr_test_out_dir(), name);
    return path[slot];
}

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(data, 1, n, f);
        fclose(f);
    }
}

static const char ply_text[] =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
    "end_header\n0 0 0\n2 0 0\n2 1 0\n0 1 0\n4 0 1 2 3\n";

static const char stl_text[] =
    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 3 0 0\nvertex 0 1 0\n"
    "endloop\nendfacet\nendsolid t\n";

static const char obj_text[] = "v 0 0 0\nv 4 0 0\nv 0 1 0\nf 1 2 3\n";

/* A binary STL with one triangle whose largest x is 5; the header starts
 * with neither "solid" nor anything else recognizable. */
static size_t binary_stl(uint8_t out[134])
{
    memset(out, 0, 134);
    memcpy(out, "BINARY", 6);
    out[80] = 1;
    const float v[12] = { 0, 0, 1, 0, 0, 0, 5, 0, 0, 0, 1, 0 };
    le_copy(out + 84, v, 12, 4);
    return 134;
}

/* Load, expect success, and check the largest x (which tells the files
 * apart, so the right reader must have run). */
static void expect_loads(const char *path, const sr_load_desc *desc, float max_x,
                         size_t triangles)
{
    sr_mesh m;
    sr_io_error err = { { 0 } };
    sr_result r = sr_load_mesh(sr_test_ctx(), path, desc, &m, &err);
    if (r != SR_OK) {
        printf("  %s: %s\n", path, err.message);
    }
    CHECK_EQ(r, SR_OK);
    sr_vec3 mn, mx;
    CHECK(sr_mesh_bounds(&m, &mn, &mx));
    CHECK_EQ(mx.x, max_x);
    CHECK_EQ(m.triangle_count, triangles);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(load_mesh_dispatches_by_extension)
{
    const char *ply = out_path("dispatch.PLY");
    const char *stl = out_path("dispatch.Stl");
    const char *obj = out_path("dispatch.obj");
    write_file(ply, ply_text, sizeof ply_text - 1);
    write_file(stl, stl_text, sizeof stl_text - 1);
    write_file(obj, obj_text, sizeof obj_text - 1);
    expect_loads(ply, NULL, 2, 2);
    expect_loads(stl, &(sr_load_desc){ 0 }, 3, 1);
    expect_loads(obj, NULL, 4, 1);

    /* The extension wins over content: PLY text named .stl is read as
     * STL and fails as STL would. */
    const char *liar = out_path("liar.stl");
    write_file(liar, ply_text, sizeof ply_text - 1);
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), liar, NULL, &m, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "liar.stl: byte 80: binary STL declares");
    CHECK(mesh_is_zero(&m));
    /* ... unless the caller names the format. */
    expect_loads(liar, &(sr_load_desc){ .format = SR_FORMAT_PLY }, 2, 2);
}

SR_TEST(load_mesh_sniffs_content_when_the_extension_is_unknown)
{
    const char *ply = out_path("sniff_ply.dat");
    const char *ascii = out_path("sniff_ascii.txt");
    const char *binary = out_path("sniff_binary");
    write_file(ply, ply_text, sizeof ply_text - 1);
    write_file(ascii, stl_text, sizeof stl_text - 1);
    uint8_t bin[134];
    write_file(binary, bin, binary_stl(bin));
    expect_loads(ply, NULL, 2, 2);
    expect_loads(ascii, NULL, 3, 1);
    expect_loads(binary, NULL, 5, 1);
}

SR_TEST(load_mesh_reports_missing_files_and_bad_arguments)
{
    sr_mesh m;
    sr_io_error err;
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), "/nonexistent/model.ply", NULL, &m, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "/nonexistent/model.ply: cannot open");
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), "/nonexistent/model.gltf", NULL, &m, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "/nonexistent/model.gltf: cannot open");
    CHECK(mesh_is_zero(&m));
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), NULL, NULL, &m, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), out_path("x.ply"), NULL, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), sr_test_out_dir(), NULL, &m, &err), SR_IO_ERROR);
    CHECK_STR_CONTAINS(err.message, "is a directory");
}

/* sr_load_mesh of path in `format` (SR_FORMAT_ASSIMP: glTF would go to
 * the own reader otherwise), the reader's message printed when it fails. */
static bool loads(const char *path, sr_model_format format, sr_mesh *m)
{
    sr_io_error err;
    sr_load_desc desc = { .format = format };
    sr_result r = sr_load_mesh(sr_test_ctx(), path, &desc, m, &err);
    if (r != SR_OK) {
        printf("  %s\n", err.message);
    }
    return r == SR_OK;
}

/* The Assimp reader's parts (gltf_parts_model): runs of meshes that take
 * one image, the embedded one as its bytes, named files joined to the
 * model's directory; two materials naming one file make one part; the
 * whole mesh's texture is the first one named.  A model whose meshes all
 * take one image has no parts. */
SR_TEST(assimp_parts_follow_textures)
{
    if (!sr_io_have_assimp()) {
        SKIP("this build reads no glTF (Assimp was not found)");
    }
    const uint8_t png[12] = { 0x89, 'P', 'N', 'G', 1, 2, 3, 4, 5, 6, 7, 8 }; /* never decoded */
    char *json = gltf_parts_model(png, sizeof png);
    REQUIRE(json);
    const char *path = out_path("parts.gltf");
    write_file(path, json, strlen(json));
    free(json);
    sr_mesh m;
    REQUIRE(loads(path, SR_FORMAT_ASSIMP, &m));
    CHECK_EQ(m.triangle_count, 10);
    REQUIRE(m.part_count == 4);
    static const size_t first[4] = { 0, 2, 4, 8 }, count[4] = { 2, 2, 4, 2 };
    for (int p = 0; p < 4; p++) {
        CHECK_EQ(m.parts[p].first_triangle, first[p]);
        CHECK_EQ(m.parts[p].triangle_count, count[p]);
    }
    CHECK(m.parts[0].texture_path == NULL);
    CHECK(m.parts[0].texture_size == sizeof png && m.parts[0].texture_data &&
          memcmp(m.parts[0].texture_data, png, sizeof png) == 0);
    CHECK(m.parts[1].texture_path == NULL && m.parts[1].texture_data == NULL);
    char want[1200];
    snprintf(want, sizeof want, "%s/blue.png", sr_test_out_dir());
    CHECK(m.parts[2].texture_path && strcmp(m.parts[2].texture_path, want) == 0);
    CHECK(m.parts[2].texture_data == NULL);
    snprintf(want, sizeof want, "%s/missing.png", sr_test_out_dir());
    CHECK(m.parts[3].texture_path && strcmp(m.parts[3].texture_path, want) == 0);
    /* The whole mesh's: the first named, a copy of its own. */
    CHECK(m.texture_path == NULL && m.texture_data && m.texture_data != m.parts[0].texture_data);
    CHECK(m.texture_size == sizeof png && memcmp(m.texture_data, png, sizeof png) == 0);
    sr_destroy_mesh(sr_test_ctx(), &m);

    /* One image for every mesh: no parts, the texture on the mesh. */
    static const gltf_quad two[2] = { { 0, 0, 1, 1, 0 }, { 1, 0, 2, 1, 1 } };
    json = gltf_quads(two, 2,
                      ",\"images\":[{\"uri\":\"wood.png\"}],"
                      "\"textures\":[{\"source\":0}],\"materials\":["
                      "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}},"
                      "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
                      "\"metallicFactor\":0.5}}]");
    REQUIRE(json);
    path = out_path("one_texture.gltf");
    write_file(path, json, strlen(json));
    free(json);
    REQUIRE(loads(path, SR_FORMAT_ASSIMP, &m));
    CHECK_EQ(m.triangle_count, 4);
    CHECK_EQ(m.part_count, 0);
    CHECK(m.parts == NULL);
    snprintf(want, sizeof want, "%s/wood.png", sr_test_out_dir());
    CHECK(m.texture_path && strcmp(m.texture_path, want) == 0);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

/* A tetrahedron in the OFF format, which only Assimp reads here. */
static const char off_text[] =
    "OFF\n4 4 0\n0 0 0\n6 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

SR_TEST(load_mesh_other_formats_need_assimp)
{
    const char *off = out_path("tetra.off");
    write_file(off, off_text, sizeof off_text - 1);
    sr_mesh m;
    sr_io_error err = { { 0 } };
    sr_result r = sr_load_mesh(sr_test_ctx(), off, NULL, &m, &err);
    if (sr_io_have_assimp()) {
        if (r != SR_OK) {
            printf("  %s\n", err.message);
        }
        CHECK_EQ(r, SR_OK);
        CHECK_EQ(m.triangle_count, 4);
        sr_vec3 mn, mx;
        CHECK(sr_mesh_bounds(&m, &mn, &mx));
        CHECK_NEAR(mx.x, 6, 1e-6);
        CHECK_NEAR(mx.z, 1, 1e-6);
        sr_destroy_mesh(sr_test_ctx(), &m);

        /* Assimp reads many formats but not every extension. */
        const char *odd = out_path("model.notaformat");
        write_file(odd, "hello\n", 6);
        CHECK_EQ(sr_load_mesh(sr_test_ctx(), odd, NULL, &m, &err), SR_UNSUPPORTED);
        CHECK_STR_CONTAINS(err.message, "model.notaformat: format not supported");
        CHECK(mesh_is_zero(&m));
    } else {
        CHECK_EQ(r, SR_UNSUPPORTED);
        char want[1200];
        snprintf(want, sizeof want,
                 "%s: format not supported (install libassimp-dev and rebuild to read "
                 ".off files)", off);
        CHECK_STR_CONTAINS(err.message, want);
        CHECK(mesh_is_zero(&m));
        SKIP("built without Assimp: checked the install hint only");
    }
}

SR_TEST(load_mesh_reads_shared_models)
{
    const char *dir = sr_test_models_dir();
    if (!dir) {
        SKIP("no shared models folder");
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/cow.obj", dir);
    sr_mesh m;
    REQUIRE(loads(path, SR_FORMAT_AUTO, &m));
    CHECK(m.triangle_count > 0);
    REQUIRE(sr_mesh_compute_normals(sr_test_ctx(), &m, SR_NORMALS_SMOOTH) == SR_OK);
    for (size_t v = 0; v < m.vertex_count; v++) {
        const float *n = m.normals + 3 * v;
        CHECK_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-4);
    }
    sr_destroy_mesh(sr_test_ctx(), &m);
}

/* Blending order: three triangles at eye depths 2, 5 and 3 (the eye looks
 * down -z through the identity view) come out farthest first; a tie keeps
 * the first order; the mean depth is that of the corners. */
SR_TEST(sort_back_to_front_and_mean_view_depth)
{
    const float pos[] = { 0, 0, -2, 1, 0, -2, 0, 1, -2,
                          0, 0, -5, 1, 0, -5, 0, 1, -5,
                          0, 0, -3, 1, 0, -3, 0, 1, -3 };
    const uint32_t idx[] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 2, 1, 0 };
    uint32_t out[12];
    sr_mat4 id = sr_mat4_identity();
    REQUIRE(sr_sort_back_to_front(sr_test_ctx(), pos, 9, idx, 4, &id, out) == SR_OK);
    const uint32_t want[] = { 3, 4, 5, 6, 7, 8, 0, 1, 2, 2, 1, 0 };
    CHECK(memcmp(out, want, sizeof want) == 0);
    float mean = 0.0f;
    REQUIRE(sr_mean_view_depth(pos, 9, idx, 3, &id, &mean) == SR_OK);
    CHECK_NEAR(mean, 10.0f / 3.0f, 1e-6f);
    /* Moved 10 away: everything is 10 farther. */
    sr_mat4 back = sr_mat4_translate(0, 0, -10);
    REQUIRE(sr_mean_view_depth(pos, 9, idx, 3, &back, &mean) == SR_OK);
    CHECK_NEAR(mean, 40.0f / 3.0f, 1e-5f);

    const uint32_t bad[] = { 0, 1, 9 };
    CHECK_EQ(sr_sort_back_to_front(sr_test_ctx(), pos, 9, bad, 1, &id, out), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(sr_test_ctx()), "sr_sort_back_to_front");
    CHECK_EQ(sr_mean_view_depth(pos, 9, bad, 1, &id, &mean), SR_INVALID_ARG);
    CHECK_EQ(sr_sort_back_to_front(sr_test_ctx(), pos, 9, idx, 1, &id, NULL), SR_INVALID_ARG);
    sr_mat4 nan = id;
    nan.m[14] = NAN;
    CHECK_EQ(sr_mean_view_depth(pos, 9, idx, 1, &nan, &mean), SR_INVALID_ARG);

    /* In place: out may be the indices themselves. */
    uint32_t inplace[12];
    memcpy(inplace, idx, sizeof inplace);
    REQUIRE(sr_sort_back_to_front(sr_test_ctx(), pos, 9, inplace, 4, &id, inplace) == SR_OK);
    CHECK(memcmp(inplace, want, sizeof want) == 0);
    /* A count whose keys cannot be allocated is refused before any index is read. */
    CHECK_EQ(sr_sort_back_to_front(sr_test_ctx(), pos, 9, idx, SIZE_MAX / 3, &id, out),
             SR_TOO_LARGE);
}

SR_TEST(order_back_to_front)
{
    const float d[] = { 2.0f, 5.0f, 3.0f, 5.0f, -1.0f };
    size_t order[5];
    REQUIRE(sr_order_back_to_front(sr_test_ctx(), d, 5, order) == SR_OK);
    const size_t want[] = { 1, 3, 2, 0, 4 };
    CHECK(memcmp(order, want, sizeof want) == 0);
    const float nan[] = { 1.0f, NAN };
    CHECK_EQ(sr_order_back_to_front(sr_test_ctx(), nan, 2, order), SR_INVALID_ARG);
    CHECK_EQ(sr_order_back_to_front(sr_test_ctx(), d, 5, NULL), SR_INVALID_ARG);
    /* A count whose keys would overflow size_t is refused before a distance is read. */
    CHECK_EQ(sr_order_back_to_front(sr_test_ctx(), d, SIZE_MAX / 2, order), SR_TOO_LARGE);
    CHECK_STR_CONTAINS(sr_context_error(sr_test_ctx()), "do not fit in memory");
}
