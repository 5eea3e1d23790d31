/* test_gltf_lights.c - KHR_lights_punctual: the reader places each light
 * by its node's world matrix with glTF's defaults, and says which JSON
 * pointer is wrong in a malformed one; the PBR program's spot cone and
 * range window follow the extension's formulas, with the same bytes at
 * every SIMD level and thread count. */
#include "sr_test.h"
#include "gltf_parse.h"

#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Every test here reads glTF. */
SR_TEST_NEEDS(sr_io_have_gltf, "softrast was built without jansson (glTF)")

#define PI 3.14159265358979


/* A document of `lights` (the extension's array) and `nodes`, every node
 * a root of scene 0 unless a node lists it as a child. */
static sr_result parse_lights(const char *lights, const char *nodes, const char *roots,
                              warnings *w, sr_scene **s, sr_io_error *e)
{
    char json[8192];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_lights_punctual\"],"
             "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":%s}},"
             "\"nodes\":%s,\"scenes\":[{\"nodes\":%s}]}",
             lights, nodes, roots);
    sr_load_desc desc = { .warn = on_warn, .user = w };
    return sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json), &desc, s,
                         e);
}

static sr_scene *load_lights(const char *lights, const char *nodes, const char *roots,
                             warnings *w)
{
    sr_scene *s = NULL;
    sr_io_error e;
    if (parse_lights(lights, nodes, roots, w, &s, &e) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s", e.message);
    }
    return s;
}

