/* test_shader.c - programmable stages: a program that restates the
 * built-in unlit model gives its bytes exactly (single-sampled and
 * multisampled); each varying qualifier against its analytic value;
 * discard, depth output, quad derivatives, lines and points, validation,
 * and the same bytes on any thread count. */
#include "sr_test.h"
#include "softrast.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A context and a framebuffer for one test. */
static bool make_target(int w, int h, sr_depth_format depth, sr_context **ctx, sr_framebuffer **fb)
{
    *fb = NULL;
    if (sr_make_context(NULL, ctx) != SR_OK) {
        return false;
    }
    return sr_make_framebuffer(*ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                            .depth_format = depth }, fb) == SR_OK;
}

static void free_target(sr_context *ctx, sr_framebuffer *fb)
{
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* ---- a program equal to SR_SHADING_UNLIT -------------------------------- */

typedef struct unlit_uniforms {
    sr_mat4 mvp;
} unlit_uniforms;

/* Clip position by the same operations in the same order as the vertex
 * stage's transform_point, and the vertex color as varyings 0..3. */
static void unlit_vs(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    const float *a = ((const unlit_uniforms *)u)->mvp.m;
    const float *p = in->position;
    for (int r = 0; r < 4; r++) {
        clip[r] = a[r] * p[0] + a[4 + r] * p[1] + a[8 + r] * p[2] + a[12 + r] * p[3];
    }
    memcpy(vary, in->color, 4 * sizeof(float));
}

static void unlit_fs(const void *u, sr_fragment_quad *q)
{
    (void)u;
    for (int c = 0; c < 4; c++) {
        for (int i = 0; i < 4; i++) {
            q->color[c][i] = q->varyings[c][i];
        }
    }
}

typedef struct scene {
    float *pos, *col;
    int tris;
    sr_mat4 view, proj;
} scene;

static scene random_scene(int tris, uint64_t seed)
{
    scene s = { malloc(sizeof(float) * 9 * (size_t)tris), malloc(sizeof(float) * 12 * (size_t)tris),
                tris, sr_mat4_identity(), sr_mat4_identity() };
    sr_rng rng = { seed };
    for (int i = 0; i < 3 * tris; i++) {
        s.pos[i * 3 + 0] = (float)sr_rng_range(&rng, -3, 3);
        s.pos[i * 3 + 1] = (float)sr_rng_range(&rng, -3, 3);
        s.pos[i * 3 + 2] = (float)sr_rng_range(&rng, -9, -1);
        for (int k = 0; k < 4; k++) {
            s.col[i * 4 + k] = (float)sr_rng_unit(&rng);
        }
    }
    s.proj = sr_perspective(1.0f, 4.0f / 3.0f, 0.5f, 20.0f, false);
    return s;
}

static void free_scene(scene *s)
{
    free(s->pos);
    free(s->col);
}

/* a and b hold the same pixels (every sample, resolved) and depth, and
 * more than half of the w x h pixels were drawn over the clear. */
static void check_same(sr_context *ctx, const sr_framebuffer *a, const sr_framebuffer *b, int w,
                       int h)
{
    const uint8_t *pa = sr_framebuffer_pixels(a), *pb = sr_framebuffer_pixels(b);
    int differ = 0, drawn = 0;
    for (int i = 0; i < w * h * 4; i++) {
        differ += pa[i] != pb[i];
    }
    for (int i = 0; i < w * h; i++) {
        drawn += pa[i * 4] != (uint8_t)(0.1f * 255 + 0.5f);
    }
    CHECK_EQ(differ, 0);
    CHECK(drawn > w * h / 2);
    float *da = malloc(sizeof(float) * (size_t)(w * h)), *db = malloc(sizeof(float) * (size_t)(w * h));
    REQUIRE(da && db);
    sr_read_depth(ctx, a, 0, 0, w, h, da, (size_t)w);
    sr_read_depth(ctx, b, 0, 0, w, h, db, (size_t)w);
    CHECK(memcmp(da, db, sizeof(float) * (size_t)(w * h)) == 0);
    free(da);
    free(db);
}

static void render_both(int samples, int threads, bool independent)
{
    enum { W = 128, H = 96 };
    scene s = random_scene(600, 17 + (uint64_t)samples);
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads }, &ctx) == SR_OK);
    sr_framebuffer *a, *b;
    sr_framebuffer_desc fd = { .width = W, .height = H, .samples = samples };
    REQUIRE(sr_make_framebuffer(ctx, &fd, &a) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &fd, &b) == SR_OK);
    sr_clear_desc cl = { .color = { 0.1f, 0.1f, 0.2f, 1 }, .depth = 1 };
    sr_clear(ctx, a, &cl);
    sr_clear(ctx, b, &cl);
    sr_draw_desc d = { .positions = s.pos, .colors = s.col, .vertex_count = 3 * (size_t)s.tris,
                       .projection = &s.proj };
    REQUIRE(sr_draw(ctx, a, &(sr_state){ .shading = SR_SHADING_UNLIT }, &d) == SR_OK);
    unlit_uniforms u = { sr_mat4_mul(&s.proj, &s.view) };
    sr_program prog = { .vertex = unlit_vs, .fragment = unlit_fs, .uniforms = &u,
                        .varying_count = 4, .independent_lanes = independent };
    REQUIRE(sr_draw(ctx, b, &(sr_state){ .program = &prog }, &d) == SR_OK);
    check_same(ctx, a, b, W, H);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
    free_scene(&s);
}

