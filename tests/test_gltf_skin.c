/* test_gltf_skin.c - skins and morph targets in the glTF reader: a
 * two-bone strip lands where linear blend skinning puts it (worked out by
 * hand below), whatever its own node's transform; morph weights come from
 * the node, else the mesh, and sparse targets move the vertices they
 * name; posed instances get arrays of their own while plain ones share
 * them; each malformed skin or target is refused with its JSON pointer.
 * Animations: a joint turned by one moves the strip to hand-worked
 * places, and sr_scene_pose on one scene gives, pose after pose, the
 * bytes of a reading in each pose. */
#include "gltf_write.h"
#include "gltf_parse.h"
#include "sr_test.h"

#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct bytes {
    uint8_t p[2048];
    size_t n;
} bytes;

/* Appends count little-endian items of `size` bytes; returns their offset. */
static size_t put(bytes *b, const void *src, size_t count, size_t size)
{
    return gltf_put(b->p, &b->n, src, count, size);
}

/* A document of buffer b (a data URI, bufferView 0 the whole of it) and
 * `body`, with the first `from` in it replaced by `to` (none when NULL).
 * malloc'd. */
static char *doc(const bytes *b, const char *body, const char *from, const char *to)
{
    char *b64 = malloc(4 * (b->n / 3 + 1) + 1);
    size_t cap = 4 * (b->n / 3 + 1) + strlen(body) + (to ? strlen(to) : 0) + 300;
    char *json = malloc(cap);
    if (!b64 || !json) {
        free(b64);
        free(json);
        return NULL;
    }
    gltf_base64(b->p, b->n, b64);
    int at = snprintf(json, cap,
                      "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu,"
                      "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
                      "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu}],",
                      b->n, b64, b->n);
    const char *cut = from ? strstr(body, from) : NULL;
    if (from && !cut) {
        sr_test_fail(__FILE__, __LINE__, "'%s' is not in the document", from);
    }
    if (cut) {
        snprintf(json + at, cap - (size_t)at, "%.*s%s%s}", (int)(cut - body), body, to,
                 cut + strlen(from));
    } else {
        snprintf(json + at, cap - (size_t)at, "%s}", body);
    }
    free(b64);
    return json;
}


static sr_scene *load(const char *json, warnings *w)
{
    sr_scene *s = NULL;
    sr_io_error e;
    if (!json || parse(json, w, &s, &e) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s", json ? e.message : "out of memory");
    }
    return s;
}

/* The document is refused, with exactly `message`. */
static void check_refused(const char *json, const char *message, int line)
{
    sr_scene *s = NULL;
    sr_io_error e;
    warnings w = { 0 };
    sr_result r = json ? parse(json, &w, &s, &e) : SR_OUT_OF_MEMORY;
    if (r == SR_OK) {
        sr_test_fail(__FILE__, line, "read, expected '%s'", message);
        sr_destroy_scene(sr_test_ctx(), s);
    } else if (strcmp(e.message, message) != 0) {
        sr_test_fail(__FILE__, line, "'%s', expected '%s'", e.message, message);
    }
}

/* ---- the two-bone strip ----------------------------------------------------
 *
 * Six vertices in rows at y = 0, 1, 2 (x = -0.5, 0.5), facing +z with
 * tangent +x.  Row 0 follows joint 0, row 2 joint 1, row 1 both by half.
 * The joints are nodes 2 and 3 under node 1, which moves them by (0, 0,
 * -3); node 3 sits at (0, 1, 0) from node 2 and turns 90 degrees about
 * +z.  The inverse bind matrices undo the rest pose (translations by
 * (0, 0, 3) and (0, -1, 3)), so joint 0's matrix is the identity and
 * joint 1's J1 = T(0, 1, -3) Rz(90) T(0, -1, 3) turns the strip about
 * (0, 1): (x, y, z) -> (1 - y, 1 + x, z).  Hence
 *   row 0: (-0.5, 0, 0), (0.5, 0, 0)                   (joint 0)
 *   row 1: half of (x, 1, 0) and (0, 1 + x, 0):
 *          (-0.25, 0.75, 0), (0.25, 1.25, 0)
 *   row 2: (-1, 0.5, 0), (-1, 1.5, 0)                   (joint 1)
 * and the tangents +x, (1, 1, 0) / sqrt 2, +y; normals stay +z.  The
 * skinned node 0 moves by (100, 0, 0) and scales by 5, which skinning
 * ignores. */

enum {
    A_POS, A_NRM, A_TAN, A_IDX, A_J16, A_WF, A_IBM, A_J8, A_W8, A_W16, A_IBM_VEC4,
    /* For the animations (unused otherwise): key times 0 and 2, two
     * rotations about +z (none, half a turn); key times 0, 1, 2, three
     * translations, two morph weights a key; a CUBICSPLINE scale of two
     * keys (in-tangent, value, out-tangent each). */
    A_T2, A_ROT, A_T3, A_TRANS, A_MW, A_CUBIC,
    A_COUNT,
    SPARSE_INDEX = A_COUNT, SPARSE_JOINTS, OFFSETS
};

/* Where strip_doc put each array in the buffer (and, past the
 * accessors', a sparse substitution of vertex 3's joints by (0, 5, 0,
 * 0)). */
static size_t strip_at[OFFSETS];

