/* test_shadow.c - shadow maps: a quad's shadow on a plane (dark under
 * it, lit beside it, a monotonic penumbra, on the side away from a
 * slanted light), no acne on a lit sphere at grazing slopes, the fit
 * covering the bounds, the ground mesh, bad input refused, the same map
 * and visibility for 1 and 2 threads and with the vector kernels off,
 * and soft shadows that widen away from the caster.  Writes shadow_*.png
 * to the test output directory to look at. */
#include "sr_test.h"
#include "softrast.h"
#include "softrast_io.h"
#include "fragment/shadow.h"
#include "failing_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- a Lambert program that multiplies by the visibility ----------------- */

typedef struct lambert_uniforms {
    sr_mat4 mvp;
    const sr_shadow_map *sm;
    float to_light[3];          /* unit */
    float base[3];
    float ambient;
    bool no_normal;             /* look up without the normal offset */
} lambert_uniforms;

/* Varyings: 0..2 world position, 3..5 world normal (model = identity). */
static void lambert_vs(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    const lambert_uniforms *l = u;
    sr_vec4 c = sr_mat4_mul_vec4(&l->mvp, (sr_vec4){ in->position[0], in->position[1],
                                                     in->position[2], 1.0f });
    clip[0] = c.x, clip[1] = c.y, clip[2] = c.z, clip[3] = c.w;
    memcpy(vary, in->position, 3 * sizeof(float));
    memcpy(vary + 3, in->normal, 3 * sizeof(float));
}

/* Red: the shaded color's luminance; green: 255 where the surface faces
 * the light by more than grazing (n.l > 0.05); blue: the visibility. */
static void lambert_fs(const void *u, sr_fragment_quad *q)
{
    const lambert_uniforms *l = u;
    float vis[4];
    sr_shadow_visibility4(l->sm, q->varyings[0], l->no_normal ? NULL : q->varyings[3], vis);
    for (int i = 0; i < 4; i++) {
        float n[3] = { q->varyings[3][i], q->varyings[4][i], q->varyings[5][i] };
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float ndl = len > 0 ? (n[0] * l->to_light[0] + n[1] * l->to_light[1] +
                               n[2] * l->to_light[2]) / len : 0;
        float k = l->ambient + (1 - l->ambient) * fmaxf(ndl, 0) * vis[i];
        for (int c = 0; c < 3; c++) {
            q->color[c][i] = l->base[c] * k;
        }
        q->color[3][i] = 1;
    }
}

static void lambert_flags_fs(const void *u, sr_fragment_quad *q)
{
    const lambert_uniforms *l = u;
    float vis[4];
    lambert_fs(u, q);
    sr_shadow_visibility4(l->sm, q->varyings[0], l->no_normal ? NULL : q->varyings[3], vis);
    for (int i = 0; i < 4; i++) {
        float n[3] = { q->varyings[3][i], q->varyings[4][i], q->varyings[5][i] };
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float ndl = (n[0] * l->to_light[0] + n[1] * l->to_light[1] + n[2] * l->to_light[2]) / len;
        q->color[1][i] = ndl > 0.05f ? 1.0f : 0.0f;
        q->color[2][i] = vis[i];
    }
}

/* A shadow catcher (docs/shadows.md): the ground shows only the shadow,
 * black at 60% where fully shadowed, fading out over the outer half of
 * the ground (its texcoords) so it has no visible edge.  Blended
 * source-over, so a lit ground leaves the background as it was.
 * Varyings: 0..2 world position, 3..5 world normal, 6..7 texcoord. */
static void catcher_vs(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    lambert_vs(u, in, clip, vary);
    vary[6] = in->texcoord[0], vary[7] = in->texcoord[1];
}

static void catcher_fs(const void *u, sr_fragment_quad *q)
{
    const lambert_uniforms *l = u;
    float vis[4];
    sr_shadow_visibility4(l->sm, q->varyings[0], q->varyings[3], vis);
    for (int i = 0; i < 4; i++) {
        float dx = q->varyings[6][i] - 0.5f, dy = q->varyings[7][i] - 0.5f;
        float r = 2.0f * sqrtf(dx * dx + dy * dy);            /* 0 centre, 1 edge midpoints */
        float fade = fminf(fmaxf(2.0f - 2.0f * r, 0.0f), 1.0f);
        for (int c = 0; c < 3; c++) {
            q->color[c][i] = 0;
        }
        q->color[3][i] = 0.6f * (1.0f - vis[i]) * fade;
    }
}

static sr_draw_desc mesh_draw(const sr_mesh *m)
{
    return (sr_draw_desc){ .positions = m->positions, .normals = m->normals,
                           .vertex_count = m->vertex_count, .indices = m->indices,
                           .index_type = SR_INDEX_U32, .index_count = 3 * m->triangle_count };
}

/* A UV sphere of radius r at c with smooth normals. */
static bool make_sphere(sr_context *ctx, sr_vec3 c, float r, int stacks, int slices, sr_mesh *out)
{
    size_t nv = (size_t)(stacks + 1) * (slices + 1), nt = (size_t)stacks * slices * 2;
    float *p = malloc(nv * 3 * sizeof *p), *n = malloc(nv * 3 * sizeof *n);
    uint32_t *idx = malloc(nt * 3 * sizeof *idx);
    bool ok = p && n && idx;
    for (int i = 0; ok && i <= stacks; i++) {
        float th = (float)M_PI * (float)i / (float)stacks;
        for (int j = 0; j <= slices; j++) {
            float ph = 2.0f * (float)M_PI * (float)j / (float)slices;
            size_t v = (size_t)i * (slices + 1) + j;
            float d[3] = { sinf(th) * cosf(ph), cosf(th), -sinf(th) * sinf(ph) };
            for (int k = 0; k < 3; k++) {
                n[3 * v + k] = d[k];
            }
            p[3 * v + 0] = c.x + r * d[0], p[3 * v + 1] = c.y + r * d[1], p[3 * v + 2] = c.z + r * d[2];
        }
    }
    size_t t = 0;
    for (int i = 0; ok && i < stacks; i++) {
        for (int j = 0; j < slices; j++) {
            uint32_t a = (uint32_t)(i * (slices + 1) + j), b = a + (uint32_t)(slices + 1);
            uint32_t q[6] = { a, b, a + 1, a + 1, b, b + 1 };
            memcpy(idx + 3 * t, q, sizeof q);
            t += 2;
        }
    }
    sr_mesh src = { .vertex_count = nv, .positions = p, .normals = n, .triangle_count = nt,
                    .indices = idx };
    ok = ok && sr_make_mesh(ctx, &src, out) == SR_OK;
    free(p), free(n), free(idx);
    return ok;
}

