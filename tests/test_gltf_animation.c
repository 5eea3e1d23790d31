/* test_gltf_animation.c - glTF animations: the reader lists a file's
 * animations, and with sr_load_desc's SR_POSE_ANIMATION places each
 * animated node by its LINEAR (slerp for rotations), STEP or CUBICSPLINE
 * sampler at the time asked, clamped outside the keys, before the world
 * matrices are made; malformed animations are refused with the JSON
 * pointer of the member at fault. */
#include "sr_test.h"

#include "batch_cli.h"
#include "gltf_write.h"
#include "image_compare.h"
#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Every test here reads glTF. */
SR_TEST_NEEDS(sr_io_have_gltf, "softrast was built without jansson (glTF)")

/* A document under construction: one buffer of every accessor's bytes,
 * a bufferView and an accessor each. */
typedef struct doc {
    uint8_t bin[8192];
    size_t size;
    char views[4096], accessors[4096];
    int count;
    char more_meshes[256];     /* ",{...}": meshes 2 and on */
    bool morph;                /* mesh 1 has two morph targets */
    const char *bin_uri;       /* the buffer in this file beside the JSON, or NULL: inline */
} doc;

static int add_accessor(doc *d, const void *bytes, size_t n, size_t esize, const char *type,
                        size_t count, int ctype, bool normalized)
{
    le_copy(d->bin + d->size, bytes, n, esize);
    size_t len = n * esize;
    snprintf(d->views + strlen(d->views), sizeof d->views - strlen(d->views),
             "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", d->count ? "," : "",
             d->size, len);
    snprintf(d->accessors + strlen(d->accessors), sizeof d->accessors - strlen(d->accessors),
             "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"%s}",
             d->count ? "," : "", d->count, ctype, count, type,
             normalized ? ",\"normalized\":true" : "");
    d->size += (len + 3) & ~(size_t)3;
    return d->count++;
}

static int add_floats(doc *d, const float *v, size_t n, const char *type)
{
    size_t per = strcmp(type, "SCALAR") == 0 ? 1 : strcmp(type, "VEC3") == 0 ? 3 : 4;
    return add_accessor(d, v, n, 4, type, n / per, 5126, false);
}

/* A document with a triangle (accessor 0) as mesh 0 and mesh 1 (with two
 * morph targets when d->morph is set); then the caller's accessors. */
static void doc_start(doc *d)
{
    memset(d, 0, sizeof *d);
    static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    add_floats(d, tri, 9, "VEC3");
}

/* The document's JSON with `nodes` and `animations`, every node listed
 * in `roots` a root of scene 0.  Malloc'd. */
static char *doc_json(const doc *d, const char *nodes, const char *roots, const char *anims)
{
    /* The buffer's URI: its file's name, or its bytes in base64. */
    size_t uri_cap = 4 * (d->size / 3 + 1) + 64 + (d->bin_uri ? strlen(d->bin_uri) : 0);
    char *b64 = malloc(uri_cap);
    size_t cap = uri_cap + strlen(d->views) + strlen(d->accessors) +
                 strlen(nodes) + strlen(anims) + 2000;
    char *json = malloc(cap);
    if (!b64 || !json) {
        free(b64);
        free(json);
        return NULL;
    }
    if (d->bin_uri) {
        snprintf(b64, uri_cap, "%s", d->bin_uri);
    } else {
        memcpy(b64, "data:application/octet-stream;base64,", 37);
        gltf_base64(d->bin, d->size, b64 + 37);
    }
    snprintf(json, cap,
             "{\"asset\":{\"version\":\"2.0\"},"
             "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"%s\"}],"
             "\"bufferViews\":[%s],\"accessors\":[%s],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]},"
             "{\"primitives\":[{\"attributes\":{\"POSITION\":0}%s}]}%s],"
             "\"nodes\":%s,\"scenes\":[{\"nodes\":%s}]%s%s}",
             d->size, b64, d->views, d->accessors,
             d->morph ? ",\"targets\":[{\"POSITION\":0},{\"POSITION\":0}]" : "",
             d->more_meshes, nodes, roots,
             anims[0] ? "," : "", anims);
    free(b64);
    return json;
}

static sr_result parse_posed(const doc *d, const char *nodes, const char *roots,
                             const char *anims, const sr_load_desc *desc, sr_scene **s,
                             sr_io_error *e)
{
    char *json = doc_json(d, nodes, roots, anims);
    if (!json) {
        return SR_OUT_OF_MEMORY;
    }
    sr_result r = sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json),
                                desc, s, e);
    free(json);
    return r;
}

/* Animation 0 of the document at time t. */
static sr_scene *at_time(const doc *d, const char *nodes, const char *roots, const char *anims,
                         float t)
{
    sr_scene *s = NULL;
    sr_io_error e;
    sr_load_desc desc = { .pose = SR_POSE_ANIMATION, .animation = 0, .animation_time = t };
    if (parse_posed(d, nodes, roots, anims, &desc, &s, &e) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s", e.message);
    }
    return s;
}

/* The world matrix of the first primitive node `node` draws. */
static const float *world_of(const sr_scene *s, int node)
{
    for (size_t i = 0; s && i < s->primitive_count; i++) {
        if (s->primitives[i].node == node) {
            return s->primitives[i].world;
        }
    }
    return NULL;
}