SR_TEST(a_program_restating_unlit_gives_its_bytes)
{
    render_both(1, 2, false);
}

SR_TEST(a_program_restating_unlit_gives_its_bytes_multisampled)
{
    render_both(4, 2, false);
}

/* Fragments of several quads in one call: each lane as in its own quad. */
SR_TEST(independent_lanes_give_the_same_bytes)
{
    render_both(1, 2, true);
    render_both(4, 2, true);
}

/* Calls and fragments a counting shader saw (one thread). */
typedef struct lane_count {
    int calls, lanes, full, contiguous;
} lane_count;

static void count_vs(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    (void)u;
    memcpy(clip, in->position, 4 * sizeof(float));
    memcpy(vary, in->color, 4 * sizeof(float));
}

static void count_fs(const void *u, sr_fragment_quad *q)
{
    lane_count *n = (lane_count *)u;   /* a test's own counters: one thread */
    int k = __builtin_popcount(q->mask);
    n->calls++;
    n->lanes += k;
    n->full += q->mask == 0xfu;
    n->contiguous += q->mask == (1u << k) - 1u;
    unlit_fs(u, q);
}

/* A triangle inside one tile: its fragments come four to a call, the
 * last call holding the rest, where quads leave lanes empty. */
SR_TEST(independent_lanes_fill_every_call_but_the_last)
{
    const float tri[9] = { -0.9f, -0.8f, 0, 0.7f, -0.3f, 0, -0.2f, 0.9f, 0 };
    lane_count seen[2];
    for (int mode = 0; mode < 2; mode++) {
        sr_context *ctx;
        sr_framebuffer *fb;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 100, .height = 100 },
                                    &fb) == SR_OK);
        sr_clear(ctx, fb, &(sr_clear_desc){ .depth = 1 });
        seen[mode] = (lane_count){ 0 };
        sr_program prog = { .vertex = count_vs, .fragment = count_fs, .uniforms = &seen[mode],
                            .varying_count = 4, .independent_lanes = mode == 1 };
        REQUIRE(sr_draw(ctx, fb, &(sr_state){ .program = &prog, .cull = SR_CULL_NONE },
                        &(sr_draw_desc){ .positions = tri, .vertex_count = 3 }) == SR_OK);
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
    }
    CHECK(seen[0].lanes > 1000);
    CHECK_EQ(seen[1].lanes, seen[0].lanes);
    CHECK_EQ(seen[1].calls, (seen[0].lanes + 3) / 4);
    CHECK_EQ(seen[1].contiguous, seen[1].calls);
    CHECK(seen[0].calls > seen[1].calls);
    CHECK(seen[0].full < seen[0].calls);
}