SR_TEST(lights_are_placed_by_their_nodes_world_matrices_in_node_order)
{
    /* Node 0 moves to (1, 2, 3) and turns 90 degrees about +Y; its child
     * node 1, 2 along its local +Z, carries the spot: world (3, 2, 3),
     * its -Z turned to -X.  Node 2 turns -90 degrees about +X: its
     * directional light points down.  Node 3, scaled by 2 under node 4
     * at (0, 1, 0), carries the point light at (0, 1, 0) + 2 (1, 0, 0). */
    const double h = sqrt(0.5);
    char nodes[1024];
    snprintf(nodes, sizeof nodes,
             "[{\"translation\":[1,2,3],\"rotation\":[0,%.17g,0,%.17g],\"children\":[1]},"
             "{\"translation\":[0,0,2],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
             "{\"rotation\":[%.17g,0,0,%.17g],"
             "\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
             "{\"translation\":[1,0,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}},"
             "{\"translation\":[0,1,0],\"scale\":[2,2,2],\"children\":[3]}]",
             h, h, -h, h);
    warnings w = { 0 };
    sr_scene *s = load_lights(
        "[{\"type\":\"spot\",\"color\":[1,0.5,0.25],\"intensity\":40,\"range\":9,"
        "\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.5}},"
        "{\"type\":\"directional\",\"intensity\":3},"
        "{\"type\":\"point\",\"intensity\":7,\"range\":4}]",
        nodes, "[0,2,4]", &w);
    REQUIRE(s);
    CHECK_EQ(s->light_count, 3);
    CHECK_EQ(w.count, 0);
    const sr_scene_light *spot = &s->lights[0], *sun = &s->lights[1], *pt = &s->lights[2];
    CHECK_EQ(spot->node, 1);
    CHECK_EQ(spot->light_index, 0);
    CHECK_EQ(spot->light.type, SR_LIGHT_SPOT);
    CHECK_NEAR(spot->light.vector.x, 3, 1e-5);
    CHECK_NEAR(spot->light.vector.y, 2, 1e-5);
    CHECK_NEAR(spot->light.vector.z, 3, 1e-5);
    CHECK_NEAR(spot->light.direction.x, -1, 1e-5);
    CHECK_NEAR(spot->light.direction.y, 0, 1e-5);
    CHECK_NEAR(spot->light.direction.z, 0, 1e-5);
    CHECK_NEAR(spot->light.color.y, 0.5, 0);
    CHECK_NEAR(spot->light.intensity, 40, 0);
    CHECK_NEAR(spot->light.range, 9, 0);
    CHECK_NEAR(spot->light.inner_cone, 0.2, 1e-7);
    CHECK_NEAR(spot->light.outer_cone, 0.5, 1e-7);
    CHECK_NEAR(spot->world[12], 3, 1e-5);
    CHECK_EQ(sun->node, 2);
    CHECK_EQ(sun->light.type, SR_LIGHT_DIRECTIONAL);
    CHECK_NEAR(sun->light.vector.x, 0, 1e-6);
    CHECK_NEAR(sun->light.vector.y, -1, 1e-6);
    CHECK_NEAR(sun->light.vector.z, 0, 1e-6);
    CHECK_EQ(pt->node, 3);
    CHECK_EQ(pt->light.type, SR_LIGHT_POINT);
    CHECK_NEAR(pt->light.vector.x, 2, 1e-6);
    CHECK_NEAR(pt->light.vector.y, 1, 1e-6);
    CHECK_NEAR(pt->light.vector.z, 0, 1e-6);
    CHECK_NEAR(pt->light.range, 4, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(lights_take_the_extensions_defaults)
{
    warnings w = { 0 };
    sr_scene *s = load_lights(
        "[{\"type\":\"spot\",\"spot\":{}},{\"type\":\"point\"},"
        "{\"type\":\"directional\",\"range\":5},{\"type\":\"point\",\"intensity\":0},"
        "{\"type\":\"point\",\"color\":[0,0,0]}]",
        "[{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
        "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
        "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}},"
        "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":3}}},"
        "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":4}}},{}]",
        "[0,1,2,3,4,5]", &w);
    REQUIRE(s);
    CHECK_EQ(s->light_count, 5);
    CHECK_EQ(w.count, 0);   /* the extension is read: no "not read" warning */
    const sr_light *spot = &s->lights[0].light, *pt = &s->lights[1].light;
    CHECK_EQ(spot->type, SR_LIGHT_SPOT);
    CHECK_NEAR(spot->color.x, 1, 0);
    CHECK_NEAR(spot->color.y, 1, 0);
    CHECK_NEAR(spot->color.z, 1, 0);
    CHECK_NEAR(spot->intensity, 1, 0);
    CHECK_NEAR(spot->range, 0, 0);            /* infinite */
    CHECK_NEAR(spot->inner_cone, 0, 0);
    CHECK_NEAR(spot->outer_cone, PI / 4, 1e-6);
    CHECK_NEAR(spot->direction.z, -1, 0);     /* an identity node's -Z */
    CHECK_EQ(pt->type, SR_LIGHT_POINT);
    CHECK_NEAR(pt->intensity, 1, 0);
    CHECK_NEAR(pt->range, 0, 0);
    CHECK_NEAR(pt->vector.x, 0, 0);
    CHECK_NEAR(s->lights[2].light.range, 0, 0);   /* a directional light has none */
    /* Intensity 0 and black are off: sr_light's zeros would mean 1 and white.
     * The kind is kept beside it, and the zero that makes it dark. */
    CHECK_EQ(s->lights[3].light.type, SR_LIGHT_OFF);
    CHECK_EQ(s->lights[4].light.type, SR_LIGHT_OFF);
    for (int i = 0; i < 5; i++) {
        static const sr_light_type kind[5] = { SR_LIGHT_SPOT, SR_LIGHT_POINT,
                                               SR_LIGHT_DIRECTIONAL, SR_LIGHT_POINT,
                                               SR_LIGHT_POINT };
        CHECK_EQ(s->lights[i].type, kind[i]);
    }
    CHECK_NEAR(s->lights[3].light.intensity, 0, 0);
    CHECK_NEAR(s->lights[4].light.intensity, 1, 0);
    CHECK_NEAR(s->lights[4].light.color.x + s->lights[4].light.color.y +
               s->lights[4].light.color.z, 0, 0);
    sr_destroy_scene(sr_test_ctx(), s);
}

