/* test_gltf_instancing.c - EXT_mesh_gpu_instancing: a grid of twelve
 * cubes one node instances, each turned, scaled and moved, with float
 * and with quantized (normalized short rotations, normalized byte scales,
 * short translations under KHR_mesh_quantization) transforms; every
 * instance's world-space vertices against a hand computation (rotation by
 * q v q*, not by a matrix), the draws sharing the mesh's arrays, the
 * node's animation, morph weights and material variant under the
 * instances, the bounds over all of them, one message with the JSON
 * pointer for each malformed extension, the draw limits, and `softrast
 * render` against tests/ref/gltf_instanced_cubes.png within 3 codes on
 * 0.5% of the pixels (test_images.c's tolerance: libm). */
#include "batch_cli.h"
#include "gltf_write.h"

#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N 12                    /* instances: 4 columns, 3 rows */
#define NODE_SCALE 1.25f
static const float node_t[3] = { 0.5f, -0.25f, -1.0f };
static const float anim_t[3] = { -2.0f, 1.0f, 0.5f };

/* Instance i's transform as the file stores it in floats. */
static void instance_trs(int i, float t[3], float q[4], float s[3])
{
    int col = i % 4, row = i / 4;
    t[0] = (float)(3 * col - 4), t[1] = (float)(3 * row - 3), t[2] = (float)(col - row);
    double angle = 0.5 + 0.4 * i, ax[3] = { 1 + col, 2 - row, 0.5 * i };
    double len = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    for (int k = 0; k < 3; k++) {
        q[k] = (float)(ax[k] / len * sin(angle / 2));
    }
    q[3] = (float)cos(angle / 2);
    s[0] = 0.4f + 0.15f * (float)col, s[1] = 0.9f - 0.2f * (float)row, s[2] = 0.7f;
}

/* The values a normalized integer of `max` (127, 32767) decodes to. */
static float unorm(float v, float max)
{
    return fmaxf((float)lrintf(v * max) / max, -1.0f);
}

static const float cube_pos[8][3] = {
    { -0.5f, -0.5f, -0.5f }, { 0.5f, -0.5f, -0.5f }, { 0.5f, 0.5f, -0.5f }, { -0.5f, 0.5f, -0.5f },
    { -0.5f, -0.5f, 0.5f },  { 0.5f, -0.5f, 0.5f },  { 0.5f, 0.5f, 0.5f },  { -0.5f, 0.5f, 0.5f },
};
static const uint16_t cube_idx[36] = { 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                       3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5 };

/* The buffer's accessors, in order. */
enum {
    A_POS, A_IDX, A_T, A_R, A_R_SHORT, A_S, A_S_BYTE, A_T_SHORT, A_ID, A_SHORT_COUNT, A_ZERO_R,
    A_NAN_T, A_COUNT0, A_TIME, A_ANIM_T, A_DELTA, A_BIG_ID, A_HUGE_ID, A_JOINTS, A_WEIGHTS,
    A_COUNT
};

typedef struct bin {
    uint8_t p[4096];
    size_t n;
} bin;

static size_t put(bin *b, const void *src, size_t count, size_t size)
{
    return gltf_put(b->p, &b->n, src, count, size);
}

/* The model: `attrs` the extension's attributes object (NULL: no
 * extension), `node` more members of node 0 (",\"mesh\":0" or not ...),
 * `used` more of extensionsUsed, `prim` more members of the primitive,
 * `root` more top-level members.  Malloc'd text. */