/* A program's early depth test takes a pixel's four samples, or a quad's
 * four pixels of one sample, at once in the common state (LESS on D24, no
 * stencil) and one at a time otherwise: a stencil test that always
 * passes and keeps the stencil sends the same draw down the per-sample
 * path, and the bytes must agree (every sample's color, through the
 * resolve, and the depth read back). */
static void vector_depth_test_matches_the_per_sample_one(int samples)
{
    enum { W = 128, H = 96 };
    scene s = random_scene(600, 29);
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_framebuffer *a, *b;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                            .samples = samples }, &a) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                            .samples = samples, .stencil = true },
                                &b) == SR_OK);
    sr_clear_desc cl = { .color = { 0.1f, 0.1f, 0.2f, 1 }, .depth = 1 };
    sr_clear(ctx, a, &cl);
    sr_clear(ctx, b, &cl);
    sr_draw_desc d = { .positions = s.pos, .colors = s.col, .vertex_count = 3 * (size_t)s.tris,
                       .projection = &s.proj };
    unlit_uniforms u = { sr_mat4_mul(&s.proj, &s.view) };
    sr_program prog = { .vertex = unlit_vs, .fragment = unlit_fs, .uniforms = &u,
                        .varying_count = 4 };
    REQUIRE(sr_draw(ctx, a, &(sr_state){ .program = &prog }, &d) == SR_OK);
    REQUIRE(sr_draw(ctx, b, &(sr_state){ .program = &prog, .stencil = { .enabled = true } },
                    &d) == SR_OK);
    check_same(ctx, a, b, W, H);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
    free_scene(&s);
}

SR_TEST(four_sample_early_depth_test_matches_the_per_sample_one)
{
    vector_depth_test_matches_the_per_sample_one(4);
}

SR_TEST(quad_early_depth_test_matches_the_per_sample_one)
{
    vector_depth_test_matches_the_per_sample_one(1);
}

/* ---- varying qualifiers -------------------------------------------------- */

/* One triangle under perspective, receding: its vertices carry
 * attribute values 0, 1, 2 in each of three varyings, one per mode. */
static void qual_vs(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    const sr_mat4 *mvp = u;
    sr_vec4 p = sr_mat4_mul_vec4(mvp, (sr_vec4){ in->position[0], in->position[1],
                                                 in->position[2], 1 });
    clip[0] = p.x, clip[1] = p.y, clip[2] = p.z, clip[3] = p.w;
    vary[0] = vary[1] = vary[2] = (float)in->index;
}

/* Writes varying k of the fragment to channel k, scaled by 1/2. */
static void qual_fs(const void *u, sr_fragment_quad *q)
{
    (void)u;
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < 3; k++) {
            q->color[k][i] = q->varyings[k][i] * 0.5f;
        }
        q->color[3][i] = 1.0f;
    }
}