#define CHECK_WORLD_T(s, node, x, y, z)                                                  \
    do {                                                                                  \
        const float *w_ = world_of(s, node);                                              \
        REQUIRE(w_);                                                                      \
        CHECK_NEAR(w_[12], x, 1e-5);                                                      \
        CHECK_NEAR(w_[13], y, 1e-5);                                                      \
        CHECK_NEAR(w_[14], z, 1e-5);                                                      \
    } while (0)

/* Times 0 and 2, translation (0,0,0) -> (4,2,0). */
static const char *linear_translation(doc *d)
{
    static char anim[512];
    static const float times[2] = { 0, 2 }, moves[6] = { 0, 0, 0, 4, 2, 0 };
    int in = add_floats(d, times, 2, "SCALAR"), out = add_floats(d, moves, 6, "VEC3");
    snprintf(anim, sizeof anim,
             "\"animations\":[{\"name\":\"slide\",\"samplers\":[{\"input\":%d,\"output\":%d}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}]}]",
             in, out);
    return anim;
}

SR_TEST(linear_translation_is_interpolated_and_clamped_outside_the_keys)
{
    doc d;
    doc_start(&d);
    const char *anim = linear_translation(&d);
    const char *nodes = "[{\"mesh\":0,\"translation\":[9,9,9]}]";
    struct { float t, x, y; } cases[] = {
        { 0.5f, 1, 0.5f }, { 1, 2, 1 }, { 2, 4, 2 }, { -3, 0, 0 }, { 7, 4, 2 }, { 0, 0, 0 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sr_scene *s = at_time(&d, nodes, "[0]", anim, cases[i].t);
        REQUIRE(s);
        CHECK_EQ(s->animation, 0);
        CHECK_NEAR(s->animation_time, cases[i].t, 0);
        CHECK_WORLD_T(s, 0, cases[i].x, cases[i].y, 0);
        sr_destroy_scene(sr_test_ctx(), s);
    }
}

SR_TEST(the_rest_pose_is_the_default_and_the_animations_are_listed)
{
    doc d;
    doc_start(&d);
    d.morph = true;
    const char *anim = linear_translation(&d);
    static const float times[3] = { 0.5f, 1, 3.25f }, scales[9] = { 1, 1, 1, 2, 2, 2, 3, 3, 3 };
    int in = add_floats(&d, times, 3, "SCALAR"), out = add_floats(&d, scales, 9, "VEC3");
    char anims[1200];
    snprintf(anims, sizeof anims,
             "%.*s,{\"samplers\":[{\"input\":%d,\"output\":%d,\"interpolation\":\"STEP\"}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"scale\"}},"
             "{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"scale\"}}]}]",
             (int)strlen(anim) - 1, anim, in, out);
    char *json = doc_json(&d, "[{\"mesh\":0,\"translation\":[9,8,7]},{}]", "[0,1]", anims);
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    sr_test_warnings w = { 0 };
    sr_load_desc zero = { .warn = sr_test_collect_warning, .user = &w };
    sr_result r = sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json),
                                &zero, &s, &e);
    free(json);
    REQUIRE(r == SR_OK);
    /* Animations are read (as morph targets are): nothing to warn of. */
    CHECK_EQ(w.count, 0);
    CHECK_EQ(s->animation, -1);
    CHECK_WORLD_T(s, 0, 9, 8, 7);
    REQUIRE(s->animation_count == 2);
    CHECK(strcmp(s->animations[0].name, "slide") == 0);
    CHECK_EQ(s->animations[0].channel_count, 1);
    CHECK_NEAR(s->animations[0].duration, 2, 0);
    CHECK(strcmp(s->animations[1].name, "") == 0);
    CHECK_EQ(s->animations[1].channel_count, 2);
    CHECK_NEAR(s->animations[1].duration, 3.25, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* Rotation by `q1` (x, y, z, w) keys: identity at 0, q1 at 2. */
static char *rotation_anim(doc *d, const float q1[4], bool shorts)
{
    static char anim[512];
    static const float times[2] = { 0, 2 };
    float q[8] = { 0, 0, 0, 1, q1[0], q1[1], q1[2], q1[3] };
    int in = add_floats(d, times, 2, "SCALAR"), out;
    if (shorts) {
        int16_t v[8];
        for (int k = 0; k < 8; k++) {
            v[k] = (int16_t)lrintf(q[k] * 32767.0f);
        }
        out = add_accessor(d, v, 8, 2, "VEC4", 2, 5122, true);
    } else {
        out = add_floats(d, q, 8, "VEC4");
    }
    snprintf(anim, sizeof anim,
             "\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"rotation\"}}]}]",
             in, out);
    return anim;
}

SR_TEST(linear_rotation_is_a_slerp_the_short_way_round)
{
    /* Halfway from the identity to 90 degrees about +Z is 45 degrees:
     * the x axis goes to (cos 45, sin 45, 0).  The same end given as
     * -q (the same rotation) must not turn the long way (135 degrees);
     * nor must normalized shorts.  120 degrees: at a quarter of the
     * time, 30 degrees (a nlerp would give 33.7). */
    const float h = (float)sqrt(0.5);
    const float ends[][4] = { { 0, 0, h, h }, { 0, 0, -h, -h } };
    for (int k = 0; k < 3; k++) {
        doc d;
        doc_start(&d);
        const char *anim = rotation_anim(&d, ends[k == 1], k == 2);
        sr_scene *s = at_time(&d, "[{\"mesh\":0}]", "[0]", anim, 1.0f);
        REQUIRE(s);
        const float *w = world_of(s, 0);
        REQUIRE(w);
        CHECK_NEAR(w[0], h, k == 2 ? 1e-4 : 1e-6);
        CHECK_NEAR(w[1], h, k == 2 ? 1e-4 : 1e-6);
        CHECK_NEAR(w[2], 0, 1e-6);
        CHECK_NEAR(w[4], -h, k == 2 ? 1e-4 : 1e-6);
        sr_destroy_scene(sr_test_ctx(), s);
    }
    doc d;
    doc_start(&d);
    const float third[4] = { 0, 0, (float)sin(M_PI / 3), (float)cos(M_PI / 3) };
    const char *anim = rotation_anim(&d, third, false);
    sr_scene *s = at_time(&d, "[{\"mesh\":0}]", "[0]", anim, 0.5f);
    REQUIRE(s);
    const float *w = world_of(s, 0);
    REQUIRE(w);
    CHECK_NEAR(w[0], cos(M_PI / 6), 1e-6);
    CHECK_NEAR(w[1], sin(M_PI / 6), 1e-6);
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(step_holds_each_key_until_the_next)
{
    doc d;
    doc_start(&d);
    static const float times[3] = { 0, 1, 2 }, scales[9] = { 1, 1, 1, 2, 2, 2, 3, 3, 3 };
    int in = add_floats(&d, times, 3, "SCALAR"), out = add_floats(&d, scales, 9, "VEC3");
    char anim[512];
    snprintf(anim, sizeof anim,
             "\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d,"
             "\"interpolation\":\"STEP\"}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"scale\"}}]}]",
             in, out);
    struct { float t, scale; } cases[] = {
        { -1, 1 }, { 0.99f, 1 }, { 1, 2 }, { 1.5f, 2 }, { 2, 3 }, { 50, 3 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sr_scene *s = at_time(&d, "[{\"mesh\":0,\"scale\":[5,5,5]}]", "[0]", anim, cases[i].t);
        REQUIRE(s);
        const float *w = world_of(s, 0);
        REQUIRE(w);
        CHECK_NEAR(w[0], cases[i].scale, 0);
        CHECK_NEAR(w[5], cases[i].scale, 0);
        CHECK_NEAR(w[10], cases[i].scale, 0);
        sr_destroy_scene(sr_test_ctx(), s);
    }
}

SR_TEST(cubicspline_follows_the_hermite_curve_of_its_tangents)
{
    /* Keys at 0 and 2 (td = 2): value 0 with out-tangent 1, value 2 with
     * in-tangent 3, along x.  p(u) = h00 0 + td h10 1 + h01 2 + td h11 3:
     * u = 1/2: 2 (1/8) + (1/2) 2 + 2 (-1/8) 3 = 0.5;
     * u = 1/4: 2 (9/64) + (5/32) 2 + 2 (-3/64) 3 = 0.3125.
     * The tangents outside the keys (in of key 0, out of key 1) are not
     * used, nor are they at the ends. */
    doc d;
    doc_start(&d);
    static const float times[2] = { 0, 2 };
    static const float keys[18] = { 99, 0, 0,  0, 0, 0,  1, 0, 0,
                                    3,  0, 0,  2, 0, 0,  -99, 0, 0 };
    int in = add_floats(&d, times, 2, "SCALAR"), out = add_floats(&d, keys, 18, "VEC3");
    char anim[512];
    snprintf(anim, sizeof anim,
             "\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d,"
             "\"interpolation\":\"CUBICSPLINE\"}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}]}]",
             in, out);
    struct { float t, x; } cases[] = {
        { 1, 0.5f }, { 0.5f, 0.3125f }, { 0, 0 }, { 2, 2 }, { -1, 0 }, { 3, 2 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sr_scene *s = at_time(&d, "[{\"mesh\":0}]", "[0]", anim, cases[i].t);
        REQUIRE(s);
        CHECK_WORLD_T(s, 0, cases[i].x, 0, 0);
        sr_destroy_scene(sr_test_ctx(), s);
    }
}

SR_TEST(an_animated_parent_carries_its_children)
{
    /* Node 0 slides (linear_translation) and turns its child node 1 by a
     * fixed 90 degrees about +Z; node 1 sits 1 along its parent's x. */
    doc d;
    doc_start(&d);
    const char *anim = linear_translation(&d);
    const double h = sqrt(0.5);
    char nodes[256];
    snprintf(nodes, sizeof nodes,
             "[{\"rotation\":[0,0,%.17g,%.17g],\"children\":[1]},"
             "{\"mesh\":0,\"translation\":[1,0,0]}]", h, h);
    sr_scene *s = at_time(&d, nodes, "[0]", anim, 1.0f);
    REQUIRE(s);
    CHECK_WORLD_T(s, 1, 2, 2, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* The message of a refused document, whose result must be `want`. */
static void check_refusal(const doc *d, const char *nodes, const char *anims,
                          const sr_load_desc *desc, sr_result want, const char *message)
{
    sr_scene *s = (sr_scene *)1;
    sr_io_error e = { { 0 } };
    sr_result r = parse_posed(d, nodes, "[0]", anims, desc, &s, &e);
    CHECK_EQ(r, want);
    CHECK(s == NULL);
    if (strcmp(e.message, message) != 0) {
        sr_test_fail(__FILE__, __LINE__, "got \"%s\", want \"%s\"", e.message, message);
    }
}

SR_TEST(malformed_animations_are_refused_with_their_json_pointer)
{
    doc d;
    doc_start(&d);
    d.morph = true;
    static const float times[2] = { 0, 1 }, back[2] = { 1, 0.5f }, v3[6] = { 0 };
    static const float q[8] = { 0, 0, 0, 1, 0, 0, 0, 1 };
    static const int16_t raw[6] = { 0 };
    int in = add_floats(&d, times, 2, "SCALAR"), out = add_floats(&d, v3, 6, "VEC3");
    int bad_in = add_floats(&d, back, 2, "SCALAR"), quat = add_floats(&d, q, 8, "VEC4");
    int shorts = add_accessor(&d, raw, 6, 2, "VEC3", 2, 5122, true);
    int v3x3 = add_floats(&d, v3, 6, "SCALAR");   /* 6 scalars: 3 weights x 2 keys */
    const char *matrix = "[{\"mesh\":0,\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}]";
    /* One sampler (input, output, interpolation) and the channels'
     * targets, on `nodes` (NULL: a node drawing mesh 0). */
    const struct {
        int input, output;
        const char *interp, *targets, *nodes, *message;
    } bad[] = {
        { in, out, NULL, "{\"node\":0,\"path\":\"translation\"}", matrix,
          "/animations/0/channels/0/target/node: node 0 has a matrix, which glTF does not "
          "animate (its animated nodes have translation, rotation and scale)" },
        { in, out, NULL, "{\"node\":0,\"path\":\"rotation\"}", NULL,
          "/animations/0/channels/0/sampler: its output has 3 components an element; rotation "
          "takes VEC4" },
        { in, out, NULL, "{\"node\":0,\"path\":\"weights\"}", NULL,
          "/animations/0/channels/0/sampler: its output has 3 components an element; weights "
          "takes SCALAR" },
        { in, out, NULL, "{\"node\":3,\"path\":\"scale\"}", NULL,
          "/animations/0/channels/0/target/node: 3 is not an index below 1" },
        { in, out, NULL, "{\"node\":0,\"path\":17}", NULL,
          "/animations/0/channels/0/target/path: expected translation, rotation, scale, "
          "weights or pointer" },
        { in, out, NULL, "{\"node\":0,\"path\":\"scale\"}},{\"sampler\":0,\"target\":"
                         "{\"node\":0,\"path\":\"scale\"}", NULL,
          "/animations/0/channels/1/target: node 0's scale is animated by another channel of "
          "this animation" },
        { bad_in, out, NULL, "{\"node\":0,\"path\":\"scale\"}", NULL,
          "/animations/0/samplers/0/input: key 1 is 0.5 s, not after the key before: key times "
          "must be at least 0 and strictly increase" },
        { out, out, NULL, "{\"node\":0,\"path\":\"scale\"}", NULL,
          "/animations/0/samplers/0/input: accessor 2 has 3 components per element, not what "
          "this attribute takes" },
        { in, out, "SMOOTH", "{\"node\":0,\"path\":\"scale\"}", NULL,
          "/animations/0/samplers/0/interpolation: expected LINEAR, STEP or CUBICSPLINE" },
        { in, out, "CUBICSPLINE", "{\"node\":0,\"path\":\"scale\"}", NULL,
          "/animations/0/channels/0/sampler: its output has 2 elements; 2 keys of scale "
          "(CUBICSPLINE: with tangents) need 6" },
        { in, quat, NULL, "{\"node\":0,\"path\":\"translation\"}", NULL,
          "/animations/0/channels/0/sampler: its output has 4 components an element; "
          "translation takes VEC3" },
        { in, shorts, NULL, "{\"node\":0,\"path\":\"translation\"}", NULL,
          "/animations/0/channels/0/sampler: its output is not of floats, which translation "
          "takes" },
        { in, v3x3, NULL, "{\"node\":0,\"path\":\"weights\"}", NULL,
          "/animations/0/channels/0/target/node: node 0 has no mesh with morph targets to "
          "weigh" },
        { in, v3x3, NULL, "{\"node\":0,\"path\":\"weights\"}", "[{\"mesh\":1}]",
          "/animations/0/channels/0/sampler: its output has 6 elements; 2 keys of weights need "
          "4" },
    };
    char a[600], message[400];
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char interp[64] = "";
        if (bad[i].interp) {
            snprintf(interp, sizeof interp, ",\"interpolation\":\"%s\"", bad[i].interp);
        }
        snprintf(a, sizeof a,
                 "\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d%s}],"
                 "\"channels\":[{\"sampler\":0,\"target\":%s}]}]",
                 bad[i].input, bad[i].output, interp, bad[i].targets);
        snprintf(message, sizeof message, "t.gltf: %s", bad[i].message);
        check_refusal(&d, bad[i].nodes ? bad[i].nodes : "[{\"mesh\":0}]", a, NULL,
                      SR_BAD_FORMAT, message);
    }
    const char *node = "[{\"mesh\":0}]";
    check_refusal(&d, node, "\"animations\":[{\"samplers\":[],\"channels\":[]}]", NULL,
                  SR_BAD_FORMAT, "t.gltf: /animations/0/channels: missing or empty");

    /* The caller's pose: an animation the file has, at a finite time. */
    snprintf(a, sizeof a,
             "\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"scale\"}}]}]",
             in, out);
    sr_load_desc posed = { .pose = SR_POSE_ANIMATION, .animation = 1 };
    check_refusal(&d, node, a, &posed, SR_INVALID_ARG,
                  "t.gltf: sr_load_desc.animation 1 is not an animation of the file (it has 1)");
    posed.animation = -1;
    check_refusal(&d, node, a, &posed, SR_INVALID_ARG,
                  "t.gltf: sr_load_desc.animation -1 is not an animation of the file (it has 1)");
    posed.animation = 0;
    posed.animation_time = NAN;
    check_refusal(&d, node, a, &posed, SR_INVALID_ARG,
                  "t.gltf: sr_load_desc.animation_time is not finite");
    posed.animation_time = INFINITY;
    check_refusal(&d, node, a, &posed, SR_INVALID_ARG,
                  "t.gltf: sr_load_desc.animation_time is not finite");
    sr_load_desc bad_pose = { .pose = (sr_load_pose)7 };
    check_refusal(&d, node, a, &bad_pose, SR_INVALID_ARG,
                  "t.gltf: sr_load_desc.pose 7 is not an sr_load_pose");
    check_refusal(&d, node, "", &(sr_load_desc){ .pose = SR_POSE_ANIMATION }, SR_INVALID_ARG,
                  "t.gltf: sr_load_desc.animation 0 is not an animation of the file (it has 0)");
}

/* A weights channel sets the weights node 0 draws mesh 1's two morph
 * targets with, in place of the mesh's (0, 0): each target moves a
 * vertex by its own position, so vertex 1, (1, 0, 0), goes to
 * (1 + w0 + w1, 0, 0).  LINEAR from (0, 0) at 0 s to (1, 0.5) at 2 s:
 * (0.5, 0.25) at 1 s, 1.75; clamped after the last key, 2.5. */
SR_TEST(a_weights_channel_morphs_the_mesh)
{
    doc d;
    doc_start(&d);
    d.morph = true;
    static const float times[2] = { 0, 2 }, weights[4] = { 0, 0, 1, 0.5f };
    int in = add_floats(&d, times, 2, "SCALAR");
    int out = add_accessor(&d, weights, 4, 4, "SCALAR", 4, 5126, false);
    char anim[400];
    snprintf(anim, sizeof anim,
             "\"animations\":[{\"samplers\":[{\"input\":%d,\"output\":%d}],"
             "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"weights\"}}]}]",
             in, out);
    const char *nodes = "[{\"mesh\":1}]";
    struct { float t, x; } cases[] = { { 1, 1.75f }, { 0, 1 }, { 5, 2.5f }, { 0.5f, 1.375f } };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sr_scene *s = at_time(&d, nodes, "[0]", anim, cases[i].t);
        REQUIRE(s && s->primitive_count == 1);
        CHECK_NEAR(s->primitives[0].positions[3], cases[i].x, 1e-6);
        CHECK_NEAR(s->primitives[0].positions[7], cases[i].x, 1e-6);   /* vertex 2's y */
        sr_destroy_scene(sr_test_ctx(), s);
    }
    /* The rest pose: the mesh's own weights, zeros. */
    sr_scene *s = NULL;
    sr_io_error e;
    REQUIRE(parse_posed(&d, nodes, "[0]", anim, NULL, &s, &e) == SR_OK);
    CHECK_NEAR(s->primitives[0].positions[3], 1, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* A path another extension defines, or a channel without a node, is left
 * to the extension with a warning. */
SR_TEST(channels_of_extensions_are_skipped_with_a_warning)
{
    doc d;
    doc_start(&d);
    const char *anim = linear_translation(&d);
    char anims[800];
    snprintf(anims, sizeof anims, "%.*s", (int)strlen(anim) - 3, anim);
    strcat(anims, ",{\"sampler\":0,\"target\":{\"path\":\"EXT_other\"}}]}]");
    char *json = doc_json(&d, "[{\"mesh\":0}]", "[0]", anims);
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    sr_test_warnings w = { 0 };
    sr_load_desc desc = { .warn = sr_test_collect_warning, .user = &w,
                          .pose = SR_POSE_ANIMATION, .animation_time = 1 };
    sr_result r = sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json),
                                &desc, &s, &e);
    free(json);
    REQUIRE(r == SR_OK);
    CHECK_STR_CONTAINS(w.text, "t.gltf: warning: /animations/0/channels/1/target: a path an "
                               "extension defines, not animated");
    CHECK_EQ(s->animations[0].channel_count, 2);
    CHECK_WORLD_T(s, 0, 2, 1, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(a_model_without_animations_cannot_be_posed_by_one)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/anim_tri.obj", sr_test_out_dir());
    const char obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    REQUIRE(sr_test_write_file(path, obj, strlen(obj)));
    sr_scene *s = NULL;
    sr_io_error e;
    sr_load_desc desc = { .pose = SR_POSE_ANIMATION };
    CHECK_EQ(sr_load_scene(sr_test_ctx(), path, &desc, &s, &e), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(e.message, "sr_load_desc.pose asks for an animation, which only glTF "
                                  "files have");
    CHECK(s == NULL);
    REQUIRE(sr_load_scene(sr_test_ctx(), path, NULL, &s, &e) == SR_OK);
    CHECK_EQ(s->animation, -1);
    CHECK_EQ(s->animation_count, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* ---- softrast render --animation ---------------------------------------- */

/* A unit cube's 36 corners, counter-clockwise seen from outside. */
static void cube_corners(float *out)
{
    static const int quads[6][4][3] = {
        { { 1, 0, 0 }, { 1, 1, 0 }, { 1, 1, 1 }, { 1, 0, 1 } },
        { { 0, 0, 0 }, { 0, 0, 1 }, { 0, 1, 1 }, { 0, 1, 0 } },
        { { 0, 1, 0 }, { 0, 1, 1 }, { 1, 1, 1 }, { 1, 1, 0 } },
        { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 0, 1 }, { 0, 0, 1 } },
        { { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } },
        { { 0, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 1, 0, 0 } },
    };
    static const int corner[6] = { 0, 1, 2, 0, 2, 3 };
    for (int f = 0; f < 6; f++) {
        for (int k = 0; k < 6; k++) {
            for (int c = 0; c < 3; c++) {
                *out++ = (float)quads[f][corner[k]][c] - 0.5f;
            }
        }
    }
}

/* The hub model: node 0 turns about +y (LINEAR, 0 to 90 degrees over 2 s)
 * and carries node 1, a cube stretched by STEP scales (y 1, then 2 from
 * 1 s), and node 2, a half-size cube lifted along a CUBICSPLINE path from
 * (1.5, 0, 0) (out-tangent (0, 2, 0)) to (1.5, 1, 0) (in-tangent
 * (0, -2, 0)) over 2 s.  With `posed_at_1_5`, no animation but the
 * nodes' own transforms set to the values hand-computed at 1.5 s:
 * 67.5 degrees; scale (1, 2, 1); u = 0.75 on the spline, h00 = 0.15625,
 * h10 = 0.046875, h01 = 0.84375, h11 = -0.140625, y = 2 (0.046875) 2 +
 * 0.84375 + 2 (-0.140625) (-2) = 1.59375.  With `bin_path`, the buffer
 * is written there and named by its file name (it must be beside the
 * JSON).  Malloc'd JSON. */
static char *hub_json(bool posed_at_1_5, const char *bin_path)
{
    doc d;
    doc_start(&d);
    float cube[108];
    cube_corners(cube);
    int pos = add_floats(&d, cube, 108, "VEC3");
    snprintf(d.more_meshes, sizeof d.more_meshes,
             ",{\"primitives\":[{\"attributes\":{\"POSITION\":%d},\"material\":0}]},"
             "{\"primitives\":[{\"attributes\":{\"POSITION\":%d},\"material\":1}]}", pos, pos);
    const double h = sqrt(0.5), a = 67.5 * M_PI / 360;
    static const float t01[2] = { 0, 1 }, t02[2] = { 0, 2 };
    static const float scales[6] = { 1, 1, 1, 1, 2, 1 };
    static const float lift[18] = { 0, 0, 0, 1.5f, 0, 0, 0, 2, 0,
                                    0, -2, 0, 1.5f, 1, 0, 0, 0, 0 };
    float turn[8] = { 0, 0, 0, 1, 0, (float)h, 0, (float)h };
    int in1 = add_floats(&d, t01, 2, "SCALAR"), in2 = add_floats(&d, t02, 2, "SCALAR");
    int turn_out = add_floats(&d, turn, 8, "VEC4"), scale_out = add_floats(&d, scales, 6, "VEC3");
    int lift_out = add_floats(&d, lift, 18, "VEC3");
    char nodes[512], anims[1024];
    if (posed_at_1_5) {
        snprintf(nodes, sizeof nodes,
                 "[{\"rotation\":[0,%.17g,0,%.17g],\"children\":[1,2]},"
                 "{\"mesh\":2,\"scale\":[1,2,1]},"
                 "{\"mesh\":3,\"translation\":[1.5,1.59375,0],\"scale\":[0.5,0.5,0.5]}]",
                 sin(a), cos(a));
        anims[0] = 0;
    } else {
        snprintf(nodes, sizeof nodes,
                 "[{\"children\":[1,2]},{\"mesh\":2},"
                 "{\"mesh\":3,\"translation\":[1.5,0,0],\"scale\":[0.5,0.5,0.5]}]");
        snprintf(anims, sizeof anims,
                 "\"animations\":[{\"name\":\"hub\",\"samplers\":["
                 "{\"input\":%d,\"output\":%d},"
                 "{\"input\":%d,\"output\":%d,\"interpolation\":\"STEP\"},"
                 "{\"input\":%d,\"output\":%d,\"interpolation\":\"CUBICSPLINE\"}],"
                 "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"rotation\"}},"
                 "{\"sampler\":1,\"target\":{\"node\":1,\"path\":\"scale\"}},"
                 "{\"sampler\":2,\"target\":{\"node\":2,\"path\":\"translation\"}}]}]",
                 in2, turn_out, in1, scale_out, in2, lift_out);
    }
    if (bin_path) {
        d.bin_uri = strrchr(bin_path, '/') ? strrchr(bin_path, '/') + 1 : bin_path;
        if (!sr_test_write_file(bin_path, d.bin, d.size)) {
            return NULL;
        }
    }
    char *json = doc_json(&d, nodes, "[0]", anims);
    if (!json) {
        return NULL;
    }
    /* Two materials, spliced in before the last brace. */
    size_t n = strlen(json);
    char *with = malloc(n + 300);
    if (with) {
        snprintf(with, n + 300, "%.*s,\"materials\":[{\"pbrMetallicRoughness\":"
                 "{\"baseColorFactor\":[0.2,0.4,0.9,1]}},{\"pbrMetallicRoughness\":"
                 "{\"baseColorFactor\":[0.9,0.7,0.2,1]}}]}", (int)n - 1, json);
    }
    free(json);
    return with;
}

static bool write_hub(const char *path, bool posed)
{
    char *json = hub_json(posed, NULL);
    bool ok = json && sr_test_write_file(path, json, strlen(json));
    free(json);
    return ok;
}

/* An RGBA8 PNG the tool wrote, or NULL after a failure. */
static uint8_t *read_png_file(const char *path, int *w, int *h)
{
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(path, NULL, w, h, &px, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s", err.message);
        return NULL;
    }
    return px;
}

/* The animation sampled at 1.5 s draws what the same nodes placed by
 * hand at 1.5 s draw, and what tests/ref/gltf_animation.png keeps (2
 * codes, 0.5% of the pixels: a last bit of the sampled rotation, or
 * another CPU's libm, can move an edge pixel); the rest pose draws
 * something else. */
SR_TEST(render_animation_at_a_time_draws_the_hand_posed_scene)
{
    NEED_CLI();
    char dir[1024], anim[1100], posed[1100], a_png[1100], p_png[1100], rest_png[1100];
    fresh_dir("gltf_anim", dir, sizeof dir);
    snprintf(anim, sizeof anim, "%s/hub.gltf", dir);
    snprintf(posed, sizeof posed, "%s/posed.gltf", dir);
    snprintf(a_png, sizeof a_png, "%s/anim.png", dir);
    snprintf(p_png, sizeof p_png, "%s/posed.png", dir);
    snprintf(rest_png, sizeof rest_png, "%s/rest.png", dir);
    REQUIRE(write_hub(anim, false) && write_hub(posed, true));
    run_result r;
    REQUIRE(run(ARGS("render", anim, "--animation", "hub", "--time", "1.5", "--size", "128x96",
                     "--shading", "flat", "--camera", "eye=3,4,6,target=0.4,0.6,0", "-o", a_png),
                &r));
    REQUIRE(r.status == 0);
    REQUIRE(run(ARGS("render", posed, "--size", "128x96", "--shading", "flat", "--camera",
                     "eye=3,4,6,target=0.4,0.6,0", "-o", p_png), &r));
    REQUIRE(r.status == 0);
    REQUIRE(run(ARGS("render", anim, "--size", "128x96", "--shading", "flat", "--camera",
                     "eye=3,4,6,target=0.4,0.6,0", "-o", rest_png), &r));
    REQUIRE(r.status == 0);
    int w, h, w2, h2, w3, h3;
    uint8_t *a = read_png_file(a_png, &w, &h), *p = read_png_file(p_png, &w2, &h2);
    uint8_t *rest = read_png_file(rest_png, &w3, &h3);
    REQUIRE(a && p && rest && w == w2 && h == h2 && w == w3 && h == h3);
    sr_test_check_posed("gltf_animation", a, p, rest, w, h, 20);
    free(a);
    free(p);
    free(rest);
}

SR_TEST(render_animation_options_are_checked_in_one_line)
{
    NEED_CLI();
    char dir[1024], anim[1100], obj[1100], png[1100];
    fresh_dir("gltf_anim_opts", dir, sizeof dir);
    snprintf(anim, sizeof anim, "%s/hub.gltf", dir);
    snprintf(obj, sizeof obj, "%s/tri.obj", dir);
    snprintf(png, sizeof png, "%s/out.png", dir);
    REQUIRE(write_hub(anim, false) && write_text(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    const struct {
        const char *const *args;
        const char *needle;
    } bad[] = {
        { ARGS("render", anim, "--time", "1", "-o", png),
          "--time: gives a time into an animation: give --animation N|NAME too" },
        { ARGS("render", anim, "--animation", "0", "--time", "soon", "-o", png),
          "--time: expected a number from -1e+06 to 1e+06 (got 'soon')" },
        { ARGS("render", anim, "--animation", "0", "--time", "inf", "-o", png),
          "--time: expected a number" },
        { ARGS("render", anim, "--animation", "1", "-o", png),
          "--animation 1: " },
        { ARGS("render", anim, "--animation", "walk", "-o", png),
          "has no animation named walk (it has 0 (hub))" },
        { ARGS("render", anim, "--animation", "-1", "-o", png), "has no animation named -1" },
        { ARGS("render", anim, "--animation", "", "-o", png), "--animation: empty value" },
        { ARGS("render", obj, "--animation", "0", "-o", png),
          "--animation: only glTF files (.gltf, .glb) have animations" },
        { ARGS("render", anim, "--fps", "10", "--output-dir", dir),
          "--fps: the frame rate of --animate with --animation: give both" },
        { ARGS("render", anim, "--animate", "a.webp", "--animation", "0", "--views", "4",
               "--output-dir", dir),
          "--views: not with --animation" },
        { ARGS("render", anim, "--animate", "a.webp", "--animation", "0", "--fps", "0",
               "--output-dir", dir),
          "--fps: expected" },
    };
    run_result r;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        REQUIRE(run(bad[i].args, &r));
        if (!(r.status == 2 && count_lines(r.err) == 1 && strstr(r.err, bad[i].needle))) {
            FAILF("case %zu: status %d, stderr \"%s\", want one line with \"%s\"", i, r.status,
                  r.err, bad[i].needle);
        }
    }
    CHECK(!file_exists(png));
}

/* --animation with --time reads the file once, whether the animation is
 * named or numbered: posed from its one reading (sr_scene_pose), not read
 * again in the pose.  The tool's --verbose counts its reads; the buffer
 * in a file of its own counts the reader's reads of the document, as the
 * library reads it once a reading of the document. */
SR_TEST(render_animation_at_a_time_reads_the_file_once)
{
    NEED_CLI();
    char dir[1024], anim[1100], bin[1100], png[1100], want[1200];
    fresh_dir("gltf_anim_once", dir, sizeof dir);
    snprintf(anim, sizeof anim, "%s/hub.gltf", dir);
    snprintf(bin, sizeof bin, "%s/hub.bin", dir);
    snprintf(png, sizeof png, "%s/out.png", dir);
    char *json = hub_json(false, bin);
    REQUIRE(json && sr_test_write_file(anim, json, strlen(json)));
    free(json);
    static const char *const animations[] = { "hub", "0" };
    for (int i = 0; i < 2; i++) {
        run_result r;
        REQUIRE(run(ARGS("render", anim, "--animation", animations[i], "--time", "1.5",
                         "--size", "32x24", "--verbose", "-o", png), &r));
        CHECK_EQ(r.status, 0);
        snprintf(want, sizeof want, "softrast: read %s (model) 1 time\n", anim);
        if (!strstr(r.err, want)) {
            FAILF("--animation %s: stderr \"%s\" lacks \"%s\"", animations[i], r.err, want);
        }
        snprintf(want, sizeof want, "softrast: read %s (glTF resource) 1 time\n", bin);
        if (!strstr(r.err, want)) {
            FAILF("--animation %s: stderr \"%s\" lacks \"%s\"", animations[i], r.err, want);
        }
    }
}

/* --animate with --animation: the animation's frames, 1/fps s apart from
 * 0 to its end (2 s at 5 fps: 11), as one animated WebP. */
SR_TEST(animate_plays_the_animation_at_fps)
{
    NEED_CLI();
    char dir[1024], anim[1100], webp[1100];
    fresh_dir("gltf_anim_play", dir, sizeof dir);
    snprintf(anim, sizeof anim, "%s/hub.gltf", dir);
    snprintf(webp, sizeof webp, "%s/hub.webp", dir);
    REQUIRE(write_hub(anim, false));
    run_result r;
    REQUIRE(run(ARGS("render", anim, "--animate", "{stem}.webp", "--animation", "0", "--fps",
                     "5", "--output-dir", dir, "--size", "40x30", "--shading", "flat"), &r));
    if (r.status == 2 && strstr(r.err, "without libwebp")) {
        SKIP("softrast was built without libwebp");
    }
    REQUIRE(r.status == 0);
    size_t n = 0;
    uint8_t *p = sr_test_read_file(webp, &n);
    REQUIRE(p);
    bool animated = false;
    int frames = count_anmf(p, n, &animated);
    free(p);
    CHECK_EQ(frames, 11);
    CHECK(animated);
}

#ifdef SR_CLI_PATH
/* The standard output of the tool run with args (a shell line, each
 * argument quoted), into out; its exit status. */
static int cli_stdout(const char *const *args, char *out, size_t size)
{
    /* The tool as the tests start it: through the emulator in a cross
     * build. */
    const char *argv[80];
    if (!sr_test_program_argv(SR_CLI_PATH, args, argv, sizeof argv / sizeof argv[0])) {
        return -1;
    }
    char line[4096] = "";
    for (size_t i = 0; argv[i]; i++) {
        size_t at = strlen(line);
        snprintf(line + at, sizeof line - at, "%s'%s'", i ? " " : "", argv[i]);
    }
    FILE *p = popen(line, "r");
    if (!p) {
        return -1;
    }
    size_t n = fread(out, 1, size - 1, p);
    out[n] = 0;
    return pclose(p);
}
#endif

/* softrast info names the animations with their durations and channels,
 * as text and as JSON. */
SR_TEST(info_lists_the_animations_with_their_durations)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], anim[1100], out[8192];
    fresh_dir("gltf_anim_info", dir, sizeof dir);
    snprintf(anim, sizeof anim, "%s/hub.gltf", dir);
    REQUIRE(write_hub(anim, false));
    CHECK_EQ(cli_stdout(ARGS("info", anim), out, sizeof out), 0);
    CHECK_STR_CONTAINS(out, "  animations  1 (--animation)\n    0  2 s, 3 channels, hub\n");
    CHECK_EQ(cli_stdout(ARGS("info", "--json", anim), out, sizeof out), 0);
    CHECK_STR_CONTAINS(out, "\"animations\": [\n  {\"name\": \"hub\", \"channels\": 3, "
                            "\"duration\": 2}\n ]");
#endif
}