static char *instanced_model(const char *attrs, const char *node, const char *used,
                             const char *prim, const char *root)
{
    bin b = { .n = 0 };
    size_t off[A_COUNT] = { 0 }, len[A_COUNT] = { 0 };
    float t[N][3], q[N][4], s[N][3], id[N];
    int16_t qs[N][4], ts[N][4];
    int8_t sb[N][4];
    for (int i = 0; i < N; i++) {
        instance_trs(i, t[i], q[i], s[i]);
        for (int k = 0; k < 4; k++) {
            qs[i][k] = (int16_t)lrintf(q[i][k] * 32767);
            ts[i][k] = k < 3 ? (int16_t)t[i][k] : 0;
            sb[i][k] = k < 3 ? (int8_t)lrintf(s[i][k] * 127) : 0;
        }
        id[i] = (float)i;
    }
    float nan_t[N][3];
    memcpy(nan_t, t, sizeof t);
    nan_t[1][2] = NAN;
    float delta[8][3];
    for (int v = 0; v < 8; v++) {
        delta[v][0] = 0, delta[v][1] = cube_pos[v][1] > 0 ? 0.5f : 0, delta[v][2] = 0;
    }
    float time0 = 0;
    uint8_t joints[8][4] = { { 0 } };
    float weights[8][4];
    for (int v = 0; v < 8; v++) {
        weights[v][0] = 1, weights[v][1] = weights[v][2] = weights[v][3] = 0;
    }
    off[A_POS] = put(&b, cube_pos, 24, 4), len[A_POS] = 96;
    off[A_IDX] = put(&b, cube_idx, 36, 2), len[A_IDX] = 72;
    off[A_T] = put(&b, t, 3 * N, 4), len[A_T] = sizeof t;
    off[A_R] = put(&b, q, 4 * N, 4), len[A_R] = sizeof q;
    off[A_R_SHORT] = put(&b, qs, 4 * N, 2), len[A_R_SHORT] = sizeof qs;
    off[A_S] = put(&b, s, 3 * N, 4), len[A_S] = sizeof s;
    off[A_S_BYTE] = put(&b, sb, 4 * N, 1), len[A_S_BYTE] = sizeof sb;
    off[A_T_SHORT] = put(&b, ts, 4 * N, 2), len[A_T_SHORT] = sizeof ts;
    off[A_ID] = put(&b, id, N, 4), len[A_ID] = sizeof id;
    off[A_NAN_T] = put(&b, nan_t, 3 * N, 4), len[A_NAN_T] = sizeof nan_t;
    off[A_TIME] = put(&b, &time0, 1, 4), len[A_TIME] = 4;
    off[A_ANIM_T] = put(&b, anim_t, 3, 4), len[A_ANIM_T] = 12;
    off[A_DELTA] = put(&b, delta, 24, 4), len[A_DELTA] = sizeof delta;
    off[A_JOINTS] = put(&b, joints, 32, 1), len[A_JOINTS] = sizeof joints;
    off[A_WEIGHTS] = put(&b, weights, 32, 4), len[A_WEIGHTS] = sizeof weights;
    off[A_SHORT_COUNT] = off[A_T], len[A_SHORT_COUNT] = 12 * (N - 1);
    char b64[6000];
    gltf_base64(b.p, b.n, b64);
    /* A view per accessor (none for the zero-filled ones), byteStride 4
     * and 8 for the byte and short VEC3s, as attributes align. */
    static const char *const acc[A_COUNT] = {
        [A_POS] = "\"componentType\":5126,\"count\":8,\"type\":\"VEC3\","
                  "\"min\":[-0.5,-0.5,-0.5],\"max\":[0.5,0.5,0.5]",
        [A_IDX] = "\"componentType\":5123,\"count\":36,\"type\":\"SCALAR\"",
        [A_T] = "\"componentType\":5126,\"count\":12,\"type\":\"VEC3\"",
        [A_R] = "\"componentType\":5126,\"count\":12,\"type\":\"VEC4\"",
        [A_R_SHORT] = "\"componentType\":5122,\"normalized\":true,\"count\":12,\"type\":\"VEC4\"",
        [A_S] = "\"componentType\":5126,\"count\":12,\"type\":\"VEC3\"",
        [A_S_BYTE] = "\"componentType\":5120,\"normalized\":true,\"count\":12,\"type\":\"VEC3\"",
        [A_T_SHORT] = "\"componentType\":5122,\"count\":12,\"type\":\"VEC3\"",
        [A_ID] = "\"componentType\":5126,\"count\":12,\"type\":\"SCALAR\"",
        [A_SHORT_COUNT] = "\"componentType\":5126,\"count\":11,\"type\":\"VEC3\"",
        [A_ZERO_R] = "\"componentType\":5126,\"count\":12,\"type\":\"VEC4\"",
        [A_NAN_T] = "\"componentType\":5126,\"count\":12,\"type\":\"VEC3\"",
        [A_COUNT0] = "\"componentType\":5126,\"count\":0,\"type\":\"SCALAR\"",
        [A_TIME] = "\"componentType\":5126,\"count\":1,\"type\":\"SCALAR\",\"min\":[0],\"max\":[0]",
        [A_ANIM_T] = "\"componentType\":5126,\"count\":1,\"type\":\"VEC3\"",
        [A_DELTA] = "\"componentType\":5126,\"count\":8,\"type\":\"VEC3\"",
        [A_BIG_ID] = "\"componentType\":5126,\"count\":600000,\"type\":\"SCALAR\"",
        [A_HUGE_ID] = "\"componentType\":5126,\"count\":2000000,\"type\":\"SCALAR\"",
        [A_JOINTS] = "\"componentType\":5121,\"count\":8,\"type\":\"VEC4\"",
        [A_WEIGHTS] = "\"componentType\":5126,\"count\":8,\"type\":\"VEC4\"",
    };
    static const int stride[A_COUNT] = { [A_S_BYTE] = 4, [A_T_SHORT] = 8 };
    size_t cap = 40000;
    char *json = malloc(cap);
    if (!json) {
        return NULL;
    }
    size_t at = (size_t)snprintf(json, cap,
                                 "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":["
                                 "\"EXT_mesh_gpu_instancing\"%s],"
                                 "\"buffers\":[{\"byteLength\":%zu,"
                                 "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
                                 "\"bufferViews\":[",
                                 used, b.n, b64);
    int views = 0, view_of[A_COUNT];
    for (int a = 0; a < A_COUNT; a++) {
        view_of[a] = -1;
        if (len[a] == 0) {
            continue;
        }
        view_of[a] = views++;
        at += (size_t)snprintf(json + at, cap - at, "%s{\"buffer\":0,\"byteOffset\":%zu,"
                               "\"byteLength\":%zu",
                               view_of[a] ? "," : "", off[a], len[a]);
        at += (size_t)(stride[a] ? snprintf(json + at, cap - at, ",\"byteStride\":%d}",
                                            stride[a])
                                 : snprintf(json + at, cap - at, "}"));
    }
    at += (size_t)snprintf(json + at, cap - at, "],\"accessors\":[");
    for (int a = 0; a < A_COUNT; a++) {
        char view[40] = "";
        if (view_of[a] >= 0) {
            snprintf(view, sizeof view, "\"bufferView\":%d,", view_of[a]);
        }
        at += (size_t)snprintf(json + at, cap - at, "%s{%s%s}", a ? "," : "", view, acc[a]);
    }
    char ext[600] = "";
    if (attrs) {
        snprintf(ext, sizeof ext, ",\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":%s}}",
                 attrs);
    }
    snprintf(json + at, cap - at,
             "],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d},\"indices\":%d,"
             "\"material\":0%s}]}],"
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.5,0.2,1],"
             "\"metallicFactor\":0,\"roughnessFactor\":0.6}},"
             "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.5,0.9,1]}}],"
             "\"nodes\":[{\"translation\":[%g,%g,%g],\"scale\":[%g,%g,%g]%s%s}],"
             "\"scenes\":[{\"nodes\":[0]}],\"scene\":0%s}",
             A_POS, A_IDX, prim, (double)node_t[0], (double)node_t[1], (double)node_t[2],
             (double)NODE_SCALE, (double)NODE_SCALE, (double)NODE_SCALE, node, ext, root);
    return json;
}

