/* test_gltf_draco.c - glTF's KHR_draco_mesh_compression: a sphere written
 * plainly and as a Draco stream (libdraco's encoder, through the C++
 * helper draco_encode.cc linked into this test only) reads as the same
 * triangles and renders the same image; malformed Draco primitives give
 * one line and exit 2 from `softrast render`; a build without libdraco
 * reads the uncompressed fallback, or refuses naming the library. */
#include "batch_cli.h"
#include "glb_write.h"
#include "sr_test.h"
#include "uv_sphere.h"

#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SR_HAVE_DRACO_TEST
#include "draco_encode.h"
#else
/* The counts and ids a file states; the stream is not decoded. */
typedef struct draco_encoded {
    uint8_t *data;
    size_t size;
    uint32_t id_pos, id_nrm, id_uv;
    size_t points, faces;
} draco_encoded;
#endif

#define PRIM "/meshes/0/primitives/0"
#define EXT PRIM "/extensions/KHR_draco_mesh_compression"

/* How a file is written. */
typedef struct file_options {
    bool draco;                 /* the primitive has the extension */
    bool used_only;             /* listed in extensionsUsed only */
    const wbuf *fallback;       /* the accessors' uncompressed data, or NULL: none */
    bool no_indices;            /* the primitive has no indices accessor */
    bool strip;                 /* mode 5: the indices are a triangle strip */
} file_options;

/* The sphere's arrays as a fallback: positions, normals, coordinates,
 * uint32 indices, little-endian. */
static wbuf sphere_bytes(const sphere *s)
{
    wbuf b = {0};
    uint8_t tmp[4];
    put_sphere_attributes(&b, s);
    for (size_t i = 0; i < s->index_count; i++) {
        le_copy(tmp, &s->idx[i], 1, 4);
        wb_put(&b, tmp, 4);
    }
    return b;
}

/* A GLB of the stream in e (BIN bytes 0..; *json NUL-terminated) and the
 * fallback after it, its accessors stating e's counts. */
static void write_file(const draco_encoded *e, file_options o, wbuf *json, wbuf *bin)
{
    *json = (wbuf){0};
    *bin = (wbuf){0};
    size_t p = e->points, corners = e->faces * 3;
    if (o.draco) {
        wb_put(bin, e->data, e->size);
        wb_put(bin, "\0\0\0", (4 - e->size % 4) % 4);
    }
    size_t fb = bin->n;
    if (o.fallback) {
        wb_put(bin, o.fallback->p, o.fallback->n);
    }
    wb_printf(json, "{\"asset\":{\"version\":\"2.0\"},");
    if (o.draco) {
        wb_printf(json, "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],%s",
                  o.used_only ? "" : "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],");
    }
    wb_printf(json, "\"buffers\":[{\"byteLength\":%zu}],\"bufferViews\":[", bin->n);
    const char *sep = "";
    if (o.draco) {
        wb_printf(json, "{\"buffer\":0,\"byteLength\":%zu}", e->size);
        sep = ",";
    }
    int view = o.draco ? 1 : 0;
    if (o.fallback) {
        size_t sizes[4] = { p * 12, p * 12, p * 8, corners * 4 };
        for (int k = 0; k < 4; k++) {
            wb_printf(json, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", sep, fb,
                      sizes[k]);
            fb += sizes[k];
            sep = ",";
        }
    }
    char v[4][32] = { "", "", "", "" };
    for (int k = 0; o.fallback && k < 4; k++) {
        snprintf(v[k], sizeof v[k], "\"bufferView\":%d,", view + k);
    }
    wb_printf(json, "],\"accessors\":[{%s\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\","
                    "\"min\":[-1,-1,-1],\"max\":[1,1,1]},",
              v[0], p);
    wb_printf(json, "{%s\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},", v[1], p);
    wb_printf(json, "{%s\"componentType\":5126,\"count\":%zu,\"type\":\"VEC2\"},", v[2], p);
    wb_printf(json, "{%s\"componentType\":5125,\"count\":%zu,\"type\":\"SCALAR\"}],", v[3],
              corners);
    wb_printf(json, "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
                    "\"TEXCOORD_0\":2},%s%s\"material\":0",
              o.no_indices ? "" : "\"indices\":3,", o.strip ? "\"mode\":5," : "");
    if (o.draco) {
        wb_printf(json, ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":0,"
                        "\"attributes\":{\"POSITION\":%u,\"NORMAL\":%u,\"TEXCOORD_0\":%u}}}",
                  e->id_pos, e->id_nrm, e->id_uv);
    }
    wb_printf(json, "%s", "}]}],\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":"
                          "[0.8,0.3,0.1,1],\"metallicFactor\":0,\"roughnessFactor\":0.4}}],"
                          "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}");
    wb_put(json, "", 1);
}