static void save(sr_framebuffer *fb, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", sr_test_out_dir(), name);
    sr_write_png(path, sr_framebuffer_width(fb), sr_framebuffer_height(fb),
                 sr_framebuffer_pixels(fb), 4 * (size_t)sr_framebuffer_width(fb), NULL, NULL);
}

/* ---- a quad over a plane ------------------------------------------------- */

/* The quad [-1, 1] x [-1, 1] at height 1 over the plane y = 0. */
static const float quad_xyz[] = { -1, 1, -1, -1, 1, 1, 1, 1, 1, 1, 1, -1 };
static const uint32_t quad_idx[] = { 0, 1, 2, 0, 2, 3 };

static sr_shadow_map *quad_map(sr_context *ctx, sr_vec3 dir, int size, float radius)
{
    sr_shadow_map *sm = NULL;
    sr_shadow_desc d = { .direction = dir, .bounds_min = { -2, 0, -2 }, .bounds_max = { 2, 1, 2 },
                         .size = size, .filter_radius = radius };
    if (sr_make_shadow_map(ctx, &d, &sm) != SR_OK) {
        return NULL;
    }
    sr_result r = sr_shadow_map_draw(ctx, sm, &(sr_draw_desc){
        .positions = quad_xyz, .vertex_count = 4, .indices = quad_idx,
        .index_type = SR_INDEX_U32, .index_count = 6 });
    if (r != SR_OK) {
        sr_destroy_shadow_map(ctx, sm);
        return NULL;
    }
    return sm;
}

static float vis_at(const sr_shadow_map *sm, float x, float y, float z)
{
    static const float up[3] = { 0, 1, 0 };
    float v = -1;
    sr_shadow_visibility(sm, (const float[3]){ x, y, z }, up, &v);
    return v;
}

SR_TEST(quad_shadows_the_plane_under_it)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_shadow_map *sm = quad_map(ctx, (sr_vec3){ 0, -1, 0 }, 256, 0);
    REQUIRE(sm);
    CHECK_NEAR(vis_at(sm, 0, 0, 0), 0, 1e-6);
    CHECK_NEAR(vis_at(sm, 0.8f, 0, -0.8f), 0, 1e-6);
    CHECK_NEAR(vis_at(sm, 1.5f, 0, 0), 1, 1e-6);
    CHECK_NEAR(vis_at(sm, -1.9f, 0, 1.9f), 1, 1e-6);
    CHECK_NEAR(vis_at(sm, 0, 0, 5), 1, 1e-6);     /* off the map */
    /* Above the quad is lit: nothing is nearer the light. */
    CHECK_NEAR(vis_at(sm, 0, 1.5f, 0), 1, 1e-6);
    /* Across the edge x = 1 the visibility rises from 0 to 1 without a
     * step back, over about 2 radius texels. */
    sr_shadow_info info;
    REQUIRE(sr_query_shadow_map(sm, &info) == SR_OK);
    float prev = 0, t = info.texel_size;
    int partial = 0;
    for (float x = 1 - 4 * t; x <= 1 + 4 * t; x += t / 16) {
        float v = vis_at(sm, x, 0, 0.3f);
        CHECK(v >= prev - 1e-6f);
        partial += v > 0.01f && v < 0.99f;
        prev = v;
    }
    CHECK_NEAR(prev, 1, 1e-6);
    CHECK(partial >= 16 * 2 && partial <= 16 * 4);   /* 2r = 3 texels of penumbra */
    sr_destroy_shadow_map(ctx, sm);
    sr_destroy_context(ctx);
}

SR_TEST(slanted_light_casts_the_shadow_away_from_it)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    /* Light travelling towards +x and down at 45 degrees: the quad's shadow
     * on y = 0 is the quad moved by +1 in x. */
    sr_shadow_map *sm = quad_map(ctx, (sr_vec3){ 1, -1, 0 }, 512, 0);
    REQUIRE(sm);
    CHECK_NEAR(vis_at(sm, 1.0f, 0, 0), 0, 1e-6);
    CHECK_NEAR(vis_at(sm, 1.9f, 0, 0.5f), 0, 1e-6);
    CHECK_NEAR(vis_at(sm, -0.5f, 0, 0), 1, 1e-6);
    CHECK_NEAR(vis_at(sm, 1.0f, 0, 1.5f), 1, 1e-6);
    sr_destroy_shadow_map(ctx, sm);
    /* Bounds around the quad alone: the plane lies past the far plane,
     * and still receives the shadow (its depth clamps to the far value,
     * which only an empty texel passes). */
    REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 1, -1, 0 }, .bounds_min = { -1, 1, -1 },
                                                       .bounds_max = { 1, 1, 1 }, .size = 512 }, &sm) == SR_OK);
    REQUIRE(sr_shadow_map_draw(ctx, sm, &(sr_draw_desc){ .positions = quad_xyz, .vertex_count = 4,
                                                         .indices = quad_idx, .index_type = SR_INDEX_U32,
                                                         .index_count = 6 }) == SR_OK);
    CHECK_NEAR(vis_at(sm, 1.0f, 0, 0), 0, 1e-6);
    CHECK_NEAR(vis_at(sm, 1.9f, 0, 0.5f), 0, 1e-6);
    CHECK_NEAR(vis_at(sm, -0.5f, 0, 0), 1, 1e-6);
    CHECK_NEAR(vis_at(sm, 2.5f, 0, 0), 1, 1e-6);
    CHECK_NEAR(vis_at(sm, 0, 2, 0), 1, 1e-6);     /* above it, before the near plane */
    sr_destroy_shadow_map(ctx, sm);
    sr_destroy_context(ctx);
}

SR_TEST(clear_empties_the_map)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_shadow_map *sm = quad_map(ctx, (sr_vec3){ 0, -1, 0 }, 64, 0);
    REQUIRE(sm);
    CHECK_NEAR(vis_at(sm, 0, 0, 0), 0, 1e-6);
    CHECK(sr_shadow_map_clear(ctx, sm) == SR_OK);
    CHECK_NEAR(vis_at(sm, 0, 0, 0), 1, 1e-6);
    /* Cleared and redrawn with the quad moved by (1, 0, 1), the map
     * answers as one that only ever held the moved quad, in the old
     * quad's place too and across the edge they share. */
    float moved[12];
    for (int i = 0; i < 12; i++) {
        moved[i] = quad_xyz[i] + (i % 3 != 1 ? 1.0f : 0.0f);
    }
    sr_draw_desc d = { .positions = moved, .vertex_count = 4, .indices = quad_idx,
                       .index_type = SR_INDEX_U32, .index_count = 6 };
    sr_shadow_map *fresh = NULL;
    REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 0, -1, 0 },
                                                       .bounds_min = { -2, 0, -2 }, .bounds_max = { 2, 1, 2 },
                                                       .size = 64 }, &fresh) == SR_OK);
    CHECK(sr_shadow_map_draw(ctx, sm, &d) == SR_OK);
    CHECK(sr_shadow_map_draw(ctx, fresh, &d) == SR_OK);
    int differ = 0, partial = 0;
    for (float z = -1.5f; z <= 1.5f; z += 0.05f) {
        for (float x = -1.5f; x <= 1.5f; x += 0.013f) {
            float a = vis_at(sm, x, 0, z), b = vis_at(fresh, x, 0, z);
            differ += a != b;
            partial += a > 0 && a < 1;
        }
    }
    CHECK_EQ(differ, 0);
    CHECK(partial > 100);
    CHECK_NEAR(vis_at(sm, -0.5f, 0, -0.5f), 1, 1e-6);
    sr_destroy_shadow_map(ctx, fresh);
    sr_destroy_shadow_map(ctx, sm);
    sr_destroy_context(ctx);
}

