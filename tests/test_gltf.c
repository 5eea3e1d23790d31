/* test_gltf.c - the glTF 2.0 reader behind sr_load_scene: node
 * hierarchies, accessors of every kind (quantized, normalized, strided,
 * sparse), primitive modes, materials with texture transforms and
 * samplers, cameras, external files, GLB, and one message naming the JSON
 * pointer for each kind of malformed file. */
#include "glb_write.h"
#include "gltf_parse.h"
#include "gltf_write.h"
#include "sr_test.h"
#include "wbuf.h"

#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Every test here reads glTF. */
SR_TEST_NEEDS(sr_io_have_gltf, "softrast was built without jansson (glTF)")

/* A document whose buffer 0 holds bin (a data URI); `body` is the rest of
 * the top-level object, starting with a comma.  malloc'd. */
static char *doc(const void *bin, size_t n, const char *body)
{
    char *b64 = malloc(4 * (n / 3 + 1) + 1);
    size_t cap = 4 * (n / 3 + 1) + strlen(body) + 200;
    char *json = malloc(cap);
    gltf_base64(bin, n, b64);
    snprintf(json, cap,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu,"
             "\"uri\":\"data:application/octet-stream;base64,%s\"}]%s}",
             n, b64, body);
    free(b64);
    return json;
}


/* bin and body as a document, parsed; NULL (a failed check) when it
 * does not parse. */
static sr_scene *load_doc(const void *bin, size_t n, const char *body, warnings *w)
{
    char *json = doc(bin, n, body);
    sr_io_error e;
    sr_scene *s = NULL;
    if (parse(json, w, &s, &e) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s", e.message);
    }
    free(json);
    return s;
}

static const float tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };

/* tri as a glTF buffer holds it (little-endian). */
static const uint8_t *tri_le(void)
{
    static uint8_t b[sizeof tri];
    le_copy(b, tri, 9, 4);
    return b;
}
/* tri's buffer view and accessor 0, for documents that write their own
 * meshes. */
#define TRI_ACCESSOR \
    ",\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}]," \
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}]"
static const char tri_mesh[] =
    TRI_ACCESSOR ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]";

SR_TEST(node_hierarchy_composes_transforms_and_flags_mirroring)
{
    char body[2048];
    snprintf(body, sizeof body,
             "%s,\"nodes\":[{\"translation\":[1,0,0],\"children\":[1]},"
             "{\"scale\":[-1,1,1],\"mesh\":0},"
             "{\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,2,0,1],\"children\":[3]},"
             "{\"rotation\":[0,0,0.70710678,0.70710678],\"mesh\":0}],"
             "\"scenes\":[{\"nodes\":[0,2]}],\"scene\":0",
             tri_mesh);
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 2);
    const sr_scene_primitive *a = &s->primitives[0], *b = &s->primitives[1];
    CHECK_EQ(a->node, 1);
    CHECK(a->mirrored);
    CHECK_NEAR(a->world[0], -1, 1e-6);
    CHECK_NEAR(a->world[12], 1, 1e-6);
    CHECK_EQ(b->node, 3);
    CHECK(!b->mirrored);
    /* T(0, 2, 0) Rz(90 degrees): x goes to y. */
    CHECK_NEAR(b->world[0], 0, 1e-6);
    CHECK_NEAR(b->world[1], 1, 1e-6);
    CHECK_NEAR(b->world[4], -1, 1e-6);
    CHECK_NEAR(b->world[13], 2, 1e-6);
    CHECK(a->positions == b->positions);   /* one mesh, two instances */
    CHECK_EQ(a->triangle_count, 1);
    CHECK_EQ(a->indices[0], 0);
    CHECK_EQ(a->indices[2], 2);
    CHECK_EQ(a->normals, NULL);
    /* Bounds: (0..1, 0..1) from node 1, (-1..0, 2..3) from node 3. */
    CHECK_NEAR(s->bounds_min.x, -1, 1e-6);
    CHECK_NEAR(s->bounds_min.y, 0, 1e-6);
    CHECK_NEAR(s->bounds_max.x, 1, 1e-6);
    CHECK_NEAR(s->bounds_max.y, 3, 1e-6);
    CHECK_EQ(s->material_count, 1);            /* the default one */
    CHECK_EQ(a->material, 0);
    CHECK_EQ(s->materials[0].metallic, 1.0f);
    CHECK_EQ(w.count, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(the_scene_property_picks_the_scene_drawn)
{
    char body[1024];
    snprintf(body, sizeof body,
             "%s,\"nodes\":[{\"mesh\":0},{\"mesh\":0,\"translation\":[0,0,7]}],"
             "\"scenes\":[{\"nodes\":[0]},{\"nodes\":[1]}],\"scene\":1",
             tri_mesh);
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 1);
    CHECK_EQ(s->primitives[0].node, 1);
    CHECK_NEAR(s->bounds_min.z, 7, 0);
    sr_destroy_scene(sr_test_ctx(), s);
    /* No scenes: every root node; whole reals taken as integers. */
    snprintf(body, sizeof body,
             "%s,\"nodes\":[{\"mesh\":0.0,\"children\":[1]},{\"mesh\":0},{\"mesh\":0}]",
             tri_mesh);
    s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 3);
    CHECK_EQ(s->primitives[0].node, 0);
    CHECK_EQ(s->primitives[1].node, 1);
    CHECK_EQ(s->primitives[2].node, 2);
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(quantized_and_normalized_attributes_are_decoded)
{
    uint8_t bin[72] = {0};
    int16_t pos[12] = { 32767, 0, 0, 0, 0, -32767, 0, 0, 0, 0, -32768, 0 };  /* stride 8 */
    int8_t nrm[12] = { 127, 0, 0, 0, 0, -127, 0, 0, 0, 0, -128, 0 };        /* stride 4 */
    uint8_t uv0[12] = { 255, 0, 0, 0, 0, 255, 0, 0, 51, 102, 0, 0 };
    uint8_t col[12] = { 255, 0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0 };
    int16_t uv1[6] = { 2, 0, 0, 3, 1, 1 };
    le_copy(bin, pos, 12, 2);
    memcpy(bin + 24, nrm, 12);
    memcpy(bin + 36, uv0, 12);
    memcpy(bin + 48, col, 12);
    le_copy(bin + 60, uv1, 6, 2);
    const char *body =
        ",\"extensionsUsed\":[\"KHR_mesh_quantization\"],"
        "\"extensionsRequired\":[\"KHR_mesh_quantization\"],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":24,\"byteStride\":8},"
        "{\"buffer\":0,\"byteOffset\":24,\"byteLength\":36,\"byteStride\":4},"
        "{\"buffer\":0,\"byteOffset\":60,\"byteLength\":12,\"byteStride\":4}],"
        "\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5122,\"normalized\":true,\"count\":3,"
        "\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5120,\"normalized\":true,\"count\":3,"
        "\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"byteOffset\":12,\"componentType\":5121,\"normalized\":true,"
        "\"count\":3,\"type\":\"VEC2\"},"
        "{\"bufferView\":1,\"byteOffset\":24,\"componentType\":5121,\"normalized\":true,"
        "\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5122,\"count\":3,\"type\":\"VEC2\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
        "\"TEXCOORD_0\":2,\"COLOR_0\":3,\"TEXCOORD_1\":4}}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]";
    warnings w = {0};
    sr_scene *s = load_doc(bin, sizeof bin, body, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 1);
    const sr_scene_primitive *p = &s->primitives[0];
    static const float want_pos[9] = { 1, 0, 0, 0, -1, 0, 0, 0, -1 };   /* -32768 clamps */
    for (int i = 0; i < 9; i++) {
        CHECK_NEAR(p->positions[i], want_pos[i], 1e-6);
        CHECK_NEAR(p->normals[i], want_pos[i], 1e-6);
    }
    /* v flipped to sr_make_texture's convention. */
    static const float want_uv0[6] = { 1, 1, 0, 0, 0.2f, 0.6f };
    static const float want_uv1[6] = { 2, 1, 0, -2, 1, 0 };
    for (int i = 0; i < 6; i++) {
        CHECK_NEAR(p->texcoords0[i], want_uv0[i], 1e-6);
        CHECK_NEAR(p->texcoords1[i], want_uv1[i], 1e-6);
    }
    static const float want_col[12] = { 1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1 };
    for (int i = 0; i < 12; i++) {
        CHECK_NEAR(p->colors[i], want_col[i], 1e-6);
    }
    sr_destroy_scene(sr_test_ctx(), s);
}

/* Float attributes interleaved in one view (32 bytes a vertex: position,
 * normal, texture coordinates) and indices of unsigned ints and shorts
 * from an offset in their views: each element from its own place. */