static const char strip_body[] =
    "\"accessors\":["
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":6,\"type\":\"VEC4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5123,\"count\":12,"
    "\"type\":\"SCALAR\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5123,\"count\":6,\"type\":\"VEC4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":6,\"type\":\"VEC4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":2,\"type\":\"MAT4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5121,\"count\":6,\"type\":\"VEC4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5121,\"normalized\":true,"
    "\"count\":6,\"type\":\"VEC4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5123,\"normalized\":true,"
    "\"count\":6,\"type\":\"VEC4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":8,\"type\":\"VEC4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":2,\"type\":\"VEC4\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":3,\"type\":\"SCALAR\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":6,\"type\":\"SCALAR\"},"
    "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TANGENT\":2,"
    "\"JOINTS_0\":4,\"WEIGHTS_0\":5},\"indices\":3}]}],"
    "\"skins\":[{\"joints\":[2,3],\"inverseBindMatrices\":6}],"
    "\"nodes\":[{\"mesh\":0,\"skin\":0,\"translation\":[100,0,0],\"scale\":[5,5,5]},"
    "{\"translation\":[0,0,-3],\"children\":[2]},{\"children\":[3]},"
    "{\"translation\":[0,1,0],\"rotation\":[0,0,0.70710678118654752,0.70710678118654752]}],"
    "\"scenes\":[{\"nodes\":[0,1]}]";

/* The strip's document, with `from` replaced by `to` (none: NULL). */
static char *strip_doc(const char *from, const char *to)
{
    static const float pos[18] = { -0.5f, 0, 0, 0.5f, 0, 0, -0.5f, 1, 0,
                                   0.5f,  1, 0, -0.5f, 2, 0, 0.5f, 2, 0 };
    static const float nrm[18] = { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    static const float tan[24] = { 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1,
                                   1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1 };
    static const uint16_t idx[12] = { 0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4 };
    static const uint16_t j16[24] = { 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0,
                                      0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0 };
    static const float wf[24] = { 1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0,
                                  0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0 };
    static const float ibm[32] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1,
                                   1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 3, 1 };
    /* Quantized: joints in bytes, weights in normalized bytes (0.5 is
     * 128 / 255, so row 1 lands within 0.01) and in shorts. */
    static const uint8_t j8[24] = { 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0,
                                    0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0 };
    static const uint8_t w8[24] = { 255, 0, 0, 0, 255, 0, 0, 0, 128, 127, 0, 0,
                                    128, 127, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0 };
    static const uint16_t w16[24] = { 65535, 0, 0, 0, 65535, 0, 0, 0, 32768, 32767, 0, 0,
                                      32768, 32767, 0, 0, 65535, 0, 0, 0, 65535, 0, 0, 0 };
    bytes b = { .n = 0 };
    size_t at[A_COUNT];
    at[A_POS] = put(&b, pos, 18, 4);
    at[A_NRM] = put(&b, nrm, 18, 4);
    at[A_TAN] = put(&b, tan, 24, 4);
    at[A_IDX] = put(&b, idx, 12, 2);
    at[A_J16] = put(&b, j16, 24, 2);
    at[A_WF] = put(&b, wf, 24, 4);
    at[A_IBM] = put(&b, ibm, 32, 4);
    at[A_J8] = put(&b, j8, 24, 1);
    at[A_W8] = put(&b, w8, 24, 1);
    at[A_W16] = put(&b, w16, 24, 2);
    at[A_IBM_VEC4] = at[A_IBM];
    static const float t2[2] = { 0, 2 }, rot[8] = { 0, 0, 0, 1, 0, 0, 1, 0 }, t3[3] = { 0, 1, 2 };
    static const float trans[9] = { 0, 0, 0, 1, 2, 3, -2, 0.5f, 1 };
    static const float mw[6] = { 0, 0, 0.75f, -0.5f, 0.25f, 1 };
    static const float cubic[18] = { 0, 0, 0, 1, 1, 1, 0.5f, -1, 2,
                                     1, 0, -1, 2, 0.5f, 1.5f, 0, 0, 0 };
    at[A_T2] = put(&b, t2, 2, 4);
    at[A_ROT] = put(&b, rot, 8, 4);
    at[A_T3] = put(&b, t3, 3, 4);
    at[A_TRANS] = put(&b, trans, 9, 4);
    at[A_MW] = put(&b, mw, 6, 4);
    at[A_CUBIC] = put(&b, cubic, 18, 4);
    static const uint16_t sparse_index[1] = { 3 }, sparse_joints[4] = { 0, 5, 0, 0 };
    strip_at[SPARSE_INDEX] = put(&b, sparse_index, 1, 2);
    strip_at[SPARSE_JOINTS] = put(&b, sparse_joints, 4, 2);
    memcpy(strip_at, at, sizeof at);
    char body[sizeof strip_body + 300];
    snprintf(body, sizeof body, strip_body, at[0], at[1], at[2], at[3], at[4], at[5], at[6],
             at[7], at[8], at[9], at[10], at[11], at[12], at[13], at[14], at[15], at[16]);
    return doc(&b, body, from, to);
}

static void check_vec(const float *v, double x, double y, double z, double tol, int line)
{
    if (fabs(v[0] - x) > tol || fabs(v[1] - y) > tol || fabs(v[2] - z) > tol) {
        sr_test_fail(__FILE__, line, "(%g, %g, %g), expected (%g, %g, %g)", (double)v[0],
                     (double)v[1], (double)v[2], x, y, z);
    }
}