#define FLOAT_ATTRS "{\"TRANSLATION\":2,\"ROTATION\":3,\"SCALE\":5,\"_ID\":8}"
#define QUANT_ATTRS "{\"TRANSLATION\":7,\"ROTATION\":4,\"SCALE\":6}"
#define QUANT_USED ",\"KHR_mesh_quantization\""
#define MESH ",\"mesh\":0"

static sr_result parse(const char *json, const sr_load_desc *desc, sr_scene **s, sr_io_error *e)
{
    return sr_parse_gltf(sr_test_ctx(), "i.gltf", (const uint8_t *)json, strlen(json), desc, s,
                         e);
}

/* Where vertex v of instance i lands: scaled, turned by q v q* (q the
 * file's, decoded, normalized), moved, then the node's scale and
 * translation (`node_scale`, `node`); first raised by `raise` in y, and
 * by `lift` more for vertices of y > 0. */
static void expected(int i, int v, bool quantized, float node_scale, const float node[3],
                     float lift, float raise, double out[3])
{
    float t[3], q[4], s[3];
    instance_trs(i, t, q, s);
    if (quantized) {
        for (int k = 0; k < 4; k++) {
            q[k] = unorm(q[k], 32767);
        }
        for (int k = 0; k < 3; k++) {
            s[k] = unorm(s[k], 127);
        }
    }
    double qn = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2] +
                     (double)q[3] * q[3]);
    double x = q[0] / qn, y = q[1] / qn, z = q[2] / qn, w = q[3] / qn;
    double p[3] = { cube_pos[v][0], cube_pos[v][1] + raise + (cube_pos[v][1] > 0 ? lift : 0),
                    cube_pos[v][2] };
    for (int k = 0; k < 3; k++) {
        p[k] *= s[k];
    }
    /* p + 2w (u x p) + 2 u x (u x p), u = (x, y, z) */
    double c1[3] = { y * p[2] - z * p[1], z * p[0] - x * p[2], x * p[1] - y * p[0] };
    double c2[3] = { y * c1[2] - z * c1[1], z * c1[0] - x * c1[2], x * c1[1] - y * c1[0] };
    for (int k = 0; k < 3; k++) {
        out[k] = (p[k] + 2 * w * c1[k] + 2 * c2[k] + t[k]) * node_scale + node[k];
    }
}