/* ---- acne ---------------------------------------------------------------- */

/* Renders the sphere lit from `to_light` with its own shadow map; returns
 * the count of pixels facing the light (n.l > 0.05) whose visibility is
 * below 1/2, and in *lit the count facing it. */
static int sphere_dark_pixels(sr_context *ctx, sr_vec3 to_light, const sr_shadow_desc *extra,
                              bool no_normal, int *lit, const char *png)
{
    enum { W = 256, H = 256 };
    sr_mesh sphere = { 0 };
    sr_shadow_map *sm = NULL;
    sr_framebuffer *fb = NULL;
    int dark = -1;
    *lit = 0;
    if (!make_sphere(ctx, (sr_vec3){ 0, 0, 0 }, 1, 48, 96, &sphere)) {
        return -1;
    }
    sr_shadow_desc d = *extra;
    d.direction = sr_vec3_scale(to_light, -1);
    d.bounds_min = (sr_vec3){ -1, -1, -1 };
    d.bounds_max = (sr_vec3){ 1, 1, 1 };
    sr_draw_desc draw = mesh_draw(&sphere);
    if (sr_make_shadow_map(ctx, &d, &sm) == SR_OK && sr_shadow_map_draw(ctx, sm, &draw) == SR_OK &&
        sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) == SR_OK) {
        sr_vec3 l = sr_vec3_normalize(to_light);
        /* The camera sees the terminator side on. */
        sr_mat4 view = sr_look_at((sr_vec3){ 0.3f, 0.5f, 3.5f }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
        sr_mat4 proj = sr_perspective(0.7f, 1, 0.5f, 10, false);
        lambert_uniforms u = { .mvp = sr_mat4_mul(&proj, &view), .sm = sm,
                               .to_light = { l.x, l.y, l.z }, .base = { 1, 1, 1 }, .ambient = 0.1f,
                               .no_normal = no_normal };
        sr_program prog = { .vertex = lambert_vs, .fragment = png ? lambert_fs : lambert_flags_fs,
                            .uniforms = &u, .varying_count = 6 };
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        if (png) {
            sr_draw(ctx, fb, &(sr_state){ .program = &prog }, &draw);
            save(fb, png);
            prog.fragment = lambert_flags_fs;
            sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        }
        if (sr_draw(ctx, fb, &(sr_state){ .program = &prog }, &draw) == SR_OK) {
            const uint8_t *px = sr_framebuffer_pixels(fb);
            dark = 0;
            for (int i = 0; i < W * H; i++) {
                if (px[4 * i + 1] == 255) {
                    ++*lit;
                    dark += px[4 * i + 2] < 230;
                }
            }
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_shadow_map(ctx, sm);
    sr_destroy_mesh(ctx, &sphere);
    return dark;
}

SR_TEST(lit_sphere_shows_no_acne_at_grazing_slopes)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(NULL, &ctx) == SR_OK);
    /* Light from the side: the terminator runs down the visible face. */
    sr_vec3 lights[] = { { 1, 0.2f, 0.1f }, { 0.3f, 1, 0.4f }, { -0.7f, 0.5f, 0.5f } };
    for (int k = 0; k < 3; k++) {
        int lit = 0;
        int dark = sphere_dark_pixels(ctx, lights[k], &(sr_shadow_desc){ .size = 1024 }, false, &lit,
                                      k == 0 ? "shadow_sphere.png" : NULL);
        CHECK(lit > 5000);
        /* No pixel facing the light is in its own shadow. */
        CHECK_EQ(dark, 0);
        /* Nor with a light of some size (wider filters, larger offsets). */
        dark = sphere_dark_pixels(ctx, lights[k], &(sr_shadow_desc){ .size = 1024, .light_radius = 0.05f },
                                  false, &lit, NULL);
        CHECK_EQ(dark, 0);
    }
    /* Without the offsets the same scene does show acne: the test can see it. */
    int lit = 0;
    int dark = sphere_dark_pixels(ctx, lights[0],
                                  &(sr_shadow_desc){ .size = 1024, .offset_factor = 1e-6f,
                                                     .offset_units = 1e-6f, .normal_offset = 1e-6f,
                                                     .filter_radius = 0.5f }, true, &lit,
                                  "shadow_sphere_no_offset.png");
    CHECK(dark > lit / 100);
    sr_destroy_context(ctx);
}

/* ---- fitting ------------------------------------------------------------- */