SR_TEST(each_varying_qualifier_interpolates_as_it_says)
{
    enum { W = 64, H = 64 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                            .depth_format = SR_DEPTH_NONE },
                                &fb) == SR_OK);
    /* A big triangle receding from z = -1 (vertex 0) to z = -8. */
    float pos[9] = { -1, -1, -1, 6, -1, -8, -1, 4, -8 };
    sr_mat4 proj = sr_perspective(1.5f, 1.0f, 0.5f, 20.0f, false);
    sr_program prog = { .vertex = qual_vs, .fragment = qual_fs, .uniforms = &proj,
                        .varying_count = 3,
                        .modes = { SR_VARYING_SMOOTH, SR_VARYING_NOPERSPECTIVE, SR_VARYING_FLAT } };
    for (int last = 0; last < 2; last++) {
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
        sr_state st = { .program = &prog,
                        .provoking = last ? SR_PROVOKING_LAST : SR_PROVOKING_FIRST };
        REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 })
                == SR_OK);
        /* Window positions of the vertices and their 1/w, for the
         * analytic values at each pixel centre. */
        double wx[3], wy[3], iw[3];
        for (int v = 0; v < 3; v++) {
            sr_vec4 c = sr_mat4_mul_vec4(&proj, (sr_vec4){ pos[v * 3], pos[v * 3 + 1],
                                                          pos[v * 3 + 2], 1 });
            wx[v] = (c.x / c.w + 1) * W / 2;
            wy[v] = (1 - c.y / c.w) * H / 2;
            iw[v] = 1.0 / c.w;
        }
        const uint8_t *px = sr_framebuffer_pixels(fb);
        int checked = 0;
        double worst_smooth = 0, worst_lin = 0, worst_smooth_vs_lin = 0;
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                double sx = x + 0.5, sy = y + 0.5;
                /* Screen-space barycentrics. */
                double den = (wy[1] - wy[2]) * (wx[0] - wx[2]) + (wx[2] - wx[1]) * (wy[0] - wy[2]);
                double l0 = ((wy[1] - wy[2]) * (sx - wx[2]) + (wx[2] - wx[1]) * (sy - wy[2])) / den;
                double l1 = ((wy[2] - wy[0]) * (sx - wx[2]) + (wx[0] - wx[2]) * (sy - wy[2])) / den;
                double l2 = 1 - l0 - l1;
                if (l0 < 0.02 || l1 < 0.02 || l2 < 0.02) {
                    continue;  /* well inside only */
                }
                const uint8_t *p = &px[(y * W + x) * 4];
                REQUIRE(p[3] == 255);
                double lin = l1 * 1 + l2 * 2;
                double q0 = l0 * iw[0], q1 = l1 * iw[1], q2 = l2 * iw[2];
                double persp = (q1 * 1 + q2 * 2) / (q0 + q1 + q2);
                worst_smooth = fmax(worst_smooth, fabs(p[0] - persp * 0.5 * 255));
                worst_lin = fmax(worst_lin, fabs(p[1] - lin * 0.5 * 255));
                worst_smooth_vs_lin = fmax(worst_smooth_vs_lin, fabs(persp - lin));
                CHECK_EQ(p[2], last ? 255 : 0);   /* vertex 2 (1.0) or vertex 0 (0) */
                checked++;
            }
        }
        CHECK(checked > 300);
        CHECK(worst_smooth <= 1.0);
        CHECK(worst_lin <= 1.0);
        /* The scene is chosen so that the two differ visibly. */
        CHECK(worst_smooth_vs_lin > 0.2);
    }
    free_target(ctx, fb);
}

/* ---- discard, depth output, derivatives ----------------------------------- */

static void plane_vs(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    (void)u;
    memcpy(clip, in->position, 3 * sizeof(float));
    clip[3] = 1.0f;
    /* Window x / 8 and y / 8 for a 64 x 64 target: NDC (x + 1) * 4. */
    vary[0] = (in->position[0] + 1.0f) * 4.0f;
    vary[1] = (1.0f - in->position[1]) * 4.0f;
}

/* A checkerboard of 8 x 8 pixel cells: odd cells are discarded. */
static void discard_fs(const void *u, sr_fragment_quad *q)
{
    (void)u;
    for (int i = 0; i < 4; i++) {
        int cx = (int)floorf(q->varyings[0][i]), cy = (int)floorf(q->varyings[1][i]);
        if ((cx + cy) & 1) {
            q->discard |= 1u << i;
        }
        q->color[0][i] = 1.0f;
        q->color[1][i] = q->color[2][i] = 0.0f;
        q->color[3][i] = 1.0f;
    }
}

/* Depth from the shader: 0.25 everywhere, whatever the plane says. */
static void depth_fs(const void *u, sr_fragment_quad *q)
{
    (void)u;
    for (int i = 0; i < 4; i++) {
        q->z[i] = 0.25f;
        q->color[1][i] = 1.0f;
        q->color[3][i] = 1.0f;
    }
}

/* The derivative of varying 0 along x, from the quad's lanes, times 8
 * (varying 0 is x / 8): one, everywhere, helper lanes included. */
static void ddx_fs(const void *u, sr_fragment_quad *q)
{
    (void)u;
    float ddx = q->varyings[0][1] - q->varyings[0][0];
    float ddy = q->varyings[1][2] - q->varyings[1][0];
    for (int i = 0; i < 4; i++) {
        q->color[0][i] = ddx * 8.0f * 0.5f;
        q->color[1][i] = ddy * 8.0f * 0.5f;
        q->color[3][i] = 1.0f;
    }
}