SR_TEST(interleaved_floats_and_offset_indices_are_read_in_place)
{
    enum { STRIDE = 32 };
    uint8_t bin[3 * STRIDE + 4 + 12 + 2 + 6] = {0};
    for (int v = 0; v < 3; v++) {
        float pos[3] = { (float)v, 10.0f + v, -0.5f * v };
        float nrm[3] = { v == 0, v == 1, v == 2 };
        float uv[2] = { 0.25f * v, 1.0f - 0.125f * v };
        le_copy(bin + STRIDE * v, pos, 3, 4);
        le_copy(bin + STRIDE * v + 12, nrm, 3, 4);
        le_copy(bin + STRIDE * v + 24, uv, 2, 4);
    }
    const uint32_t i32[3] = { 2, 1, 0 };
    const uint16_t i16[3] = { 1, 2, 0 };
    le_copy(bin + 3 * STRIDE + 4, i32, 3, 4);
    le_copy(bin + 3 * STRIDE + 4 + 12 + 2, i16, 3, 2);
    char body[2000];
    snprintf(body, sizeof body,
             ",\"bufferViews\":[{\"buffer\":0,\"byteLength\":%d,\"byteStride\":%d},"
             "{\"buffer\":0,\"byteOffset\":%d,\"byteLength\":24}],"
             "\"accessors\":["
             "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
             "\"min\":[0,10,-1],\"max\":[2,12,0]},"
             "{\"bufferView\":0,\"byteOffset\":12,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\"},"
             "{\"bufferView\":0,\"byteOffset\":24,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC2\"},"
             "{\"bufferView\":1,\"byteOffset\":4,\"componentType\":5125,\"count\":3,"
             "\"type\":\"SCALAR\"},"
             "{\"bufferView\":1,\"byteOffset\":18,\"componentType\":5123,\"count\":3,"
             "\"type\":\"SCALAR\"}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
             "\"TEXCOORD_0\":2},\"indices\":3},{\"attributes\":{\"POSITION\":0},"
             "\"indices\":4}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]",
             3 * STRIDE, STRIDE, 3 * STRIDE);
    warnings w = {0};
    sr_scene *s = load_doc(bin, sizeof bin, body, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 2);
    for (int k = 0; k < 2; k++) {
        const sr_scene_primitive *p = &s->primitives[k];
        REQUIRE(p->vertex_count == 3 && p->triangle_count == 1);
        for (int v = 0; v < 3; v++) {
            CHECK_EQ(p->positions[3 * v], (float)v);
            CHECK_EQ(p->positions[3 * v + 1], 10.0f + v);
            CHECK_EQ(p->positions[3 * v + 2], -0.5f * v);
            CHECK_EQ(p->indices[v], k == 0 ? i32[v] : i16[v]);
        }
    }
    const sr_scene_primitive *p = &s->primitives[0];
    for (int v = 0; v < 3; v++) {
        for (int c = 0; c < 3; c++) {
            CHECK_EQ(p->normals[3 * v + c], (float)(v == c));
        }
        /* v flipped to sr_make_texture's convention. */
        CHECK_EQ(p->texcoords0[2 * v], 0.25f * v);
        CHECK_EQ(p->texcoords0[2 * v + 1], 0.125f * v);
    }
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(sparse_accessors_replace_elements_with_or_without_a_buffer_view)
{
    uint8_t bin[64] = {0};
    memcpy(bin, tri_le(), 36);
    bin[36] = 2;                                     /* sparse index, UNSIGNED_BYTE */
    const float v[3] = { 5, 6, 7 };
    le_copy(bin + 40, v, 3, 4);
    const uint16_t uv_index = 1;
    le_copy(bin + 52, &uv_index, 1, 2);
    const float uv[2] = { 0.5f, 0.25f };
    le_copy(bin + 56, uv, 2, 4);
    const char *body =
        ",\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
        "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":1},"
        "{\"buffer\":0,\"byteOffset\":40,\"byteLength\":12},"
        "{\"buffer\":0,\"byteOffset\":52,\"byteLength\":2},"
        "{\"buffer\":0,\"byteOffset\":56,\"byteLength\":8}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
        "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5121},"
        "\"values\":{\"bufferView\":2}}},"
        "{\"componentType\":5126,\"count\":3,\"type\":\"VEC2\","
        "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":3,\"componentType\":5123},"
        "\"values\":{\"bufferView\":4}}}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1}}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]";
    warnings w = {0};
    sr_scene *s = load_doc(bin, sizeof bin, body, &w);
    REQUIRE(s);
    const sr_scene_primitive *p = &s->primitives[0];
    static const float want[9] = { 0, 0, 0, 1, 0, 0, 5, 6, 7 };
    for (int i = 0; i < 9; i++) {
        CHECK_EQ(p->positions[i], want[i]);
    }
    static const float want_uv[6] = { 0, 1, 0.5f, 0.75f, 0, 1 };   /* v flipped */
    for (int i = 0; i < 6; i++) {
        CHECK_EQ(p->texcoords0[i], want_uv[i]);
    }
    sr_destroy_scene(sr_test_ctx(), s);
}

/* glTF asks for strictly increasing sparse indices: a repeated or
 * decreasing one is refused, naming it, rather than left to the order
 * the substitution happens to run in. */
SR_TEST(sparse_indices_that_do_not_increase_are_refused)
{
    static const uint8_t orders[][2] = { { 2, 2 }, { 2, 1 }, { 1, 2 } };
    for (int o = 0; o < 3; o++) {
        uint8_t bin[64] = {0};
        memcpy(bin, tri_le(), 36);
        bin[36] = orders[o][0];
        bin[37] = orders[o][1];
        const float v[6] = { 5, 6, 7, 8, 9, 10 };
        le_copy(bin + 40, v, 6, 4);
        const char *body =
            ",\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
            "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":2},"
            "{\"buffer\":0,\"byteOffset\":40,\"byteLength\":24}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
            "\"type\":\"VEC3\",\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":1,"
            "\"componentType\":5121},\"values\":{\"bufferView\":2}}}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
            "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]";
        char *json = doc(bin, sizeof bin, body);
        sr_scene *s = NULL;
        sr_io_error e;
        warnings w = {0};
        sr_result r = parse(json, &w, &s, &e);
        free(json);
        if (orders[o][1] > orders[o][0]) {
            CHECK_EQ(r, SR_OK);
            if (s) {
                CHECK_EQ(s->primitives[0].positions[3], 5);   /* vertex 1 */
                CHECK_EQ(s->primitives[0].positions[8], 10);  /* vertex 2 */
            }
            sr_destroy_scene(sr_test_ctx(), s);
            continue;
        }
        CHECK_EQ(r, SR_BAD_FORMAT);
        CHECK(s == NULL);
        char want[200];
        snprintf(want, sizeof want,
                 "t.gltf: /accessors/0/sparse/indices: index 1 is %d, not above index 0 (2): "
                 "sparse indices must strictly increase", orders[o][1]);
        CHECK_STR_CONTAINS(e.message, want);
    }
}

/* A node with both `matrix` and translation/rotation/scale, which glTF
 * forbids, is drawn with its matrix after one warning naming the node, as
 * three.js and Blender draw it. */