SR_TEST(fit_covers_the_bounds_from_any_direction)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_rng rng = { 0x5eed5 };
    for (int k = 0; k < 200; k++) {
        sr_vec3 dir = { (float)sr_rng_range(&rng, -1, 1), (float)sr_rng_range(&rng, -1, 1),
                        (float)sr_rng_range(&rng, -1, 1) };
        if (k == 0) {
            dir = (sr_vec3){ 0, -1, 0 };     /* straight down: the up hint must change */
        }
        sr_vec3 lo = { (float)sr_rng_range(&rng, -100, 100), (float)sr_rng_range(&rng, -100, 100),
                       (float)sr_rng_range(&rng, -100, 100) };
        sr_vec3 hi = { lo.x + (float)sr_rng_range(&rng, 0, 50), lo.y + (float)sr_rng_range(&rng, 0, 50),
                       lo.z + (k == 1 ? 0.0f : (float)sr_rng_range(&rng, 0, 50)) };
        sr_shadow_map *sm = NULL;
        REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = dir, .bounds_min = lo,
                                                           .bounds_max = hi, .size = 64 }, &sm) == SR_OK);
        sr_shadow_info info;
        REQUIRE(sr_query_shadow_map(sm, &info) == SR_OK);
        sr_mat4 vp = sr_mat4_mul(&info.projection, &info.view);
        /* Every corner inside the square, the filter's margin (radius + 2
         * texels) from its edge, and inside the depth range. */
        float margin = 2.0f * (info.filter_radius + 2.0f) / (float)info.size;
        float widest = 0;
        for (int i = 0; i < 8; i++) {
            sr_vec4 c = sr_mat4_mul_vec4(&vp, (sr_vec4){ i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y,
                                                         i & 4 ? hi.z : lo.z, 1 });
            CHECK(fabsf(c.x) <= 1 - margin + 1e-5f);
            CHECK(fabsf(c.y) <= 1 - margin + 1e-5f);
            CHECK(c.z > 0 && c.z < 1);
            widest = fmaxf(widest, fmaxf(fabsf(c.x), fabsf(c.y)));
        }
        /* And tightly: some corner reaches the margin. */
        CHECK(widest >= 1 - margin - 1e-4f);
        /* The light looks along the direction: a point nearer the light
         * has the smaller depth. */
        sr_vec3 c = sr_vec3_scale(sr_vec3_add(lo, hi), 0.5f);
        sr_vec3 toward = sr_vec3_sub(c, sr_vec3_scale(sr_vec3_normalize(dir), 0.1f));
        sr_vec4 a = sr_mat4_mul_vec4(&vp, (sr_vec4){ c.x, c.y, c.z, 1 });
        sr_vec4 b = sr_mat4_mul_vec4(&vp, (sr_vec4){ toward.x, toward.y, toward.z, 1 });
        CHECK(b.z < a.z);
        sr_destroy_shadow_map(ctx, sm);
    }
    sr_destroy_context(ctx);
}

/* ---- the ground ---------------------------------------------------------- */

SR_TEST(ground_lies_under_the_bounds_facing_up)
{
    sr_context *ctx = sr_test_ctx();
    struct { sr_vec3 up; int axis; } cases[] = { { { 0, 0, 0 }, 1 }, { { 0, 0, 2 }, 2 }, { { -1, 0, 0 }, 0 } };
    sr_vec3 lo = { -1, 2, 3 }, hi = { 3, 4, 4 };
    for (int k = 0; k < 3; k++) {
        sr_mesh g = { 0 };
        REQUIRE(sr_make_ground_mesh(ctx, &(sr_ground_desc){ .bounds_min = lo, .bounds_max = hi,
                                                            .up = cases[k].up, .scale = 2 }, &g) == SR_OK);
        CHECK_EQ(g.vertex_count, 4);
        CHECK_EQ(g.triangle_count, 2);
        int a = cases[k].axis;
        float sign = k == 2 ? -1.0f : 1.0f;
        float base = sign > 0 ? (&lo.x)[a] : (&hi.x)[a];
        float extent = 0;
        for (int j = 0; j < 3; j++) {
            extent = j == a ? extent : fmaxf(extent, (&hi.x)[j] - (&lo.x)[j]);
        }
        for (size_t v = 0; v < 4; v++) {
            CHECK_NEAR(g.positions[3 * v + a], base, 1e-5);
            CHECK_NEAR(g.normals[3 * v + a], sign, 1e-6);
            /* Centred under the box, 2 x its widest extent a side. */
            for (int j = 0; j < 3; j++) {
                if (j != a) {
                    float mid = 0.5f * ((&lo.x)[j] + (&hi.x)[j]);
                    CHECK_NEAR(fabsf(g.positions[3 * v + j] - mid), extent, 1e-4);
                }
            }
        }
        /* Counter-clockwise seen from above: the winding's normal is up. */
        for (size_t t = 0; t < 2; t++) {
            const float *p0 = &g.positions[3 * g.indices[3 * t]];
            const float *p1 = &g.positions[3 * g.indices[3 * t + 1]];
            const float *p2 = &g.positions[3 * g.indices[3 * t + 2]];
            sr_vec3 e1 = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
            sr_vec3 e2 = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
            sr_vec3 n = sr_vec3_cross(e1, e2);
            CHECK((&n.x)[a] * sign > 0);
        }
        sr_destroy_mesh(ctx, &g);
    }
}

/* ---- bad input ----------------------------------------------------------- */