static const double strip_posed[6][3] = { { -0.5, 0, 0 },    { 0.5, 0, 0 },  { -0.25, 0.75, 0 },
                                           { 0.25, 1.25, 0 }, { -1, 0.5, 0 }, { -1, 1.5, 0 } };

static void check_strip(const sr_scene *s, double tol)
{
    REQUIRE(s->primitive_count == 1);
    const sr_scene_primitive *p = &s->primitives[0];
    const double h = sqrt(0.5);
    const double tangent[6][3] = { { 1, 0, 0 }, { 1, 0, 0 }, { h, h, 0 },
                                   { h, h, 0 }, { 0, 1, 0 }, { 0, 1, 0 } };
    for (int i = 0; i < 6; i++) {
        check_vec(p->positions + 3 * i, strip_posed[i][0], strip_posed[i][1], strip_posed[i][2],
                  tol, __LINE__);
        check_vec(p->normals + 3 * i, 0, 0, 1, 1e-6, __LINE__);
        check_vec(p->tangents + 4 * i, tangent[i][0], tangent[i][1], tangent[i][2], tol,
                  __LINE__);
        CHECK_EQ(p->tangents[4 * i + 3], 1.0f);
    }
    /* In world space already: the node's (100, 0, 0) and scale 5 are not
     * applied, and the bounds are the posed vertices'. */
    for (int k = 0; k < 16; k++) {
        CHECK_EQ(p->world[k], k % 5 == 0 ? 1.0f : 0.0f);
    }
    CHECK(!p->mirrored);
    CHECK_NEAR(s->bounds_min.x, -1, tol);
    CHECK_NEAR(s->bounds_max.y, 1.5, tol);
    CHECK_NEAR(s->bounds_max.x, 0.5, tol);
}

SR_TEST(two_bone_strip_lands_where_linear_blend_skinning_puts_it)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    warnings w = { 0 };
    char *json = strip_doc(NULL, NULL);
    sr_scene *s = load(json, &w);
    REQUIRE(s);
    check_strip(s, 1e-6);
    CHECK_EQ(w.count, 0);   /* skins are no longer "not read" */
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

SR_TEST(quantized_joints_and_weights_pose_the_strip_alike)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    const char *weights[2] = { "\"WEIGHTS_0\":8", "\"WEIGHTS_0\":9" };
    for (int k = 0; k < 2; k++) {
        warnings w = { 0 };
        char to[64];
        snprintf(to, sizeof to, "\"JOINTS_0\":7,%s", weights[k]);
        char *json = strip_doc("\"JOINTS_0\":4,\"WEIGHTS_0\":5", to);
        sr_scene *s = load(json, &w);
        REQUIRE(s);
        check_strip(s, 0.01);
        sr_destroy_scene(sr_test_ctx(), s);
        free(json);
    }
}

/* The same strip with a second influence set that adds nothing (weights
 * 0 on joint 1) and with its weights split over two sets. */
SR_TEST(a_second_influence_set_adds_its_joints)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    warnings w = { 0 };
    /* Set 1 takes set 0's joints with normalized-byte weights: every
     * vertex then weighs about 2, doubling its position. */
    char *json = strip_doc("\"WEIGHTS_0\":5", "\"WEIGHTS_0\":5,\"JOINTS_1\":4,\"WEIGHTS_1\":8");
    sr_scene *s = load(json, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 1);
    for (int i = 0; i < 6; i++) {
        check_vec(s->primitives[0].positions + 3 * i, 2 * strip_posed[i][0],
                  2 * strip_posed[i][1], 0, 0.02, __LINE__);
    }
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

/* Skinning ignores the skinned node's transform: with the node moved,
 * scaled and mirrored the strip lands in the same place, not mirrored. */
SR_TEST(the_node_transform_of_a_skinned_mesh_is_ignored)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    warnings w = { 0 };
    char *json = strip_doc("\"translation\":[100,0,0],\"scale\":[5,5,5]",
                           "\"matrix\":[-2,0,0,0,0,3,0,0,0,0,1,0,7,8,9,1]");
    sr_scene *s = load(json, &w);
    REQUIRE(s);
    check_strip(s, 1e-6);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

/* Two nodes drawing the skinned mesh, one with the skin and one
 * without: two primitives, the plain one drawn by its node's transform. */
SR_TEST(a_mesh_drawn_skinned_and_plain_gives_two_arrays)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    warnings w = { 0 };
    char *json = strip_doc("\"scenes\":[{\"nodes\":[0,1]}]",
                           "\"scenes\":[{\"nodes\":[0,1,4]}]");
    char *json2 = json ? malloc(strlen(json) + 64) : NULL;
    REQUIRE(json2);
    /* A fifth node: the mesh, no skin, moved by (10, 0, 0). */
    char *nodes_end = strstr(json, "]}],\"scenes\"");
    REQUIRE(nodes_end);
    sprintf(json2, "%.*s]},{\"mesh\":0,\"translation\":[10,0,0]}%s", (int)(nodes_end - json),
            json, nodes_end + 2);
    sr_scene *s = load(json2, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 2);
    const sr_scene_primitive *skinned = &s->primitives[0], *plain = &s->primitives[1];
    CHECK(skinned->positions != plain->positions);
    check_vec(skinned->positions + 3 * 5, -1, 1.5, 0, 1e-6, __LINE__);
    check_vec(plain->positions + 3 * 5, 0.5, 2, 0, 0, __LINE__);
    CHECK_EQ(plain->world[12], 10.0f);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
    free(json2);
}