SR_TEST(a_file_without_the_extension_has_no_lights)
{
    const char *json = "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{}]}";
    sr_scene *s = NULL;
    sr_io_error e;
    REQUIRE(sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json), NULL, &s,
                          &e) == SR_OK);
    CHECK_EQ(s->light_count, 0);
    CHECK(s->lights == NULL);
    sr_destroy_scene(sr_test_ctx(), s);
}

static void expect_error(const char *lights, const char *nodes, const char *message)
{
    warnings w = { 0 };
    sr_scene *s = (sr_scene *)1;
    sr_io_error e;
    CHECK_EQ(parse_lights(lights, nodes, "[0]", &w, &s, &e), SR_BAD_FORMAT);
    CHECK(s == NULL);
    CHECK_STR_CONTAINS(e.message, message);
}

#define NODE0 "[{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}]"
#define LP "t.gltf: /extensions/KHR_lights_punctual/lights/"

SR_TEST(each_malformed_light_is_named_by_its_json_pointer)
{
    expect_error("[{\"type\":\"point\"},{\"type\":\"point\"},"
                 "{\"type\":\"spot\",\"spot\":{\"outerConeAngle\":2}}]",
                 NODE0, LP "2/spot/outerConeAngle: 2 is outside (0, pi/2]");
    expect_error("[{\"type\":\"spot\",\"spot\":{\"outerConeAngle\":0}}]", NODE0,
                 LP "0/spot/outerConeAngle: 0 is outside (0, pi/2]");
    expect_error("[{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.5,\"outerConeAngle\":0.5}}]",
                 NODE0, LP "0/spot/innerConeAngle: 0.5 is outside [0, outerConeAngle 0.5)");
    expect_error("[{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":-0.1}}]", NODE0,
                 LP "0/spot/innerConeAngle: -0.1 is outside");
    expect_error("[{\"type\":\"spot\"}]", NODE0, LP "0/spot: missing");
    expect_error("[{\"type\":\"point\",\"intensity\":-1}]", NODE0,
                 LP "0/intensity: -1 is negative");
    expect_error("[{\"type\":\"point\",\"range\":-2}]", NODE0, LP "0/range: -2 is not > 0");
    expect_error("[{\"type\":\"point\",\"range\":0}]", NODE0, LP "0/range: 0 is not > 0");
    expect_error("[{\"type\":\"point\",\"color\":[1,-1,0]}]", NODE0,
                 LP "0/color/1: -1 is negative");
    expect_error("[{\"type\":\"point\",\"color\":[1,1]}]", NODE0,
                 LP "0/color: not an array of 3 numbers");
    expect_error("[{\"type\":\"area\"}]", NODE0,
                 LP "0/type: \"area\" is not directional, point or spot");
    expect_error("[{\"intensity\":1}]", NODE0, LP "0/type: missing");
    expect_error("[7]", NODE0, LP "0: not an object");
    expect_error("[{\"type\":\"point\"}]", "[{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}}]",
                 "t.gltf: /nodes/0/extensions/KHR_lights_punctual/light: 1 is not an index below 1");
    expect_error("[{\"type\":\"point\"}]", "[{\"extensions\":{\"KHR_lights_punctual\":{}}}]",
                 "t.gltf: /nodes/0/extensions/KHR_lights_punctual/light: missing");
    expect_error("[{\"type\":\"spot\",\"spot\":{}}]",
                 "[{\"scale\":[1,1,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}]",
                 "t.gltf: /nodes/0/extensions/KHR_lights_punctual: the node's matrix collapses");
    expect_error("{}", NODE0, "t.gltf: /extensions/KHR_lights_punctual/lights: not an array");
}