SR_TEST(bad_input_is_refused)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_shadow_map *sm = NULL;
    const sr_shadow_desc good = { .direction = { 0, -1, 0 }, .bounds_min = { -1, -1, -1 },
                                  .bounds_max = { 1, 1, 1 }, .size = 32 };
    CHECK_EQ(sr_make_shadow_map(NULL, &good, &sm), SR_INVALID_ARG);
    CHECK_EQ(sr_make_shadow_map(ctx, NULL, &sm), SR_INVALID_ARG);
    CHECK_EQ(sr_make_shadow_map(ctx, &good, NULL), SR_INVALID_ARG);
    struct { sr_shadow_desc d; sr_result r; const char *field; } bad[] = {
        { { .bounds_min = { -1, -1, -1 }, .bounds_max = { 1, 1, 1 } }, SR_INVALID_ARG, "direction" },
        { { .direction = { NAN, -1, 0 }, .bounds_max = { 1, 1, 1 } }, SR_INVALID_ARG, "direction" },
        { { .direction = { 0, -INFINITY, 0 }, .bounds_max = { 1, 1, 1 } }, SR_INVALID_ARG, "direction" },
        { { .direction = { 0, -1, 0 }, .bounds_min = { 0, NAN, 0 } }, SR_INVALID_ARG, "bounds" },
        { { .direction = { 0, -1, 0 }, .bounds_min = { 2, 0, 0 }, .bounds_max = { 1, 1, 1 } },
          SR_INVALID_ARG, "bounds_min must be <= bounds_max" },
        { { .direction = { 0, -1, 0 }, .bounds_max = { 1e30f, 1, 1 } }, SR_TOO_LARGE, "1e18" },
        { { .direction = { 0, -1, 0 }, .bounds_max = { 1, 1, 1 }, .size = 8 }, SR_INVALID_ARG, "size" },
        { { .direction = { 0, -1, 0 }, .bounds_max = { 1, 1, 1 }, .size = 100000 }, SR_INVALID_ARG, "size" },
        { { .direction = { 0, -1, 0 }, .bounds_max = { 1, 1, 1 }, .size = -4 }, SR_INVALID_ARG, "size" },
        { { .direction = { 0, -1, 0 }, .bounds_max = { 1, 1, 1 }, .filter_radius = 100 },
          SR_INVALID_ARG, "filter_radius" },
        { { .direction = { 0, -1, 0 }, .bounds_max = { 1, 1, 1 }, .filter_radius = NAN },
          SR_INVALID_ARG, "filter_radius" },
        { { .direction = { 0, -1, 0 }, .bounds_max = { 1, 1, 1 }, .normal_offset = -1 },
          SR_INVALID_ARG, "normal_offset" },
        { { .direction = { 0, -1, 0 }, .bounds_max = { 1, 1, 1 }, .offset_factor = INFINITY },
          SR_INVALID_ARG, "offset_factor" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sm = (sr_shadow_map *)&good;   /* must come back NULL */
        CHECK_EQ(sr_make_shadow_map(ctx, &bad[i].d, &sm), bad[i].r);
        CHECK(sm == NULL);
        CHECK_STR_CONTAINS(sr_context_error(ctx), bad[i].field);
    }
    REQUIRE(sr_make_shadow_map(ctx, &good, &sm) == SR_OK);
    float v = 0, v4[4];
    const float p[12] = { 0 };
    CHECK_EQ(sr_shadow_map_draw(ctx, sm, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_shadow_map_draw(ctx, NULL, &(sr_draw_desc){ 0 }), SR_INVALID_ARG);
    CHECK_EQ(sr_shadow_map_draw(ctx, sm, &(sr_draw_desc){ .vertex_count = 3 }), SR_INVALID_ARG);
    CHECK_EQ(sr_shadow_map_clear(ctx, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_shadow_visibility(NULL, p, NULL, &v), SR_INVALID_ARG);
    CHECK_EQ(sr_shadow_visibility(sm, NULL, NULL, &v), SR_INVALID_ARG);
    CHECK_EQ(sr_shadow_visibility(sm, p, NULL, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_shadow_visibility4(NULL, p, NULL, v4), SR_INVALID_ARG);
    CHECK_EQ(sr_shadow_visibility4(sm, p, NULL, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_query_shadow_map(sm, NULL), SR_INVALID_ARG);
    /* A point that is not finite is lit, not NaN. */
    CHECK_EQ(sr_shadow_visibility(sm, (const float[3]){ NAN, 0, 0 }, NULL, &v), SR_OK);
    CHECK(v == 1.0f);
    sr_destroy_shadow_map(ctx, sm);

    sr_mesh g = { 0 };
    CHECK_EQ(sr_make_ground_mesh(NULL, &(sr_ground_desc){ 0 }, &g), SR_INVALID_ARG);
    CHECK_EQ(sr_make_ground_mesh(ctx, NULL, &g), SR_INVALID_ARG);
    CHECK_EQ(sr_make_ground_mesh(ctx, &(sr_ground_desc){ 0 }, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_make_ground_mesh(ctx, &(sr_ground_desc){ .bounds_min = { 1, 0, 0 } }, &g), SR_INVALID_ARG);
    CHECK_EQ(sr_make_ground_mesh(ctx, &(sr_ground_desc){ .up = { NAN, 1, 0 } }, &g), SR_INVALID_ARG);
    CHECK_EQ(sr_make_ground_mesh(ctx, &(sr_ground_desc){ .scale = -1 }, &g), SR_INVALID_ARG);
    CHECK_EQ(sr_make_ground_mesh(ctx, &(sr_ground_desc){ .drop = 2 }, &g), SR_INVALID_ARG);
    CHECK(g.positions == NULL);
    sr_destroy_context(ctx);
}

/* ---- threads ------------------------------------------------------------- */

/* The teapot's map and a grid of lookups over the ground, on a context
 * of `threads` threads: the map's depth words then the visibilities. */
static bool teapot_map_bytes(int threads, sr_simd_level simd, uint32_t **depth, float **vis, int *size)
{
    enum { N = 64 };
    sr_context *ctx = NULL;
    sr_mesh pot = { 0 };
    sr_shadow_map *sm = NULL;
    bool ok = sr_make_context(&(sr_context_desc){ .threads = threads, .simd = simd }, &ctx) == SR_OK &&
              sr_make_teapot(ctx, 6, &pot) == SR_OK;
    sr_vec3 lo, hi;
    ok = ok && sr_mesh_bounds(&pot, &lo, &hi);
    ok = ok && sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 0.4f, -1, -0.3f },
                                                          .bounds_min = lo, .bounds_max = hi,
                                                          .size = 512 }, &sm) == SR_OK;
    sr_draw_desc draw = mesh_draw(&pot);
    ok = ok && sr_shadow_map_draw(ctx, sm, &draw) == SR_OK;
    if (ok) {
        *size = sm->size;
        *depth = malloc((size_t)sm->size * sm->size * sizeof **depth);
        *vis = malloc(N * N * sizeof **vis);
        ok = *depth && *vis;
    }
    if (ok) {
        memcpy(*depth, sm->depth, (size_t)sm->size * sm->size * sizeof **depth);
        for (int j = 0; j < N; j++) {
            for (int i = 0; i < N; i++) {
                float p[3] = { lo.x + (hi.x - lo.x) * i / (N - 1), lo.y, lo.z + (hi.z - lo.z) * j / (N - 1) };
                sr_shadow_visibility(sm, p, (const float[3]){ 0, 1, 0 }, &(*vis)[j * N + i]);
            }
        }
    }
    sr_destroy_shadow_map(ctx, sm);
    sr_destroy_mesh(ctx, &pot);
    sr_destroy_context(ctx);
    return ok;
}

SR_TEST(same_map_and_visibility_for_any_threads_and_simd)
{
    uint32_t *d1 = NULL, *d2 = NULL, *d3 = NULL;
    float *v1 = NULL, *v2 = NULL, *v3 = NULL;
    int s1 = 0, s2 = 0, s3 = 0;
    REQUIRE(teapot_map_bytes(1, SR_SIMD_DEFAULT, &d1, &v1, &s1));
    REQUIRE(teapot_map_bytes(2, SR_SIMD_DEFAULT, &d2, &v2, &s2));
    /* And with the scalar kernels drawing the map. */
    REQUIRE(teapot_map_bytes(2, SR_SIMD_OFF, &d3, &v3, &s3));
    CHECK_EQ(s1, s2);
    CHECK_EQ(s1, s3);
    CHECK(memcmp(d1, d2, (size_t)s1 * s1 * sizeof *d1) == 0);
    CHECK(memcmp(v1, v2, 64 * 64 * sizeof *v1) == 0);
    CHECK(memcmp(d1, d3, (size_t)s1 * s1 * sizeof *d1) == 0);
    CHECK(memcmp(v1, v3, 64 * 64 * sizeof *v1) == 0);
    /* The pot's shadow is on the ground: some of it dark, some lit. */
    int dark = 0, lit = 0;
    for (int i = 0; i < 64 * 64; i++) {
        dark += v1[i] < 0.01f;
        lit += v1[i] > 0.99f;
    }
    CHECK(dark > 200);
    CHECK(lit > 200);
    free(d1), free(d2), free(d3), free(v1), free(v2), free(v3);
}

/* Four lanes scattered, or clustered as a fragment quad's are (which the
 * quad test settles together when it can), with the fixed filter and
 * with a light of some size: each lane equals the one-point lookup. */
SR_TEST(lanes_match_the_single_lookup)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    for (int soft = 0; soft < 2; soft++) {
        float xyz[12];
        for (int i = 0; i < 12; i++) {
            xyz[i] = quad_xyz[i] * (i % 3 == 1 ? 0.5f : 1.0f);   /* at height 0.5 */
        }
        sr_shadow_map *sm = NULL;
        REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 0.3f, -1, 0.2f },
                                                           .bounds_min = { -2, 0, -2 }, .bounds_max = { 2, 1, 2 },
                                                           .size = 128, .filter_radius = 2.5f,
                                                           .light_radius = soft ? 0.1f : 0 }, &sm) == SR_OK);
        REQUIRE(sr_shadow_map_draw(ctx, sm, &(sr_draw_desc){ .positions = xyz, .vertex_count = 4,
                                                             .indices = quad_idx, .index_type = SR_INDEX_U32,
                                                             .index_count = 6 }) == SR_OK);
        sr_rng rng = { 77 };
        int settled[3] = { 0 };   /* quads all lit, all dark, mixed */
        for (int k = 0; k < 4000; k++) {
            float pos[12], nrm[12], out[4];
            float spread = k & 1 ? 2.0f : 0.01f;
            float base[3] = { (float)sr_rng_range(&rng, -2, 2), (float)sr_rng_range(&rng, 0, 0.3),
                              (float)sr_rng_range(&rng, -2, 2) };
            for (int i = 0; i < 12; i++) {
                pos[i] = base[i / 4] + (float)sr_rng_range(&rng, -spread, spread) * (i / 4 == 1 ? 0.1f : 1.0f);
                nrm[i] = (float)sr_rng_range(&rng, -1, 1) + (i / 4 == 1 ? 1.5f : 0.0f);
            }
            REQUIRE(sr_shadow_visibility4(sm, pos, nrm, out) == SR_OK);
            int lit = 0, dark = 0;
            for (int i = 0; i < 4; i++) {
                float v;
                sr_shadow_visibility(sm, (const float[3]){ pos[i], pos[4 + i], pos[8 + i] },
                                     (const float[3]){ nrm[i], nrm[4 + i], nrm[8 + i] }, &v);
                CHECK(v == out[i]);
                CHECK(v >= 0 && v <= 1);
                lit += v == 1, dark += v == 0;
            }
            settled[lit == 4 ? 0 : dark == 4 ? 1 : 2]++;
        }
        /* Every kind of quad came up. */
        CHECK(settled[0] > 100 && settled[1] > 100 && settled[2] > 100);
        sr_destroy_shadow_map(ctx, sm);
    }
    sr_destroy_context(ctx);
}