SR_TEST(a_node_with_matrix_and_trs_uses_the_matrix_with_a_warning)
{
    char body[1024];
    snprintf(body, sizeof body,
             "%s,\"nodes\":[{\"mesh\":0,\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,2,0,1],"
             "\"translation\":[5,0,0],\"scale\":[3,3,3]}],\"scenes\":[{\"nodes\":[0]}]",
             tri_mesh);
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    CHECK_NEAR(s->primitives[0].world[0], 1, 1e-6);
    CHECK_NEAR(s->primitives[0].world[12], 0, 1e-6);
    CHECK_NEAR(s->primitives[0].world[13], 2, 1e-6);
    CHECK_EQ(w.count, 1);
    CHECK_STR_CONTAINS(w.last, "t.gltf: warning: /nodes/0: both matrix and translation (glTF "
                               "allows one): the matrix is used");
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(strips_and_fans_become_triangles_and_points_are_skipped)
{
    const float quad[12] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
    const char *body =
        ",\"bufferViews\":[{\"buffer\":0,\"byteLength\":48}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"mode\":5},"
        "{\"attributes\":{\"POSITION\":0},\"mode\":6},"
        "{\"attributes\":{\"POSITION\":0},\"mode\":0}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]";
    uint8_t bin[sizeof quad];
    le_copy(bin, quad, 12, 4);
    warnings w = {0};
    sr_scene *s = load_doc(bin, sizeof bin, body, &w);
    REQUIRE(s);
    REQUIRE(s->primitive_count == 2);
    static const uint32_t strip[6] = { 0, 1, 2, 1, 3, 2 }, fan[6] = { 1, 2, 0, 2, 3, 0 };
    CHECK_EQ(s->primitives[0].triangle_count, 2);
    CHECK_EQ(s->primitives[1].triangle_count, 2);
    for (int i = 0; i < 6; i++) {
        CHECK_EQ(s->primitives[0].indices[i], strip[i]);
        CHECK_EQ(s->primitives[1].indices[i], fan[i]);
    }
    CHECK_EQ(w.count, 1);
    CHECK_EQ(s->warning_count, 1);
    CHECK_STR_CONTAINS(w.last, "t.gltf: warning: /meshes/0/primitives/2/mode: points and lines");
    sr_destroy_scene(sr_test_ctx(), s);
}

/* A 2x2 PNG in memory. */
static bool collect(void *user, const void *data, size_t size)
{
    wb_put(user, data, size);
    return true;
}

static wbuf small_png(void)
{
    static const uint8_t rgba[16] = { 255, 0, 0, 255, 0, 255, 0, 255,
                                      0, 0, 255, 255, 255, 255, 255, 255 };
    wbuf b = {0};
    sr_io_error e;
    sr_encode_png(collect, &b, 2, 2, rgba, 8, NULL, &e);
    return b;
}

/* small_png() as base64 for a data: URI; malloc'd, NULL if it failed. */
static char *small_png_base64(void)
{
    wbuf png = small_png();
    char *b64 = png.n > 0 ? malloc(4 * (png.n / 3 + 1) + 1) : NULL;
    if (b64) {
        gltf_base64(png.p, png.n, b64);
    }
    free(png.p);
    return b64;
}

SR_TEST(texture_transform_sampler_and_uv_set_reach_the_slot)
{
    char *b64 = small_png_base64();
    REQUIRE(b64);
    char *body = malloc(strlen(b64) + 4096);
    sprintf(body,
            "%s,\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
            "\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
            "\"samplers\":[{\"magFilter\":9728,\"minFilter\":9728,\"wrapS\":33071,"
            "\"wrapT\":33648}],"
            "\"textures\":[{\"source\":0,\"sampler\":0},{\"source\":0}],"
            "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0,"
            "\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.5,0.25],"
            "\"rotation\":0.5,\"scale\":[2,3],\"texCoord\":1}}},"
            "\"metallicRoughnessTexture\":{\"index\":1}},"
            "\"emissiveTexture\":{\"index\":1}}]",
            TRI_ACCESSOR ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
            "\"material\":0}]}]", b64);
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    REQUIRE(s->material_count == 2);
    const sr_pbr_material *m = &s->materials[0];
    const sr_texture_slot *t = &m->base_color_texture;
    REQUIRE(t->texture != NULL);
    CHECK_EQ(t->texcoord, 1);                    /* the extension's texCoord wins */
    CHECK_EQ(t->filter, SR_FILTER_NEAREST);
    CHECK_EQ(t->wrap_u, SR_WRAP_CLAMP);
    CHECK_EQ(t->wrap_v, SR_WRAP_MIRROR);
    CHECK_NEAR(t->rotation, 0.5, 1e-6);
    CHECK_NEAR(t->scale[0], 2, 0);
    CHECK_NEAR(t->scale[1], 3, 0);
    /* The slot's transform in flipped space agrees with glTF's in its
     * own: for a few uv, flip(T R S (uv)) == T' R' S' (flip(uv)), with
     * glTF's R = [c s; -s c] and the slot's counter-clockwise [c -s; s c]. */
    const float uvs[3][2] = { { 0, 0 }, { 1, 0.25f }, { 0.3f, 0.9f } };
    for (int i = 0; i < 3; i++) {
        float su = 2 * uvs[i][0], sv = 3 * uvs[i][1], c = cosf(0.5f), sn = sinf(0.5f);
        float gu = c * su + sn * sv + 0.5f, gv = -sn * su + c * sv + 0.25f;
        float fu = t->scale[0] * uvs[i][0], fv = t->scale[1] * (1 - uvs[i][1]);
        float ou = c * fu - sn * fv + t->offset[0], ov = sn * fu + c * fv + t->offset[1];
        CHECK_NEAR(ou, gu, 1e-5);
        CHECK_NEAR(ov, 1 - gv, 1e-5);
    }
    /* Samplerless texture: defaults; the image as sRGB (base color,
     * emissive: one texture) and linear (metallic-roughness). */
    CHECK_EQ(m->emissive_texture.texture, t->texture);
    CHECK(m->metallic_roughness_texture.texture != t->texture);
    CHECK_EQ(m->metallic_roughness_texture.filter, SR_FILTER_DEFAULT);
    CHECK_EQ(m->emissive_texture.scale[0], 1.0f);
    CHECK_EQ(m->emissive_texture.offset[1], 0.0f);   /* identity stays identity */
    CHECK_EQ(s->texture_count, 2);
    /* The triangle has no texture coordinates: its textures cannot be
     * mapped, which one warning says (of the first set missing). */
    CHECK_EQ(w.count, 1);
    CHECK(strcmp(w.last, "t.gltf: warning: /meshes/0/primitives/0/attributes: no TEXCOORD_1, "
                         "which material 0's textures read (drawn with one color of the "
                         "texture)") == 0);
    sr_destroy_scene(sr_test_ctx(), s);
    free(body);
    free(b64);
}

SR_TEST(material_factors_and_extensions_are_read)
{
    char body[2048];
    snprintf(body, sizeof body,
             "%s,\"nodes\":[{\"mesh\":0},{\"mesh\":1}],\"scenes\":[{\"nodes\":[0,1]}],"
             "\"extensionsUsed\":[\"KHR_materials_unlit\",\"EXT_whatever\"],"
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.1,0.2,0.3,0.4],"
             "\"metallicFactor\":0.25,\"roughnessFactor\":0.75},"
             "\"emissiveFactor\":[1,0.5,0],\"alphaMode\":\"MASK\",\"alphaCutoff\":0.3,"
             "\"doubleSided\":true,\"extensions\":{\"KHR_materials_emissive_strength\":"
             "{\"emissiveStrength\":4},\"KHR_materials_unlit\":{},\"EXT_whatever\":{}}},"
             "{\"alphaMode\":\"BLEND\"},{\"alphaMode\":\"MASK\",\"alphaCutoff\":0,"
             "\"emissiveFactor\":[1,1,1],\"extensions\":{\"KHR_materials_emissive_strength\":"
             "{\"emissiveStrength\":0}}}]",
             "");
    /* Two meshes: one with material 0, one with none. */
    char full[4096];
    snprintf(full, sizeof full,
             ",\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\"}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]},"
             "{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]%s",
             body);
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, full, &w);
    REQUIRE(s);
    REQUIRE(s->material_count == 4);
    REQUIRE(s->primitive_count == 2);
    const sr_pbr_material *m = &s->materials[s->primitives[0].material];
    CHECK_NEAR(m->base_color[2], 0.3, 1e-6);
    CHECK_NEAR(m->base_color[3], 0.4, 1e-6);
    CHECK_NEAR(m->metallic, 0.25, 0);
    CHECK_NEAR(m->roughness, 0.75, 0);
    CHECK_NEAR(m->emissive[1], 0.5, 0);
    CHECK_NEAR(m->emissive_strength, 4, 0);
    CHECK_EQ(m->alpha_mode, SR_ALPHA_MASK);
    CHECK_NEAR(m->alpha_cutoff, 0.3, 1e-6);
    CHECK(m->double_sided);
    CHECK(m->unlit);
    CHECK_EQ(s->materials[1].alpha_mode, SR_ALPHA_BLEND);
    CHECK(!s->materials[1].unlit);
    /* A cutoff of 0 keeps every fragment (opaque); a strength of 0 is
     * kept as set (no emission), with the file's factor. */
    CHECK_EQ(s->materials[2].alpha_mode, SR_ALPHA_OPAQUE);
    CHECK_EQ(s->materials[2].emissive[0], 1.0f);
    CHECK_EQ(s->materials[2].emissive_strength, 0.0f);
    CHECK(s->materials[2].emissive_strength_set);
    /* No material: glTF's default, white, metallic and rough. */
    CHECK_EQ(s->primitives[1].material, 3);
    const sr_pbr_material *d = &s->materials[3];
    CHECK_EQ(d->base_color[0], 1.0f);
    CHECK_EQ(d->metallic, 1.0f);
    CHECK_EQ(d->roughness, 1.0f);
    CHECK_EQ(d->alpha_mode, SR_ALPHA_OPAQUE);
    /* The extension not read is named, the one read is not. */
    CHECK_EQ(w.count, 1);
    CHECK(strcmp(w.last, "t.gltf: warning: not read, the scene is drawn without them: "
                         "/extensionsUsed/1 (EXT_whatever)") == 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* Factors outside the specification's ranges are clamped into them, each
 * with a warning naming it: a metallic of 5 drew black, a negative
 * emission took light away. */
SR_TEST(material_factors_out_of_range_are_clamped_with_a_warning)
{
    const char body[] =
        TRI_ACCESSOR
        ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
        "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[2,-1,0.5,1.0000000001],"
        "\"metallicFactor\":5},\"emissiveFactor\":[1,1,1],"
        "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":-3}}}]";
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    const sr_pbr_material *m = &s->materials[0];
    CHECK_EQ(m->base_color[0], 1.0f);
    CHECK_EQ(m->base_color[1], 0.0f);
    CHECK_EQ(m->base_color[2], 0.5f);
    CHECK_EQ(m->base_color[3], 1.0f);
    CHECK_EQ(m->metallic, 1.0f);
    CHECK(m->emissive_strength >= 0.0f);
    /* Strength clamped to 0: no emission. */
    CHECK_EQ(m->emissive[0] * m->emissive_strength, 0.0f);
    CHECK_EQ(w.count, 4);   /* the rounding of 1.0000000001 says nothing */
    CHECK(strcmp(w.last, "t.gltf: warning: /materials/0/extensions/"
                         "KHR_materials_emissive_strength/emissiveStrength: -3 is negative, "
                         "taken as 0") == 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* KHR_materials_ior, _specular, _clearcoat and _sheen reach the material
 * with their textures (through the slots, KHR_texture_transform
 * included) and each extension's defaults; out-of-range factors are
 * clamped with a warning each; a material without them keeps zeros
 * (absent); none of them is named among the extensions not read. */
SR_TEST(physically_based_extensions_are_read)
{
    char *b64 = small_png_base64();
    REQUIRE(b64);
    char *body = malloc(strlen(b64) + 4096);
    sprintf(body,
            "%s,\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
            "\"extensionsUsed\":[\"KHR_materials_ior\",\"KHR_materials_specular\","
            "\"KHR_materials_clearcoat\",\"KHR_materials_sheen\"],"
            "\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
            "\"textures\":[{\"source\":0}],"
            "\"materials\":[{\"extensions\":{"
            "\"KHR_materials_ior\":{\"ior\":1.33},"
            "\"KHR_materials_specular\":{\"specularFactor\":0.5,"
            "\"specularColorTexture\":{\"index\":0}},"
            "\"KHR_materials_clearcoat\":{\"clearcoatFactor\":0.75,"
            "\"clearcoatRoughnessFactor\":0.25,\"clearcoatNormalTexture\":{\"index\":0,"
            "\"scale\":0.5,\"extensions\":{\"KHR_texture_transform\":{\"scale\":[2,2]}}}},"
            "\"KHR_materials_sheen\":{\"sheenColorFactor\":[0.5,0.25,1],"
            "\"sheenRoughnessTexture\":{\"index\":0}}}},"
            "{\"extensions\":{\"KHR_materials_ior\":{},\"KHR_materials_specular\":{},"
            "\"KHR_materials_clearcoat\":{},\"KHR_materials_sheen\":{}}},"
            "{\"extensions\":{\"KHR_materials_ior\":{\"ior\":0.5},"
            "\"KHR_materials_specular\":{\"specularFactor\":2,\"specularColorFactor\":[-1,1,3]},"
            "\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1.5,"
            "\"clearcoatRoughnessFactor\":-1},"
            "\"KHR_materials_sheen\":{\"sheenColorFactor\":[2,0,0],\"sheenRoughnessFactor\":3}}},"
            "{}]",
            TRI_ACCESSOR ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]",
            b64);
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    REQUIRE(s->material_count == 5);
    const sr_pbr_material *m = &s->materials[0];
    CHECK_NEAR(m->ior, 1.33, 1e-6);
    CHECK(m->specular_set);
    CHECK_NEAR(m->specular, 0.5, 0);
    CHECK_EQ(m->specular_color[2], 1.0f);
    REQUIRE(m->specular_color_texture.texture != NULL);
    CHECK(m->specular_texture.texture == NULL);
    CHECK_NEAR(m->clearcoat, 0.75, 0);
    CHECK_NEAR(m->clearcoat_roughness, 0.25, 0);
    REQUIRE(m->clearcoat_normal_texture.texture != NULL);
    CHECK_NEAR(m->clearcoat_normal_scale, 0.5, 0);
    CHECK_NEAR(m->clearcoat_normal_texture.scale[0], 2, 0);
    /* The color textures are sRGB, the others linear: two textures. */
    CHECK(m->clearcoat_normal_texture.texture != m->specular_color_texture.texture);
    CHECK_EQ(m->sheen_roughness_texture.texture, m->clearcoat_normal_texture.texture);
    CHECK_NEAR(m->sheen_color[1], 0.25, 0);
    CHECK_EQ(m->sheen_roughness, 0.0f);
    /* Present but empty: the extensions' defaults. */
    const sr_pbr_material *e = &s->materials[1];
    CHECK_NEAR(e->ior, 1.5, 0);
    CHECK(e->specular_set);
    CHECK_EQ(e->specular, 1.0f);
    CHECK_EQ(e->specular_color[0], 1.0f);
    CHECK_EQ(e->clearcoat, 0.0f);
    CHECK_EQ(e->sheen_color[0], 0.0f);
    /* Clamped, one warning per factor. */
    const sr_pbr_material *c = &s->materials[2];
    CHECK_EQ(c->ior, 1.0f);
    CHECK_EQ(c->specular, 1.0f);
    CHECK_EQ(c->specular_color[0], 0.0f);
    CHECK_EQ(c->specular_color[2], 3.0f);
    CHECK_EQ(c->clearcoat, 1.0f);
    CHECK_EQ(c->clearcoat_roughness, 0.0f);
    CHECK_EQ(c->sheen_color[0], 1.0f);
    CHECK_EQ(c->sheen_roughness, 1.0f);
    /* Absent: zeros. */
    const sr_pbr_material *a = &s->materials[3];
    CHECK(a->ior == 0.0f && !a->specular_set && a->clearcoat == 0.0f &&
          a->sheen_color[0] == 0.0f && a->clearcoat_normal_scale == 0.0f);
    CHECK_EQ(w.count, 7);
    CHECK_STR_CONTAINS(w.last, "/materials/2/extensions/KHR_materials_sheen/"
                               "sheenRoughnessFactor: 3 is outside the specification's 0..1, "
                               "taken as 1");
    sr_destroy_scene(sr_test_ctx(), s);
    free(body);
    free(b64);
}