SR_TEST(malformed_skins_are_refused_with_their_pointer)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    static const struct {
        const char *from, *to, *message;
    } cases[] = {
        { "\"joints\":[2,3]", "\"joints\":[2,7]",
          "t.gltf: /skins/0/joints/1: not a node index below 4" },
        { "\"joints\":[2,3]", "\"joints\":[2,2]",
          "t.gltf: /skins/0/joints/1: node 2 is listed twice" },
        { "\"joints\":[2,3]", "\"joints\":[]", "t.gltf: /skins/0/joints: missing or empty" },
        { "\"joints\":[2,3]", "\"joints\":[3]",
          "t.gltf: /meshes/0/primitives/0/attributes/JOINTS_0: element 0 names joint 1, but "
          "/skins/0 has 1 joints (/nodes/0/skin)" },
        { "\"inverseBindMatrices\":6", "\"inverseBindMatrices\":10",
          "t.gltf: /skins/0/inverseBindMatrices: accessor 10 is not a MAT4 of floats" },
        { "\"count\":2,\"type\":\"MAT4\"", "\"count\":1,\"type\":\"MAT4\"",
          "t.gltf: /skins/0/inverseBindMatrices: accessor 6 has 1 matrices, fewer than the 2 "
          "joints" },
        { "\"skin\":0", "\"skin\":1", "t.gltf: /nodes/0/skin: skin 1 does not exist (1 of them)" },
        { "\"mesh\":0,\"skin\":0", "\"skin\":0",
          "t.gltf: /nodes/0/skin: skin 0 on a node without a mesh" },
        { "\"JOINTS_0\":4", "\"JOINTS_0\":5",
          "t.gltf: /meshes/0/primitives/0/attributes/JOINTS_0: accessor 5 is not of unsigned "
          "bytes or shorts (not normalized)" },
        { "\"WEIGHTS_0\":5", "\"WEIGHTS_0\":7",
          "t.gltf: /meshes/0/primitives/0/attributes/WEIGHTS_0: accessor 7 is not of floats or "
          "normalized unsigned bytes or shorts" },
        { "\"WEIGHTS_0\":5", "\"WEIGHTS_0\":10",
          "t.gltf: /meshes/0/primitives/0/attributes/WEIGHTS_0: accessor 10 has 8 elements, "
          "POSITION 6" },
        { ",\"WEIGHTS_0\":5", "",
          "t.gltf: /meshes/0/primitives/0/attributes: JOINTS_0 without WEIGHTS_0 or the other "
          "way round" },
        { ",\"JOINTS_0\":4,\"WEIGHTS_0\":5", "",
          "t.gltf: /meshes/0/primitives/0/attributes: no JOINTS_0 and WEIGHTS_0, but "
          "/nodes/0/skin skins it" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char *json = strip_doc(cases[i].from, cases[i].to);
        check_refused(json, cases[i].message, __LINE__);
        free(json);
    }
}

/* A joint index past the skin's joints, in a sparse JOINTS accessor whose
 * dense part is in range: the substituted value is checked too. */
SR_TEST(joint_indices_past_the_skin_are_refused_in_sparse_accessors_too)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    free(strip_doc(NULL, NULL));   /* to learn the offsets */
    char to[400];
    snprintf(to, sizeof to,
             "\"componentType\":5123,\"count\":6,\"type\":\"VEC4\",\"sparse\":{\"count\":1,"
             "\"indices\":{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5123},"
             "\"values\":{\"bufferView\":0,\"byteOffset\":%zu}}}",
             strip_at[SPARSE_INDEX], strip_at[SPARSE_JOINTS]);
    char *json = strip_doc("\"componentType\":5123,\"count\":6,\"type\":\"VEC4\"}", to);
    check_refused(json,
                  "t.gltf: /meshes/0/primitives/0/attributes/JOINTS_0: element 3 names joint 5, "
                  "but /skins/0 has 2 joints (/nodes/0/skin)",
                  __LINE__);
    free(json);
}

/* ---- morph targets -------------------------------------------------------
 *
 * A triangle (0, 0, 0), (1, 0, 0), (0, 1, 0) with two targets: target 0
 * moves every vertex by (0, 0, 1) (and tilts the normals toward +x),
 * target 1 is sparse and moves vertex 2 alone by (0, 2, 0).  Mesh 0 has
 * weights (0.5, 0); mesh 1 is the triangle without targets. */