static wbuf file_glb(const draco_encoded *e, file_options o)
{
    wbuf json, bin;
    write_file(e, o, &json, &bin);
    wbuf out = glb((const char *)json.p, bin.p, bin.n);
    free(json.p);
    free(bin.p);
    return out;
}

/* The plain sphere: its own counts, no extension; its indices a strip
 * (mode 5) with `strip`. */
static wbuf plain_glb_mode(const sphere *s, bool strip)
{
    draco_encoded counts = { .points = VERTS, .faces = s->index_count / 3 };
    wbuf data = sphere_bytes(s);
    wbuf out = file_glb(&counts, (file_options){ .fallback = &data, .strip = strip });
    free(data.p);
    return out;
}

static wbuf plain_glb(const sphere *s)
{
    return plain_glb_mode(s, false);
}

static sr_scene *parse_glb(const wbuf *b, sr_io_error *e)
{
    sr_scene *s = NULL;
    if (sr_parse_gltf(sr_test_ctx(), "t.glb", b->p, b->n, NULL, &s, e) != SR_OK) {
        return NULL;
    }
    return s;
}

/* Whether corner k of triangle t of p and corner j of triangle u of q
 * lie within tol of each other. */
static bool same_position(const sr_scene_primitive *p, size_t t, int k,
                          const sr_scene_primitive *q, size_t u, int j, double tol)
{
    const float *a = p->positions + 3 * (size_t)p->indices[3 * t + (size_t)k];
    const float *b = q->positions + 3 * (size_t)q->indices[3 * u + (size_t)j];
    return fabs(a[0] - b[0]) <= tol && fabs(a[1] - b[1]) <= tol && fabs(a[2] - b[2]) <= tol;
}

static double max_diff(const float *a, const float *b, int n)
{
    double d = 0;
    for (int c = 0; c < n; c++) {
        d = fmax(d, fabs(a[c] - b[c]));
    }
    return d;
}

/* The decoded scene holds the plain one's triangles, in any order and from
 * any corner but with the same winding: each plain triangle matched once
 * by position (within tol_pos), its matched corners' normals within
 * tol_nrm and coordinates within tol_uv. */
static void check_same_triangles(const sr_scene *a, const sr_scene *b, double tol_pos,
                                 double tol_nrm, double tol_uv)
{
    REQUIRE(a->primitive_count == 1 && b->primitive_count == 1);
    const sr_scene_primitive *p = &a->primitives[0], *q = &b->primitives[0];
    REQUIRE(q->normals && q->texcoords0);
    CHECK_EQ(p->triangle_count, q->triangle_count);
    bool *used = calloc(q->triangle_count + 1, 1);
    size_t unmatched = 0;
    double dn = 0, dt = 0;
    for (size_t t = 0; t < p->triangle_count; t++) {
        bool found = false;
        for (size_t u = 0; u < q->triangle_count && !found; u++) {
            for (int r = 0; r < 3 && !used[u] && !found; r++) {
                if (!same_position(p, t, 0, q, u, r, tol_pos) ||
                    !same_position(p, t, 1, q, u, (r + 1) % 3, tol_pos) ||
                    !same_position(p, t, 2, q, u, (r + 2) % 3, tol_pos)) {
                    continue;
                }
                found = used[u] = true;
                for (int k = 0; k < 3; k++) {
                    size_t i = p->indices[3 * t + (size_t)k];
                    size_t j = q->indices[3 * u + (size_t)(r + k) % 3];
                    dn = fmax(dn, max_diff(p->normals + 3 * i, q->normals + 3 * j, 3));
                    dt = fmax(dt, max_diff(p->texcoords0 + 2 * i, q->texcoords0 + 2 * j, 2));
                }
            }
        }
        unmatched += !found;
    }
    CHECK_EQ(unmatched, 0);
    CHECK(dn <= tol_nrm);
    CHECK(dt <= tol_uv);
    free(used);
}

