/* test_gltf_pointer.c - glTF animations beyond node transforms:
 * KHR_animation_pointer channels animate materials, cameras, lights,
 * node transforms and KHR_node_visibility's `visible`, the same through
 * sr_load_desc's pose and sr_scene_pose, the rest pose kept; malformed
 * pointers are refused with the channel's JSON pointer, pointers softrast
 * does not animate warned about; quantized rotation outputs decode by the
 * specification's formulas. */
#include "sr_test.h"

#include "batch_cli.h"
#include "gltf_write.h"
#include "image_compare.h"
#include "softrast.h"
#include "uv_sphere.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Every test here reads glTF. */
SR_TEST_NEEDS(sr_io_have_gltf, "softrast was built without jansson (glTF)")

/* The bytes of every accessor, one bufferView each. */
typedef struct blob {
    uint8_t bin[2048];
    size_t size;
    char accessors[2048];
    int count;
} blob;

static int put(blob *b, const void *v, size_t n, size_t esize, const char *type, size_t count,
               int ctype, bool normalized)
{
    size_t at = gltf_put(b->bin, &b->size, v, n, esize);
    size_t len = strlen(b->accessors);
    snprintf(b->accessors + len, sizeof b->accessors - len,
             "%s{\"bufferView\":%d,\"byteOffset\":0,\"componentType\":%d,\"count\":%zu,"
             "\"type\":\"%s\"%s,\"_at\":%zu,\"_len\":%zu}", b->count ? "," : "", b->count, ctype,
             count, type, normalized ? ",\"normalized\":true" : "", at, n * esize);
    return b->count++;
}

/* The document: a triangle drawn by nodes 0, 3, 4 and 5 with material 0
 * (`material`, a texture without a source for it to name),
 * point light 0 on node 1, perspective camera 0 on node 2; node 3 hidden
 * (KHR_node_visibility) with node 4 its child, node 5 shown; `channels`
 * and `samplers` the one animation's.  Malloc'd. */
static char *scene_json_with(const blob *b, const char *material, const char *samplers,
                             const char *channels)
{
    char views[2048] = "", acc[2048], *o = acc;
    const char *p = b->accessors;
    /* Each accessor's "_at"/"_len" become its bufferView. */
    for (int i = 0; i < b->count; i++) {
        size_t at, len;
        const char *m = strstr(p, ",\"_at\":");
        sscanf(m, ",\"_at\":%zu,\"_len\":%zu", &at, &len);
        o += sprintf(o, "%.*s}", (int)(m - p), p);
        p = strchr(m, '}') + 1;
        if (*p == ',') {
            *o++ = *p++;
        }
        size_t vl = strlen(views);
        snprintf(views + vl, sizeof views - vl, "%s{\"buffer\":0,\"byteOffset\":%zu,"
                 "\"byteLength\":%zu}", i ? "," : "", at, len);
    }
    *o = 0;
    char b64[4 * sizeof b->bin / 3 + 8];
    gltf_base64(b->bin, b->size, b64);
    size_t cap = strlen(b64) + strlen(views) + strlen(acc) + strlen(material) + strlen(samplers) +
                 strlen(channels) + 2048;
    char *json = malloc(cap);
    if (json) {
        snprintf(json, cap,
                 "{\"asset\":{\"version\":\"2.0\"},"
                 "\"extensionsUsed\":[\"KHR_animation_pointer\",\"KHR_node_visibility\","
                 "\"KHR_lights_punctual\"],"
                 "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\","
                 "\"intensity\":10}]}},"
                 "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;"
                 "base64,%s\"}],\"bufferViews\":[%s],\"accessors\":[%s],"
                 "\"materials\":[%s],\"textures\":[{}],"
                 "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
                 "\"material\":0}]}],"
                 "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,"
                 "\"znear\":0.1}}],"
                 "\"nodes\":[{\"mesh\":0},"
                 "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},{\"camera\":0},"
                 "{\"mesh\":0,\"children\":[4],\"translation\":[5,0,0],"
                 "\"extensions\":{\"KHR_node_visibility\":{\"visible\":false}}},"
                 "{\"mesh\":0,\"extensions\":{\"KHR_node_visibility\":{\"visible\":true}}},"
                 "{\"mesh\":0,\"extensions\":{\"KHR_node_visibility\":{}}}],"
                 "\"scenes\":[{\"nodes\":[0,1,2,3,5]}],"
                 "\"animations\":[{\"samplers\":[%s],\"channels\":[%s]}]}",
                 b->size, b64, views, acc, material, samplers, channels);
    }
    return json;
}

static const char *const red = "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0,0,1]}}";

static char *scene_json(const blob *b, const char *samplers, const char *channels)
{
    return scene_json_with(b, red, samplers, channels);
}

static sr_result parse(const char *json, const sr_load_desc *desc, sr_scene **s, sr_io_error *e)
{
    return sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json), desc, s,
                         e);
}

/* A channel of sampler `sampler` to `pointer`. */
static void add_channel(char *list, size_t cap, int sampler, const char *pointer)
{
    size_t n = strlen(list);
    snprintf(list + n, cap - n, "%s{\"sampler\":%d,\"target\":{\"path\":\"pointer\","
             "\"extensions\":{\"KHR_animation_pointer\":{\"pointer\":\"%s\"}}}}",
             n ? "," : "", sampler, pointer);
}

/* The document of the main test: keys at 0 and 2 s (LINEAR) for the base
 * color (red to blue), the roughness (normalized unsigned bytes 0 to
 * 255), the light's intensity (10 to 30), the camera's yfov (0.8 to 1.2)
 * and node 0's translation (x 0 to 2); node 5's `visible` STEP from
 * true to false at 1 s. */
static char *animated_json(void)
{
    blob b = { .size = 0 };
    static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    static const float t02[2] = { 0, 2 }, t01[2] = { 0, 1 };
    static const float color[8] = { 1, 0, 0, 1, 0, 0, 1, 1 };
    static const uint8_t rough[2] = { 0, 255 }, shown[2] = { 1, 0 };
    static const float power[2] = { 10, 30 }, fov[2] = { 0.8f, 1.2f };
    static const float move[6] = { 0, 0, 0, 2, 0, 0 };
    put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
    int in2 = put(&b, t02, 2, 4, "SCALAR", 2, 5126, false);
    int in1 = put(&b, t01, 2, 4, "SCALAR", 2, 5126, false);
    int c = put(&b, color, 8, 4, "VEC4", 2, 5126, false);
    int r = put(&b, rough, 2, 1, "SCALAR", 2, 5121, true);
    int p = put(&b, power, 2, 4, "SCALAR", 2, 5126, false);
    int f = put(&b, fov, 2, 4, "SCALAR", 2, 5126, false);
    int m = put(&b, move, 6, 4, "VEC3", 2, 5126, false);
    int v = put(&b, shown, 2, 1, "SCALAR", 2, 5121, false);
    char samplers[1024], channels[2048] = "";
    snprintf(samplers, sizeof samplers,
             "{\"input\":%d,\"output\":%d},{\"input\":%d,\"output\":%d},"
             "{\"input\":%d,\"output\":%d},{\"input\":%d,\"output\":%d},"
             "{\"input\":%d,\"output\":%d},"
             "{\"input\":%d,\"output\":%d,\"interpolation\":\"STEP\"}",
             in2, c, in2, r, in2, p, in2, f, in2, m, in1, v);
    add_channel(channels, sizeof channels, 0, "/materials/0/pbrMetallicRoughness/baseColorFactor");
    add_channel(channels, sizeof channels, 1, "/materials/0/pbrMetallicRoughness/roughnessFactor");
    add_channel(channels, sizeof channels, 2, "/extensions/KHR_lights_punctual/lights/0/intensity");
    add_channel(channels, sizeof channels, 3, "/cameras/0/perspective/yfov");
    add_channel(channels, sizeof channels, 4, "/nodes/0/translation");
    add_channel(channels, sizeof channels, 5, "/nodes/5/extensions/KHR_node_visibility/visible");
    return scene_json(&b, samplers, channels);
}

static size_t triangles_of(const sr_scene *s, int node)
{
    size_t n = 0;
    for (size_t i = 0; i < s->primitive_count; i++) {
        n += s->primitives[i].node == node ? s->primitives[i].triangle_count : 0;
    }
    return n;
}

static const float *world_of(const sr_scene *s, int node)
{
    for (size_t i = 0; i < s->primitive_count; i++) {
        if (s->primitives[i].node == node) {
            return s->primitives[i].world;
        }
    }
    return NULL;
}

/* What a pose changes, the same in two scenes. */
static void check_same(const sr_scene *a, const sr_scene *b)
{
    REQUIRE(a->material_count == b->material_count && a->light_count == b->light_count &&
            a->camera_count == b->camera_count && a->primitive_count == b->primitive_count);
    CHECK(memcmp(a->materials, b->materials, a->material_count * sizeof *a->materials) == 0);
    CHECK(memcmp(a->lights, b->lights, a->light_count * sizeof *a->lights) == 0);
    CHECK(memcmp(a->cameras, b->cameras, a->camera_count * sizeof *a->cameras) == 0);
    for (size_t i = 0; i < a->primitive_count; i++) {
        CHECK_EQ(a->primitives[i].triangle_count, b->primitives[i].triangle_count);
        CHECK(memcmp(a->primitives[i].world, b->primitives[i].world, sizeof a->primitives[i].world)
              == 0);
    }
    CHECK(memcmp(&a->bounds_min, &b->bounds_min, sizeof a->bounds_min) == 0);
    CHECK(memcmp(&a->bounds_max, &b->bounds_max, sizeof a->bounds_max) == 0);
}