/* A one-triangle document whose image 0 and texture 0 are a small PNG,
 * with extensionsUsed `used` and the materials array `materials`. */
static sr_scene *load_textured(const char *used, const char *materials, warnings *w)
{
    char *b64 = small_png_base64();
    if (!b64) {
        return NULL;
    }
    size_t n = strlen(b64) + strlen(used) + strlen(materials) + 1024;
    char *body = malloc(n);
    if (!body) {
        free(b64);
        return NULL;
    }
    snprintf(body, n,
             "%s,\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"extensionsUsed\":%s,"
             "\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
             "\"textures\":[{\"source\":0}],\"materials\":%s",
             TRI_ACCESSOR ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]",
             used, b64, materials);
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, w);
    free(body);
    free(b64);
    return s;
}

/* KHR_materials_anisotropy and _iridescence: factors, the textures
 * through the slots (KHR_texture_transform included), the defaults of a
 * present but empty extension (iridescence 0, its ior 1.3 and 100..400
 * nm); out-of-range factors clamped with one warning each; a film of no
 * thickness keeps its factor and its 0 nm (iridescence_thickness_set);
 * absent, the zeros; neither is named
 * among the extensions not read. */
SR_TEST(anisotropy_and_iridescence_are_read)
{
    warnings w = {0};
    sr_scene *s = load_textured(
        "[\"KHR_materials_anisotropy\",\"KHR_materials_iridescence\"]",
        "[{\"extensions\":{"
        "\"KHR_materials_anisotropy\":{\"anisotropyStrength\":0.6,"
        "\"anisotropyRotation\":1.25,\"anisotropyTexture\":{\"index\":0,"
        "\"extensions\":{\"KHR_texture_transform\":{\"scale\":[3,3]}}}},"
        "\"KHR_materials_iridescence\":{\"iridescenceFactor\":0.5,"
        "\"iridescenceIor\":1.8,\"iridescenceThicknessMinimum\":50,"
        "\"iridescenceThicknessMaximum\":800,\"iridescenceTexture\":{\"index\":0},"
        "\"iridescenceThicknessTexture\":{\"index\":0}}}},"
        "{\"extensions\":{\"KHR_materials_anisotropy\":{},"
        "\"KHR_materials_iridescence\":{}}},"
        "{\"extensions\":{\"KHR_materials_anisotropy\":{\"anisotropyStrength\":1.5},"
        "\"KHR_materials_iridescence\":{\"iridescenceFactor\":-1,\"iridescenceIor\":0.5,"
        "\"iridescenceThicknessMaximum\":-20}}},"
        "{\"extensions\":{\"KHR_materials_iridescence\":{\"iridescenceFactor\":1,"
        "\"iridescenceThicknessMaximum\":0}}},"
        "{}]",
        &w);
    REQUIRE(s);
    REQUIRE(s->material_count == 6);
    const sr_pbr_material *m = &s->materials[0];
    CHECK_NEAR(m->anisotropy_strength, 0.6, 1e-7);
    CHECK_NEAR(m->anisotropy_rotation, 1.25, 0);
    REQUIRE(m->anisotropy_texture.texture != NULL);
    CHECK_NEAR(m->anisotropy_texture.scale[0], 3, 0);
    CHECK_NEAR(m->iridescence, 0.5, 0);
    CHECK_NEAR(m->iridescence_ior, 1.8, 1e-7);
    CHECK_NEAR(m->iridescence_thickness_min, 50, 0);
    CHECK_NEAR(m->iridescence_thickness_max, 800, 0);
    /* Linear, all three: one texture. */
    CHECK_EQ(m->iridescence_texture.texture, m->anisotropy_texture.texture);
    CHECK_EQ(m->iridescence_thickness_texture.texture, m->anisotropy_texture.texture);
    const sr_pbr_material *e = &s->materials[1];
    CHECK_EQ(e->anisotropy_strength, 0.0f);
    CHECK_EQ(e->iridescence, 0.0f);
    CHECK_NEAR(e->iridescence_ior, 1.3, 1e-7);
    CHECK_EQ(e->iridescence_thickness_min, 100.0f);
    CHECK_EQ(e->iridescence_thickness_max, 400.0f);
    const sr_pbr_material *c = &s->materials[2];
    CHECK_EQ(c->anisotropy_strength, 1.0f);
    CHECK_EQ(c->iridescence_ior, 1.0f);
    CHECK_EQ(c->iridescence_thickness_max, 0.0f);
    CHECK_EQ(c->iridescence, 0.0f);
    /* No thickness: the factor stays the file's, 0 nm drawing no film
     * (sr_pbr_material's thicknesses are as given, not the defaults). */
    CHECK_EQ(s->materials[3].iridescence, 1.0f);
    CHECK(s->materials[3].iridescence_thickness_set);
    CHECK_EQ(s->materials[3].iridescence_thickness_max, 0.0f);
    CHECK(e->iridescence_thickness_set);
    const sr_pbr_material *a = &s->materials[4];
    CHECK(a->anisotropy_strength == 0.0f && a->iridescence == 0.0f &&
          a->iridescence_ior == 0.0f && a->iridescence_thickness_max == 0.0f &&
          !a->iridescence_thickness_set);
    CHECK_EQ(w.count, 4);
    CHECK_STR_CONTAINS(w.last, "/materials/2/extensions/KHR_materials_iridescence/"
                               "iridescenceThicknessMaximum: -20 is negative, taken as 0");
    sr_destroy_scene(sr_test_ctx(), s);
}

/* KHR_materials_dispersion and KHR_materials_diffuse_transmission: the
 * factors, the textures through the slots (A linear, RGB sRGB: two
 * textures of one image; KHR_texture_transform and texCoord honoured),
 * the defaults of present but empty extensions (0, color white);
 * out-of-range factors clamped with one warning each naming the JSON
 * pointer; unlit materials read neither (the extensions exclude it). */
SR_TEST(dispersion_and_diffuse_transmission_are_read)
{
    warnings w = {0};
    sr_scene *s = load_textured(
        "[\"KHR_materials_dispersion\",\"KHR_materials_diffuse_transmission\"]",
        "[{\"extensions\":{\"KHR_materials_dispersion\":{\"dispersion\":0.36},"
        "\"KHR_materials_diffuse_transmission\":{\"diffuseTransmissionFactor\":0.25,"
        "\"diffuseTransmissionTexture\":{\"index\":0,\"texCoord\":1},"
        "\"diffuseTransmissionColorFactor\":[1,0.9,0.85],"
        "\"diffuseTransmissionColorTexture\":{\"index\":0,"
        "\"extensions\":{\"KHR_texture_transform\":{\"scale\":[2,4]}}}}}},"
        "{\"extensions\":{\"KHR_materials_dispersion\":{},"
        "\"KHR_materials_diffuse_transmission\":{}}},"
        "{\"extensions\":{\"KHR_materials_dispersion\":{\"dispersion\":-2},"
        "\"KHR_materials_diffuse_transmission\":{\"diffuseTransmissionFactor\":3,"
        "\"diffuseTransmissionColorFactor\":[1.5,0.5,-1]}}},"
        "{\"extensions\":{\"KHR_materials_unlit\":{},"
        "\"KHR_materials_diffuse_transmission\":{\"diffuseTransmissionFactor\":1}}},"
        "{}]",
        &w);
    REQUIRE(s);
    REQUIRE(s->material_count == 6);
    const sr_pbr_material *m = &s->materials[0];
    CHECK_NEAR(m->dispersion, 0.36, 1e-7);
    CHECK_NEAR(m->diffuse_transmission, 0.25, 0);
    CHECK_NEAR(m->diffuse_transmission_color[1], 0.9, 1e-7);
    CHECK_NEAR(m->diffuse_transmission_color[2], 0.85, 1e-7);
    REQUIRE(m->diffuse_transmission_texture.texture != NULL);
    REQUIRE(m->diffuse_transmission_color_texture.texture != NULL);
    CHECK_EQ(m->diffuse_transmission_texture.texcoord, 1);
    CHECK_NEAR(m->diffuse_transmission_color_texture.scale[0], 2, 0);
    CHECK_NEAR(m->diffuse_transmission_color_texture.scale[1], 4, 0);
    /* The factor's texture is linear, the color's sRGB: two textures. */
    CHECK(m->diffuse_transmission_texture.texture != m->diffuse_transmission_color_texture.texture);
    const sr_pbr_material *e = &s->materials[1];
    CHECK_EQ(e->dispersion, 0.0f);
    CHECK_EQ(e->diffuse_transmission, 0.0f);
    CHECK(e->diffuse_transmission_color[0] == 1.0f && e->diffuse_transmission_color[1] == 1.0f &&
          e->diffuse_transmission_color[2] == 1.0f);
    const sr_pbr_material *c = &s->materials[2];
    CHECK_EQ(c->dispersion, 0.0f);
    CHECK_EQ(c->diffuse_transmission, 1.0f);
    CHECK(c->diffuse_transmission_color[0] == 1.0f && c->diffuse_transmission_color[2] == 0.0f);
    CHECK_EQ(s->materials[3].diffuse_transmission, 0.0f);
    CHECK_EQ(s->materials[4].diffuse_transmission, 0.0f);
    CHECK_EQ(w.count, 4);
    CHECK_STR_CONTAINS(w.last, "/materials/2/extensions/KHR_materials_diffuse_transmission/"
                               "diffuseTransmissionColorFactor/2: -1 is outside the "
                               "specification's 0..1, taken as 0");
    sr_destroy_scene(sr_test_ctx(), s);
}

/* KHR_materials_transmission and KHR_materials_volume: factors, the
 * textures through the slots (R and G, linear), the attenuation; their
 * factors clamped with one warning each; a material without them keeps
 * the zeros that mean "absent". */