static char *morph_doc(const char *from, const char *to)
{
    static const float pos[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    static const float nrm[9] = { 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    static const float up[9] = { 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    static const float tilt[9] = { 1, 0, 0, 1, 0, 0, 1, 0, 0 };
    static const uint16_t idx[3] = { 0, 1, 2 }, sparse_idx[1] = { 2 };
    static const float sparse_val[3] = { 0, 2, 0 };
    bytes b = { .n = 0 };
    size_t a_pos = put(&b, pos, 9, 4), a_nrm = put(&b, nrm, 9, 4), a_up = put(&b, up, 9, 4);
    size_t a_tilt = put(&b, tilt, 9, 4), a_idx = put(&b, idx, 3, 2);
    size_t a_si = put(&b, sparse_idx, 1, 2), a_sv = put(&b, sparse_val, 3, 4);
    char body[4096];
    snprintf(body, sizeof body,
             "\"accessors\":["
             "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\"},"
             "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\"},"
             "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\"},"
             "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\"},"
             "{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5123,\"count\":3,"
             "\"type\":\"SCALAR\"},"
             "{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"sparse\":{\"count\":1,"
             "\"indices\":{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5123},"
             "\"values\":{\"bufferView\":0,\"byteOffset\":%zu}}},"
             "{\"bufferView\":0,\"byteOffset\":0,\"componentType\":5126,\"count\":2,"
             "\"type\":\"VEC3\"}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},"
             "\"indices\":4,\"targets\":[{\"POSITION\":2,\"NORMAL\":3},{\"POSITION\":5}]}],"
             "\"weights\":[0.5,0]},"
             "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":4}]}],"
             "\"nodes\":[{\"mesh\":0},{\"mesh\":0,\"weights\":[0.25,1]},"
             "{\"mesh\":0,\"weights\":[0,0]},{\"mesh\":1},{\"mesh\":1,\"translation\":[5,0,0]},"
             "{\"mesh\":0,\"weights\":[0,0]}],"
             "\"scenes\":[{\"nodes\":[0,1,2,3,4,5]}]",
             a_pos, a_nrm, a_up, a_tilt, a_idx, a_si, a_sv);
    return doc(&b, body, from, to);
}

SR_TEST(morph_weights_come_from_the_node_else_the_mesh)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    warnings w = { 0 };
    char *json = morph_doc(NULL, NULL);
    sr_scene *s = load(json, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 6);
    CHECK_EQ(w.count, 0);   /* targets are no longer "not read" */
    const sr_scene_primitive *p = s->primitives;
    /* Node 0, the mesh's weights (0.5, 0): up by 0.5, normals tilted
     * half way toward +x and made unit length again. */
    const double h = sqrt(0.2);
    check_vec(p[0].positions + 0, 0, 0, 0.5, 0, __LINE__);
    check_vec(p[0].positions + 3, 1, 0, 0.5, 0, __LINE__);
    check_vec(p[0].positions + 6, 0, 1, 0.5, 0, __LINE__);
    check_vec(p[0].normals + 3, h, 0, 2 * h, 1e-6, __LINE__);
    /* Node 1, its own weights (0.25, 1): up by 0.25, and the sparse
     * target lifts vertex 2 by 2; vertices 0 and 1 stay put. */
    check_vec(p[1].positions + 0, 0, 0, 0.25, 0, __LINE__);
    check_vec(p[1].positions + 3, 1, 0, 0.25, 0, __LINE__);
    check_vec(p[1].positions + 6, 0, 3, 0.25, 0, __LINE__);
    CHECK(p[0].positions != p[1].positions);
    /* Nodes 2 and 5, weights zero: the mesh's own arrays, shared. */
    check_vec(p[2].positions + 6, 0, 1, 0, 0, __LINE__);
    CHECK(p[2].positions == p[5].positions);
    CHECK(p[2].normals == p[5].normals);
    /* Nodes 3 and 4 draw the plain mesh from one array. */
    CHECK(p[3].positions == p[4].positions);
    CHECK_EQ(p[4].world[12], 5.0f);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

SR_TEST(malformed_morph_targets_are_refused_with_their_pointer)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    static const struct {
        const char *from, *to, *message;
    } cases[] = {
        { "\"weights\":[0.5,0]", "\"weights\":[0.5]",
          "t.gltf: /meshes/0/weights: 1 weights, but the mesh's primitives have 2 morph "
          "targets" },
        { "\"weights\":[0.25,1]", "\"weights\":[0.25,1,2]",
          "t.gltf: /nodes/1/weights: 3 weights, but the mesh's primitives have 2 morph "
          "targets" },
        { "\"weights\":[0.25,1]", "\"weights\":[0.25,\"x\"]",
          "t.gltf: /nodes/1/weights/1: not a finite number" },
        { "{\"POSITION\":5}", "{\"POSITION\":6}",
          "t.gltf: /meshes/0/primitives/0/targets/1/POSITION: accessor 6 has 2 elements, "
          "POSITION 3" },
        { "{\"POSITION\":5}", "7",
          "t.gltf: /meshes/0/primitives/0/targets/1: not an object" },
        { "\"NORMAL\":3}", "\"NORMAL\":4}",
          "t.gltf: /meshes/0/primitives/0/targets/0/NORMAL: accessor 4 has 1 components per "
          "element, not what this attribute takes" },
        { "\"indices\":4}]}]", "\"indices\":4},{\"attributes\":{\"POSITION\":0},"
          "\"targets\":[{\"POSITION\":2}]}]}]",
          "t.gltf: /meshes/1/primitives/1/targets: 1 morph targets, primitive 0 has 0 (all of a "
          "mesh's primitives have the same number)" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char *json = morph_doc(cases[i].from, cases[i].to);
        check_refused(json, cases[i].message, __LINE__);
        free(json);
    }
}

/* Posed arrays count in the decoding budget: 100 000 vertices of zeros
 * (no bufferView: a few bytes of JSON) morphed by node after node would
 * otherwise make 1.2 MB of arrays a node for a few bytes of file.  The
 * accessors take 600 000 of the 2^20 + 16 a byte, the first node 300 000,
 * and the second no longer fits. */