/* Vertex v of draw p in world space. */
static void world_point(const sr_scene_primitive *p, int v, double out[3])
{
    const float *x = p->positions + 3 * v;
    for (int k = 0; k < 3; k++) {
        out[k] = (double)p->world[k] * x[0] + (double)p->world[4 + k] * x[1] +
                 (double)p->world[8 + k] * x[2] + p->world[12 + k];
    }
}

/* Every draw of s is instance i of the cube, at the hand computation. */
static void check_instances(const sr_scene *s, bool quantized, const float node[3], float lift)
{
    REQUIRE(s->primitive_count == N);
    CHECK_EQ(s->instanced_draws, N);
    CHECK_EQ(s->instanced_nodes, 1);
    double worst = 0;
    for (int i = 0; i < N; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        CHECK_EQ(p->node, 0);
        CHECK_EQ(p->vertex_count, 8);
        CHECK_EQ(p->triangle_count, 12);
        /* shared, not copied per instance */
        CHECK(p->positions == s->primitives[0].positions);
        CHECK(p->indices == s->primitives[0].indices);
        CHECK(!p->mirrored);
        for (int v = 0; v < 8; v++) {
            double want[3], got[3];
            expected(i, v, quantized, NODE_SCALE, node, lift, 0, want);
            world_point(p, v, got);
            for (int k = 0; k < 3; k++) {
                worst = fmax(worst, fabs(got[k] - want[k]));
            }
        }
    }
    CHECK(worst < 2e-5);
    if (worst >= 2e-5) {
        FAILF("an instance's vertex is %g off", worst);
    }
}

SR_TEST(each_instance_is_a_draw_at_node_world_times_its_trs)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *json = instanced_model(FLOAT_ATTRS, MESH, "", "", "");
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    sr_test_warnings w = { 0 };
    sr_load_desc desc = { .warn = sr_test_collect_warning, .user = &w };
    if (parse(json, &desc, &s, &e) != SR_OK) {
        FAILF("%s", e.message);
        free(json);
        return;
    }
    check_instances(s, false, node_t, 0);
    CHECK_EQ(w.count, 0);   /* the extension is not "not read" */
    /* The bounds hold every instance's corners. */
    for (int i = 0; i < N; i++) {
        for (int v = 0; v < 8; v++) {
            double want[3];
            expected(i, v, false, NODE_SCALE, node_t, 0, 0, want);
            CHECK(want[0] >= s->bounds_min.x - 1e-4 && want[0] <= s->bounds_max.x + 1e-4);
            CHECK(want[1] >= s->bounds_min.y - 1e-4 && want[1] <= s->bounds_max.y + 1e-4);
            CHECK(want[2] >= s->bounds_min.z - 1e-4 && want[2] <= s->bounds_max.z + 1e-4);
        }
    }
    CHECK(s->bounds_max.x - s->bounds_min.x > 10);
    sr_destroy_scene(sr_test_ctx(), s);
    /* Required is accepted now. */
    free(json);
    json = instanced_model(FLOAT_ATTRS, MESH, "],\"extensionsRequired\":[\"EXT_mesh_gpu_instancing\"",
                           "", "");
    REQUIRE(json);
    CHECK_EQ(parse(json, NULL, &s, &e), SR_OK);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