SR_TEST(transmission_and_volume_are_read)
{
    char *b64 = small_png_base64();
    REQUIRE(b64);
    char *body = malloc(strlen(b64) + 4096);
    sprintf(body,
            "%s,\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
            "\"extensionsUsed\":[\"KHR_materials_transmission\",\"KHR_materials_volume\"],"
            "\"extensionsRequired\":[\"KHR_materials_transmission\"],"
            "\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
            "\"samplers\":[{\"magFilter\":9728,\"minFilter\":9728}],"
            "\"textures\":[{\"source\":0,\"sampler\":0}],"
            "\"materials\":[{\"extensions\":{\"KHR_materials_transmission\":"
            "{\"transmissionFactor\":0.75,\"transmissionTexture\":{\"index\":0,\"texCoord\":1}},"
            "\"KHR_materials_volume\":{\"thicknessFactor\":0.5,"
            "\"thicknessTexture\":{\"index\":0},\"attenuationColor\":[0.9,0.5,0.25],"
            "\"attenuationDistance\":2}}},"
            "{\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1.5},"
            "\"KHR_materials_volume\":{\"thicknessFactor\":-1,\"attenuationColor\":[2,0.5,-1],"
            "\"attenuationDistance\":0}}},{}]",
            TRI_ACCESSOR ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
            "\"material\":0}]}]", b64);
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    REQUIRE(s->material_count == 4);
    const sr_pbr_material *m = &s->materials[0];
    CHECK_NEAR(m->transmission, 0.75, 0);
    REQUIRE(m->transmission_texture.texture != NULL);
    CHECK_EQ(m->transmission_texture.texcoord, 1);
    CHECK_EQ(m->transmission_texture.filter, SR_FILTER_NEAREST);
    CHECK_EQ(m->thickness_texture.texture, m->transmission_texture.texture);   /* one, linear */
    CHECK_EQ(m->thickness_texture.texcoord, 0);
    CHECK_NEAR(m->thickness, 0.5, 0);
    CHECK_NEAR(m->attenuation_color[1], 0.5, 0);
    CHECK_NEAR(m->attenuation_color[2], 0.25, 0);
    CHECK_NEAR(m->attenuation_distance, 2, 0);
    CHECK_EQ(s->texture_count, 1);
    /* Out of range: clamped, one warning each (transmission, thickness,
     * two attenuation channels, the distance). */
    const sr_pbr_material *c = &s->materials[1];
    CHECK_EQ(c->transmission, 1.0f);
    CHECK_EQ(c->thickness, 0.0f);
    CHECK_EQ(c->attenuation_color[0], 1.0f);
    CHECK_EQ(c->attenuation_color[2], 0.0f);
    CHECK_EQ(c->attenuation_distance, 0.0f);
    CHECK_EQ(w.count, 5);
    CHECK(strcmp(w.last, "t.gltf: warning: /materials/1/extensions/KHR_materials_volume/"
                         "attenuationDistance: 0 is not positive, taken as infinite") == 0);
    /* Neither extension: no transmission, white attenuation, as
     * sr_pbr_default_material has it. */
    const sr_pbr_material *n = &s->materials[2];
    CHECK_EQ(n->transmission, 0.0f);
    CHECK_EQ(n->thickness, 0.0f);
    CHECK_EQ(n->attenuation_distance, 0.0f);
    CHECK_EQ(n->attenuation_color[0], 1.0f);
    CHECK(n->transmission_texture.texture == NULL);
    sr_destroy_scene(sr_test_ctx(), s);
    free(body);
    free(b64);
}

/* The extensions not read are named in one warning; skins and morph
 * targets are read (test_gltf_skin.c), animations too
 * (test_gltf_animation.c), and not named.  A file without them warns of
 * nothing (node_hierarchy_... checks). */
SR_TEST(unread_extensions_give_one_warning)
{
    const char body[] =
        TRI_ACCESSOR ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]},"
        "{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
        "\"targets\":[{\"POSITION\":0}]}],\"weights\":[1]}],"
        "\"nodes\":[{\"mesh\":0},{\"mesh\":1},{}],\"scenes\":[{\"nodes\":[0,1,2]}],"
        "\"skins\":[{\"joints\":[2]}],"
        "\"extensionsUsed\":[\"KHR_texture_basisu\"]";
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    CHECK_EQ(s->primitive_count, 2);
    CHECK_EQ(w.count, 1);
    CHECK_EQ(s->warning_count, 1);
    CHECK(strcmp(w.last, "t.gltf: warning: not read, the scene is drawn without them: "
                         "/extensionsUsed/0 (KHR_texture_basisu)") == 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(cameras_come_with_their_world_transforms_in_node_order)
{
    char body[2048];
    snprintf(body, sizeof body,
             "%s,\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,"
             "\"znear\":0.1,\"aspectRatio\":1.5}},"
             "{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":2,\"ymag\":1,\"znear\":0,"
             "\"zfar\":50}}],"
             "\"nodes\":[{\"mesh\":0,\"children\":[1,2]},{\"camera\":1,\"translation\":[0,0,5]},"
             "{\"camera\":0,\"translation\":[3,0,0]}],\"scenes\":[{\"nodes\":[0]}]",
             tri_mesh);
    warnings w = {0};
    sr_scene *s = load_doc(tri_le(), sizeof tri, body, &w);
    REQUIRE(s);
    REQUIRE(s->camera_count == 2);
    const sr_scene_camera *o = &s->cameras[0], *p = &s->cameras[1];
    CHECK_EQ(o->type, SR_SCENE_CAMERA_ORTHOGRAPHIC);
    CHECK_EQ(o->camera, 1);
    CHECK_EQ(o->node, 1);
    CHECK_NEAR(o->xmag, 2, 0);
    CHECK_NEAR(o->ymag, 1, 0);
    CHECK_NEAR(o->zfar, 50, 0);
    CHECK_NEAR(o->world[14], 5, 0);
    CHECK_EQ(p->type, SR_SCENE_CAMERA_PERSPECTIVE);
    CHECK_NEAR(p->yfov, 0.8, 1e-6);
    CHECK_NEAR(p->aspect, 1.5, 0);
    CHECK_NEAR(p->znear, 0.1, 1e-6);
    CHECK_EQ(p->zfar, 0.0f);                  /* infinite */
    CHECK_NEAR(p->world[12], 3, 0);
    /* Matrices for a 2:1 viewport: the perspective camera at (3, 0, 0)
     * looking down -Z; infinite far plane, vertical field kept. */
    sr_mat4 v, pr;
    REQUIRE(sr_scene_camera_matrices(p, 2.0f, &v, &pr) == SR_OK);
    sr_vec4 e = sr_mat4_mul_vec4(&v, (sr_vec4){ 3, 0, -10, 1 });
    CHECK_NEAR(e.x, 0, 1e-6);
    CHECK_NEAR(e.z, -10, 1e-6);
    sr_vec4 c = sr_mat4_mul_vec4(&pr, (sr_vec4){ 0, tanf(0.4f), -1, 1 });
    CHECK_NEAR(c.y / c.w, 1, 1e-5);                 /* the top of the field */
    CHECK_NEAR(c.w, 1, 0);
    c = sr_mat4_mul_vec4(&pr, (sr_vec4){ 0, 0, -0.1f, 1 });
    CHECK_NEAR(c.z / c.w, -1, 1e-5);                /* znear at -1 */
    c = sr_mat4_mul_vec4(&pr, (sr_vec4){ 2 * tanf(0.4f), 0, -1, 1 });
    CHECK_NEAR(c.x / c.w, 1, 1e-5);                 /* the viewport's aspect */
    /* The orthographic one 5 units up Z: its box is 2 ymag high. */
    REQUIRE(sr_scene_camera_matrices(o, 1.0f, &v, &pr) == SR_OK);
    c = sr_mat4_mul_vec4(&pr, sr_mat4_mul_vec4(&v, (sr_vec4){ 1, 1, 0, 1 }));
    CHECK_NEAR(c.x, 1, 1e-6);
    CHECK_NEAR(c.y, 1, 1e-6);
    CHECK_EQ(sr_scene_camera_matrices(o, 0.0f, &v, &pr), SR_INVALID_ARG);
    CHECK_EQ(sr_scene_camera_matrices(NULL, 1.0f, &v, &pr), SR_INVALID_ARG);
    /* A camera no file gives is refused, and the outputs keep their bytes. */
    sr_mat4 v0 = v, pr0 = pr;
    sr_scene_camera bad = *p;
    bad.type = (sr_scene_camera_type)7;
    CHECK_EQ(sr_scene_camera_matrices(&bad, 1.0f, &v, &pr), SR_INVALID_ARG);
    bad = *p;
    bad.world[5] = NAN;
    CHECK_EQ(sr_scene_camera_matrices(&bad, 1.0f, &v, &pr), SR_INVALID_ARG);
    bad = *p;
    bad.yfov = 4.0f;
    CHECK_EQ(sr_scene_camera_matrices(&bad, 1.0f, &v, &pr), SR_INVALID_ARG);
    bad = *o;
    bad.zfar = INFINITY;
    CHECK_EQ(sr_scene_camera_matrices(&bad, 1.0f, &v, &pr), SR_INVALID_ARG);
    /* Finite clip distances whose matrices overflow floats (a file's, or
     * a KHR_animation_pointer pose's): (f + n) and 2 f n go to infinity. */
    bad = *p;
    bad.znear = 3e38f;
    bad.zfar = 3.4e38f;
    CHECK_EQ(sr_scene_camera_matrices(&bad, 1.0f, &v, &pr), SR_INVALID_ARG);
    bad.zfar = 0;                                   /* infinite: -2 znear */
    CHECK_EQ(sr_scene_camera_matrices(&bad, 1.0f, &v, &pr), SR_INVALID_ARG);
    bad = *o;
    bad.znear = 3e38f;
    bad.zfar = 3.4e38f;
    CHECK_EQ(sr_scene_camera_matrices(&bad, 1.0f, &v, &pr), SR_INVALID_ARG);
    CHECK(memcmp(&v, &v0, sizeof v) == 0 && memcmp(&pr, &pr0, sizeof pr) == 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    REQUIRE(f);
    fwrite(data, 1, n, f);
    fclose(f);
}

typedef struct reads {
    int count;
    char paths[4][512];
} reads;

static void on_read(void *user, const char *path)
{
    reads *r = user;
    if (r->count < 4) {
        snprintf(r->paths[r->count], sizeof r->paths[0], "%s", path);
    }
    r->count++;
}

SR_TEST(external_buffers_and_images_are_read_beside_the_file)
{
    char dir[512], path[600];
    snprintf(dir, sizeof dir, "%s", sr_test_out_dir());
    snprintf(path, sizeof path, "%s/gltf ext.bin", dir);
    write_file(path, tri_le(), sizeof tri);
    wbuf png = small_png();
    snprintf(path, sizeof path, "%s/gltf tex.png", dir);
    write_file(path, png.p, png.n);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},"
             "\"buffers\":[{\"byteLength\":36,\"uri\":\"gltf%%20ext.bin\"}]%s,"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
             "\"images\":[{\"uri\":\"gltf%%20tex.png\"}],\"textures\":[{\"source\":0}],"
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]}",
             tri_mesh);
    snprintf(path, sizeof path, "%s/gltf_ext.gltf", dir);
    write_file(path, json, strlen(json));
    reads r = {0};
    sr_scene *s;
    sr_io_error e;
    sr_load_desc desc = { .file_read = on_read, .user = &r };
    REQUIRE(sr_load_scene(sr_test_ctx(), path, &desc, &s, &e) == SR_OK);
    CHECK_EQ(s->primitive_count, 1);
    CHECK_EQ(s->primitives[0].positions[3], 1.0f);
    CHECK(s->materials[0].base_color_texture.texture != NULL);
    CHECK_EQ(r.count, 2);
    /* Materials are read first, so the image comes before the buffer. */
    CHECK_STR_CONTAINS(r.paths[0], "/gltf tex.png");
    CHECK_STR_CONTAINS(r.paths[1], "/gltf ext.bin");
    sr_destroy_scene(sr_test_ctx(), s);
    free(png.p);
}