#ifdef SR_HAVE_DRACO_TEST

/* The sphere's indices rewritten as one triangle strip: each band between
 * two rings (upper a, lower b) as a0 b0 a1 b1 ..., which gives the band's
 * triangles with their winding, the bands joined by two repeated indices
 * (degenerate triangles, an even number so that every band starts on an
 * even triangle), the end padded by its last index to a multiple of 3 (a
 * Draco stream holds whole faces). */
static void make_strip(sphere *s)
{
    size_t n = 0;
    for (uint32_t i = 0; i < STACKS; i++) {
        uint32_t a = i * (SLICES + 1), b = a + SLICES + 1;
        if (i > 0) {
            s->idx[n] = s->idx[n - 1];
            n++;
            s->idx[n++] = a;
        }
        for (uint32_t j = 0; j <= SLICES; j++) {
            s->idx[n++] = a + j;
            s->idx[n++] = b + j;
        }
    }
    while (n % 3 != 0) {
        s->idx[n] = s->idx[n - 1];
        n++;
    }
    s->index_count = n;
}

/* Position bits: 14 over the sphere's extent of 2 is a step of
 * 2 / (2^14 - 1); draco rounds to the nearest. */
enum { POS_BITS = 14 };
#define POS_STEP (2.0 / ((1 << POS_BITS) - 1))

static draco_encoded encode_sphere(const sphere *s, bool point_cloud, bool sequential)
{
    draco_encoded e = draco_encode(&s->pos[0][0], &s->nrm[0][0], &s->uv[0][0], VERTS, s->idx,
                                   s->index_count / 3, POS_BITS, point_cloud, sequential);
    if (!e.data) {
        FAILF("libdraco did not encode the sphere");
    }
    return e;
}

SR_TEST(draco_sphere_reads_as_the_plain_one)
{
    static sphere s;
    make_sphere(&s);
    wbuf plain = plain_glb(&s);
    sr_io_error err;
    sr_scene *a = parse_glb(&plain, &err);
    REQUIRE(a);
    draco_encoded e = encode_sphere(&s, false, false);
    REQUIRE(e.data);
    CHECK_EQ(e.faces * 3, s.index_count);
    /* Zeros for a fallback: a reader that took them would draw nothing. */
    wbuf zeros = {0};
    for (size_t i = 0; i < e.points * 32 + e.faces * 12; i++) {
        wb_put(&zeros, "", 1);
    }
    static const file_options variants[] = {
        { .draco = true },                                  /* what exporters write */
        { .draco = true, .used_only = true, .fallback = NULL },
        { .draco = true, .no_indices = true },              /* the stream's triangles */
    };
    for (size_t k = 0; k < sizeof variants / sizeof *variants; k++) {
        file_options o = variants[k];
        if (o.used_only) {
            o.fallback = &zeros;
        }
        wbuf file = file_glb(&e, o);
        CHECK(k != 0 || file.n * 3 < plain.n);
        sr_scene *b = parse_glb(&file, &err);
        if (!b) {
            FAILF("variant %zu: %s", k, err.message);
        } else {
            /* Normals of 10 bits: 0.003 here; coordinates of 12 bits: one step. */
            check_same_triangles(a, b, POS_STEP, 0.01, 1.0 / 4095);
            CHECK_EQ(b->primitives[0].vertex_count, e.points);
            sr_destroy_scene(sr_test_ctx(), b);
        }
        free(file.p);
    }
    sr_destroy_scene(sr_test_ctx(), a);
    free(zeros.p);
    free(e.data);
    free(plain.p);
}

SR_TEST(draco_sphere_renders_as_the_plain_one)
{
    NEED_CLI();
    static sphere s;
    make_sphere(&s);
    wbuf plain = plain_glb(&s);
    draco_encoded e = encode_sphere(&s, false, false);
    REQUIRE(e.data);
    wbuf file = file_glb(&e, (file_options){ .draco = true });
    /* Quantized normals move the shading by a level or two; positions
     * moved by up to half a step (0.007 pixels here) flip the coverage of
     * a few pixels on the silhouette (11 of its some 700, here). */
    check_same_render("draco_sphere", (const void *[]){ plain.p, file.p },
                      (size_t[]){ plain.n, file.n }, 8, 32);
    free(plain.p);
    free(file.p);
    free(e.data);
}