SR_TEST(the_rest_pose_hides_the_invisible_subtree_and_keeps_the_file_values)
{
    char *json = animated_json();
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    sr_test_warnings w = { 0 };
    sr_load_desc desc = { .warn = sr_test_collect_warning, .user = &w };
    REQUIRE(parse(json, &desc, &s, &e) == SR_OK);
    free(json);
    CHECK_EQ(w.count, 0);   /* both extensions are read: no "not read" warning */
    CHECK_EQ(triangles_of(s, 0), 1);
    CHECK_EQ(triangles_of(s, 3), 0);   /* visible: false */
    CHECK_EQ(triangles_of(s, 4), 0);   /* true, but under node 3 */
    CHECK_EQ(triangles_of(s, 5), 1);   /* the extension without `visible`: shown */
    /* The hidden draws leave the bounds (node 3 stands at x = 5). */
    CHECK_NEAR(s->bounds_max.x, 1, 0);
    CHECK_NEAR(s->materials[0].base_color[0], 1, 0);
    CHECK_NEAR(s->materials[0].roughness, 1, 0);
    CHECK_NEAR(s->lights[0].light.intensity, 10, 0);
    CHECK_NEAR(s->cameras[0].yfov, 0.8f, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(pointer_channels_animate_materials_lights_cameras_nodes_and_visibility)
{
    char *json = animated_json();
    REQUIRE(json);
    sr_scene *s = NULL, *rest = NULL, *posed = NULL;
    sr_io_error e;
    sr_load_desc at = { .pose = SR_POSE_ANIMATION, .animation_time = 1.5f };
    REQUIRE(parse(json, &at, &s, &e) == SR_OK);
    /* 0.75 of the way from the first keys to the second. */
    CHECK_NEAR(s->materials[0].base_color[0], 0.25f, 1e-6);
    CHECK_NEAR(s->materials[0].base_color[2], 0.75f, 1e-6);
    CHECK_NEAR(s->materials[0].roughness, 0.75f, 1e-6);
    CHECK_NEAR(s->lights[0].light.intensity, 25, 1e-5);
    CHECK_EQ(s->lights[0].light.type, SR_LIGHT_POINT);
    CHECK_NEAR(s->cameras[0].yfov, 1.1f, 1e-6);
    const float *w0 = world_of(s, 0);
    REQUIRE(w0);
    CHECK_NEAR(w0[12], 1.5f, 1e-6);
    CHECK_EQ(triangles_of(s, 5), 0);   /* STEP to false at 1 s */
    CHECK_EQ(triangles_of(s, 3), 0);
    /* sr_scene_pose makes the same bytes from a rest reading, and goes
     * back to the rest pose's. */
    REQUIRE(parse(json, NULL, &rest, &e) == SR_OK);
    REQUIRE(parse(json, NULL, &posed, &e) == SR_OK);
    const sr_pbr_material *materials = posed->materials;
    REQUIRE(sr_scene_pose(posed, SR_POSE_ANIMATION, 0, 1.5f, &e) == SR_OK);
    CHECK(posed->materials == materials);
    check_same(s, posed);
    REQUIRE(sr_scene_pose(posed, SR_POSE_ANIMATION, 0, 0.5f, &e) == SR_OK);
    CHECK_EQ(triangles_of(posed, 5), 1);
    CHECK_NEAR(posed->materials[0].base_color[0], 0.75f, 1e-6);
    REQUIRE(sr_scene_pose(posed, SR_POSE_REST, 0, 0, &e) == SR_OK);
    check_same(rest, posed);
    free(json);
    sr_destroy_scene(sr_test_ctx(), s);
    sr_destroy_scene(sr_test_ctx(), rest);
    sr_destroy_scene(sr_test_ctx(), posed);
}

/* One channel of a one-key sampler (output accessor of `type` floats, or
 * of unsigned bytes when `bytes`) to `pointer`, with `interp`; parsed in
 * the rest pose. */
/* One channel to `pointer` on the document whose material 0 is
 * `material`. */
static sr_result one_channel_on(const char *material, const char *pointer, const char *type,
                                bool bytes, const char *interp, const char *target_extra,
                                sr_test_warnings *w, sr_io_error *e)
{
    blob b = { .size = 0 };
    static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, t0[1] = { 0 };
    static const float v[4] = { 0.5f, 0.5f, 0.5f, 1 };
    static const uint8_t one[1] = { 1 };
    int n = strcmp(type, "SCALAR") == 0 ? 1 : type[3] - '0';
    put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
    int in = put(&b, t0, 1, 4, "SCALAR", 1, 5126, false);
    int out = bytes ? put(&b, one, 1, 1, "SCALAR", 1, 5121, false)
                    : put(&b, v, (size_t)n, 4, type, 1, 5126, false);
    char samplers[256], channels[512];
    snprintf(samplers, sizeof samplers, "{\"input\":%d,\"output\":%d,\"interpolation\":\"%s\"}",
             in, out, interp);
    snprintf(channels, sizeof channels, "{\"sampler\":0,\"target\":{%s\"path\":\"pointer\","
             "\"extensions\":{\"KHR_animation_pointer\":{\"pointer\":\"%s\"}}}}", target_extra,
             pointer);
    char *json = scene_json_with(&b, material, samplers, channels);
    if (!json) {
        return SR_OUT_OF_MEMORY;
    }
    sr_scene *s = NULL;
    sr_load_desc desc = { .warn = sr_test_collect_warning, .user = w };
    sr_result r = parse(json, &desc, &s, e);
    free(json);
    sr_destroy_scene(sr_test_ctx(), s);
    return r;
}

static sr_result one_channel(const char *pointer, const char *type, bool bytes,
                             const char *interp, const char *target_extra, sr_test_warnings *w,
                             sr_io_error *e)
{
    return one_channel_on(red, pointer, type, bytes, interp, target_extra, w, e);
}

SR_TEST(malformed_pointers_are_refused_with_the_channel_pointer)
{
    static const struct {
        const char *pointer, *type;
        bool bytes;
        const char *interp, *extra, *message;
    } cases[] = {
        { "materials/0/emissiveFactor", "VEC3", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"materials/0/emissiveFactor\" is "
          "not a JSON pointer" },
        { "/materials/0~2/x", "SCALAR", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"/materials/0~2/x\" is not a "
          "JSON pointer" },
        { "/materials/3/emissiveFactor", "VEC3", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"/materials/3/emissiveFactor\": "
          "materials 3 is not in the file (it has 1)" },
        /* Digits that name no element: as out of range, not as a name. */
        { "/materials/99999999999999999999/emissiveFactor", "VEC3", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"/materials/99999999999999999999/"
          "emissiveFactor\": materials 99999999999999999999 is not in the file (it has 1)" },
        { "/materials/00/emissiveFactor", "VEC3", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"/materials/00/emissiveFactor\": "
          "materials 00 is not in the file (it has 1)" },
        { "/extensions/KHR_lights_punctual/lights/1/color", "VEC3", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"/extensions/KHR_lights_punctual"
          "/lights/1/color\": lights 1 is not in the file (it has 1)" },
        { "/materials/0/emissiveFactor", "VEC4", false, "LINEAR", "",
          "/sampler: its output has 4 components an element; the property takes 3" },
        { "/cameras/0/perspective/aspectRatio", "SCALAR", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"/cameras/0/perspective/"
          "aspectRatio\" names a property the file does not define (it has no default)" },
        { "/materials/0/extensions/KHR_materials_ior/ior", "SCALAR", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"/materials/0/extensions/"
          "KHR_materials_ior/ior\" names a property the file does not define" },
        { "/nodes/5/extensions/KHR_node_visibility/visible", "SCALAR", false, "STEP", "",
          "/sampler: its output is not of unsigned bytes, which a boolean takes" },
        { "/nodes/5/extensions/KHR_node_visibility/visible", "SCALAR", true, "LINEAR", "",
          "/sampler: a boolean is animated by STEP" },
        { "/nodes/0/extensions/KHR_node_visibility/visible", "SCALAR", true, "STEP", "",
          "/target/extensions/KHR_animation_pointer/pointer: \"/nodes/0/extensions/"
          "KHR_node_visibility/visible\": node 0 has no KHR_node_visibility object" },
        { "/meshes/0/weights", "SCALAR", false, "LINEAR", "",
          "/target/extensions/KHR_animation_pointer/pointer: mesh 0 has no morph targets to "
          "weigh" },
        { "/nodes/0/rotation", "VEC3", false, "LINEAR", "",
          "/sampler: its output has 3 components an element; rotation takes VEC4" },
        { "/nodes/0/translation", "VEC3", false, "LINEAR", "\"node\":0,",
          "/target/node: given with path \"pointer\", which KHR_animation_pointer forbids" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sr_test_warnings w = { 0 };
        sr_io_error e = { { 0 } };
        sr_result r = one_channel(cases[i].pointer, cases[i].type, cases[i].bytes,
                                  cases[i].interp, cases[i].extra, &w, &e);
        char want[512];
        snprintf(want, sizeof want, "t.gltf: /animations/0/channels/0%s", cases[i].message);
        CHECK_EQ(r, SR_BAD_FORMAT);
        if (strcmp(e.message, want) != 0) {
            sr_test_fail(__FILE__, __LINE__, "case %zu: got \"%s\", want \"%s\"", i, e.message,
                         want);
        }
    }
}

SR_TEST(pointers_softrast_does_not_animate_are_warned_about_once)
{
    static const char *const skipped[] = {
        "/meshes/0/primitives/0/material",
        "/materials/0/doubleSided",
        "/cameras/0/type",
        /* "~1" escapes a '/' inside one member's name: the material has
         * no member "pbrMetallicRoughness/baseColorFactor". */
        "/materials/0/pbrMetallicRoughness~1baseColorFactor",
        "/materials/0/pbrMetallicRoughness~1baseColorTexture/extensions/KHR_texture_transform/"
        "offset",
    };
    for (size_t i = 0; i < sizeof skipped / sizeof *skipped; i++) {
        sr_test_warnings w = { 0 };
        sr_io_error e;
        sr_result r = one_channel(skipped[i], "VEC2", false, "LINEAR", "", &w, &e);
        if (r != SR_OK) {
            sr_test_fail(__FILE__, __LINE__, "%s", e.message);
        }
        CHECK_EQ(w.count, 1);
        char want[512];
        snprintf(want, sizeof want, "/animations/0/channels/0/target/extensions/"
                 "KHR_animation_pointer/pointer: \"%s\" is not a property softrast animates, "
                 "not animated", skipped[i]);
        CHECK_STR_CONTAINS(w.text, want);
    }
}

/* A specular-glossiness material: the metallic-roughness fallback beside
 * its factors is not animated, whose fields hold the diffuse color it
 * draws (its own factors are: every_material_factor_posed_...). */
SR_TEST(specular_glossiness_fallbacks_are_not_animated)
{
    static const char *const sg =
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0,0,1]},\"extensions\":"
        "{\"KHR_materials_pbrSpecularGlossiness\":{\"diffuseFactor\":[0,1,0,1]}}}";
    static const char *const pointer = "/materials/0/pbrMetallicRoughness/baseColorFactor";
    {
        sr_test_warnings w = { 0 };
        sr_io_error e;
        if (one_channel_on(sg, pointer, "VEC4", false, "LINEAR", "", &w, &e) != SR_OK) {
            sr_test_fail(__FILE__, __LINE__, "%s", e.message);
        }
        CHECK_EQ(w.count, 1);
        char want[512];
        snprintf(want, sizeof want, "KHR_animation_pointer/pointer: \"%s\": material 0 is "
                 "drawn with KHR_materials_pbrSpecularGlossiness, not animated", pointer);
        CHECK_STR_CONTAINS(w.text, want);
    }
    /* Nor an extension the specular-glossiness one excludes, which the
     * reader dropped (its own warning, then the pointer's). */
    static const char *const coated =
        "{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{},"
        "\"KHR_materials_clearcoat\":{\"clearcoatFactor\":0.25}}}";
    sr_test_warnings w = { 0 };
    sr_io_error e;
    if (one_channel_on(coated, "/materials/0/extensions/KHR_materials_clearcoat/clearcoatFactor",
                       "SCALAR", false, "LINEAR", "", &w, &e) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s", e.message);
    }
    CHECK_EQ(w.count, 2);
    CHECK_STR_CONTAINS(w.text, "/materials/0/extensions/KHR_materials_clearcoat: not read on a "
                               "material with KHR_materials_pbrSpecularGlossiness");
    CHECK_STR_CONTAINS(w.text, "KHR_animation_pointer/pointer: \"/materials/0/extensions/"
                               "KHR_materials_clearcoat/clearcoatFactor\": material 0 is drawn "
                               "with KHR_materials_pbrSpecularGlossiness, which excludes "
                               "KHR_materials_clearcoat, not animated");
}

SR_TEST(a_bad_visible_is_refused)
{
    blob b = { .size = 0 };
    static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
    char *json = scene_json(&b, "", "");
    REQUIRE(json);
    char *at = strstr(json, "\"visible\":false");
    REQUIRE(at);
    memcpy(at, "\"visible\":0    ", 15);
    /* An animation without channels is refused first: drop it. */
    char *anim = strstr(json, ",\"animations\"");
    REQUIRE(anim);
    strcpy(anim, "}");
    sr_scene *s = NULL;
    sr_io_error e;
    CHECK_EQ(parse(json, NULL, &s, &e), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, "t.gltf: /nodes/3/extensions/KHR_node_visibility/visible: "
                                  "not true or false");
    free(json);
}

/* glTF 2.0's animation output table: rotations of normalized unsigned
 * shorts and bytes (c / 65535, c / 255) and signed bytes (max(c / 127,
 * -1)), decoded before the slerp; integers not normalized are refused. */
SR_TEST(quantized_rotation_outputs_decode_by_the_specification)
{
    static const struct {
        int ctype;
        size_t esize;
        bool normalized;
        double tol;
    } kinds[] = { { 5123, 2, true, 1e-4 }, { 5121, 1, true, 1e-2 }, { 5120, 1, true, 1e-2 },
                  { 5123, 2, false, 0 } };
    const double h = sqrt(0.5);
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
        blob b = { .size = 0 };
        static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, t02[2] = { 0, 2 };
        double full = kinds[k].ctype == 5123 ? 65535 : kinds[k].ctype == 5121 ? 255 : 127;
        /* The identity, then 90 degrees about +z. */
        double q[8] = { 0, 0, 0, 1, 0, 0, h, h };
        uint8_t raw[16];
        for (int c = 0; c < 8; c++) {
            long v = lrint(q[c] * full);
            if (kinds[k].esize == 2) {
                uint16_t u = (uint16_t)v;
                memcpy(raw + 2 * c, &u, 2);
            } else {
                raw[c] = (uint8_t)v;
            }
        }
        put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
        int in = put(&b, t02, 2, 4, "SCALAR", 2, 5126, false);
        int out = put(&b, raw, 8, kinds[k].esize, "VEC4", 2, kinds[k].ctype,
                      kinds[k].normalized);
        char samplers[128];
        snprintf(samplers, sizeof samplers, "{\"input\":%d,\"output\":%d}", in, out);
        char *json = scene_json(&b, samplers, "{\"sampler\":0,\"target\":{\"node\":0,"
                                              "\"path\":\"rotation\"}}");
        REQUIRE(json);
        sr_scene *s = NULL;
        sr_io_error e;
        sr_load_desc desc = { .pose = SR_POSE_ANIMATION, .animation_time = 1 };
        sr_result r = parse(json, &desc, &s, &e);
        free(json);
        if (!kinds[k].normalized) {
            CHECK_EQ(r, SR_BAD_FORMAT);
            CHECK_STR_CONTAINS(e.message, "/animations/0/channels/0/sampler: its output is of "
                                          "integers not normalized");
            continue;
        }
        REQUIRE(r == SR_OK);
        const float *w = world_of(s, 0);
        REQUIRE(w);
        /* Halfway: 45 degrees, x to (cos 45, sin 45). */
        CHECK_NEAR(w[0], cos(M_PI / 4), kinds[k].tol);
        CHECK_NEAR(w[1], sin(M_PI / 4), kinds[k].tol);
        sr_destroy_scene(sr_test_ctx(), s);
    }
}