static const float full_quad[18] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0 };

SR_TEST(discard_drops_fragments_before_any_write)
{
    enum { W = 64, H = 64 };
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(make_target(W, H, SR_DEPTH_DEFAULT, &ctx, &fb));
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 1, 1 }, .depth = 1 });
    sr_program prog = { .vertex = plane_vs, .fragment = discard_fs, .varying_count = 2,
                        .may_discard = true };
    REQUIRE(sr_draw(ctx, fb, &(sr_state){ .program = &prog },
                    &(sr_draw_desc){ .positions = full_quad, .vertex_count = 6 }) == SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    float depth[W * H];
    sr_read_depth(ctx, fb, 0, 0, W, H, depth, W);
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            bool kept = !(((x / 8) + (y / 8)) & 1);
            CHECK_EQ(px[(y * W + x) * 4 + 0], kept ? 255 : 0);
            CHECK_EQ(px[(y * W + x) * 4 + 2], kept ? 0 : 255);
            /* A discarded fragment leaves the depth buffer alone. */
            CHECK(kept ? depth[y * W + x] < 0.6f : depth[y * W + x] == 1.0f);
        }
    }
    CHECK_EQ(sr_last_draw_info(ctx).fragments, W * H / 2);
    free_target(ctx, fb);
}

SR_TEST(fragment_depth_output_is_tested_and_written)
{
    enum { W = 32, H = 32 };
    sr_context *ctx;
    REQUIRE(sr_make_context(NULL, &ctx) == SR_OK);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                            .depth_format = SR_DEPTH_D32F },
                                &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
    /* The plane itself sits at window depth 0.5 (z = 0); the shader
     * says 0.25. */
    sr_program prog = { .vertex = plane_vs, .fragment = depth_fs, .varying_count = 2,
                        .writes_depth = true };
    REQUIRE(sr_draw(ctx, fb, &(sr_state){ .program = &prog },
                    &(sr_draw_desc){ .positions = full_quad, .vertex_count = 6 }) == SR_OK);
    float depth[W * H];
    sr_read_depth(ctx, fb, 0, 0, W, H, depth, W);
    for (int i = 0; i < W * H; i++) {
        CHECK(depth[i] == 0.25f);
    }
    /* A plane at 0.3 (z = -0.4) now fails LESS against the shader's 0.25
     * although its own plane depth is nearer than the first plane's. */
    float nearer[18];
    memcpy(nearer, full_quad, sizeof nearer);
    for (int v = 0; v < 6; v++) {
        nearer[v * 3 + 2] = -0.4f;
    }
    sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 0, 0 } } };
    REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = nearer, .vertex_count = 6 })
            == SR_OK);
    CHECK_EQ(sr_last_draw_info(ctx).fragments, 0);
    CHECK_EQ(sr_framebuffer_pixels(fb)[1], 255);
    free_target(ctx, fb);
}

SR_TEST(quads_give_screen_space_derivatives)
{
    enum { W = 64, H = 64 };
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(make_target(W, H, SR_DEPTH_DEFAULT, &ctx, &fb));
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 }, .depth = 1 });
    /* A thin triangle: many of its quads have helper lanes. */
    float tri[9] = { -1, -1, 0, 1, -0.8f, 0, -1, 1, 0 };
    sr_program prog = { .vertex = plane_vs, .fragment = ddx_fs, .varying_count = 2 };
    REQUIRE(sr_draw(ctx, fb, &(sr_state){ .program = &prog },
                    &(sr_draw_desc){ .positions = tri, .vertex_count = 3 }) == SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    int drawn = 0;
    for (int i = 0; i < W * H; i++) {
        if (px[i * 4 + 3]) {
            drawn++;
            CHECK_NEAR(px[i * 4 + 0], 128, 1);   /* d(x/8)/dx * 8 / 2 */
            CHECK_NEAR(px[i * 4 + 1], 128, 1);
        }
    }
    CHECK(drawn > 500);
    free_target(ctx, fb);
}