SR_TEST(draco_strip_reads_and_renders_as_the_plain_one)
{
    /* The extension allows TRIANGLE_STRIP: the stream's corners, face
     * after face, are the strip's indices.  Encoded with sequential
     * connectivity, which keeps them in order, as a writer of strips
     * must. */
    static sphere s;
    make_sphere(&s);
    make_strip(&s);
    wbuf plain = plain_glb_mode(&s, true);
    sr_io_error err;
    sr_scene *a = parse_glb(&plain, &err);
    REQUIRE(a);
    CHECK_EQ(a->primitives[0].triangle_count, s.index_count - 2);
    draco_encoded e = encode_sphere(&s, false, true);
    REQUIRE(e.data);
    CHECK_EQ(e.faces * 3, s.index_count);
    for (int no_indices = 0; no_indices < 2; no_indices++) {
        wbuf file = file_glb(&e, (file_options){ .draco = true, .strip = true,
                                                 .no_indices = no_indices });
        sr_scene *b = parse_glb(&file, &err);
        if (!b) {
            FAILF("no_indices %d: %s", no_indices, err.message);
        } else {
            check_same_triangles(a, b, POS_STEP, 0.01, 1.0 / 4095);
            sr_destroy_scene(sr_test_ctx(), b);
        }
        if (no_indices) {
            free(file.p);
            continue;
        }
#ifdef SR_CLI_PATH
        check_same_render("draco_strip", (const void *[]){ plain.p, file.p },
                          (size_t[]){ plain.n, file.n }, 8, 32);
#endif
        free(file.p);
    }
    sr_destroy_scene(sr_test_ctx(), a);
    free(e.data);
    free(plain.p);
}

/* A strip's indices that are not the stream's corners are refused with
 * the stream's faces named as such: a strip of N indices draws N - 2
 * triangles, not N / 3. */
SR_TEST(draco_strip_with_too_many_indices_names_faces_not_triangles)
{
    static sphere s;
    make_sphere(&s);
    make_strip(&s);
    draco_encoded e = encode_sphere(&s, false, true);
    REQUIRE(e.data);
    char corners[64], corners3[64], want[300];
    snprintf(corners, sizeof corners, "\"count\":%zu,\"type\":\"SCALAR\"", e.faces * 3);
    snprintf(corners3, sizeof corners3, "\"count\":%zu,\"type\":\"SCALAR\"", e.faces * 3 + 3);
    snprintf(want, sizeof want,
             PRIM "/indices: accessor 3 has %zu elements, but the Draco stream (" EXT
                  ") has %zu faces (%zu corners, the strip's indices)",
             e.faces * 3 + 3, e.faces, e.faces * 3);
    wbuf json, bin;
    write_file(&e, (file_options){ .draco = true, .strip = true }, &json, &bin);
    CHECK(edit_text(&json, corners, corners3));
    wbuf file = glb((const char *)json.p, bin.p, bin.n);
    sr_io_error err;
    sr_scene *b = parse_glb(&file, &err);
    CHECK(!b);
    if (b) {
        sr_destroy_scene(sr_test_ctx(), b);
    } else {
        CHECK_STR_CONTAINS(err.message, want);
    }
    free(file.p);
    free(json.p);
    free(bin.p);
    free(e.data);
}

typedef struct bad_case {
    const char *from, *to;       /* the JSON edit ("%zu": the points, "%u": an id) */
    int corrupt;                 /* 1: the stream's magic broken, 2: a point cloud */
    const char *message;
} bad_case;