SR_TEST(glb_json_chunk_of_unaligned_length_reads_the_next_chunk_where_it_is)
{
    /* 1 + 4 * 29 + 2 characters: never a multiple of 4. */
    const char *json =
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":36}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
        "\"type\":\"VEC3\"}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}";
    size_t n = strlen(json), pad = (4 - n % 4) % 4;
    REQUIRE(pad != 0);
    sr_scene *s;
    sr_io_error e;
    /* Not padded at all (the next chunk right after the length, as three.js
     * and the Khronos validator read it), and padded without counting it. */
    for (size_t p = 0; p <= pad; p += pad) {
        wbuf g = glb_framed(json, (uint32_t)n, p, tri_le(), 36);
        CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "odd.glb", g.p, g.n, NULL, &s, &e), SR_OK);
        if (s) {
            CHECK_EQ(s->primitive_count, 1);
            CHECK_EQ(s->primitives[0].positions[7], 1.0f);
            sr_destroy_scene(sr_test_ctx(), s);
        }
        free(g.p);
    }
    /* A JSON length that ends inside the text: the message names it, not the
     * length read from the JSON text that follows it. */
    wbuf g = glb_framed(json, 3, pad, tri_le(), 36);
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "short.glb", g.p, g.n, NULL, &s, &e), SR_BAD_FORMAT);
    CHECK_EQ(s, NULL);
    CHECK_STR_CONTAINS(e.message, "short.glb: byte 12: JSON chunk length 3 (not a multiple of 4)");
    free(g.p);
}

SR_TEST(glb_reads_its_bin_chunk_and_images_from_buffer_views)
{
    wbuf png = small_png();
    uint8_t bin[512];
    REQUIRE(png.n + 36 <= sizeof bin);
    memcpy(bin, tri_le(), 36);
    memcpy(bin + 36, png.p, png.n);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},"
             "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":%zu}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\"}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
             "\"images\":[{\"bufferView\":1,\"mimeType\":\"image/png\"}],"
             "\"textures\":[{\"source\":0}],"
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]}",
             36 + png.n, png.n);
    wbuf g = glb(json, bin, 36 + png.n);
    char path[600];
    snprintf(path, sizeof path, "%s/gltf_bin.glb", sr_test_out_dir());
    write_file(path, g.p, g.n);
    sr_scene *s;
    sr_io_error e;
    REQUIRE(sr_load_scene(sr_test_ctx(), path, NULL, &s, &e) == SR_OK);
    CHECK_EQ(s->primitive_count, 1);
    CHECK_EQ(s->primitives[0].positions[7], 1.0f);
    CHECK(s->materials[0].base_color_texture.texture != NULL);
    sr_destroy_scene(sr_test_ctx(), s);
    /* The same bytes in memory, and cut short. */
    REQUIRE(sr_parse_gltf(sr_test_ctx(), "m.glb", g.p, g.n, NULL, &s, &e) == SR_OK);
    sr_destroy_scene(sr_test_ctx(), s);
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "m.glb", g.p, g.n - 4, NULL, &s, &e), SR_BAD_FORMAT);
    CHECK_EQ(s, NULL);
    CHECK_STR_CONTAINS(e.message, "m.glb: byte 8: GLB length");
    free(g.p);
    free(png.p);
}

SR_TEST(other_formats_become_one_primitive_with_a_dielectric)
{
    char path[600];
    snprintf(path, sizeof path, "%s/gltf_scene.obj", sr_test_out_dir());
    const char obj[] = "v 0 0 0\nv 2 0 0\nv 0 3 0\nf 1 2 3\n";
    write_file(path, obj, strlen(obj));
    sr_scene *s;
    sr_io_error e;
    REQUIRE(sr_load_scene(sr_test_ctx(), path, NULL, &s, &e) == SR_OK);
    REQUIRE(s->primitive_count == 1);
    REQUIRE(s->material_count == 1);
    const sr_pbr_material *m = &s->materials[0];
    CHECK_NEAR(m->base_color[0], 0.8, 1e-6);
    CHECK_EQ(m->metallic, 0.0f);
    CHECK_EQ(m->roughness, 0.5f);
    CHECK_EQ(m->base_color_texture.texture, NULL);
    CHECK_EQ(s->primitives[0].node, -1);
    CHECK_EQ(s->primitives[0].world[15], 1.0f);
    CHECK(!s->primitives[0].mirrored);
    CHECK_NEAR(s->bounds_max.y, 3, 0);
    CHECK_EQ(s->primitives[0].colors, NULL);
    sr_destroy_scene(sr_test_ctx(), s);
    /* Vertex colors (here OBJ's extension; an MTL's Kd comes the same way)
     * are the base color: the factor is white. */
    const char colored[] = "v 0 0 0 1 0 0\nv 2 0 0 1 0 0\nv 0 3 0 1 0 0\nf 1 2 3\n";
    write_file(path, colored, strlen(colored));
    REQUIRE(sr_load_scene(sr_test_ctx(), path, NULL, &s, &e) == SR_OK);
    REQUIRE(s->primitives[0].colors != NULL);
    CHECK_EQ(s->primitives[0].colors[0], 1.0f);
    CHECK_EQ(s->materials[0].base_color[1], 1.0f);
    CHECK_EQ(s->materials[0].roughness, 0.5f);
    sr_destroy_scene(sr_test_ctx(), s);
}

/* ---- malformed files: one message with the JSON pointer ------------------ */

typedef struct bad_case {
    const char *body;        /* after the buffer; the triangle's 36 bytes in buffer 0 */
    sr_result result;
    const char *message;     /* the whole message starts so */
} bad_case;

#define MESH_OF(acc) \
    ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" acc "}}]}]"
#define NODES ",\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]"
#define VIEW0 ",\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}]"
#define ACC(extra) \
    ",\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"type\":\"VEC3\"," extra "}]"

static const bad_case bad_cases[] = {
    { VIEW0 ACC("\"count\":4") MESH_OF("0") NODES, SR_BAD_FORMAT,
      "bad.gltf: /accessors/0/count: 4 elements of 12 bytes, 12 apart, from byte 0 run past "
      "the 36 bytes of bufferView 0" },
    { ",\"bufferViews\":[{\"buffer\":0,\"byteOffset\":8,\"byteLength\":36}]"
      ACC("\"count\":3") MESH_OF("0") NODES, SR_BAD_FORMAT,
      "bad.gltf: /bufferViews/0/byteLength: bytes 8..44 run past the 36 bytes of buffer 0" },
    { ",\"nodes\":[{\"children\":[1]},{\"children\":[0]}]", SR_BAD_FORMAT,
      "bad.gltf: /nodes/1/children: node 0 is its own ancestor (a cycle)" },
    { ",\"nodes\":[{\"children\":[2]},{\"children\":[2]},{}]", SR_BAD_FORMAT,
      "bad.gltf: /nodes/1/children/0: node 2 already has a parent (node 0)" },
    { ",\"nodes\":[{\"children\":[1]},{}],\"scenes\":[{\"nodes\":[0,1]}]", SR_BAD_FORMAT,
      "bad.gltf: /scenes/0/nodes/1: node 1 is not a root (node 0's child)" },
    { ",\"accessors\":[{\"componentType\":5126,\"type\":\"VEC3\",\"count\":100000000}]"
      MESH_OF("0") NODES, SR_TOO_LARGE,
      "bad.gltf: /accessors/0/count: 100000000 elements of 3 components are more than" },
    { VIEW0 ACC("\"count\":3") ",\"meshes\":[{\"primitives\":[{\"attributes\":"
      "{\"POSITION\":0},\"indices\":1}]}],\"accessors\":[]" NODES, SR_BAD_FORMAT,
      "bad.gltf:1: invalid JSON: duplicate object key" },
    { VIEW0 ",\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"type\":\"VEC3\","
      "\"count\":3},{\"bufferView\":0,\"byteOffset\":12,\"componentType\":5121,"
      "\"type\":\"SCALAR\",\"count\":3}]"
      ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}]" NODES,
      SR_BAD_FORMAT,
      "bad.gltf: /meshes/0/primitives/0/indices: element 2 is 128, past the 3 vertices" },
    { VIEW0 ACC("\"count\":3") MESH_OF("5") NODES, SR_BAD_FORMAT,
      "bad.gltf: /meshes/0/primitives/0/attributes/POSITION: accessor 5 does not exist "
      "(1 accessors)" },
    { VIEW0 ACC("\"count\":3")
      ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":3}]}]" NODES,
      SR_BAD_FORMAT, "bad.gltf: /meshes/0/primitives/0/material: 3 is not an index below 0" },
    { VIEW0 ACC("\"count\":3") MESH_OF("0")
      ",\"nodes\":[{\"mesh\":-1}],\"scenes\":[{\"nodes\":[0]}]", SR_BAD_FORMAT,
      "bad.gltf: /nodes/0/mesh: -1 is negative, not an index" },
    { VIEW0 ",\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"type\":\"VEC3\","
      "\"count\":3},{\"bufferView\":0,\"componentType\":5121,\"normalized\":true,"
      "\"type\":\"MAT2\",\"count\":3}],\"meshes\":[{\"primitives\":[{\"attributes\":"
      "{\"POSITION\":0,\"TANGENT\":1}}]}]" NODES, SR_BAD_FORMAT,
      "bad.gltf: /meshes/0/primitives/0/attributes/TANGENT: accessor 1 holds matrices, not "
      "vectors" },
    { VIEW0 ACC("\"count\":3") ",\"meshes\":[{\"primitives\":[{\"attributes\":"
      "{\"POSITION\":0,\"TEXCOORD_0\":0}}]}]" NODES, SR_BAD_FORMAT,
      "bad.gltf: /meshes/0/primitives/0/attributes/TEXCOORD_0: accessor 0 has 3 components per "
      "element, not what this attribute takes" },
    { ",\"extensionsRequired\":[\"KHR_texture_basisu\"]", SR_UNSUPPORTED,
      "bad.gltf: /extensionsRequired/0: extension KHR_texture_basisu is not "
      "supported" },
    { VIEW0 ACC("\"count\":3") MESH_OF("0") NODES
      ",\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"no_such_image.png\"}],"
      "\"materials\":[{\"emissiveTexture\":{\"index\":0}}]", SR_IO_ERROR,
      "bad.gltf: /images/0/uri: no_such_image.png: cannot open" },
    { VIEW0 ACC("\"count\":3,\"byteOffset\":2") MESH_OF("0") NODES, SR_BAD_FORMAT,
      "bad.gltf: /accessors/0/byteOffset: 2 is not a multiple of the component size 4" },
    { VIEW0 ACC("\"count\":3") MESH_OF("0")
      ",\"nodes\":[{\"mesh\":0,\"scale\":[1,1]}],\"scenes\":[{\"nodes\":[0]}]", SR_BAD_FORMAT,
      "bad.gltf: /nodes/0/scale: not an array of 3 numbers" },
    { ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.5}}],"
      "\"nodes\":[{\"camera\":0}]", SR_BAD_FORMAT,
      "bad.gltf: /cameras/0/perspective/znear: missing or out of range" },
    { ",\"materials\":[{},{\"extensions\":{\"KHR_materials_dispersion\":"
      "{\"dispersion\":\"high\"}}}]", SR_BAD_FORMAT,
      "bad.gltf: /materials/1/extensions/KHR_materials_dispersion/dispersion: not a finite "
      "number" },
    { ",\"materials\":[{\"extensions\":{\"KHR_materials_diffuse_transmission\":"
      "{\"diffuseTransmissionColorFactor\":[1,true,1]}}}]", SR_BAD_FORMAT,
      "bad.gltf: /materials/0/extensions/KHR_materials_diffuse_transmission/"
      "diffuseTransmissionColorFactor/1: not a finite number" },
};