SR_TEST(posed_arrays_count_in_the_decoding_budget)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    const char json[] =
        "{\"asset\":{\"version\":\"2.0\"},"
        "\"accessors\":[{\"componentType\":5126,\"count\":99999,\"type\":\"VEC3\"},"
        "{\"componentType\":5126,\"count\":99999,\"type\":\"VEC3\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
        "\"targets\":[{\"POSITION\":1}]}],\"weights\":[1]}],"
        "\"nodes\":[{\"mesh\":0},{\"mesh\":0},{\"mesh\":0},{\"mesh\":0}],"
        "\"scenes\":[{\"nodes\":[0,1,2,3]}]}";
    check_refused(json,
                  "t.gltf: /nodes/1: posing 99999 more vertices is more than a file of this size "
                  "may decode",
                  __LINE__);
    /* Weights of zero pose nothing: the same file reads. */
    char *zero = strdup(json);
    REQUIRE(zero);
    memcpy(strstr(zero, "[1]"), "[0]", 3);
    warnings w = { 0 };
    sr_scene *s = load(zero, &w);
    REQUIRE(s);
    CHECK_EQ(s->primitive_count, 4);
    sr_destroy_scene(sr_test_ctx(), s);
    free(zero);
}

/* ---- joints and the whole scene posed by animations -----------------------
 *
 * The strip's joint 1 (node 3) turned by an animation instead of its own
 * rotation: LINEAR from none at 0 s to half a turn about +z at 2 s.  Its
 * matrix J1 = T(0, 1, -3) Rz(a) T(0, -1, 3) turns the strip about (0, 1):
 *   at 0 s the identity: the strip as the file has it;
 *   at 1 s a quarter turn: strip_posed above;
 *   at 2 s half a turn, (x, y) -> (-x, 2 - y): row 2 lands on (0.5, 0)
 *          and (-0.5, 0), row 1 on half of (x, 1) and (-x, 1), (0, 1)
 *          for both; row 0 follows joint 0 and stays. */
static const char joint_still[] =
    "{\"translation\":[0,1,0],\"rotation\":[0,0,0.70710678118654752,0.70710678118654752]}],"
    "\"scenes\":[{\"nodes\":[0,1]}]";
static const char joint_turned[] =
    "{\"translation\":[0,1,0]}],\"scenes\":[{\"nodes\":[0,1]}],"
    "\"animations\":[{\"channels\":[{\"sampler\":0,\"target\":{\"node\":3,\"path\":\"rotation\"}}],"
    "\"samplers\":[{\"input\":11,\"output\":12}]}]";

static void check_turned_strip(const sr_scene *s, int seconds, int line)
{
    static const double half[6][3] = { { -0.5, 0, 0 }, { 0.5, 0, 0 }, { 0, 1, 0 },
                                       { 0, 1, 0 },    { 0.5, 0, 0 }, { -0.5, 0, 0 } };
    if (seconds == 1) {
        check_strip(s, 1e-6);
        return;
    }
    REQUIRE(s->primitive_count == 1);
    for (int i = 0; i < 6; i++) {
        const float *v = s->primitives[0].positions + 3 * i;
        if (seconds == 0) {
            check_vec(v, i % 2 ? 0.5 : -0.5, i / 2, 0, 1e-6, line);
        } else {
            check_vec(v, half[i][0], half[i][1], half[i][2], 1e-6, line);
        }
    }
}

SR_TEST(an_animated_joint_moves_the_skinned_vertices)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *json = strip_doc(joint_still, joint_turned);
    REQUIRE(json);
    /* Read in each pose, and posed again on one scene read at rest. */
    sr_scene *again = NULL;
    sr_io_error e;
    sr_result r = sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json),
                                NULL, &again, &e);
    REQUIRE(r == SR_OK);
    check_turned_strip(again, 0, __LINE__);
    static const int times[] = { 2, 0, 1, 2 };
    for (size_t k = 0; k < sizeof times / sizeof *times; k++) {
        sr_load_desc desc = { .pose = SR_POSE_ANIMATION, .animation_time = (float)times[k] };
        sr_scene *s = NULL;
        r = sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json), &desc,
                          &s, &e);
        REQUIRE(r == SR_OK);
        check_turned_strip(s, times[k], __LINE__);
        sr_destroy_scene(sr_test_ctx(), s);
        REQUIRE(sr_scene_pose(again, SR_POSE_ANIMATION, 0, (float)times[k], &e) == SR_OK);
        check_turned_strip(again, times[k], __LINE__);
    }
    sr_destroy_scene(sr_test_ctx(), again);
    free(json);
}

/* Everything posing touches: the skinned strip, also morphed (node 0);
 * mesh 0 drawn morphed without its skin (node 4, rest weights zero, so
 * its mesh's arrays until an animation weighs it); node 7 never posed;
 * a camera and a spot light on node 5, scaled by a CUBICSPLINE under the
 * STEP-translated node 4; a point light on a mirroring matrix (node 6).
 * Animation 0 turns joint 1 (LINEAR) and the joints' parent (STEP),
 * weighs nodes 0 and 4; animation 1 turns joint 0 and moves node 5. */