SR_TEST(lights_past_the_programs_limit_are_named_in_one_warning)
{
    char lights[2048] = "[", nodes[2048] = "[", roots[256] = "[";
    for (int i = 0; i < SR_MAX_LIGHTS + 3; i++) {
        /* Light 1 is off: it takes no place among the eight. */
        snprintf(lights + strlen(lights), sizeof lights - strlen(lights),
                 "%s{\"type\":\"point\",\"intensity\":%d}", i ? "," : "", i == 1 ? 0 : 1);
        snprintf(nodes + strlen(nodes), sizeof nodes - strlen(nodes),
                 "%s{\"extensions\":{\"KHR_lights_punctual\":{\"light\":%d}}}", i ? "," : "", i);
        snprintf(roots + strlen(roots), sizeof roots - strlen(roots), "%s%d", i ? "," : "", i);
    }
    strcat(lights, "]");
    strcat(nodes, "]");
    strcat(roots, "]");
    warnings w = { 0 };
    sr_scene *s = load_lights(lights, nodes, roots, &w);
    REQUIRE(s);
    CHECK_EQ(s->light_count, SR_MAX_LIGHTS + 3);
    CHECK_EQ(w.count, 1);
    CHECK_STR_CONTAINS(w.last, "t.gltf: warning: /extensions/KHR_lights_punctual: 10 lights are "
                               "placed and a program takes 8, the first in node order: not "
                               "drawn: /nodes/9 (light 9), /nodes/10 (light 10)");
    sr_destroy_scene(sr_test_ctx(), s);
}

/* ---- the program's spot cone and range window ---------------------------- */

#define SIZE 96

/* A white, fully rough dielectric plane z = 0 over [-1.2, 1.2]^2, seen
 * from above orthographically onto [-1.2, 1.2]^2, lit by `light` alone
 * with no ambient, no tone curve: pixel (x, y) is the plane point
 * (-1.2 + 2.4 (x + 0.5) / SIZE, 1.2 - 2.4 (y + 0.5) / SIZE). */
static sr_framebuffer *lit_plane(sr_context *ctx, const sr_light *light)
{
    static const float pos[12] = { -1.2f, -1.2f, 0, 1.2f, -1.2f, 0, 1.2f, 1.2f, 0, -1.2f, 1.2f, 0 };
    static const float nrm[12] = { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    static const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 0, 5 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_ortho(-1.2f, 1.2f, -1.2f, 1.2f, 1.0f, 10.0f, false);
    sr_pbr_material m = sr_pbr_default_material();
    m.metallic = 0;
    m.roughness = 1;
    sr_pbr_desc d = { .material = &m, .view = &view, .projection = &proj,
                      .tonemap = SR_TONEMAP_NONE };
    d.lights[0] = *light;
    sr_framebuffer *fb = NULL;
    sr_pbr *p = NULL;
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = SIZE, .height = SIZE }, &fb) !=
            SR_OK ||
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } }) != SR_OK ||
        sr_make_pbr_program(ctx, &d, &p) != SR_OK ||
        sr_draw(ctx, fb, &(sr_state){ .program = sr_pbr_program(p), .cull = SR_CULL_NONE },
                &(sr_draw_desc){ .positions = pos, .normals = nrm, .vertex_count = 4,
                                 .indices = idx, .index_type = SR_INDEX_U32,
                                 .index_count = 6 }) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "drawing the plane failed");
    }
    sr_destroy_pbr_program(ctx, p);
    return fb;
}

static float plane_x(int x)
{
    return -1.2f + 2.4f * ((float)x + 0.5f) / SIZE;
}