SR_TEST(malformed_draco_primitives_give_one_line_and_exit_2)
{
    NEED_CLI();
    static sphere s;
    make_sphere(&s);
    draco_encoded e = encode_sphere(&s, false, false);
    draco_encoded cloud = encode_sphere(&s, true, false);
    REQUIRE(e.data && cloud.data);
    char count[64], count1[64], big[64], ext_ids[4][128], msg_budget[200];
    char corners[64], corners3[64], msg_count[200], msg_corners[200];
    snprintf(count, sizeof count, "\"count\":%zu,\"type\":\"VEC3\",\"min\"", e.points);
    snprintf(count1, sizeof count1, "\"count\":%zu,\"type\":\"VEC3\",\"min\"", e.points + 1);
    snprintf(big, sizeof big, "\"count\":100000000,\"type\":\"VEC3\",\"min\"");
    /* The extension's attributes: as written, POSITION's id unknown,
     * TEXCOORD_0 naming the normals, and one more attribute. */
    const uint32_t ids[3][3] = { { e.id_pos, e.id_nrm, e.id_uv }, { 9, e.id_nrm, e.id_uv },
                                 { e.id_pos, e.id_nrm, e.id_nrm } };
    for (int k = 0; k < 3; k++) {
        snprintf(ext_ids[k], sizeof ext_ids[k],
                 "{\"POSITION\":%u,\"NORMAL\":%u,\"TEXCOORD_0\":%u}}", ids[k][0], ids[k][1],
                 ids[k][2]);
    }
    snprintf(ext_ids[3], sizeof ext_ids[3], "{\"COLOR_0\":7,%.100s", ext_ids[0] + 1);
    snprintf(corners, sizeof corners, "\"count\":%zu,\"type\":\"SCALAR\"", e.faces * 3);
    snprintf(corners3, sizeof corners3, "\"count\":%zu,\"type\":\"SCALAR\"", e.faces * 3 + 3);
    snprintf(msg_count, sizeof msg_count,
             EXT "/attributes/POSITION: the Draco stream has %zu points, but accessor 0 ("
                 PRIM "/attributes/POSITION) has %zu elements",
             e.points, e.points + 1);
    /* 10^8 positions, the other attributes, the indices: 4 bytes a component */
    snprintf(msg_budget, sizeof msg_budget,
             EXT ": %zu bytes to decode are more than a file of this size may decode",
             (size_t)100000000 * 12 + e.points * 20 + e.faces * 12);
    snprintf(msg_corners, sizeof msg_corners,
             PRIM "/indices: accessor 3 has %zu elements, but the Draco stream (" EXT
                  ") has %zu triangles",
             e.faces * 3 + 3, e.faces);
    const bad_case cases[] = {
        /* the stream cut short, then its magic broken */
        { "{\"buffer\":0,\"byteLength\":", "{\"buffer\":0,\"byteLength\":40,\"x\":", 0,
          EXT "/bufferView: the Draco stream does not decode (corrupt or truncated; libdraco: " },
        { NULL, NULL, 1, EXT "/bufferView: the Draco stream does not decode" },
        { NULL, NULL, 2,
          EXT "/bufferView: the Draco stream is a point cloud, not a triangle mesh" },
        { ext_ids[0], ext_ids[1], 0,
          EXT "/attributes/POSITION: the Draco stream has no attribute of unique id 9" },
        { ext_ids[0], ext_ids[2], 0,
          EXT "/attributes/TEXCOORD_0: Draco attribute 1 does not match accessor 2 (" PRIM
              "/attributes/TEXCOORD_0): it has 3 components per point, the accessor 2" },
        { "{\"componentType\":5126,\"count\":", "{\"componentType\":5123,\"count\":", 0,
          EXT "/attributes/POSITION: Draco attribute 0 does not match accessor 0 (" PRIM
              "/attributes/POSITION): it holds float32 values, which componentType 5123 does "
              "not take" },
        { count, count1, 0, msg_count },
        { corners, corners3, 0, msg_corners },
        { count, big, 0,
          msg_budget },
        { "\"TEXCOORD_0\":2},", "\"TEXCOORD_0\":2},\"mode\":6,", 0,
          PRIM "/mode: 6, but KHR_draco_mesh_compression allows triangles (4) and triangle "
               "strips (5) only" },
        { "\"TEXCOORD_0\":2},", "\"TEXCOORD_0\":2},\"mode\":1,", 0,
          PRIM "/mode: 1, but KHR_draco_mesh_compression allows triangles (4) and triangle "
               "strips (5) only" },
        /* libdraco's default encoding reorders the faces: no strip */
        { "\"TEXCOORD_0\":2},", "\"TEXCOORD_0\":2},\"mode\":5,", 0,
          PRIM "/mode: 5 (a triangle strip), but the Draco stream (" EXT "/bufferView) is "
               "edgebreaker-encoded, which reorders the triangles: a strip needs sequential "
               "connectivity" },
        { ext_ids[0], ext_ids[3], 0,
          EXT "/attributes/COLOR_0: not one of the primitive's attributes" },
        { "{\"bufferView\":0,\"attributes\"", "{\"attributes\"", 0, EXT "/bufferView: missing" },
        { "{\"bufferView\":0,\"attributes\"", "{\"bufferView\":7,\"attributes\"", 0,
          EXT "/bufferView: bufferViews 7 does not exist (1 of them)" },
    };
    char dir[1024];
    fresh_dir("draco_bad", dir, sizeof dir);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const bad_case *c = &cases[i];
        wbuf json, bin;
        write_file(c->corrupt == 2 ? &cloud : &e, (file_options){ .draco = true }, &json, &bin);
        if (c->corrupt == 2) {
            /* the cloud's counts: the mesh's accessors */
            wbuf mesh_json, mesh_bin;
            write_file(&e, (file_options){ .draco = true }, &mesh_json, &mesh_bin);
            free(json.p);
            json = mesh_json;
            free(mesh_bin.p);
        }
        if (c->from && !edit_text(&json, c->from, c->to)) {
            free(json.p);
            free(bin.p);
            continue;
        }
        if (c->corrupt == 1) {
            bin.p[0] ^= 0xFF;
        }
        wbuf file = glb((const char *)json.p, bin.p, bin.n);
        check_refused(dir, i, file.p, file.n, c->message);
        free(file.p);
        free(json.p);
        free(bin.p);
    }
    free(e.data);
    free(cloud.data);
}