/* Two channels of one animation on one target are refused by the rule
 * node paths follow, naming the second channel's pointer. */
SR_TEST(two_channels_on_one_pointer_target_are_refused)
{
    static const struct {
        const char *first, *second, *message;
    } cases[] = {
        { "/materials/0/alphaCutoff", "/materials/0/alphaCutoff",
          "/extensions/KHR_animation_pointer/pointer: \"/materials/0/alphaCutoff\" is "
          "animated by another channel of this animation" },
        { "/cameras/0/perspective/yfov", "/cameras/0/perspective/yfov",
          "/extensions/KHR_animation_pointer/pointer: \"/cameras/0/perspective/yfov\" is "
          "animated by another channel of this animation" },
        { "/extensions/KHR_lights_punctual/lights/0/intensity",
          "/extensions/KHR_lights_punctual/lights/0/intensity",
          "/extensions/KHR_animation_pointer/pointer: \"/extensions/KHR_lights_punctual/"
          "lights/0/intensity\" is animated by another channel of this animation" },
        { "/materials/0/emissiveTexture/extensions/KHR_texture_transform/rotation",
          "/materials/0/emissiveTexture/extensions/KHR_texture_transform/rotation",
          "/extensions/KHR_animation_pointer/pointer: \"/materials/0/emissiveTexture/"
          "extensions/KHR_texture_transform/rotation\" is animated by another channel of this "
          "animation" },
        { "/nodes/0/scale", "/nodes/0/scale",
          "/extensions/KHR_animation_pointer/pointer: node 0's scale is animated by another "
          "channel of this animation" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        blob b = { .size = 0 };
        static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, t0[1] = { 0 };
        static const float v3[3] = { 0.5f, 0.5f, 0.5f };
        bool vec = strstr(cases[i].first, "scale") != NULL;
        put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
        int in = put(&b, t0, 1, 4, "SCALAR", 1, 5126, false);
        int out = put(&b, v3, vec ? 3 : 1, 4, vec ? "VEC3" : "SCALAR", 1, 5126, false);
        char samplers[128], channels[1024] = "";
        snprintf(samplers, sizeof samplers, "{\"input\":%d,\"output\":%d}", in, out);
        add_channel(channels, sizeof channels, 0, cases[i].first);
        add_channel(channels, sizeof channels, 0, cases[i].second);
        const char *mat = "{\"emissiveTexture\":{\"index\":0,\"extensions\":"
                          "{\"KHR_texture_transform\":{}}}}";
        char *json = scene_json_with(&b, mat, samplers, channels);
        REQUIRE(json);
        sr_scene *s = NULL;
        sr_io_error e = { { 0 } };
        CHECK_EQ(parse(json, NULL, &s, &e), SR_BAD_FORMAT);
        char want[512];
        snprintf(want, sizeof want, "t.gltf: /animations/0/channels/1/target%s",
                 cases[i].message);
        CHECK_STR_CONTAINS(e.message, want);
        free(json);
        sr_destroy_scene(sr_test_ctx(), s);
    }
    /* A node path and a pointer to it: one target. */
    blob b = { .size = 0 };
    static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, t0[1] = { 0 };
    static const float v3[3] = { 1, 2, 3 };
    put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
    int in = put(&b, t0, 1, 4, "SCALAR", 1, 5126, false);
    int out = put(&b, v3, 3, 4, "VEC3", 1, 5126, false);
    char samplers[128], channels[1024];
    snprintf(samplers, sizeof samplers, "{\"input\":%d,\"output\":%d}", in, out);
    snprintf(channels, sizeof channels, "{\"sampler\":0,\"target\":{\"node\":0,"
             "\"path\":\"translation\"}}");
    add_channel(channels, sizeof channels, 0, "/nodes/0/translation");
    char *json = scene_json(&b, samplers, channels);
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e = { { 0 } };
    CHECK_EQ(parse(json, NULL, &s, &e), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, "t.gltf: /animations/0/channels/1/target/extensions/"
                            "KHR_animation_pointer/pointer: node 0's translation is animated by "
                            "another channel of this animation");
    free(json);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* The document of one LINEAR channel of `width` floats (1 or 3) to
 * `pointer`, keys k[0 .. width) at 0 s and k[width .. 2 width) at 2 s,
 * with material 0 `material`.  Malloc'd. */
static char *channel_json(const char *material, const float *k, int width, const char *pointer)
{
    blob b = { .size = 0 };
    static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, t02[2] = { 0, 2 };
    put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
    int in = put(&b, t02, 2, 4, "SCALAR", 2, 5126, false);
    static const char *const type[5] = { "", "SCALAR", "VEC2", "VEC3", "VEC4" };
    int out = put(&b, k, 2 * (size_t)width, 4, type[width], 2, 5126, false);
    char samplers[128], channels[512] = "";
    snprintf(samplers, sizeof samplers, "{\"input\":%d,\"output\":%d}", in, out);
    add_channel(channels, sizeof channels, 0, pointer);
    return scene_json_with(&b, material, samplers, channels);
}

static char *scalar_channel_json(const char *material, const float k[2], const char *pointer)
{
    return channel_json(material, k, 1, pointer);
}

/* A MASK material whose file cutoff is 0 reads OPAQUE (a cutoff of 0
 * keeps every fragment); posed with an animated cutoff above 0 it is the
 * file's MASK with that cutoff, and OPAQUE again at the rest pose and
 * where the cutoff is 0.  An OPAQUE material's cutoff changes no mode. */
SR_TEST(an_animated_cutoff_masks_a_mask_material_read_opaque)
{
    static const char *const modes[2] = { "MASK", "OPAQUE" };
    for (int k = 0; k < 2; k++) {
        static const float cut[2] = { 0, 0.4f };
        char mat[128];
        snprintf(mat, sizeof mat, "{\"alphaMode\":\"%s\",\"alphaCutoff\":0}", modes[k]);
        char *json = scalar_channel_json(mat, cut, "/materials/0/alphaCutoff");
        REQUIRE(json);
        sr_scene *s = NULL, *posed = NULL;
        sr_io_error e;
        sr_load_desc at = { .pose = SR_POSE_ANIMATION, .animation_time = 1 };
        REQUIRE(parse(json, NULL, &s, &e) == SR_OK);
        REQUIRE(parse(json, &at, &posed, &e) == SR_OK);
        free(json);
        sr_alpha_mode want = k == 0 ? SR_ALPHA_MASK : SR_ALPHA_OPAQUE;
        CHECK_EQ(s->materials[0].alpha_mode, SR_ALPHA_OPAQUE);
        CHECK_EQ(posed->materials[0].alpha_mode, want);
        CHECK_NEAR(posed->materials[0].alpha_cutoff, 0.2f, 1e-6);
        REQUIRE(sr_scene_pose(s, SR_POSE_ANIMATION, 0, 1, &e) == SR_OK);
        CHECK_EQ(s->materials[0].alpha_mode, want);
        CHECK_NEAR(s->materials[0].alpha_cutoff, 0.2f, 1e-6);
        REQUIRE(sr_scene_pose(s, SR_POSE_ANIMATION, 0, 0, &e) == SR_OK);
        CHECK_EQ(s->materials[0].alpha_mode, SR_ALPHA_OPAQUE);
        REQUIRE(sr_scene_pose(s, SR_POSE_ANIMATION, 0, 2, &e) == SR_OK);
        CHECK_EQ(s->materials[0].alpha_mode, want);
        REQUIRE(sr_scene_pose(s, SR_POSE_REST, 0, 0, &e) == SR_OK);
        CHECK_EQ(s->materials[0].alpha_mode, SR_ALPHA_OPAQUE);
        CHECK_NEAR(s->materials[0].alpha_cutoff, 0, 0);
        sr_destroy_scene(sr_test_ctx(), s);
        sr_destroy_scene(sr_test_ctx(), posed);
    }
}

/* The iridescence film's ior and thickness range and the volume's
 * attenuation distance, interpolated and clamped to the reader's ranges
 * (keys at 0 and 2 s, read at 1 s): an ior under 1 is 1, a negative
 * thickness 0, a distance not positive 0 (no absorption); a film whose
 * thickness reaches 0 keeps its factor (0 nm draws no film by itself,
 * iridescence_thickness_set), for the thickness to grow back. */
SR_TEST(film_and_volume_properties_animate_within_the_reader_ranges)
{
    static const struct {
        const char *ext, *name;
        float k0, k1;
        size_t offset;
        float want, factor;
    } cases[] = {
        { "iridescence", "iridescenceIor", 1.2f, 1.8f, offsetof(sr_pbr_material, iridescence_ior),
          1.5f, 1 },
        { "iridescence", "iridescenceIor", 0, 0.5f, offsetof(sr_pbr_material, iridescence_ior), 1,
          1 },
        { "iridescence", "iridescenceThicknessMinimum", 100, 300,
          offsetof(sr_pbr_material, iridescence_thickness_min), 200, 1 },
        { "iridescence", "iridescenceThicknessMaximum", 400, -200,
          offsetof(sr_pbr_material, iridescence_thickness_max), 100, 1 },
        { "iridescence", "iridescenceThicknessMaximum", 0, -200,
          offsetof(sr_pbr_material, iridescence_thickness_max), 0, 1 },
        { "volume", "attenuationDistance", 2, 4,
          offsetof(sr_pbr_material, attenuation_distance), 3, 1 },
        { "volume", "attenuationDistance", 2, -4,
          offsetof(sr_pbr_material, attenuation_distance), 0, 1 },
    };
    const char *mat = "{\"extensions\":{\"KHR_materials_iridescence\":{\"iridescenceFactor\":1},"
                      "\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
                      "\"KHR_materials_volume\":{\"attenuationDistance\":2}}}";
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const float keys[2] = { cases[i].k0, cases[i].k1 };
        char pointer[256];
        snprintf(pointer, sizeof pointer, "/materials/0/extensions/KHR_materials_%s/%s",
                 cases[i].ext, cases[i].name);
        char *json = scalar_channel_json(mat, keys, pointer);
        REQUIRE(json);
        sr_scene *s = NULL;
        sr_io_error e;
        sr_test_warnings w = { 0 };
        sr_load_desc at = { .pose = SR_POSE_ANIMATION, .animation_time = 1, .warn =
                            sr_test_collect_warning, .user = &w };
        REQUIRE(parse(json, &at, &s, &e) == SR_OK);
        free(json);
        CHECK(strstr(w.text, "not animated") == NULL);
        float got;
        memcpy(&got, (const char *)&s->materials[0] + cases[i].offset, sizeof got);
        CHECK_NEAR(got, cases[i].want, 1e-5);
        CHECK_NEAR(s->materials[0].iridescence, cases[i].factor, 0);
        CHECK(s->materials[0].iridescence_thickness_set);
        sr_destroy_scene(sr_test_ctx(), s);
    }
}

enum { FILM_SIZE = 96 };

/* RGBA8 pixels of FILM_SIZE squared as out/NAME.png; NULL name: none. */
static void save_film(const uint8_t *px, const char *name)
{
    if (name) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s.png", sr_test_out_dir(), name);
        sr_write_png(path, FILM_SIZE, FILM_SIZE, px, 4 * FILM_SIZE, NULL, NULL);
    }
}