SR_TEST(lines_and_points_run_the_program)
{
    enum { W = 64, H = 64 };
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(make_target(W, H, SR_DEPTH_DEFAULT, &ctx, &fb));
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 }, .depth = 1 });
    sr_program prog = { .vertex = plane_vs, .fragment = discard_fs, .varying_count = 2,
                        .may_discard = true };
    /* A horizontal line through row 4 (cells 0..7 along it alternate). */
    float line[6] = { -1, 1 - 4.5f / 32, 0, 1, 1 - 4.5f / 32, 0 };
    REQUIRE(sr_draw(ctx, fb, &(sr_state){ .program = &prog },
                    &(sr_draw_desc){ .primitive = SR_PRIM_LINES, .positions = line,
                                     .vertex_count = 2 }) == SR_OK);
    float pt[3] = { 20.5f / 32 - 1, 1 - 20.5f / 32, 0 };   /* cell (2, 2): kept */
    REQUIRE(sr_draw(ctx, fb, &(sr_state){ .program = &prog, .point_size = 3 },
                    &(sr_draw_desc){ .primitive = SR_PRIM_POINTS, .positions = pt,
                                     .vertex_count = 1 }) == SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int x = 0; x < W; x++) {
        CHECK_EQ(px[(4 * W + x) * 4], ((x / 8) & 1) ? 0 : 255);
    }
    CHECK_EQ(px[(20 * W + 20) * 4], 255);
    CHECK_EQ(px[(20 * W + 22) * 4], 0);
    free_target(ctx, fb);
}

SR_TEST(programs_are_validated)
{
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(make_target(8, 8, SR_DEPTH_DEFAULT, &ctx, &fb));
    sr_draw_desc d = { .positions = full_quad, .vertex_count = 6 };
    sr_program p = { .vertex = plane_vs };
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ .program = &p }, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "fragment");
    p = (sr_program){ .vertex = plane_vs, .fragment = unlit_fs, .varying_count = 17 };
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ .program = &p }, &d), SR_INVALID_ARG);
    p.varying_count = 2;
    p.modes[1] = (sr_varying_mode)7;
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ .program = &p }, &d), SR_INVALID_ARG);
    /* A program needs no normals even if `shading` would. */
    p.modes[1] = SR_VARYING_SMOOTH;
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ .program = &p, .shading = SR_SHADING_PHONG }, &d),
             SR_OK);
    free_target(ctx, fb);
}

SR_TEST(programs_give_the_same_bytes_on_any_thread_count)
{
    enum { W = 160, H = 120 };
    scene s = random_scene(2000, 5);
    uint8_t *first = NULL;
    static const int threads[] = { 1, 2, 3, 8 };
    for (int t = 0; t < 4; t++) {
        sr_context *ctx;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads[t] }, &ctx) == SR_OK);
        sr_framebuffer *fb;
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                                .samples = 4 }, &fb) == SR_OK);
        sr_clear(ctx, fb, &(sr_clear_desc){ .depth = 1 });
        unlit_uniforms u = { sr_mat4_mul(&s.proj, &s.view) };
        sr_program prog = { .vertex = unlit_vs, .fragment = discard_fs, .uniforms = &u,
                            .varying_count = 4, .may_discard = true };
        REQUIRE(sr_draw(ctx, fb, &(sr_state){ .program = &prog,
                                              .blend = { .enabled = true,
                                                         .src_rgb = SR_BLEND_ONE,
                                                         .dst_rgb = SR_BLEND_ONE } },
                        &(sr_draw_desc){ .positions = s.pos, .colors = s.col,
                                         .vertex_count = 3 * (size_t)s.tris }) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(fb);
        if (!first) {
            first = malloc((size_t)W * H * 4);
            memcpy(first, px, (size_t)W * H * 4);
        } else {
            CHECK(memcmp(first, px, (size_t)W * H * 4) == 0);
        }
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
    }
    free(first);
    free_scene(&s);
}

/* ---- the built-in models as programs ------------------------------------- */

/* A UV sphere with normals, colors and texture coordinates. */
typedef struct sphere {
    float pos[33 * 17 * 3], nrm[33 * 17 * 3], col[33 * 17 * 4], uv[33 * 17 * 2];
    uint32_t idx[32 * 16 * 6];
    size_t nv, ni;
} sphere;