/* ---- a thumbnail ----------------------------------------------------------- */

/* The teapot over a ground plane lit from the upper left (the light
 * travels towards +x): shadow_teapot.png.  The ground right of the pot is
 * in shadow, left of it lit.  Then with the ground as a shadow catcher
 * and a soft light: shadow_catcher.png, and sr_draw_shadow_catcher's
 * catcher alone: shadow_catcher_only.png. */
SR_TEST(teapot_shadow_falls_on_the_ground_away_from_the_light)
{
    enum { W = 480, H = 320 };
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(NULL, &ctx) == SR_OK);
    sr_mesh pot = { 0 }, ground = { 0 };
    sr_shadow_map *sm = NULL;
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_teapot(ctx, 8, &pot) == SR_OK);
    sr_vec3 lo, hi;
    REQUIRE(sr_mesh_bounds(&pot, &lo, &hi));
    REQUIRE(sr_make_ground_mesh(ctx, &(sr_ground_desc){ .bounds_min = lo, .bounds_max = hi }, &ground) == SR_OK);
    sr_vec3 dir = { 1, -1.2f, -0.5f };
    REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = dir, .bounds_min = lo,
                                                       .bounds_max = hi }, &sm) == SR_OK);
    sr_draw_desc pot_draw = mesh_draw(&pot), ground_draw = mesh_draw(&ground);
    REQUIRE(sr_shadow_map_draw(ctx, sm, &pot_draw) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H, .samples = 4 },
                                &fb) == SR_OK);
    sr_vec3 l = sr_vec3_normalize(sr_vec3_scale(dir, -1));
    sr_mat4 view = sr_look_at((sr_vec3){ 1.5f, 4.5f, 8.0f }, (sr_vec3){ 0.6f, 0.8f, 0 },
                              (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.75f, (float)W / H, 1, 30, false);
    lambert_uniforms u = { .mvp = sr_mat4_mul(&proj, &view), .sm = sm, .to_light = { l.x, l.y, l.z },
                           .base = { 0.9f, 0.55f, 0.3f }, .ambient = 0.25f };
    lambert_uniforms ug = u;
    ug.base[0] = ug.base[1] = ug.base[2] = 0.85f;
    sr_program prog = { .vertex = lambert_vs, .fragment = lambert_fs, .uniforms = &u, .varying_count = 6 };
    sr_program progg = prog;
    progg.uniforms = &ug;
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.2f, 0.22f, 0.25f, 1 } });
    CHECK(sr_draw(ctx, fb, &(sr_state){ .program = &progg }, &ground_draw) == SR_OK);
    CHECK(sr_draw(ctx, fb, &(sr_state){ .program = &prog }, &pot_draw) == SR_OK);
    save(fb, "shadow_teapot.png");
    /* On the ground: right of the pot and behind it (the shadow's side), left of it. */
    float shade = -1, lit = -1;
    sr_shadow_visibility(sm, (const float[3]){ 2.0f, lo.y, -0.8f }, (const float[3]){ 0, 1, 0 }, &shade);
    sr_shadow_visibility(sm, (const float[3]){ lo.x - 0.3f, lo.y, 0 }, (const float[3]){ 0, 1, 0 }, &lit);
    CHECK(shade < 0.05f);
    CHECK(lit > 0.95f);

    /* The same scene with the ground as a shadow catcher over the
     * background, and a light of 0.04 rad for a shadow that softens away
     * from the pot: the ground's lit part leaves the background's bytes. */
    sr_shadow_map *soft = NULL;
    REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = dir, .bounds_min = lo, .bounds_max = hi,
                                                       .size = 1024, .light_radius = 0.04f }, &soft) == SR_OK);
    REQUIRE(sr_shadow_map_draw(ctx, soft, &pot_draw) == SR_OK);
    u.sm = ug.sm = soft;
    sr_program catcher = { .vertex = catcher_vs, .fragment = catcher_fs, .uniforms = &ug,
                           .varying_count = 8 };
    sr_state blend = { .program = &catcher, .depth_write = SR_OFF,
                       .blend = { .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                  .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA, .src_alpha = SR_BLEND_ZERO,
                                  .dst_alpha = SR_BLEND_ONE } };
    const float bg[4] = { 0.93f, 0.93f, 0.95f, 1 };
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { bg[0], bg[1], bg[2], bg[3] } });
    CHECK(sr_draw(ctx, fb, &blend, &(sr_draw_desc){ .positions = ground.positions, .normals = ground.normals,
                                                    .texcoords = ground.texcoords, .vertex_count = 4,
                                                    .indices = ground.indices, .index_type = SR_INDEX_U32,
                                                    .index_count = 6 }) == SR_OK);
    CHECK(sr_draw(ctx, fb, &(sr_state){ .program = &prog }, &pot_draw) == SR_OK);
    save(fb, "shadow_catcher.png");
    const uint8_t *px = sr_framebuffer_pixels(fb);
    const uint8_t *corner = px + 4 * ((H - 2) * W + 2);        /* ground, lit, far from the pot */
    CHECK_EQ(corner[0], px[0]);                                /* the background's bytes */
    CHECK_EQ(corner[1], px[1]);
    int darker = 0;
    for (int i = 0; i < W * H; i++) {
        darker += px[4 * i + 2] < px[2] - 40 && px[4 * i] < px[0] - 40;
    }
    CHECK(darker > 2000);                                      /* the pot and its shadow */

    /* sr_draw_shadow_catcher alone, in a framebuffer of one sample: the
     * shadow and nothing else - the lit ground keeps the background's
     * bytes, the shadow falls away from the light; a light from below
     * draws nothing; bad arguments are refused. */
    sr_destroy_framebuffer(ctx, fb);
    fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    sr_shadow_catcher_desc d = { .ground = &ground, .map = soft, .direction = dir,
                                 .bounds_min = lo, .bounds_max = hi, .view = &view,
                                 .projection = &proj };
    const sr_state state = { 0 };
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { bg[0], bg[1], bg[2], bg[3] } });
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, &d), SR_OK);
    save(fb, "shadow_catcher_only.png");
    px = sr_framebuffer_pixels(fb);
    /* The pixels of world points on the ground, left of the pot (lit) and
     * right of and behind it (in its shadow). */
    sr_mat4 vp = u.mvp;
    int at[2];
    const sr_vec3 points[2] = { { lo.x - 0.3f, lo.y, 0 }, { 2.0f, lo.y, -0.8f } };
    for (int k = 0; k < 2; k++) {
        sr_vec4 c = sr_mat4_mul_vec4(&vp, (sr_vec4){ points[k].x, points[k].y, points[k].z, 1 });
        int x = (int)((c.x / c.w + 1) * 0.5f * W), y = (int)((1 - c.y / c.w) * 0.5f * H);
        REQUIRE(x >= 0 && x < W && y >= 0 && y < H);
        at[k] = y * W + x;
    }
    CHECK_EQ(px[4 * at[0]], px[0]);                            /* lit: the background's bytes */
    CHECK_EQ(px[4 * at[0] + 2], px[2]);
    CHECK(px[4 * at[1]] < px[0] - 60);                         /* shadowed: darker */
    int shadowed = 0, other = 0;
    for (int i = 0; i < W * H; i++) {
        shadowed += px[4 * i] < px[0];
        /* Black blended over: every channel scaled alike, never tinted. */
        other += px[4 * i] > px[0] || px[4 * i + 2] > px[2] || px[4 * i + 3] != 255;
    }
    CHECK(shadowed > 2000);
    CHECK_EQ(other, 0);

    /* A light from below casts nothing on the ground: nothing is drawn. */
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.5f, 0.5f, 0.5f, 1 } });
    sr_shadow_catcher_desc up = d;
    up.direction = (sr_vec3){ 0, 1, 0 };
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, &up), SR_OK);
    px = sr_framebuffer_pixels(fb);
    int changed = 0;
    for (int i = 0; i < W * H; i++) {
        changed += px[4 * i] != px[0];
    }
    CHECK_EQ(changed, 0);

    CHECK_EQ(sr_draw_shadow_catcher(NULL, fb, &state, &d), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_shadow_catcher(ctx, NULL, &state, &d), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, NULL, &d), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, NULL), SR_INVALID_ARG);
    sr_shadow_catcher_desc bad = d;
    bad.map = NULL;
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, &bad), SR_INVALID_ARG);
    bad = d;
    bad.direction.x = NAN;
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, &bad), SR_INVALID_ARG);
    bad = d;
    bad.bounds_min = hi, bad.bounds_max = lo;
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, &bad), SR_INVALID_ARG);
    sr_mesh no_uv = ground;
    no_uv.texcoords = NULL;
    bad = d;
    bad.ground = &no_uv;
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, &bad), SR_INVALID_ARG);
    /* The state is checked as sr_draw checks it, drawn or not: the light
     * from below draws nothing, and still a bad depth function is named. */
    sr_state bad_state = state;
    bad_state.depth_func = (sr_depth_func)99;
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &bad_state, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_state.depth_func 99");
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &bad_state, &up), SR_INVALID_ARG);
    bad = d;
    bad.direction = (sr_vec3){ 0, 0, 0 };
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, &bad), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "direction must not be zero");
    sr_mat4 nan_view = *d.view;
    nan_view.m[12] = NAN;
    bad = d;
    bad.view = &nan_view;
    CHECK_EQ(sr_draw_shadow_catcher(ctx, fb, &state, &bad), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_shadow_catcher_desc.view has a NaN");
    sr_destroy_shadow_map(ctx, soft);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_shadow_map(ctx, sm);
    sr_destroy_mesh(ctx, &ground);
    sr_destroy_mesh(ctx, &pot);
    sr_destroy_context(ctx);
}