/* The unit sphere drawn with material m (its factors; the scene's
 * triangle has no normals) under a white key light, into a malloc'd
 * RGBA8 image of FILM_SIZE squared, saved as out/NAME.png (save_film). */
static uint8_t *draw_film(const sr_pbr_material *m, const char *name)
{
    static sphere s;
    make_sphere(&s);
    sr_context *ctx = sr_test_ctx();
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 0, 3 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.8f, 1.0f, 0.5f, 10.0f, false);
    sr_pbr_desc d = { .material = m, .view = &view, .projection = &proj,
                      .sky = { 0.3f, 0.3f, 0.3f }, .ground = { 0.1f, 0.1f, 0.1f } };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { -0.4f, -0.5f, -1 },
                              .color = { 1, 1, 1 }, .intensity = 3 };
    sr_framebuffer *fb = NULL;
    sr_pbr *p = NULL;
    uint8_t *px = NULL;
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = FILM_SIZE,
                                                         .height = FILM_SIZE }, &fb) != SR_OK) {
        return NULL;
    }
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    if (sr_make_pbr_program(ctx, &d, &p) == SR_OK &&
        sr_draw(ctx, fb, &(sr_state){ .program = sr_pbr_program(p) },
                &(sr_draw_desc){ .positions = &s.pos[0][0], .normals = &s.nrm[0][0],
                                 .texcoords = &s.uv[0][0], .vertex_count = VERTS,
                                 .indices = s.idx, .index_type = SR_INDEX_U32,
                                 .index_count = s.index_count }) == SR_OK &&
        (px = malloc(4 * FILM_SIZE * FILM_SIZE)) != NULL) {
        memcpy(px, sr_framebuffer_pixels(fb), 4 * FILM_SIZE * FILM_SIZE);
        save_film(px, name);
    }
    sr_destroy_pbr_program(ctx, p);
    sr_destroy_framebuffer(ctx, fb);
    return px;
}