static void make_sphere(sphere *s)
{
    s->nv = s->ni = 0;
    for (int j = 0; j <= 16; j++) {
        for (int i = 0; i <= 32; i++) {
            float th = (float)M_PI * j / 16, ph = 2 * (float)M_PI * i / 32;
            float n[3] = { sinf(th) * cosf(ph), cosf(th), sinf(th) * sinf(ph) };
            memcpy(&s->pos[s->nv * 3], n, sizeof n);
            memcpy(&s->nrm[s->nv * 3], n, sizeof n);
            float c[4] = { 0.5f + 0.5f * n[0], 0.5f + 0.5f * n[1], 0.7f, 1 };
            memcpy(&s->col[s->nv * 4], c, sizeof c);
            s->uv[s->nv * 2] = i / 32.0f * 4;
            s->uv[s->nv * 2 + 1] = j / 16.0f * 2;
            s->nv++;
        }
    }
    for (int j = 0; j < 16; j++) {
        for (int i = 0; i < 32; i++) {
            uint32_t a = (uint32_t)(j * 33 + i), b = a + 1, c = a + 33, d = c + 1;
            uint32_t t[6] = { a, c, b, b, c, d };
            memcpy(&s->idx[s->ni], t, sizeof t);
            s->ni += 6;
        }
    }
}

/* Max and mean channel difference of two renders of the sphere, one
 * through the built-in path and one through its program form. */
static void compare_builtin(const sr_state *st, int *max_diff, double *mean_diff, int *drawn)
{
    enum { W = 160, H = 120 };
    static sphere s;
    make_sphere(&s);
    sr_context *ctx;
    sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx);
    sr_framebuffer *a, *b;
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &a);
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &b);
    sr_mat4 model = sr_mat4_rotate(0.4f, (sr_vec3){ 1, 1, 0 });
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 0.5f, 3 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.9f, (float)W / H, 0.5f, 10.0f, false);
    sr_draw_desc d = { .positions = s.pos, .normals = s.nrm, .colors = s.col, .texcoords = s.uv,
                       .vertex_count = s.nv, .indices = s.idx, .index_type = SR_INDEX_U32,
                       .index_count = s.ni, .model = &model, .view = &view, .projection = &proj };
    sr_clear_desc cl = { .color = { 0, 0, 0, 1 }, .depth = 1 };
    sr_clear(ctx, a, &cl);
    sr_clear(ctx, b, &cl);
    sr_builtin *bp = NULL;
    if (sr_draw(ctx, a, st, &d) != SR_OK ||
        sr_make_builtin_program(ctx, st, &model, &view, &proj, &bp) != SR_OK) {
        *max_diff = 999;
        return;
    }
    sr_state ps = *st;
    ps.program = sr_builtin_program(bp);
    sr_result r = sr_draw(ctx, b, &ps, &d);
    const uint8_t *pa = sr_framebuffer_pixels(a), *pb = sr_framebuffer_pixels(b);
    long sum = 0;
    *max_diff = r == SR_OK ? 0 : 999;
    *drawn = 0;
    for (int i = 0; i < W * H * 4; i++) {
        int dd = abs(pa[i] - pb[i]);
        *max_diff = dd > *max_diff ? dd : *max_diff;
        sum += dd;
    }
    for (int i = 0; i < W * H; i++) {
        *drawn += pa[i * 4] | pa[i * 4 + 1] | pa[i * 4 + 2] ? 1 : 0;
    }
    *mean_diff = (double)sum / (W * H * 4);
    sr_destroy_builtin_program(ctx, bp);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