SR_TEST(quantized_rotations_scales_and_translations_are_decoded)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *json = instanced_model(QUANT_ATTRS, MESH, QUANT_USED, "", "");
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    if (parse(json, NULL, &s, &e) != SR_OK) {
        FAILF("%s", e.message);
    } else {
        check_instances(s, true, node_t, 0);
        sr_destroy_scene(sr_test_ctx(), s);
    }
    free(json);
    /* A missing transform is the identity's part: scale alone. */
    json = instanced_model("{\"SCALE\":5}", MESH, "", "", "");
    REQUIRE(json && parse(json, NULL, &s, &e) == SR_OK);
    REQUIRE(s->primitive_count == N);
    float t[3], q[4], sc[3];
    instance_trs(5, t, q, sc);
    CHECK_NEAR(s->primitives[5].world[0], sc[0] * NODE_SCALE, 1e-6);
    CHECK_NEAR(s->primitives[5].world[5], sc[1] * NODE_SCALE, 1e-6);
    CHECK_NEAR(s->primitives[5].world[12], node_t[0], 1e-6);
    CHECK_NEAR(s->primitives[5].world[4], 0, 1e-6);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

SR_TEST(instances_follow_the_nodes_animation_morph_weights_variant_and_mirror)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    /* The node's animated translation replaces its own; the instances
     * follow it. */
    char anim[300];
    snprintf(anim, sizeof anim,
             ",\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}]}]",
             A_TIME, A_ANIM_T);
    char *json = instanced_model(FLOAT_ATTRS, MESH, "", "", anim);
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    sr_load_desc desc = { .pose = SR_POSE_ANIMATION, .animation = 0, .animation_time = 0 };
    if (parse(json, &desc, &s, &e) != SR_OK) {
        FAILF("%s", e.message);
    } else {
        check_instances(s, false, anim_t, 0);
        sr_destroy_scene(sr_test_ctx(), s);
    }
    free(json);
    /* Morphed once for the node, the posed arrays shared by every
     * instance. */
    char target[100];
    snprintf(target, sizeof target, ",\"targets\":[{\"POSITION\":%d}]", A_DELTA);
    json = instanced_model(FLOAT_ATTRS, MESH ",\"weights\":[0.5]", "", target, "");
    REQUIRE(json);
    if (parse(json, NULL, &s, &e) != SR_OK) {
        FAILF("%s", e.message);
    } else {
        check_instances(s, false, node_t, 0.25f);
        sr_destroy_scene(sr_test_ctx(), s);
    }
    free(json);
    /* The variant's material on every instance. */
    json = instanced_model(FLOAT_ATTRS, MESH, ",\"KHR_materials_variants\"",
                           ",\"extensions\":{\"KHR_materials_variants\":{\"mappings\":"
                           "[{\"material\":1,\"variants\":[0]}]}}",
                           ",\"extensions\":{\"KHR_materials_variants\":{\"variants\":"
                           "[{\"name\":\"Blue\"}]}}");
    REQUIRE(json);
    desc = (sr_load_desc){ .variant = 1 };
    if (parse(json, &desc, &s, &e) != SR_OK) {
        FAILF("%s", e.message);
    } else {
        REQUIRE(s->primitive_count == N);
        for (int i = 0; i < N; i++) {
            CHECK_EQ(s->primitives[i].material, 1);
        }
        sr_destroy_scene(sr_test_ctx(), s);
    }
    free(json);
    /* A node that mirrors mirrors every instance. */
    json = text_replaced(instanced_model("{\"SCALE\":5}", MESH, "", "", ""), "\"scale\":[1.25,",
                    "\"scale\":[-1.25,");
    REQUIRE(json);
    REQUIRE(parse(json, NULL, &s, &e) == SR_OK);
    REQUIRE(s->primitive_count == N);
    for (int i = 0; i < N; i++) {
        CHECK(s->primitives[i].mirrored);
    }
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