static const char posed_scene[] =
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TANGENT\":2,"
    "\"JOINTS_0\":4,\"WEIGHTS_0\":5},\"indices\":3,\"targets\":[{\"POSITION\":1},"
    "{\"POSITION\":0,\"NORMAL\":0,\"TANGENT\":1}]}],\"weights\":[0.5,0]},"
    "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":3}]}],"
    "\"skins\":[{\"joints\":[2,3],\"inverseBindMatrices\":6}],"
    "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1}}],"
    "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"spot\",\"spot\":{}},"
    "{\"type\":\"point\"}]}},"
    "\"nodes\":[{\"mesh\":0,\"skin\":0},{\"translation\":[0,0,-3],\"children\":[2]},"
    "{\"children\":[3]},{\"translation\":[0,1,0]},"
    "{\"mesh\":0,\"translation\":[3,0,0],\"children\":[5],\"weights\":[0,0]},"
    "{\"mesh\":1,\"camera\":0,\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
    "{\"mesh\":1,\"matrix\":[-1,0,0,0,0,1,0,0,0,0,1,0,0,0,5,1],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
    "{\"mesh\":0,\"weights\":[0,0]}],"
    "\"scenes\":[{\"nodes\":[0,1,4,6,7]}],"
    "\"animations\":[{\"channels\":["
    "{\"sampler\":0,\"target\":{\"node\":3,\"path\":\"rotation\"}},"
    "{\"sampler\":1,\"target\":{\"node\":4,\"path\":\"translation\"}},"
    "{\"sampler\":2,\"target\":{\"node\":0,\"path\":\"weights\"}},"
    "{\"sampler\":3,\"target\":{\"node\":4,\"path\":\"weights\"}},"
    "{\"sampler\":4,\"target\":{\"node\":5,\"path\":\"scale\"}},"
    "{\"sampler\":5,\"target\":{\"node\":1,\"path\":\"rotation\"}}],"
    "\"samplers\":[{\"input\":11,\"output\":12},"
    "{\"input\":13,\"output\":14,\"interpolation\":\"STEP\"},{\"input\":13,\"output\":15},"
    "{\"input\":13,\"output\":15,\"interpolation\":\"STEP\"},"
    "{\"input\":11,\"output\":16,\"interpolation\":\"CUBICSPLINE\"},"
    "{\"input\":11,\"output\":12,\"interpolation\":\"STEP\"}]},"
    "{\"name\":\"second\",\"channels\":["
    "{\"sampler\":0,\"target\":{\"node\":2,\"path\":\"rotation\"}},"
    "{\"sampler\":1,\"target\":{\"node\":5,\"path\":\"translation\"}}],"
    "\"samplers\":[{\"input\":11,\"output\":12},{\"input\":13,\"output\":14}]}]";

#define CHECK_STR_EQ(a, b)                                                             \
    do {                                                                                 \
        if (strcmp(a, b) != 0) {                                                         \
            sr_test_fail(__FILE__, __LINE__, "'%s', expected '%s'", a, b);               \
        }                                                                                \
    } while (0)

static bool same_array(const float *a, const float *b, size_t n)
{
    return (a == NULL) == (b == NULL) && (!a || memcmp(a, b, n * sizeof *a) == 0);
}

/* b, posed again, has every byte a holds, read in that pose. */
static void check_same_pose(const sr_scene *a, const sr_scene *b, const char *what)
{
    bool same = a->primitive_count == b->primitive_count &&
                a->camera_count == b->camera_count && a->light_count == b->light_count &&
                a->animation == b->animation &&
                memcmp(&a->animation_time, &b->animation_time, sizeof(float)) == 0 &&
                memcmp(&a->bounds_min, &b->bounds_min, sizeof a->bounds_min) == 0 &&
                memcmp(&a->bounds_max, &b->bounds_max, sizeof a->bounds_max) == 0;
    for (size_t i = 0; same && i < a->primitive_count; i++) {
        const sr_scene_primitive *p = &a->primitives[i], *q = &b->primitives[i];
        size_t n = p->vertex_count;
        same = memcmp(p->world, q->world, sizeof p->world) == 0 && p->mirrored == q->mirrored &&
               p->material == q->material && p->node == q->node && p->mesh == q->mesh &&
               n == q->vertex_count && p->triangle_count == q->triangle_count &&
               same_array(p->positions, q->positions, 3 * n) &&
               same_array(p->normals, q->normals, 3 * n) &&
               same_array(p->tangents, q->tangents, 4 * n) &&
               same_array(p->texcoords0, q->texcoords0, 2 * n) &&
               same_array(p->colors, q->colors, 4 * n) &&
               memcmp(p->indices, q->indices, 3 * p->triangle_count * sizeof *p->indices) == 0;
    }
    for (size_t i = 0; same && i < a->camera_count; i++) {
        same = memcmp(a->cameras[i].world, b->cameras[i].world, sizeof a->cameras[i].world) == 0;
    }
    for (size_t i = 0; same && i < a->light_count; i++) {
        const sr_scene_light *l = &a->lights[i], *m = &b->lights[i];
        same = memcmp(l->world, m->world, sizeof l->world) == 0 &&
               memcmp(&l->light.vector, &m->light.vector, sizeof l->light.vector) == 0 &&
               memcmp(&l->light.direction, &m->light.direction, sizeof l->light.direction) == 0 &&
               l->light.type == m->light.type && l->node == m->node;
    }
    if (!same) {
        sr_test_fail(__FILE__, __LINE__, "%s: posed again, the scene differs from a reading",
                     what);
    }
}