/* Five materials of one property drawn on the sphere as out/names[k].png:
 * posed from 0 through sr_load_desc and through sr_scene_pose, the file
 * at the posed value, the file at 0 and the value's material without the
 * property.  The property shows (over 600 channels of the third apart
 * from the fifth by more than 8, `what` printed with their count), both
 * posed draw the file's bytes at the value and the file at 0 draws the
 * bytes of no property. */
static void check_posed_spheres(const sr_pbr_material m[5], const char *const names[5],
                                const char *what)
{
    uint8_t *px[5];
    for (int k = 0; k < 5; k++) {
        px[k] = draw_film(&m[k], names[k]);
    }
    for (int k = 0; k < 5; k++) {
        REQUIRE(px[k]);
    }
    size_t n = 4 * FILM_SIZE * FILM_SIZE;
    int shown = 0;
    for (size_t i = 0; i < n; i++) {
        shown += abs(px[2][i] - px[4][i]) > 8;
    }
    fprintf(stderr, "%d channels %s\n", shown, what);
    CHECK(shown > 600);                         /* the property shows */
    CHECK(memcmp(px[0], px[2], n) == 0);
    CHECK(memcmp(px[1], px[2], n) == 0);
    CHECK(memcmp(px[3], px[4], n) == 0);        /* at 0: none */
    for (int k = 0; k < 5; k++) {
        free(px[k]);
    }
}

/* Material 0 of the document whose material is `mat`: `animated`, its
 * `pointer` keyed k as channel_json's (`width` floats a key) and posed at `time` through
 * sr_load_desc (by_scene_pose false) or sr_scene_pose from the rest pose;
 * else read at rest (the document's one channel, to the roughness, left
 * unplayed).  false on failure. */
static bool keyed_material(const char *mat, const char *pointer, const float *k, int width,
                           bool animated, bool by_scene_pose, float time, sr_pbr_material *out)
{
    char *json = animated ? channel_json(mat, k, width, pointer)
                          : scalar_channel_json(mat, k, "/materials/0/pbrMetallicRoughness/"
                                                        "roughnessFactor");
    sr_scene *s = NULL;
    sr_io_error e;
    sr_load_desc at = { .pose = SR_POSE_ANIMATION, .animation_time = time };
    bool ok = json && parse(json, by_scene_pose || !animated ? NULL : &at, &s, &e) == SR_OK &&
              (!by_scene_pose || sr_scene_pose(s, SR_POSE_ANIMATION, 0, time, &e) == SR_OK);
    if (ok) {
        *out = s->materials[0];   /* factors only: no texture to outlive the scene */
    }
    free(json);
    sr_destroy_scene(sr_test_ctx(), s);
    return ok;
}

/* A film's material from the document whose iridescence extension is
 * `film`, its maximum keyed 0 and 400 nm when `animated` (keyed_material). */
static bool film_material(const char *film, bool animated, bool by_scene_pose, float time,
                          sr_pbr_material *out)
{
    static const float nm[2] = { 0, 400 };
    char mat[512];
    snprintf(mat, sizeof mat, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.1,0.1,0.12,1],"
             "\"metallicFactor\":0,\"roughnessFactor\":0.3},"
             "\"extensions\":{\"KHR_materials_iridescence\":%s}}", film);
    return keyed_material(mat, "/materials/0/extensions/KHR_materials_iridescence/"
                               "iridescenceThicknessMaximum", nm, 1, animated, by_scene_pose, time,
                          out);
}

SR_TEST(an_animated_film_thickness_grows_a_film_from_0_nm)
{
    const char *thin = "{\"iridescenceFactor\":1,\"iridescenceThicknessMaximum\":0}";
    const char *thick = "{\"iridescenceFactor\":1,\"iridescenceThicknessMaximum\":400}";
    sr_pbr_material posed, reposed, want, rest, none;
    REQUIRE(film_material(thin, true, false, 2, &posed));
    REQUIRE(film_material(thin, true, true, 2, &reposed));
    REQUIRE(film_material(thick, false, false, 0, &want));
    REQUIRE(film_material(thin, false, false, 0, &rest));
    none = want;
    none.iridescence = 0;
    CHECK_EQ(posed.iridescence, 1.0f);
    CHECK_EQ(posed.iridescence_thickness_max, 400.0f);
    static const char *const names[5] = { "gltf_film_posed", "gltf_film_reposed",
                                          "gltf_film_400nm", "gltf_film_0nm", "gltf_film_none" };
    check_posed_spheres((const sr_pbr_material[5]){ posed, reposed, want, rest, none }, names,
                        "tinted by the 400 nm film");
}

/* An emissive material whose KHR_materials_emissive_strength is 0 in the
 * file draws no emission at rest; animated up to 2 (posed by sr_load_desc
 * and by sr_scene_pose) it draws the bytes of the file at strength 2 at
 * rest: the reader keeps the file's emissiveFactor (emissive_strength_set)
 * where it zeroed it, and the posed sphere stayed dark. */
SR_TEST(an_animated_emissive_strength_lights_a_material_from_0)
{
    static const float strength[2] = { 0, 2 };
    static const char *const pointer =
        "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength";
    char off[512], on[512];
    static const char *const fmt =
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.2,0.2,1],"
        "\"metallicFactor\":0,\"roughnessFactor\":0.5},\"emissiveFactor\":[0.4,0.2,0.05],"
        "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":%d}}}";
    snprintf(off, sizeof off, fmt, 0);
    snprintf(on, sizeof on, fmt, 2);
    sr_pbr_material posed, reposed, want, rest, none;
    REQUIRE(keyed_material(off, pointer, strength, 1, true, false, 2, &posed));
    REQUIRE(keyed_material(off, pointer, strength, 1, true, true, 2, &reposed));
    REQUIRE(keyed_material(on, pointer, strength, 1, false, false, 0, &want));
    REQUIRE(keyed_material(off, pointer, strength, 1, false, false, 0, &rest));
    none = want;
    memset(none.emissive, 0, sizeof none.emissive);
    CHECK_EQ(posed.emissive_strength, 2.0f);
    CHECK_EQ(posed.emissive[0], 0.4f);
    CHECK(rest.emissive_strength_set);
    CHECK_EQ(rest.emissive_strength, 0.0f);
    static const char *const names[5] = { "gltf_emissive_posed", "gltf_emissive_reposed",
                                          "gltf_emissive_2", "gltf_emissive_0",
                                          "gltf_emissive_none" };
    check_posed_spheres((const sr_pbr_material[5]){ posed, reposed, want, rest, none }, names,
                        "lit by the emission");
}