/* The extension says nothing of skins.  A skinned primitive is in world
 * space already (its node's matrix not applied, as glTF says); each
 * instance's transform is applied to the skinned pose.  One joint (node
 * 1, at y = 5, inverse bind the identity) lifts the cube by 5. */
SR_TEST(a_skinned_instanced_node_places_its_skinned_pose_per_instance)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char prim[120];
    snprintf(prim, sizeof prim, "\"attributes\":{\"POSITION\":%d,\"JOINTS_0\":%d,\"WEIGHTS_0\":%d}",
             A_POS, A_JOINTS, A_WEIGHTS);
    char from[60];
    snprintf(from, sizeof from, "\"attributes\":{\"POSITION\":%d}", A_POS);
    char *json = text_replaced(instanced_model(FLOAT_ATTRS, MESH ",\"skin\":0", "", "",
                                          ",\"skins\":[{\"joints\":[1]}]"),
                          from, prim);
    json = text_replaced(json, "\"scenes\":[{\"nodes\":[0]}]", "\"scenes\":[{\"nodes\":[0,1]}]");
    json = text_replaced(json, "}],\"scenes\"", "},{\"translation\":[0,5,0]}],\"scenes\"");
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    if (parse(json, NULL, &s, &e) != SR_OK) {
        FAILF("%s", e.message);
        free(json);
        return;
    }
    REQUIRE(s->primitive_count == N);
    double worst = 0;
    for (int i = 0; i < N; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        CHECK(p->positions == s->primitives[0].positions);   /* skinned once */
        for (int v = 0; v < 8; v++) {
            /* the instance alone on the lifted cube: no node matrix */
            static const float zero[3] = { 0, 0, 0 };
            double want[3], got[3];
            expected(i, v, false, 1, zero, 0, 5, want);
            world_point(p, v, got);
            for (int k = 0; k < 3; k++) {
                worst = fmax(worst, fabs(got[k] - want[k]));
            }
        }
    }
    CHECK(worst < 2e-5);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

/* b, posed again, draws what a, read in that pose, draws: the worlds,
 * mirrors and posed positions of every instance. */
static bool same_draws(const sr_scene *a, const sr_scene *b)
{
    if (a->primitive_count != b->primitive_count) {
        return false;
    }
    for (size_t i = 0; i < a->primitive_count; i++) {
        const sr_scene_primitive *p = &a->primitives[i], *q = &b->primitives[i];
        if (memcmp(p->world, q->world, sizeof p->world) != 0 || p->mirrored != q->mirrored ||
            p->vertex_count != q->vertex_count ||
            memcmp(p->positions, q->positions, 3 * p->vertex_count * sizeof(float)) != 0) {
            return false;
        }
    }
    return true;
}

/* sr_scene_pose on an instanced scene read at rest gives the bytes of a
 * reading in the animation's pose, and back: the instances keep their
 * transforms after the node's new world (or the skin's new pose). */
static void check_posed_again(const char *json, const char *what)
{
    sr_scene *again = NULL, *posed = NULL, *rest = NULL;
    sr_io_error e;
    sr_load_desc desc = { .pose = SR_POSE_ANIMATION, .animation = 0, .animation_time = 0 };
    if (parse(json, NULL, &again, &e) != SR_OK || parse(json, NULL, &rest, &e) != SR_OK ||
        parse(json, &desc, &posed, &e) != SR_OK) {
        FAILF("%s: %s", what, e.message);
    } else {
        CHECK(!same_draws(rest, posed));
        if (sr_scene_pose(again, SR_POSE_ANIMATION, 0, 0, &e) != SR_OK) {
            FAILF("%s: %s", what, e.message);
        }
        if (!same_draws(posed, again)) {
            FAILF("%s: posed again, the instances differ from a reading in that pose", what);
        }
        if (sr_scene_pose(again, SR_POSE_REST, 0, 0, &e) != SR_OK) {
            FAILF("%s: %s", what, e.message);
        }
        if (!same_draws(rest, again)) {
            FAILF("%s: posed back to rest, the instances differ from a reading at rest", what);
        }
    }
    sr_destroy_scene(sr_test_ctx(), again);
    sr_destroy_scene(sr_test_ctx(), posed);
    sr_destroy_scene(sr_test_ctx(), rest);
}