/* ---- soft shadows from a light of some size -------------------------------- */

/* Samples of a sweep across the shadow edge x = 1 of a quad at `height`
 * over y = 0 (straight-down light of angular radius `light`, 512^2 map
 * over a 4-unit box) whose visibility lies strictly between 0 and 1. */
static int penumbra_samples(sr_context *ctx, float height, float light)
{
    float xyz[12];
    for (int i = 0; i < 12; i++) {
        xyz[i] = i % 3 == 1 ? height : quad_xyz[i];
    }
    sr_shadow_map *sm = NULL;
    if (sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 0, -1, 0 }, .bounds_min = { -2, 0, -2 },
                                                   .bounds_max = { 2, 2, 2 }, .size = 512,
                                                   .light_radius = light }, &sm) != SR_OK ||
        sr_shadow_map_draw(ctx, sm, &(sr_draw_desc){ .positions = xyz, .vertex_count = 4,
                                                     .indices = quad_idx, .index_type = SR_INDEX_U32,
                                                     .index_count = 6 }) != SR_OK) {
        sr_destroy_shadow_map(ctx, sm);
        return -1;
    }
    int partial = 0;
    float prev = 0;
    bool monotonic = true;
    for (float x = 0.8f; x <= 1.2f; x += 0.001f) {
        float v = vis_at(sm, x, 0, 0.2f);
        partial += v > 0.001f && v < 0.999f;
        monotonic &= v >= prev - 0.02f;   /* the blocker search may wobble a little */
        prev = v;
    }
    sr_destroy_shadow_map(ctx, sm);
    return monotonic && prev == 1.0f ? partial : -2;
}