#define BASE "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.4,0.3,1]," \
             "\"metallicFactor\":0,\"roughnessFactor\":0.4}"
#define X(ext) "/materials/0/extensions/KHR_materials_" ext "/"
#define VOL "\"KHR_materials_volume\":{\"thicknessFactor\":1,\"attenuationDistance\":1," \
            "\"attenuationColor\":[0.9,0.5,0.2]}"

/* Every animatable material factor softrast draws without a texture,
 * keyed between 0 (a zero color) and a value v: posed at v (from a file
 * at 0) and at 0 (from a file at v), through sr_load_desc, it draws the
 * very bytes of the file at that value at rest.  A reader that folds a
 * zero into another field (as emissive strength 0 once zeroed the
 * emissive factor) loses the value the animation brings back. */
SR_TEST(every_material_factor_posed_draws_the_file_read_with_it)
{
    static const struct {
        const char *mat;   /* one %s for the value */
        const char *pointer;
        int width;
        float v[4];
    } cases[] = {
        { "{" BASE ",\"emissiveFactor\":[0.3,0.2,0.1],\"extensions\":{"
          "\"KHR_materials_emissive_strength\":{\"emissiveStrength\":%s}}}",
          X("emissive_strength") "emissiveStrength", 1, { 2 } },
        { "{" BASE ",\"emissiveFactor\":%s,\"extensions\":{"
          "\"KHR_materials_emissive_strength\":{\"emissiveStrength\":2}}}",
          "/materials/0/emissiveFactor", 3, { 0.3f, 0.2f, 0.1f } },
        { "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.4,0.3,1],\"metallicFactor\":%s,"
          "\"roughnessFactor\":0.4}}", "/materials/0/pbrMetallicRoughness/metallicFactor", 1,
          { 1 } },
        { "{\"alphaMode\":\"MASK\",\"alphaCutoff\":%s,\"pbrMetallicRoughness\":{"
          "\"baseColorFactor\":[0.5,0.4,0.3,0.5]}}", "/materials/0/alphaCutoff", 1, { 0.6f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":%s},"
          VOL "}}", X("transmission") "transmissionFactor", 1, { 1 } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
          "\"KHR_materials_volume\":{\"thicknessFactor\":%s,\"attenuationDistance\":1,"
          "\"attenuationColor\":[0.9,0.5,0.2]}}}", X("volume") "thicknessFactor", 1, { 1 } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
          "\"KHR_materials_volume\":{\"thicknessFactor\":1,\"attenuationDistance\":%s,"
          "\"attenuationColor\":[0.9,0.5,0.2]}}}", X("volume") "attenuationDistance", 1, { 1 } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
          "\"KHR_materials_volume\":{\"thicknessFactor\":1,\"attenuationDistance\":1,"
          "\"attenuationColor\":%s}}}", X("volume") "attenuationColor", 3, { 0.9f, 0.5f, 0.2f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_dispersion\":{\"dispersion\":%s},"
          "\"KHR_materials_transmission\":{\"transmissionFactor\":1}," VOL "}}",
          X("dispersion") "dispersion", 1, { 1 } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_clearcoat\":{\"clearcoatFactor\":%s,"
          "\"clearcoatRoughnessFactor\":0.2}}}", X("clearcoat") "clearcoatFactor", 1, { 1 } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1,"
          "\"clearcoatRoughnessFactor\":%s}}}", X("clearcoat") "clearcoatRoughnessFactor", 1,
          { 0.6f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_sheen\":{\"sheenColorFactor\":%s,"
          "\"sheenRoughnessFactor\":0.5}}}", X("sheen") "sheenColorFactor", 3,
          { 0.8f, 0.5f, 0.2f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_sheen\":{\"sheenColorFactor\":[0.8,0.5,0.2],"
          "\"sheenRoughnessFactor\":%s}}}", X("sheen") "sheenRoughnessFactor", 1, { 0.7f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_anisotropy\":{\"anisotropyStrength\":%s,"
          "\"anisotropyRotation\":0.5}}}", X("anisotropy") "anisotropyStrength", 1, { 0.8f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_specular\":{\"specularFactor\":%s}}}",
          X("specular") "specularFactor", 1, { 0.5f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_specular\":{\"specularColorFactor\":%s}}}",
          X("specular") "specularColorFactor", 3, { 1, 0.5f, 0.2f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_ior\":{\"ior\":%s}}}", X("ior") "ior", 1,
          { 1.8f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_iridescence\":{\"iridescenceFactor\":%s}}}",
          X("iridescence") "iridescenceFactor", 1, { 1 } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_iridescence\":{\"iridescenceFactor\":1,"
          "\"iridescenceIor\":%s}}}", X("iridescence") "iridescenceIor", 1, { 1.8f } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_diffuse_transmission\":{"
          "\"diffuseTransmissionFactor\":%s}}}",
          X("diffuse_transmission") "diffuseTransmissionFactor", 1, { 1 } },
        { "{" BASE ",\"extensions\":{\"KHR_materials_diffuse_transmission\":{"
          "\"diffuseTransmissionFactor\":1,\"diffuseTransmissionColorFactor\":%s}}}",
          X("diffuse_transmission") "diffuseTransmissionColorFactor", 3, { 0.9f, 0.4f, 0.1f } },
        { "{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{\"diffuseFactor\":%s,"
          "\"specularFactor\":[0.2,0.2,0.2],\"glossinessFactor\":0.6}}}",
          X("pbrSpecularGlossiness") "diffuseFactor", 4, { 0.8f, 0.5f, 0.2f, 1 } },
        { "{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{\"diffuseFactor\":"
          "[0.5,0.4,0.3,1],\"specularFactor\":%s,\"glossinessFactor\":0.6}}}",
          X("pbrSpecularGlossiness") "specularFactor", 3, { 0.9f, 0.6f, 0.3f } },
        { "{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{\"diffuseFactor\":"
          "[0.5,0.4,0.3,1],\"specularFactor\":[0.2,0.2,0.2],\"glossinessFactor\":%s}}}",
          X("pbrSpecularGlossiness") "glossinessFactor", 1, { 0.9f } },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        int w = cases[i].width;
        float keys[2][8] = { { 0 } };   /* [0]: 0 to v; [1]: v to 0 */
        char val[2][64], mat[2][1024];
        for (int c = 0; c < w; c++) {
            keys[0][w + c] = keys[1][c] = cases[i].v[c];
        }
        for (int k = 0; k < 2; k++) {
            const float *f = k ? cases[i].v : (const float[4]){ 0, 0, 0, 0 };
            int at = snprintf(val[k], sizeof val[k], w == 1 ? "%.9g" : "[%.9g", (double)f[0]);
            for (int c = 1; c < w; c++) {
                at += snprintf(val[k] + at, sizeof val[k] - (size_t)at, ",%.9g", (double)f[c]);
            }
            if (w > 1) {
                snprintf(val[k] + at, sizeof val[k] - (size_t)at, "]");
            }
            snprintf(mat[k], sizeof mat[k], cases[i].mat, val[k]);
        }
        uint8_t *read[2] = { NULL, NULL };   /* the files at v and at 0 */
        for (int k = 0; k < 2; k++) {
            /* k 0: posed at v from the file at 0; k 1: at 0 from v. */
            sr_pbr_material posed, want;
            REQUIRE(keyed_material(mat[k], cases[i].pointer, keys[k], w, true, false, 2, &posed));
            REQUIRE(keyed_material(mat[!k], cases[i].pointer, keys[k], w, false, false, 0, &want));
            uint8_t *a = draw_film(&posed, NULL), *b = draw_film(&want, NULL);
            REQUIRE(a && b);
            bool same = memcmp(a, b, 4 * FILM_SIZE * FILM_SIZE) == 0;
            if (!same) {
                char name[64];
                snprintf(name, sizeof name, "gltf_posed_factor_%zu_%s", i, k ? "to_0" : "from_0");
                save_film(a, name);
                snprintf(name, sizeof name, "gltf_read_factor_%zu_%s", i, k ? "to_0" : "from_0");
                save_film(b, name);
                fprintf(stderr, "%s posed at %s draws other bytes than the file at %s\n",
                        cases[i].pointer, val[!k], val[!k]);
            }
            CHECK(same);
            free(a);
            read[k] = b;
        }
        /* The value shows: else the bytes above would prove nothing. */
        if (memcmp(read[0], read[1], 4 * FILM_SIZE * FILM_SIZE) == 0) {
            fprintf(stderr, "%s: %s and %s draw the same bytes\n", cases[i].pointer, val[0],
                    val[1]);
            CHECK(false);
        }
        free(read[0]);
        free(read[1]);
    }
}
#undef VOL
#undef X
#undef BASE

static const float *positions_of(const sr_scene *s, int node)
{
    for (size_t i = 0; i < s->primitive_count; i++) {
        if (s->primitives[i].node == node) {
            return s->primitives[i].positions;
        }
    }
    return NULL;
}

/* /meshes/0/weights (one target moving every vertex +1 in x, 0 to 1 over
 * 2 s) weighs the nodes drawing the mesh without weights of their own
 * (node 0), not node 5 with its own; a node's weights channel comes
 * first (`node_too`: node 0's weights held at 0). */
SR_TEST(mesh_weights_animate_the_nodes_without_their_own)
{
    for (int node_too = 0; node_too < 2; node_too++) {
        blob b = { .size = 0 };
        static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, t02[2] = { 0, 2 };
        static const float dx[9] = { 1, 0, 0, 1, 0, 0, 1, 0, 0 }, up[2] = { 0, 1 };
        static const float zero[2] = { 0, 0 };
        put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
        int in = put(&b, t02, 2, 4, "SCALAR", 2, 5126, false);
        int out = put(&b, up, 2, 4, "SCALAR", 2, 5126, false);
        int held = put(&b, zero, 2, 4, "SCALAR", 2, 5126, false);
        int target = put(&b, dx, 9, 4, "VEC3", 3, 5126, false);
        char samplers[256], channels[1024] = "", prim[128];
        snprintf(samplers, sizeof samplers,
                 "{\"input\":%d,\"output\":%d},{\"input\":%d,\"output\":%d}", in, out, in,
                 held);
        add_channel(channels, sizeof channels, 0, "/meshes/0/weights");
        if (node_too) {
            add_channel(channels, sizeof channels, 1, "/nodes/0/weights");
        }
        char *json = scene_json(&b, samplers, channels);
        REQUIRE(json);
        /* The mesh gets the target, node 5 weights of its own. */
        const char *p0 = "\"attributes\":{\"POSITION\":0},";
        const char *n5 = "{\"mesh\":0,\"extensions\":{\"KHR_node_visibility\":{}}}";
        snprintf(prim, sizeof prim, "%s\"targets\":[{\"POSITION\":%d}],", p0, target);
        size_t cap = strlen(json) + 256;
        char *full = malloc(cap), *at = strstr(json, p0), *at5 = strstr(json, n5);
        REQUIRE(full && at && at5 && at < at5);
        snprintf(full, cap, "%.*s%s%.*s{\"mesh\":0,\"weights\":[0]}%s", (int)(at - json), json,
                 prim, (int)(at5 - at - strlen(p0)), at + strlen(p0), at5 + strlen(n5));
        free(json);
        sr_scene *s = NULL, *posed = NULL;
        sr_io_error e;
        sr_load_desc at1 = { .pose = SR_POSE_ANIMATION, .animation_time = 1 };
        sr_result r = parse(full, &at1, &s, &e);
        if (r != SR_OK) {
            sr_test_fail(__FILE__, __LINE__, "%s", e.message);
        }
        REQUIRE(r == SR_OK);
        REQUIRE(parse(full, NULL, &posed, &e) == SR_OK);
        free(full);
        const float *v0 = positions_of(s, 0), *v5 = positions_of(s, 5);
        REQUIRE(v0 && v5);
        CHECK_NEAR(v0[0], node_too ? 0 : 0.5f, 1e-6);
        CHECK_NEAR(v0[3], node_too ? 1 : 1.5f, 1e-6);
        CHECK_NEAR(v5[0], 0, 0);
        /* sr_scene_pose: the same, and the rest pose's back. */
        REQUIRE(sr_scene_pose(posed, SR_POSE_ANIMATION, 0, 1, &e) == SR_OK);
        const float *p0v = positions_of(posed, 0);
        REQUIRE(p0v);
        CHECK_NEAR(p0v[0], node_too ? 0 : 0.5f, 1e-6);
        REQUIRE(sr_scene_pose(posed, SR_POSE_REST, 0, 0, &e) == SR_OK);
        p0v = positions_of(posed, 0);
        REQUIRE(p0v);
        CHECK_NEAR(p0v[0], 0, 0);
        sr_destroy_scene(sr_test_ctx(), s);
        sr_destroy_scene(sr_test_ctx(), posed);
    }
}

/* KHR_texture_transform's members animated by pointer: the slot a
 * reading of the file with those values gives (its offset converted to
 * sr_texture_slot's v up with the rotation and the scale). */
SR_TEST(texture_transforms_animate_as_the_file_would_write_them)
{
    static const char *const member[3] = { "rotation", "offset", "scale" };
    static const float keys[3][2] = { { 0.5f, 0 }, { 0.3f, 0.4f }, { 1.5f, 0.5f } };
    static const char *const target[3] = {
        "\"offset\":[0.1,0.2],\"rotation\":0.5,\"scale\":[2,3]",
        "\"offset\":[0.3,0.4],\"rotation\":0.25,\"scale\":[2,3]",
        "\"offset\":[0.1,0.2],\"rotation\":0.25,\"scale\":[1.5,0.5]",
    };
    for (int k = 0; k < 3; k++) {
        blob b = { .size = 0 };
        static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, t0[1] = { 0 };
        put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
        int in = put(&b, t0, 1, 4, "SCALAR", 1, 5126, false);
        int out = put(&b, keys[k], k == 0 ? 1 : 2, 4, k == 0 ? "SCALAR" : "VEC2", 1, 5126,
                      false);
        char samplers[128], channels[512] = "", pointer[256], mat[2][256];
        snprintf(samplers, sizeof samplers, "{\"input\":%d,\"output\":%d}", in, out);
        snprintf(pointer, sizeof pointer, "/materials/0/emissiveTexture/extensions/"
                 "KHR_texture_transform/%s", member[k]);
        add_channel(channels, sizeof channels, 0, pointer);
        snprintf(mat[0], sizeof mat[0], "{\"emissiveTexture\":{\"index\":0,\"extensions\":"
                 "{\"KHR_texture_transform\":{\"offset\":[0.1,0.2],\"rotation\":0.25,"
                 "\"scale\":[2,3]}}}}");
        snprintf(mat[1], sizeof mat[1], "{\"emissiveTexture\":{\"index\":0,\"extensions\":"
                 "{\"KHR_texture_transform\":{%s}}}}", target[k]);
        char *animated = scene_json_with(&b, mat[0], samplers, channels);
        char *written = scene_json_with(&b, mat[1], samplers, "");
        REQUIRE(animated && written);
        /* The one without a channel has no animation to carry. */
        strcpy(strstr(written, ",\"animations\""), "}");
        sr_scene *s = NULL, *want = NULL;
        sr_io_error e;
        sr_load_desc at = { .pose = SR_POSE_ANIMATION, .animation_time = 0 };
        REQUIRE(parse(animated, &at, &s, &e) == SR_OK);
        REQUIRE(parse(written, NULL, &want, &e) == SR_OK);
        const sr_texture_slot *got = &s->materials[0].emissive_texture;
        const sr_texture_slot *ref = &want->materials[0].emissive_texture;
        CHECK_NEAR(got->rotation, ref->rotation, 1e-6);
        for (int c = 0; c < 2; c++) {
            CHECK_NEAR(got->offset[c], ref->offset[c], 1e-6);
            CHECK_NEAR(got->scale[c], ref->scale[c], 1e-6);
        }
        free(animated);
        free(written);
        sr_destroy_scene(sr_test_ctx(), s);
        sr_destroy_scene(sr_test_ctx(), want);
    }
}

/* A document of one triangle whose material is `material` (JSON), with
 * one sampler keying its emissive texture's KHR_texture_transform scale
 * to `key` at 0 s; `animated`: the channel to it, else none (the
 * document's animations dropped).  Malloc'd. */
static char *scale_keyed_json(const char *material, const float key[2], bool animated)
{
    blob b = { .size = 0 };
    static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, t0[1] = { 0 };
    put(&b, tri, 9, 4, "VEC3", 3, 5126, false);
    int in = put(&b, t0, 1, 4, "SCALAR", 1, 5126, false);
    int out = put(&b, key, 2, 4, "VEC2", 1, 5126, false);
    char samplers[128], channels[512] = "";
    snprintf(samplers, sizeof samplers, "{\"input\":%d,\"output\":%d}", in, out);
    add_channel(channels, sizeof channels, 0,
                "/materials/0/emissiveTexture/extensions/KHR_texture_transform/scale");
    char *json = scene_json_with(&b, material, samplers, animated ? channels : "");
    if (json && !animated) {
        strcpy(strstr(json, ",\"animations\""), "}");
    }
    return json;
}

/* A texture scaled up from 0 by pointer: at 0 every coordinate lands on
 * the offset's texel (the extension's 0, not sr_texture_slot's zeroed
 * identity). */
SR_TEST(a_texture_scale_animated_to_zero_collapses_onto_the_offset)
{
    static const float zero[2] = { 0, 0 };
    char *json = scale_keyed_json("{\"emissiveTexture\":{\"index\":0,\"extensions\":"
                                  "{\"KHR_texture_transform\":{\"offset\":[0.25,0.5],"
                                  "\"scale\":[2,3]}}}}", zero, true);
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    sr_load_desc at = { .pose = SR_POSE_ANIMATION, .animation_time = 0 };
    REQUIRE(parse(json, &at, &s, &e) == SR_OK);
    const float uv[4] = { 0, 0, 0.9f, 0.3f };
    float got[4];
    REQUIRE(sr_texture_slot_uv(sr_test_ctx(), &s->materials[0].emissive_texture, uv, 2, got) ==
            SR_OK);
    /* glTF's (0.25, 0.5) from the top left is sr_texture's (0.25, 0.5). */
    for (int i = 0; i < 4; i++) {
        CHECK_NEAR(got[i], i & 1 ? 0.5f : 0.25f, 1e-6);
    }
    free(json);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* An offset and a scale each finite whose sum in the slot's convention
 * (offset' = 1 - o.y - s.y cos r) is not: the file's refused with its
 * pointer; an animation's leaves the slot as it was, finite, which the
 * PBR program takes. */
SR_TEST(texture_transforms_that_overflow_a_float_are_refused_or_held)
{
    static const float huge[2] = { 1, 3e38f };
    const char *both = "{\"emissiveTexture\":{\"index\":0,\"extensions\":"
                       "{\"KHR_texture_transform\":{\"offset\":[0,3e38],\"scale\":[1,3e38]}}}}";
    const char *offset = "{\"emissiveTexture\":{\"index\":0,\"extensions\":"
                         "{\"KHR_texture_transform\":{\"offset\":[0,3e38]}}}}";
    char *file = scale_keyed_json(both, huge, false);
    char *animated = scale_keyed_json(offset, huge, true);
    REQUIRE(file && animated);
    sr_scene *s = NULL;
    sr_io_error e;
    CHECK_EQ(parse(file, NULL, &s, &e), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, "t.gltf: /materials/0/emissiveTexture/extensions/"
                                  "KHR_texture_transform: offset (0, 3e+38) and scale (1, 3e+38) "
                                  "overflow a float together");
    sr_load_desc at = { .pose = SR_POSE_ANIMATION, .animation_time = 0 };
    REQUIRE(parse(animated, &at, &s, &e) == SR_OK);
    const sr_texture_slot *got = &s->materials[0].emissive_texture;
    CHECK(isfinite(got->offset[0]) && isfinite(got->offset[1]));
    CHECK_NEAR(got->scale[1], 1, 0);
    CHECK_NEAR(got->offset[1], 1 - 3e38f - 1, 0);
    free(file);
    free(animated);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* ---- softrast render --animation ---------------------------------------- */

/* Three quads in a row: material 0 (red, to blue over 2 s), node 1's
 * green one (visible, STEP hidden from 1 s) and an emissive one (its
 * KHR_materials_emissive_strength 0.5 to 4 over 2 s), and a fourth
 * hidden above.  `posed_at_1_5`: no animation, the values of 1.5 s
 * written in the file instead: color (0.25, 0, 0.75), green hidden,
 * strength 3.125.  Malloc'd. */
static char *row_json(bool posed_at_1_5)
{
    blob b = { .size = 0 };
    static const float quad[12] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    static const uint16_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    static const float t02[2] = { 0, 2 }, t01[2] = { 0, 1 }, color[8] = { 1, 0, 0, 1, 0, 0, 1, 1 };
    static const float power[2] = { 0.5f, 4 };
    static const uint8_t shown[2] = { 1, 0 };
    put(&b, quad, 12, 4, "VEC3", 4, 5126, false);
    put(&b, idx, 6, 2, "SCALAR", 6, 5123, false);
    int in2 = put(&b, t02, 2, 4, "SCALAR", 2, 5126, false);
    int in1 = put(&b, t01, 2, 4, "SCALAR", 2, 5126, false);
    int c = put(&b, color, 8, 4, "VEC4", 2, 5126, false);
    int p = put(&b, power, 2, 4, "SCALAR", 2, 5126, false);
    int v = put(&b, shown, 2, 1, "SCALAR", 2, 5121, false);
    char samplers[512], channels[1024] = "";
    snprintf(samplers, sizeof samplers, "{\"input\":%d,\"output\":%d},{\"input\":%d,"
             "\"output\":%d,\"interpolation\":\"STEP\"},{\"input\":%d,\"output\":%d}",
             in2, c, in1, v, in2, p);
    add_channel(channels, sizeof channels, 0, "/materials/0/pbrMetallicRoughness/baseColorFactor");
    add_channel(channels, sizeof channels, 1, "/nodes/1/extensions/KHR_node_visibility/visible");
    add_channel(channels, sizeof channels, 2,
                "/materials/2/extensions/KHR_materials_emissive_strength/emissiveStrength");
    /* The document scene_json makes, its materials, meshes and nodes
     * replaced by the row's. */
    char *json = scene_json(&b, samplers, channels), *out = json ? malloc(strlen(json) + 2048)
                                                               : NULL;
    if (!out) {
        free(json);
        return NULL;
    }
    char *mats = strstr(json, "\"materials\""), *anims = strstr(json, ",\"animations\"");
    snprintf(out, strlen(json) + 2048,
             "%.*s\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":%s,"
             "\"metallicFactor\":0}},{\"pbrMetallicRoughness\":{\"baseColorFactor\":"
             "[0.2,0.9,0.2,1],\"metallicFactor\":0}},{\"pbrMetallicRoughness\":"
             "{\"baseColorFactor\":[0.9,0.9,0.9,1],\"metallicFactor\":0},\"emissiveFactor\":"
             "[1,0.5,0],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":"
             "%s}}}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
             "\"material\":0}]},{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
             "\"material\":1}]},{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,"
             "\"material\":2}]}],\"nodes\":[{\"mesh\":0,\"translation\":[-2.2,0,0]},"
             "{\"mesh\":1,\"extensions\":{\"KHR_node_visibility\":{\"visible\":%s}}},"
             "{\"mesh\":2,\"translation\":[2.2,0,0]},{\"mesh\":1,\"translation\":[0,2.2,0],"
             "\"extensions\":{\"KHR_node_visibility\":{\"visible\":false}}}],"
             "\"scenes\":[{\"nodes\":[0,1,2,3]}]%s",
             (int)(mats - json), json, posed_at_1_5 ? "[0.25,0,0.75,1]" : "[1,0,0,1]",
             posed_at_1_5 ? "3.125" : "0.5", posed_at_1_5 ? "false" : "true",
             posed_at_1_5 ? "}" : anims);
    free(json);
    return out;
}

static uint8_t *render_row(const char *dir, bool posed, const char *time, int *w, int *h)
{
    char gltf[1100], png[1200];
    snprintf(gltf, sizeof gltf, "%s/row%s.gltf", dir, posed ? "_posed" : time ? "" : "_rest");
    snprintf(png, sizeof png, "%s.png", gltf);
    char *json = row_json(posed);
    bool ok = json && sr_test_write_file(gltf, json, strlen(json));
    free(json);
    run_result r;
    if (!ok) {
        sr_test_fail(__FILE__, __LINE__, "cannot write %s", gltf);
        return NULL;
    }
    return render_read(time ? ARGS("render", gltf, "--animation", "0", "--time", time, "--size",
                                   "160x64", "--camera", "eye=0,0,6,target=0,0,0", "-o", png)
                            : ARGS("render", gltf, "--size", "160x64", "--camera",
                                   "eye=0,0,6,target=0,0,0", "-o", png),
                       png, w, h, &r);
}

/* The animation at 1.5 s draws what the file with 1.5 s's values written
 * in draws, and what tests/ref/gltf_pointer.png keeps (2 codes, 0.5% of
 * the pixels); the rest pose draws something else. */
SR_TEST(render_animation_draws_the_pointer_values_at_the_time)
{
    NEED_CLI();
    char dir[1024];
    fresh_dir("gltf_pointer", dir, sizeof dir);
    int w, h, w2, h2, w3, h3;
    uint8_t *a = render_row(dir, false, "1.5", &w, &h);
    uint8_t *p = render_row(dir, true, NULL, &w2, &h2);
    uint8_t *rest = render_row(dir, false, NULL, &w3, &h3);
    REQUIRE(a && p && rest && w == w2 && h == h2 && w == w3 && h == h3);
    sr_test_check_posed("gltf_pointer", a, p, rest, w, h, 10);
    free(a);
    free(p);
    free(rest);
}

/* A hidden node's light is off (its kind and values kept); cameras are
 * not affected by visibility. */
SR_TEST(a_hidden_node_turns_its_light_off)
{
    char *json = animated_json();
    REQUIRE(json);
    const char *lit = "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}";
    const char *dark = "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0},"
                       "\"KHR_node_visibility\":{\"visible\":false}}}";
    char *at = strstr(json, lit);
    REQUIRE(at);
    size_t n = strlen(json) + strlen(dark);
    char *hidden = malloc(n);
    REQUIRE(hidden);
    snprintf(hidden, n, "%.*s%s%s", (int)(at - json), json, dark, at + strlen(lit));
    free(json);
    sr_scene *s = NULL;
    sr_io_error e;
    sr_load_desc at_1 = { .pose = SR_POSE_ANIMATION, .animation_time = 1 };
    REQUIRE(parse(hidden, &at_1, &s, &e) == SR_OK);
    free(hidden);
    REQUIRE(s->light_count == 1);
    CHECK_EQ(s->lights[0].light.type, SR_LIGHT_OFF);
    CHECK_EQ(s->lights[0].type, SR_LIGHT_POINT);
    CHECK_NEAR(s->lights[0].light.intensity, 20, 1e-5);
    CHECK_EQ(s->camera_count, 1);
    sr_destroy_scene(sr_test_ctx(), s);
}