SR_TEST(posing_an_instanced_scene_again_gives_the_bytes_of_a_reading)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    /* A morphed instanced node whose translation is animated. */
    char anim[300], target[100];
    snprintf(anim, sizeof anim,
             ",\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":%%d,\"path\":\"translation\"}}]}]",
             A_TIME, A_ANIM_T);
    char node_anim[300];
    snprintf(node_anim, sizeof node_anim, anim, 0);
    snprintf(target, sizeof target, ",\"targets\":[{\"POSITION\":%d}]", A_DELTA);
    char *json = instanced_model(FLOAT_ATTRS, MESH ",\"weights\":[0.5]", "", target, node_anim);
    REQUIRE(json);
    check_posed_again(json, "morphed node moved by its animation");
    free(json);
    /* A skinned instanced node whose joint (node 1) the animation moves. */
    char joint_anim[300];
    snprintf(joint_anim, sizeof joint_anim, anim, 1);
    char prim[120], from[60], root[400];
    snprintf(prim, sizeof prim, "\"attributes\":{\"POSITION\":%d,\"JOINTS_0\":%d,\"WEIGHTS_0\":%d}",
             A_POS, A_JOINTS, A_WEIGHTS);
    snprintf(from, sizeof from, "\"attributes\":{\"POSITION\":%d}", A_POS);
    snprintf(root, sizeof root, ",\"skins\":[{\"joints\":[1]}]%s", joint_anim);
    json = text_replaced(instanced_model(QUANT_ATTRS, MESH ",\"skin\":0", QUANT_USED, "", root),
                         from, prim);
    json = text_replaced(json, "\"scenes\":[{\"nodes\":[0]}]", "\"scenes\":[{\"nodes\":[0,1]}]");
    json = text_replaced(json, "}],\"scenes\"", "},{\"translation\":[0,5,0]}],\"scenes\"");
    REQUIRE(json);
    check_posed_again(json, "skinned node whose joint is animated");
    free(json);
}

typedef struct bad_instancing {
    const char *attrs, *node, *used, *root;
    sr_result result;
    const char *message;
} bad_instancing;

#define EXT "i.gltf: /nodes/0/extensions/EXT_mesh_gpu_instancing"

static const bad_instancing bad_cases[] = {
    { "{\"TRANSLATION\":2,\"SCALE\":9}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/SCALE: accessor 9 has 11 elements, TRANSLATION 12" },
    { "{\"ROTATION\":3,\"_ID\":9}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/_ID: accessor 9 has 11 elements, ROTATION 12" },
    { "{\"TRANSLATION\":3}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/TRANSLATION: accessor 3 is 4 components of type 5126, not a VEC3 of floats" },
    { "{\"ROTATION\":2}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/ROTATION: accessor 2 is 3 components of type 5126, not a VEC4 of floats, "
          "or of normalized bytes or shorts" },
    { "{\"ROTATION\":7}", MESH, QUANT_USED, "", SR_BAD_FORMAT,
      EXT "/attributes/ROTATION: accessor 7 is 3 components of type 5122" },
    { "{\"SCALE\":6}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/SCALE: accessor 6 is 3 components of type 5120 normalized, not a VEC3 of "
          "floats (bytes and shorts need KHR_mesh_quantization)" },
    { "{\"TRANSLATION\":7}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/TRANSLATION: accessor 7 is 3 components of type 5122, not a VEC3 of floats "
          "(bytes and shorts need KHR_mesh_quantization)" },
    { "{\"TRANSLATION\":11}", MESH, "", "", SR_BAD_FORMAT,
      "i.gltf: /accessors/11: element 1 is not finite" },
    { "{\"ROTATION\":10}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/ROTATION: element 0 is (0, 0, 0, 0), not a rotation" },
    { "{\"TRANSLATION\":99}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/TRANSLATION: accessor 99 does not exist (20 accessors)" },
    { "{\"TRANSLATION\":-1}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/TRANSLATION: -1 is negative, not an index" },
    { "{\"TRANSLATION\":\"2\"}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes/TRANSLATION: not an integer" },
    { "{\"_ID\":12}", MESH, "", "", SR_BAD_FORMAT, "i.gltf: /accessors/12/count: 0 is outside 1.." },
    { "{}", MESH, "", "", SR_BAD_FORMAT,
      EXT "/attributes: missing or empty (the extension needs one attribute at least)" },
    { "[2]", MESH, "", "", SR_BAD_FORMAT, EXT "/attributes: not an object" },
    { FLOAT_ATTRS, "", "", "", SR_BAD_FORMAT,
      EXT ": on a node without a mesh (it instances the node's mesh)" },
    { "{\"_ID\":17}", MESH, "", "", SR_TOO_LARGE,
      EXT "/attributes/_ID: accessor 17 gives 2000000 instances, more than the 1048576 draws the "
          "scene has room for (of 1048576)" },
};