SR_TEST(light_radius_softens_the_shadow_with_distance_from_the_caster)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    int fixed_low = penumbra_samples(ctx, 0.1f, 0);
    int fixed_high = penumbra_samples(ctx, 1.5f, 0);
    int soft_low = penumbra_samples(ctx, 0.1f, 0.02f);
    int soft_high = penumbra_samples(ctx, 1.5f, 0.02f);
    REQUIRE(fixed_low > 0 && fixed_high > 0 && soft_low > 0 && soft_high > 0);
    /* The fixed filter: the same 3 texels (0.024 units) at any height. */
    CHECK(abs(fixed_low - fixed_high) <= 2);
    /* A light of 0.02 rad: the penumbra's half-width is the height times
     * tan 0.02 (0.03 units at 1.5, clamped to 8 texels = 0.0625 units),
     * and near the caster no wider than the fixed filter's. */
    CHECK(soft_high >= 50 && soft_high <= 70);   /* 2 x 0.03 units in steps of 0.001 */
    CHECK(soft_low <= fixed_low + 4);
    sr_shadow_map *sm = NULL;
    CHECK_EQ(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 0, -1, 0 }, .bounds_max = { 1, 1, 1 },
                                                        .light_radius = 1 }, &sm), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "light_radius");
    sr_destroy_context(ctx);
}

/* The same quad placed by a model matrix, or given as 4-component
 * positions, shadows exactly as the quad moved in its own positions. */
SR_TEST(model_matrix_and_w_positions_shadow_as_moved_positions)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    float moved[12], xyzw[16];
    for (int v = 0; v < 4; v++) {
        for (int c = 0; c < 3; c++) {
            moved[3 * v + c] = quad_xyz[3 * v + c] + (c != 1 ? 0.7f : 0.0f);
            xyzw[4 * v + c] = 2.0f * moved[3 * v + c];
        }
        xyzw[4 * v + 3] = 2.0f;
    }
    sr_mat4 model = sr_mat4_translate(0.7f, 0, 0.7f);
    sr_draw_desc draws[3] = {
        { .positions = moved, .vertex_count = 4, .indices = quad_idx, .index_type = SR_INDEX_U32, .index_count = 6 },
        { .positions = quad_xyz, .vertex_count = 4, .indices = quad_idx, .index_type = SR_INDEX_U32,
          .index_count = 6, .model = &model },
        { .positions = xyzw, .position_size = 4, .vertex_count = 4, .indices = quad_idx,
          .index_type = SR_INDEX_U32, .index_count = 6 },
    };
    sr_shadow_map *sm[3] = { 0 };
    for (int k = 0; k < 3; k++) {
        REQUIRE(sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 0.2f, -1, 0.1f },
                                                           .bounds_min = { -2, 0, -2 }, .bounds_max = { 2, 1, 2 },
                                                           .size = 128 }, &sm[k]) == SR_OK);
        REQUIRE(sr_shadow_map_draw(ctx, sm[k], &draws[k]) == SR_OK);
    }
    int differ = 0, dark = 0;
    for (float z = -1.9f; z <= 1.9f; z += 0.021f) {
        for (float x = -1.9f; x <= 1.9f; x += 0.017f) {
            float a = vis_at(sm[0], x, 0, z);
            differ += a != vis_at(sm[1], x, 0, z);
            differ += a != vis_at(sm[2], x, 0, z);
            dark += a == 0;
        }
    }
    CHECK(dark > 1000);
    CHECK(differ <= 20);   /* the pipeline may round transformed positions a little apart */
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(vis_at(sm[k], 0.7f + 0.2f, 0, 0.7f + 0.1f), 0, 1e-6);
        CHECK_NEAR(vis_at(sm[k], -1.0f, 0, -1.0f), 1, 1e-6);
        sr_destroy_shadow_map(ctx, sm[k]);
    }
    sr_destroy_context(ctx);
}

/* Every allocation of making, drawing and looking up a map refused in
 * turn: each failure is SR_OUT_OF_MEMORY (or the draw's own), nothing
 * leaks, and a map that was made still answers sanely. */
SR_TEST(every_allocation_failure_is_reported_cleanly)
{
    for (long fail_at = 0;; fail_at++) {
        failing f = { .fail_at = fail_at };
        sr_context *ctx = NULL;
        if (sr_make_context(&(sr_context_desc){ .threads = 1,
                                                .allocator = { fail_alloc, fail_free, &f } }, &ctx) != SR_OK) {
            CHECK_EQ(f.live, 0);
            continue;
        }
        sr_shadow_map *sm = NULL;
        sr_result r = sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { 0, -1, 0 },
                                                                 .bounds_min = { -2, 0, -2 },
                                                                 .bounds_max = { 2, 1, 2 }, .size = 64 }, &sm);
        if (r == SR_OK) {
            r = sr_shadow_map_draw(ctx, sm, &(sr_draw_desc){ .positions = quad_xyz, .vertex_count = 4,
                                                             .indices = quad_idx, .index_type = SR_INDEX_U32,
                                                             .index_count = 6 });
            /* Drawn or not, the map answers from what it holds. */
            float v = vis_at(sm, 0, 0, 0);
            CHECK(r == SR_OK ? v == 0.0f : (v == 0.0f || v == 1.0f));
            CHECK_NEAR(vis_at(sm, 1.8f, 0, 1.8f), 1, 0);
        } else {
            CHECK(sm == NULL);
        }
        CHECK(r == SR_OK || r == SR_OUT_OF_MEMORY);
        sr_destroy_shadow_map(ctx, sm);
        sr_destroy_context(ctx);
        CHECK_EQ(f.live, 0);
        if (f.failed == 0) {
            break;   /* a run that refused nothing: every allocation was tried */
        }
    }
}