SR_TEST(builtin_models_as_programs_give_the_builtin_pixels)
{
    sr_state base = { .cull = SR_CULL_BACK,
                      .material = { .diffuse = { 0.8f, 0.5f, 0.3f }, .specular = { 0.6f, 0.6f, 0.6f },
                                    .shininess = 24 },
                      .ambient = { 0.1f, 0.1f, 0.1f },
                      .lights = { { .type = SR_LIGHT_DIRECTIONAL, .vector = { -1, -1, -1 } },
                                  { .type = SR_LIGHT_POINT, .vector = { 2, 1, 2 },
                                    .color = { 0.3f, 0.3f, 0.6f } } } };
    static const sr_shading exact[] = { SR_SHADING_UNLIT, SR_SHADING_GOURAUD, SR_SHADING_PHONG,
                                        SR_SHADING_NORMALS, SR_SHADING_DEPTH };
    for (int k = 0; k < 5; k++) {
        sr_state st = base;
        st.shading = exact[k];
        int max_diff, drawn;
        double mean;
        compare_builtin(&st, &max_diff, &mean, &drawn);
        CHECK_EQ(max_diff, 0);
        CHECK(drawn > 3000);
    }
    /* Flat: the face normal from the quad's lane differences. */
    sr_state st = base;
    st.shading = SR_SHADING_FLAT;
    int max_diff, drawn;
    double mean;
    compare_builtin(&st, &max_diff, &mean, &drawn);
    CHECK(mean < 0.5);
    CHECK(max_diff <= 2);
    /* Textured Gouraud, bilinear (exact) and trilinear (level of detail
     * from the quad). */
    uint8_t texels[16 * 16 * 4];
    for (int i = 0; i < 16 * 16; i++) {
        bool on = ((i % 16) / 4 + (i / 16) / 4) & 1;
        texels[i * 4 + 0] = on ? 255 : 40;
        texels[i * 4 + 1] = on ? 200 : 40;
        texels[i * 4 + 2] = 60;
        texels[i * 4 + 3] = 255;
    }
    sr_context *ctx;
    REQUIRE(sr_make_context(NULL, &ctx) == SR_OK);
    sr_texture *tex;
    REQUIRE(sr_make_texture(ctx, &(sr_texture_desc){ .width = 16, .height = 16, .pixels = texels },
                            &tex) == SR_OK);
    st = base;
    st.shading = SR_SHADING_GOURAUD;
    st.texture = tex;
    st.texture_filter = SR_FILTER_BILINEAR;
    compare_builtin(&st, &max_diff, &mean, &drawn);
    CHECK_EQ(max_diff, 0);
    /* One level of detail per quad from lane differences instead of per
     * pixel from exact steps: the mip blend moves a little, at most a
     * tenth of this texture's contrast, on average under one level. */
    st.texture_filter = SR_FILTER_TRILINEAR;
    compare_builtin(&st, &max_diff, &mean, &drawn);
    CHECK(mean < 1.0);
    CHECK(max_diff <= 24);
    sr_destroy_texture(ctx, tex);
    /* Validation. */
    sr_builtin *bp = (sr_builtin *)1;
    st = (sr_state){ .shading = SR_SHADING_ATTRIBUTE };
    CHECK_EQ(sr_make_builtin_program(ctx, &st, NULL, NULL, NULL, &bp), SR_INVALID_ARG);
    CHECK(bp == NULL);
    /* The state is checked as sr_draw checks it, and the matrices too: the
     * program bakes them in for every fragment to read. */
    struct { sr_state st; const char *needle; } bad[] = {
        { { .lights[0] = { .type = 9 } }, "sr_state.lights[0].type 9" },
        { { .lights[1] = { .type = SR_LIGHT_POINT, .vector = { NAN, 0, 0 } } },
          "sr_state.lights[1]" },
        { { .material = { .shininess = NAN } }, "sr_state.material" },
        { { .texture_filter = 77 }, "sr_state.texture_filter" },
        { { .interpolation = 5 }, "sr_state.interpolation 5" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        bp = (sr_builtin *)1;
        CHECK_EQ(sr_make_builtin_program(ctx, &bad[i].st, NULL, NULL, NULL, &bp), SR_INVALID_ARG);
        CHECK_STR_CONTAINS(sr_context_error(ctx), bad[i].needle);
        CHECK(bp == NULL);
    }
    sr_mat4 nan_view = sr_mat4_identity();
    nan_view.m[13] = NAN;
    CHECK_EQ(sr_make_builtin_program(ctx, &(sr_state){0}, NULL, &nan_view, NULL, &bp),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_make_builtin_program: view has a NaN");
    sr_destroy_context(ctx);
}