#else /* !SR_HAVE_DRACO_TEST */

/* Without libdraco: the file that only uses the extension reads its
 * fallback (the stream is not looked at), the one without a fallback is
 * refused, and so is the one that requires the extension. */
SR_TEST(a_build_without_libdraco_reads_the_fallback_or_refuses)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    static sphere s;
    make_sphere(&s);
    wbuf plain = plain_glb(&s), data = sphere_bytes(&s);
    static uint8_t not_draco[16] = "not a stream";
    draco_encoded counts = { .data = not_draco, .size = sizeof not_draco, .points = VERTS,
                             .faces = s.index_count / 3, .id_nrm = 1, .id_uv = 2 };
    sr_io_error err;
    sr_scene *a = parse_glb(&plain, &err);
    REQUIRE(a);
    wbuf used = file_glb(&counts, (file_options){ .draco = true, .used_only = true,
                                                  .fallback = &data });
    sr_scene *b = parse_glb(&used, &err);
    if (!b) {
        FAILF("%s", err.message);
    } else {
        check_same_triangles(a, b, 0, 0, 0);
        sr_destroy_scene(sr_test_ctx(), b);
    }
    /* The extension is ignored, not checked: its missing bufferView does
     * not matter to a reader without Draco. */
    wbuf json, bin;
    write_file(&counts, (file_options){ .draco = true, .used_only = true, .fallback = &data },
               &json, &bin);
    if (edit_text(&json, "{\"bufferView\":0,\"attributes\"", "{\"attributes\"")) {
        wbuf odd = glb((const char *)json.p, bin.p, bin.n);
        b = parse_glb(&odd, &err);
        if (!b) {
            FAILF("%s", err.message);
        }
        sr_destroy_scene(sr_test_ctx(), b);
        free(odd.p);
    }
    free(json.p);
    free(bin.p);
    wbuf bare = file_glb(&counts, (file_options){ .draco = true, .used_only = true });
    CHECK(parse_glb(&bare, &err) == NULL);
    CHECK_STR_CONTAINS(err.message, PRIM "/attributes/POSITION: softrast was built without "
                                    "libdraco, and accessor 0 holds no uncompressed fallback");
    wbuf required = file_glb(&counts, (file_options){ .draco = true, .fallback = &data });
    CHECK(parse_glb(&required, &err) == NULL);
    CHECK_STR_CONTAINS(err.message, "/extensionsRequired/0: extension KHR_draco_mesh_compression "
                                    "is not supported (softrast was built without libdraco)");
    sr_destroy_scene(sr_test_ctx(), a);
    free(plain.p);
    free(data.p);
    free(used.p);
    free(bare.p);
    free(required.p);
}

#endif