SR_TEST(malformed_files_give_one_message_with_the_json_pointer)
{
    for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
        char *json = doc(tri_le(), sizeof tri, bad_cases[i].body);
        sr_scene *s = (sr_scene *)json;  /* must come back NULL */
        sr_io_error e;
        sr_result r = sr_parse_gltf(sr_test_ctx(), "bad.gltf", (const uint8_t *)json,
                                    strlen(json), NULL, &s, &e);
        if (r != bad_cases[i].result || s != NULL ||
            strncmp(e.message, bad_cases[i].message, strlen(bad_cases[i].message)) != 0 ||
            strchr(e.message, '\n')) {
            sr_test_fail(__FILE__, __LINE__, "case %zu: %s (%s), want %s (%s)", i,
                         sr_result_name(r), e.message, sr_result_name(bad_cases[i].result),
                         bad_cases[i].message);
        }
        free(json);
    }
}

SR_TEST(missing_buffers_and_bad_documents_are_reported)
{
    sr_scene *s;
    sr_io_error e;
    const char *missing = "{\"asset\":{\"version\":\"2.0\"},"
                          "\"buffers\":[{\"byteLength\":36,\"uri\":\"no_such.bin\"}]" VIEW0
                          ACC("\"count\":3") MESH_OF("0") NODES "}";
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "bad.gltf", (const uint8_t *)missing, strlen(missing),
                           NULL, &s, &e),
             SR_IO_ERROR);
    CHECK_STR_CONTAINS(e.message, "bad.gltf: /buffers/0/uri: no_such.bin: cannot open");
    const char *absolute = "{\"asset\":{\"version\":\"2.0\"},"
                           "\"buffers\":[{\"byteLength\":36,\"uri\":\"/etc/passwd\"}]" VIEW0
                           ACC("\"count\":3") MESH_OF("0") NODES "}";
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "bad.gltf", (const uint8_t *)absolute,
                           strlen(absolute), NULL, &s, &e),
             SR_UNSUPPORTED);
    CHECK_STR_CONTAINS(e.message, "bad.gltf: /buffers/0/uri: only relative file names");
    /* Nor by climbing out of the model's directory, or with a "/" in
     * percent-encoding; a ".." that stays inside is read. */
    static const char *const outside[] = { "../no_such.bin", "a/../../no_such.bin",
                                           "%2Fetc%2Fpasswd", "%2e%2e/no_such.bin" };
    for (size_t i = 0; i < sizeof outside / sizeof *outside; i++) {
        char escaping[600];
        snprintf(escaping, sizeof escaping,
                 "{\"asset\":{\"version\":\"2.0\"},"
                 "\"buffers\":[{\"byteLength\":36,\"uri\":\"%s\"}]" VIEW0
                 ACC("\"count\":3") MESH_OF("0") NODES "}",
                 outside[i]);
        CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "bad.gltf", (const uint8_t *)escaping,
                               strlen(escaping), NULL, &s, &e),
                 SR_UNSUPPORTED);
        CHECK_STR_CONTAINS(e.message,
                           "bad.gltf: /buffers/0/uri: only file names inside the model's "
                           "directory are read");
    }
    const char *inside = "{\"asset\":{\"version\":\"2.0\"},"
                         "\"buffers\":[{\"byteLength\":36,\"uri\":\"a/./../no_such.bin\"}]"
                         VIEW0 ACC("\"count\":3") MESH_OF("0") NODES "}";
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "bad.gltf", (const uint8_t *)inside, strlen(inside),
                           NULL, &s, &e),
             SR_IO_ERROR);
    CHECK_STR_CONTAINS(e.message, "a/./../no_such.bin: cannot open");
    const char *broken = "{\"asset\":{\"version\":\"2.0\"},\n\"nodes\":[}";
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "bad.gltf", (const uint8_t *)broken, strlen(broken),
                           NULL, &s, &e),
             SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, "bad.gltf:2: invalid JSON");
    const char *v1 = "{\"asset\":{\"version\":\"1.0\"}}";
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "bad.gltf", (const uint8_t *)v1, strlen(v1), NULL, &s,
                           &e),
             SR_UNSUPPORTED);
    CHECK_STR_CONTAINS(e.message, "bad.gltf: /asset/version: \"1.0\" is not glTF 2.x");
    /* An empty file, and a PNG named .glb: said as such, not "invalid JSON". */
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "empty.glb", (const uint8_t *)"", 0, NULL, &s, &e),
             SR_BAD_FORMAT);
    CHECK(strcmp(e.message, "empty.glb: file is empty") == 0);
    const uint8_t png[] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13 };
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "image.GLB", png, sizeof png, NULL, &s, &e),
             SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, "image.GLB: byte 0: not a GLB file");
    CHECK(s == NULL);
    /* a JSON document named .glb still reads as one */
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "v1.glb", (const uint8_t *)v1, strlen(v1), NULL, &s,
                           &e),
             SR_UNSUPPORTED);
    CHECK_STR_CONTAINS(e.message, "v1.glb: /asset/version");
    CHECK_EQ(sr_parse_gltf(NULL, "x", (const uint8_t *)v1, 3, NULL, &s, &e), SR_INVALID_ARG);
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "x", (const uint8_t *)v1, 3, NULL, NULL, &e),
             SR_INVALID_ARG);
    CHECK_EQ(sr_load_scene(sr_test_ctx(), NULL, NULL, &s, &e), SR_INVALID_ARG);
    sr_destroy_scene(sr_test_ctx(), NULL);
}

/* `head` (accessors and mesh 0) and `nodes` nodes placing mesh 0, parsed
 * as big.gltf: it must be refused as too large with `message`. */
static void expect_too_many_instances(const char *head, int nodes, const char *message)
{
    size_t cap = (size_t)nodes * 16 + strlen(head) + 64;
    char *body = malloc(cap);
    size_t at = (size_t)snprintf(body, cap, "%s,\"nodes\":[", head);
    for (int i = 0; i < nodes; i++) {
        at += (size_t)snprintf(body + at, cap - at, "%s{\"mesh\":0}", i ? "," : "");
    }
    snprintf(body + at, cap - at, "]");
    char *json = doc(tri_le(), sizeof tri, body);
    sr_scene *s;
    sr_io_error e;
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "big.gltf", (const uint8_t *)json, strlen(json), NULL,
                           &s, &e),
             SR_TOO_LARGE);
    CHECK_STR_CONTAINS(e.message, message);
    free(json);
    free(body);
}

SR_TEST(instancing_a_mesh_past_the_vertex_limit_is_refused)
{
    /* 131070 zero vertices (no bufferView: cheap to store), drawn by 1025
     * nodes: 134 346 750 vertices, past 2^27. */
    expect_too_many_instances(",\"accessors\":[{\"componentType\":5126,\"type\":\"VEC3\","
                              "\"count\":131070}]" MESH_OF("0"),
                              1025, "big.gltf: /nodes/1024: more than 134217728 vertices to draw");
}

SR_TEST(instancing_a_long_index_list_past_the_triangle_limit_is_refused)
{
    /* Three vertices indexed by 1 048 575 zeros (no bufferView), placed by
     * 769 nodes: 268 784 725 triangles, past 2^28, from a few kilobytes;
     * the vertices (2307) are far below their limit. */
    expect_too_many_instances(
        VIEW0 ",\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"type\":\"VEC3\","
        "\"count\":3},{\"componentType\":5125,\"type\":\"SCALAR\",\"count\":1048575}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}]",
        769, "big.gltf: /nodes/768: more than 268435456 triangles to draw in all");
}

/* json written to `name` in the tests' output folder; its path. */
static const char *write_doc(const char *name, char *json)
{
    static char path[600];
    snprintf(path, sizeof path, "%s/%s", sr_test_out_dir(), name);
    write_file(path, json, strlen(json));
    free(json);
    return path;
}

/* bin and body as a document written to `name`, read by sr_load_mesh;
 * its message printed when it fails. */