/* The green channel of pixel (x, y) back to linear light. */
static double linear_at(const sr_framebuffer *fb, int x, int y)
{
    double c = sr_framebuffer_pixels(fb)[4 * ((size_t)y * SIZE + (size_t)x) + 1] / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static void save(const sr_framebuffer *fb, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.png", sr_test_out_dir(), name);
    sr_io_error err;
    sr_write_png(path, SIZE, SIZE, sr_framebuffer_pixels(fb), 4 * SIZE, NULL, &err);
}

SR_TEST(a_spot_light_follows_the_extensions_cone_falloff)
{
    /* A spot 1 above the plane's centre pointing down, cones 0.3 and 0.6
     * rad, against the point light in the same place: along the middle
     * row their ratio is t^2, t = (cos a - cos outer) / (cos inner - cos
     * outer) clamped, a the angle off the axis. */
    sr_context *ctx = sr_test_ctx();
    const double inner = 0.3, outer = 0.6;
    sr_light spot = { .type = SR_LIGHT_SPOT, .vector = { 0, 0, 1 }, .direction = { 0, 0, -2 },
                      .intensity = 2, .inner_cone = (float)inner, .outer_cone = (float)outer };
    sr_light point = { .type = SR_LIGHT_POINT, .vector = { 0, 0, 1 }, .intensity = 2 };
    sr_framebuffer *a = lit_plane(ctx, &spot), *b = lit_plane(ctx, &point);
    save(a, "gltf_lights_spot");
    int y = SIZE / 2, inside = 0, between = 0, outside = 0;
    double last = INFINITY;
    for (int x = SIZE / 2; x < SIZE; x++) {
        double r = plane_x(x), ang = atan2(fabs(r), 1.0);
        double t = (cos(ang) - cos(outer)) / (cos(inner) - cos(outer));
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        double got = linear_at(a, x, y), full = linear_at(b, x, y);
        uint8_t g = sr_framebuffer_pixels(a)[4 * ((size_t)y * SIZE + (size_t)x) + 1];
        if (ang < inner - 0.01) {
            /* Inside the inner cone the spot is the point light, bit for bit. */
            CHECK_EQ(g, sr_framebuffer_pixels(b)[4 * ((size_t)y * SIZE + (size_t)x) + 1]);
            inside++;
        } else if (ang > outer + 0.01) {
            CHECK_EQ(g, 0);
            outside++;
        } else {
            /* 8-bit sRGB codes: half a code is under 1% of the value here. */
            CHECK_NEAR(got, t * t * full, 0.004 + 0.02 * full);
            between++;
        }
        CHECK(got <= last);   /* never brighter farther out */
        last = got;
    }
    CHECK(inside >= 5);
    CHECK(between >= 8);
    CHECK(outside >= 5);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
}

SR_TEST(a_range_windows_the_falloff_to_zero_at_the_range)
{
    /* A point light 0.5 above the plane with range 1: the distance
     * reaches it at r = sqrt(0.75) ~ 0.866 on the plane.  The window is
     * clamp(1 - (d / range)^4, 0, 1)^2 of the unwindowed light. */
    sr_context *ctx = sr_test_ctx();
    sr_light ranged = { .type = SR_LIGHT_POINT, .vector = { 0, 0, 0.5f }, .intensity = 0.5f,
                        .range = 1 };
    sr_light open = { .type = SR_LIGHT_POINT, .vector = { 0, 0, 0.5f }, .intensity = 0.5f };
    sr_framebuffer *a = lit_plane(ctx, &ranged), *b = lit_plane(ctx, &open);
    save(a, "gltf_lights_range");
    int y = SIZE / 2, beyond = 0;
    for (int x = SIZE / 2; x < SIZE; x++) {
        double r = plane_x(x), dist = sqrt(r * r + 0.25);
        double q = dist * dist * dist * dist, wnd = 1 - q;
        wnd = wnd < 0 ? 0 : wnd * wnd;
        double got = linear_at(a, x, y), full = linear_at(b, x, y);
        CHECK_NEAR(got, wnd * full, 0.004 + 0.02 * full);
        if (dist >= 1.0) {
            CHECK_EQ(sr_framebuffer_pixels(a)[4 * ((size_t)y * SIZE + (size_t)x) + 1], 0);
            CHECK(full > 0.01);   /* the open light still reaches there */
            beyond++;
        }
    }
    CHECK(beyond >= 5);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
}

SR_TEST(spot_and_range_give_the_same_bytes_at_every_simd_level_and_thread_count)
{
    sr_light spot = { .type = SR_LIGHT_SPOT, .vector = { 0.3f, -0.2f, 0.9f },
                      .direction = { -0.2f, 0.1f, -1 }, .intensity = 1.5f, .range = 2.5f,
                      .inner_cone = 0.25f, .outer_cone = 0.7f, .color = { 1, 0.8f, 0.6f } };
    static const sr_simd_level levels[] = { SR_SIMD_OFF, SR_SIMD_BASE, SR_SIMD_AVX2,
                                            SR_SIMD_AVX512 };
    uint8_t *first = NULL;
    for (size_t l = 0; l < sizeof levels / sizeof *levels; l++) {
        for (int threads = 1; threads <= 3; threads += 2) {
            sr_context *ctx = NULL;
            REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads, .simd = levels[l] },
                                    &ctx) == SR_OK);
            sr_framebuffer *fb = lit_plane(ctx, &spot);
            const uint8_t *px = sr_framebuffer_pixels(fb);
            if (!first) {
                first = malloc(4 * SIZE * SIZE);
                REQUIRE(first);
                memcpy(first, px, 4 * SIZE * SIZE);
            } else if (memcmp(first, px, 4 * SIZE * SIZE) != 0) {
                sr_test_fail(__FILE__, __LINE__, "simd level %d, %d threads: other bytes",
                             (int)sr_context_simd(ctx), threads);
            }
            sr_destroy_framebuffer(ctx, fb);
            sr_destroy_context(ctx);
        }
    }
    free(first);
}