SR_TEST(malformed_instancing_gives_one_message_with_the_json_pointer)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    for (size_t i = 0; i < sizeof bad_cases / sizeof *bad_cases; i++) {
        const bad_instancing *b = &bad_cases[i];
        char *json = instanced_model(b->attrs, b->node, b->used, "", b->root);
        REQUIRE(json);
        sr_scene *s = (sr_scene *)json;
        sr_io_error e = { { 0 } };
        sr_result r = parse(json, NULL, &s, &e);
        if (r != b->result || s != NULL ||
            strncmp(e.message, b->message, strlen(b->message)) != 0 || strchr(e.message, '\n')) {
            FAILF("case %zu: %s (%s), want %s", i, sr_result_name(r), e.message, b->message);
        }
        free(json);
    }
    /* Not an object at all. */
    char *json = text_replaced(instanced_model(FLOAT_ATTRS, MESH, "", "", ""),
                          "{\"attributes\":" FLOAT_ATTRS "}", "7");
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    CHECK_EQ(parse(json, NULL, &s, &e), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, EXT ": not an object");
    free(json);
}

SR_TEST(instances_count_against_the_draw_limits)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    /* Two primitives in 600000 instances: 1.2 million draws, refused
     * before any is made, by the extension's pointer. */
    char *json = instanced_model("{\"_ID\":16}", MESH, "", "", "");
    REQUIRE(json);
    char prim[200];
    snprintf(prim, sizeof prim, "{\"attributes\":{\"POSITION\":%d},\"indices\":%d,\"material\":0}",
             A_POS, A_IDX);
    char *at = strstr(json, prim);
    REQUIRE(at);
    size_t cap = strlen(json) + strlen(prim) + 2;
    char *two = malloc(cap);
    REQUIRE(two);
    snprintf(two, cap, "%.*s%s,%s", (int)(at - json), json, prim, at);
    sr_scene *s = (sr_scene *)json;
    sr_io_error e;
    CHECK_EQ(parse(two, NULL, &s, &e), SR_TOO_LARGE);
    CHECK(s == NULL);
    CHECK_STR_CONTAINS(e.message, EXT ": 599999 more instances of 2 primitives (16 vertices, 24 "
                                  "triangles): more than 1048576 primitives to draw");
    /* One primitive 600000 times fits. */
    REQUIRE(parse(json, NULL, &s, &e) == SR_OK);
    CHECK_EQ(s->primitive_count, 600000);
    CHECK_EQ(s->instanced_draws, 600000);
    CHECK(s->primitives[599999].positions == s->primitives[0].positions);
    sr_destroy_scene(sr_test_ctx(), s);
    free(two);
    free(json);
}

/* ---- softrast render ------------------------------------------------------ */

SR_TEST(render_draws_every_instance)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    check_model_render("instancing", "cubes.gltf",
                       instanced_model(QUANT_ATTRS, MESH, QUANT_USED, "", ""), "240x180", NULL,
                       "gltf_instanced_cubes");
}