static bool load_mesh(const char *name, const void *bin, size_t n, const char *body, sr_mesh *m)
{
    const char *path = write_doc(name, doc(bin, n, body));
    sr_io_error e;
    sr_result r = sr_load_mesh(sr_test_ctx(), path, NULL, m, &e);
    if (r != SR_OK) {
        printf("  %s\n", e.message);
    }
    return r == SR_OK;
}

SR_TEST(load_mesh_flattens_instances_into_world_space)
{
    /* tri with the normal (1, 1, 0) / sqrt 2 at every corner, placed by
     * a translated, unevenly scaled node and by a mirroring one. */
    float nrm[9];
    for (int i = 0; i < 3; i++) {
        nrm[3 * i] = nrm[3 * i + 1] = 0.70710678f;
        nrm[3 * i + 2] = 0;
    }
    uint8_t bin[72];
    le_copy(bin, tri, 9, 4);
    le_copy(bin + 36, nrm, 9, 4);
    const char *body =
        ",\"bufferViews\":[{\"buffer\":0,\"byteLength\":72}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":0,\"byteOffset\":36,\"componentType\":5126,\"count\":3,"
        "\"type\":\"VEC3\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1}}]}],"
        "\"nodes\":[{\"translation\":[1,2,3],\"scale\":[2,3,1],\"mesh\":0},"
        "{\"scale\":[-1,1,1],\"mesh\":0},{\"translation\":[9,9,9],\"mesh\":0}],"
        "\"scenes\":[{\"nodes\":[0,1]},{\"nodes\":[2]}],\"scene\":0";
    sr_mesh m;
    REQUIRE(load_mesh("instances.gltf", bin, sizeof bin, body, &m));
    REQUIRE(m.vertex_count == 6);
    REQUIRE(m.triangle_count == 2);
    static const float want_pos[18] = { 1, 2, 3, 3, 2, 3, 1, 5, 3,
                                        0, 0, 0, -1, 0, 0, 0, 1, 0 };
    for (int i = 0; i < 18; i++) {
        CHECK_NEAR(m.positions[i], want_pos[i], 1e-6);
    }
    /* Normals by the inverse transpose: (1/2, 1/3, 0) normalized, and
     * (-1, 1, 0) normalized. */
    REQUIRE(m.normals);
    CHECK_NEAR(m.normals[0], 0.83205029f, 1e-6);
    CHECK_NEAR(m.normals[1], 0.5547002f, 1e-6);
    CHECK_NEAR(m.normals[2], 0, 1e-6);
    CHECK_NEAR(m.normals[9], -0.70710678f, 1e-6);
    CHECK_NEAR(m.normals[10], 0.70710678f, 1e-6);
    CHECK(m.texcoords == NULL && m.colors == NULL);
    /* Both triangles face +z in world space: the mirrored one's corners
     * were swapped. */
    for (size_t t = 0; t < 2; t++) {
        const float *a = &m.positions[3 * m.indices[3 * t]];
        const float *b = &m.positions[3 * m.indices[3 * t + 1]];
        const float *c = &m.positions[3 * m.indices[3 * t + 2]];
        float z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        CHECK(z > 0);
    }
    CHECK_EQ(m.indices[3], 3);
    CHECK_EQ(m.indices[4], 5);
    CHECK_EQ(m.indices[5], 4);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

/* KHR_mesh_quantization's integer positions, which Assimp misreads: read
 * by the own reader even in a build that has Assimp. */
SR_TEST(load_mesh_reads_quantized_gltf_with_the_own_reader)
{
    uint16_t pos[12] = { 0, 0, 0, 0, 2, 0, 0, 0, 0, 3, 0, 0 };   /* stride 8 */
    uint8_t bin[24];
    le_copy(bin, pos, 12, 2);
    const char *body =
        ",\"extensionsUsed\":[\"KHR_mesh_quantization\"],"
        "\"extensionsRequired\":[\"KHR_mesh_quantization\"],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":24,\"byteStride\":8}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5123,\"count\":3,"
        "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[2,3,0]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"nodes\":[{\"scale\":[0.5,0.5,0.5],\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]";
    sr_mesh m;
    REQUIRE(load_mesh("quantized.gltf", bin, sizeof bin, body, &m));
    REQUIRE(m.vertex_count == 3 && m.triangle_count == 1);
    static const float want[9] = { 0, 0, 0, 1, 0, 0, 0, 1.5f, 0 };
    for (int i = 0; i < 9; i++) {
        CHECK_NEAR(m.positions[i], want[i], 1e-6);
    }
    CHECK(m.normals == NULL);
    sr_destroy_mesh(sr_test_ctx(), &m);
}

SR_TEST(load_mesh_gltf_errors_name_the_json_pointer)
{
    char body[1024];
    snprintf(body, sizeof body,
             "%s,\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]",
             TRI_ACCESSOR ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":7}}]}]");
    const char *path = write_doc("bad_accessor.gltf", doc(tri_le(), sizeof tri, body));
    sr_mesh m;
    sr_io_error e;
    CHECK_EQ(sr_load_mesh(sr_test_ctx(), path, NULL, &m, &e), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, "bad_accessor.gltf: /meshes/0/primitives/0/attributes/POSITION");
    CHECK(strchr(e.message, '\n') == NULL);
    CHECK(m.positions == NULL && m.vertex_count == 0);
}

/* The base color images go into the mesh as the Assimp path gives them:
 * the first for the whole mesh, and runs of primitives that take one
 * image (or none) as parts, each with its own copy of the encoded bytes. */
SR_TEST(load_mesh_keeps_the_base_color_images_as_parts)
{
    wbuf png = small_png();
    char *b64 = small_png_base64();
    REQUIRE(png.p && b64);
    char tail[4096];
    snprintf(tail, sizeof tail,
             ",\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
             "\"textures\":[{\"source\":0}],\"materials\":["
             "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}},{}]",
             b64);
    free(b64);
    static const gltf_quad quads[3] = { { 0, 0, 1, 1, 0 }, { 1, 0, 2, 1, 1 },
                                        { 2, 0, 3, 1, 0 } };
    const char *path = write_doc("parts.gltf", gltf_quads(quads, 3, tail));
    sr_mesh m;
    sr_io_error e;
    REQUIRE(sr_load_mesh(sr_test_ctx(), path, NULL, &m, &e) == SR_OK);
    CHECK_EQ(m.triangle_count, 6);
    REQUIRE(m.part_count == 3);
    for (int p = 0; p < 3; p++) {
        CHECK_EQ(m.parts[p].first_triangle, 2 * (size_t)p);
        CHECK_EQ(m.parts[p].triangle_count, 2);
        CHECK(m.parts[p].texture_path == NULL);
    }
    CHECK(m.parts[1].texture_data == NULL);
    for (int p = 0; p < 3; p += 2) {
        CHECK(m.parts[p].texture_size == png.n && m.parts[p].texture_data &&
              memcmp(m.parts[p].texture_data, png.p, png.n) == 0);
    }
    CHECK(m.texture_size == png.n && m.texture_data &&
          memcmp(m.texture_data, png.p, png.n) == 0);
    REQUIRE(m.texcoords);
    CHECK_NEAR(m.texcoords[1], 0, 1e-6);   /* glTF's v = 1, flipped */
    sr_destroy_mesh(sr_test_ctx(), &m);
    free(png.p);
}

/* sr_load_mesh reads the images its mesh shows, the base color ones, and
 * no other: a material whose normal map is damaged and whose occlusion
 * image is missing loads, silently, where sr_load_scene (which draws
 * them) refuses the file; a damaged base color image stays an error.
 * The texcoords are where the base color texture is sampled: glTF's
 * KHR_texture_transform applied, then v flipped. */
SR_TEST(load_mesh_reads_only_the_base_color_images)
{
    wbuf png = small_png();
    char *b64 = small_png_base64();
    REQUIRE(png.p && b64);
    static const gltf_quad quad = { 0, 0, 1, 1, 0 };
    const char *material =
        "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":%d,"
        "\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.5,0.25],\"rotation\":0.5,"
        "\"scale\":[2,3]}}}},\"normalTexture\":{\"index\":%d},"
        "\"occlusionTexture\":{\"index\":2}}]";
    for (int broken_base = 0; broken_base < 2; broken_base++) {
        char tail[4096];
        int at = snprintf(tail, sizeof tail,
                          ",\"images\":[{\"uri\":\"data:image/png;base64,%s\"},"
                          "{\"uri\":\"data:image/png;base64,iVBORw0KGgoAAAANSUhEUg==\"},"
                          "{\"uri\":\"no_such_occlusion.png\"}],"
                          "\"textures\":[{\"source\":0},{\"source\":1},{\"source\":2}],",
                          b64);
        snprintf(tail + at, sizeof tail - (size_t)at, material, broken_base ? 1 : 0,
                 broken_base ? 0 : 1);
        const char *path = write_doc("damaged_normal_map.gltf", gltf_quads(&quad, 1, tail));
        warnings w = {0};
        sr_load_desc desc = { .warn = on_warn, .user = &w };
        sr_mesh m;
        sr_io_error e;
        sr_result r = sr_load_mesh(sr_test_ctx(), path, &desc, &m, &e);
        if (broken_base) {
            CHECK_EQ(r, SR_BAD_FORMAT);
            CHECK_STR_CONTAINS(e.message, "damaged_normal_map.gltf: /images/1: ");
            continue;
        }
        REQUIRE(r == SR_OK);
        CHECK_EQ(w.count, 0);
        CHECK(m.texture_size == png.n && memcmp(m.texture_data, png.p, png.n) == 0);
        REQUIRE(m.texcoords && m.vertex_count == 4);
        /* gltf_quads' corners take glTF uv (0, 1), (1, 1), (1, 0), (0, 0). */
        static const float gl[4][2] = { { 0, 1 }, { 1, 1 }, { 1, 0 }, { 0, 0 } };
        for (int i = 0; i < 4; i++) {
            float su = 2 * gl[i][0], sv = 3 * gl[i][1], c = cosf(0.5f), sn = sinf(0.5f);
            float gu = c * su + sn * sv + 0.5f, gv = -sn * su + c * sv + 0.25f;
            CHECK_NEAR(m.texcoords[2 * i], gu, 1e-5);
            CHECK_NEAR(m.texcoords[2 * i + 1], 1 - gv, 1e-5);
        }
        sr_destroy_mesh(sr_test_ctx(), &m);
        sr_scene *s = NULL;
        CHECK_EQ(sr_load_scene(sr_test_ctx(), path, NULL, &s, &e), SR_BAD_FORMAT);
        CHECK_STR_CONTAINS(e.message, "/images/1: ");
    }
    free(b64);
    free(png.p);
}