SR_TEST(the_program_refuses_bad_spot_lights_and_the_classic_shading_refuses_spots)
{
    sr_context *ctx = sr_test_ctx();
    sr_pbr *p = NULL;
    sr_pbr_desc d = { 0 };
    d.lights[2] = (sr_light){ .type = SR_LIGHT_SPOT, .direction = { 0, 0, -1 },
                              .inner_cone = 0.9f };   /* outer: pi/4 */
    CHECK_EQ(sr_make_pbr_program(ctx, &d, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_pbr_desc.lights[2]: cones must be");
    d.lights[2] = (sr_light){ .type = SR_LIGHT_SPOT };
    CHECK_EQ(sr_make_pbr_program(ctx, &d, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_pbr_desc.lights[2].direction must not be zero");
    d.lights[2] = (sr_light){ .type = SR_LIGHT_POINT, .range = -1 };
    CHECK_EQ(sr_make_pbr_program(ctx, &d, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_pbr_desc.lights[2].range must be >= 0");
    d.lights[2] = (sr_light){ .type = SR_LIGHT_SPOT + 1 };
    CHECK_EQ(sr_make_pbr_program(ctx, &d, &p), SR_INVALID_ARG);

    static const float pos[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    static const float nrm[9] = { 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) ==
            SR_OK);
    sr_state st = { .shading = SR_SHADING_PHONG };
    st.lights[0] = (sr_light){ .type = SR_LIGHT_SPOT, .vector = { 0, 0, 1 },
                               .direction = { 0, 0, -1 } };
    sr_draw_desc dd = { .positions = pos, .normals = nrm, .vertex_count = 3 };
    CHECK_EQ(sr_draw(ctx, fb, &st, &dd), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_state.lights[0]: spot lights and range are the "
                                           "PBR program's");
    st.lights[0] = (sr_light){ .type = SR_LIGHT_POINT, .vector = { 0, 0, 1 }, .range = 3 };
    CHECK_EQ(sr_draw(ctx, fb, &st, &dd), SR_INVALID_ARG);
    sr_destroy_framebuffer(ctx, fb);
}