SR_TEST(posing_again_gives_the_bytes_of_a_reading_in_that_pose)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *json = strip_doc(strstr(strip_body, "\"meshes\":"), posed_scene);
    REQUIRE(json);
    sr_io_error e;
    sr_scene *again = NULL;
    sr_result r = sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json),
                                NULL, &again, &e);
    if (r != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s", e.message);
    }
    REQUIRE(again);
    REQUIRE(again->primitive_count == 5 && again->light_count == 2 && again->camera_count == 1);
    /* Node 4 and node 7 share mesh 0's arrays at rest. */
    CHECK(again->primitives[1].positions == again->primitives[4].positions);
    static const struct {
        sr_load_pose pose;
        int animation;
        float time;
    } poses[] = {
        { SR_POSE_ANIMATION, 0, 0.25f }, { SR_POSE_ANIMATION, 0, 1.0f },
        { SR_POSE_ANIMATION, 1, 0.7f },  { SR_POSE_ANIMATION, 0, 1.5f },
        { SR_POSE_REST, 0, 0 },          { SR_POSE_ANIMATION, 0, 2.0f },
        { SR_POSE_ANIMATION, 0, 0.0f },  { SR_POSE_ANIMATION, 1, 2.5f },
        { SR_POSE_ANIMATION, 0, 3.0f },  { SR_POSE_DEFAULT, 0, 0 },
        { SR_POSE_ANIMATION, 0, 1.25f },
    };
    const float *morphed = NULL;
    for (size_t k = 0; k < sizeof poses / sizeof *poses; k++) {
        char what[64];
        snprintf(what, sizeof what, "pose %zu (animation %d at %g s)", k, poses[k].animation,
                 (double)poses[k].time);
        sr_load_desc desc = { .pose = poses[k].pose, .animation = poses[k].animation,
                              .animation_time = poses[k].time };
        sr_scene *read = NULL;
        r = sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json), &desc,
                          &read, &e);
        REQUIRE(r == SR_OK);
        r = sr_scene_pose(again, poses[k].pose, poses[k].animation, poses[k].time, &e);
        if (r != SR_OK) {
            sr_test_fail(__FILE__, __LINE__, "%s: %s", what, e.message);
        }
        check_same_pose(read, again, what);
        sr_destroy_scene(sr_test_ctx(), read);
        /* Node 4's morphed arrays, once made, are reused: posing again
         * and again does not grow the scene. */
        const float *p4 = again->primitives[1].positions;
        if (p4 != again->primitives[4].positions) {
            CHECK(!morphed || p4 == morphed);
            morphed = p4;
        }
    }
    CHECK(morphed != NULL);
    sr_destroy_scene(sr_test_ctx(), again);
    free(json);
}

SR_TEST(posing_again_checks_its_arguments_and_keeps_the_scene_on_error)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *json = strip_doc(joint_still, joint_turned);
    REQUIRE(json);
    sr_io_error e;
    sr_scene *s = NULL;
    REQUIRE(sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json), NULL, &s,
                          &e) == SR_OK);
    REQUIRE(sr_scene_pose(s, SR_POSE_ANIMATION, 0, 1.0f, &e) == SR_OK);
    float before[18];
    memcpy(before, s->primitives[0].positions, sizeof before);
    CHECK_EQ(sr_scene_pose(NULL, SR_POSE_REST, 0, 0, &e), SR_INVALID_ARG);
    CHECK_STR_EQ(e.message, "sr_scene_pose: scene is NULL");
    CHECK_EQ(sr_scene_pose(s, (sr_load_pose)7, 0, 0, &e), SR_INVALID_ARG);
    CHECK_STR_EQ(e.message, "sr_scene_pose: pose 7 is not an sr_load_pose");
    CHECK_EQ(sr_scene_pose(s, SR_POSE_ANIMATION, 1, 0, &e), SR_INVALID_ARG);
    CHECK_STR_EQ(e.message,
                 "t.gltf: sr_scene_pose: animation 1 is not an animation of the scene (it has 1)");
    CHECK_EQ(sr_scene_pose(s, SR_POSE_ANIMATION, -1, 0, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_scene_pose(s, SR_POSE_ANIMATION, 0, NAN, &e), SR_INVALID_ARG);
    CHECK_STR_EQ(e.message, "t.gltf: sr_scene_pose: time nan is not finite");
    CHECK_EQ(sr_scene_pose(s, SR_POSE_ANIMATION, 0, INFINITY, &e), SR_INVALID_ARG);
    CHECK(memcmp(before, s->primitives[0].positions, sizeof before) == 0);
    CHECK_EQ(s->animation, 0);
    CHECK_EQ(s->animation_time, 1.0f);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
    /* A scene without animations has its rest pose alone. */
    json = strip_doc(NULL, NULL);
    REQUIRE(sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json), NULL, &s,
                          &e) == SR_OK);
    CHECK_EQ(sr_scene_pose(s, SR_POSE_REST, 0, 0, &e), SR_OK);
    CHECK_EQ(sr_scene_pose(s, SR_POSE_ANIMATION, 0, 0, &e), SR_INVALID_ARG);
    CHECK_STR_EQ(e.message,
                 "sr_scene_pose: animation 0 is not an animation of the scene (it has 0)");
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}
