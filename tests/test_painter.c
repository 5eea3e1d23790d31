/* test_painter.c - the painter's algorithm (SR_VISIBILITY_PAINTER) against
 * the z-buffer: the same pixels on scenes whose triangles have disjoint
 * depth ranges (random triangles, each in its own depth band, drawn out of
 * depth order, under a frustum and an orthographic box); different pixels,
 * exactly where expected, on three cyclically overlapping triangles and on
 * two interpenetrating ones; the same bytes for any thread count; the
 * refusals.  Fixed seeds. */
#include "sr_test.h"
#include "softrast.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 96, H = 96 };

typedef struct rng { uint64_t s; } rng;
static float uni(rng *r, float lo, float hi)
{
    r->s = r->s * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * (float)((double)(r->s >> 11) / 9007199254740992.0);
}

static sr_context *context(int threads)
{
    sr_context *ctx = NULL;
    if (sr_make_context(&(sr_context_desc){ .threads = threads }, &ctx) != SR_OK) {
        fprintf(stderr, "test_painter: no context with %d threads\n", threads);
        exit(1);
    }
    return ctx;
}

/* Draws ntri triangles (x, y, z per vertex, RGB per vertex) on a cleared
 * framebuffer and copies the pixels out. */
static void render_state(sr_context *ctx, sr_state st, const float *pos, const float *rgb,
                         int ntri, const sr_mat4 *proj, uint8_t out[W * H * 4])
{
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1.0f });
    st.cull = SR_CULL_NONE;
    CHECK_EQ(sr_draw(ctx, fb, &st,
                     &(sr_draw_desc){ .positions = pos, .vertex_count = (size_t)ntri * 3,
                                      .colors = rgb, .color_size = 3, .projection = proj }),
             SR_OK);
    memcpy(out, sr_framebuffer_pixels(fb), (size_t)W * H * 4);
    sr_destroy_framebuffer(ctx, fb);
}

static void render(sr_context *ctx, sr_visibility vis, const float *pos, const float *rgb,
                   int ntri, const sr_mat4 *proj, uint8_t out[W * H * 4])
{
    render_state(ctx, (sr_state){ .visibility = vis }, pos, rgb, ntri, proj, out);
}

static int count_differing(const uint8_t *a, const uint8_t *b)
{
    int n = 0;
    for (int i = 0; i < W * H; i++) {
        n += memcmp(a + 4 * i, b + 4 * i, 4) != 0;
    }
    return n;
}

/* Random triangles, each within its own depth band (eye distances
 * 2 + 0.25 k .. 2 + 0.25 k + 0.2), tilted within it, overlapping on
 * screen and drawn in a shuffled order: no cycles, no interpenetration. */
enum { LAYERS = 40 };
static void layered_scene(uint64_t seed, float reach, float pos[LAYERS * 9],
                          float rgb[LAYERS * 9])
{
    rng r = { seed };
    int band[LAYERS];
    for (int k = 0; k < LAYERS; k++) {
        band[k] = k;
    }
    for (int k = LAYERS - 1; k > 0; k--) {
        int j = (int)uni(&r, 0.0f, (float)k + 0.999f), t = band[k];
        band[k] = band[j];
        band[j] = t;
    }
    for (int k = 0; k < LAYERS; k++) {
        for (int v = 0; v < 3; v++) {
            float depth = 2.0f + 0.25f * (float)band[k] + uni(&r, 0.0f, 0.2f);
            float s = reach * depth / 2.0f; /* the frustum widens with depth */
            pos[9 * k + 3 * v + 0] = uni(&r, -s, s);
            pos[9 * k + 3 * v + 1] = uni(&r, -s, s);
            pos[9 * k + 3 * v + 2] = -depth;
            for (int c = 0; c < 3; c++) {
                rgb[9 * k + 3 * v + c] = uni(&r, 0.0f, 1.0f);
            }
        }
    }
}

SR_TEST(painter_draws_the_z_buffers_pixels_when_depth_ranges_are_disjoint)
{
    sr_context *ctx = context(1);
    sr_mat4 proj[2] = { sr_perspective(1.2f, 1.0f, 1.0f, 20.0f, false),
                        sr_ortho(-1.5f, 1.5f, -1.5f, 1.5f, 1.0f, 20.0f, false) };
    static uint8_t zb[W * H * 4], pa[W * H * 4];
    long covered = 0, unsorted_differ = 0;
    for (int p = 0; p < 2; p++) {
        for (uint64_t seed = 1; seed <= 5; seed++) {
            float pos[LAYERS * 9], rgb[LAYERS * 9];
            layered_scene(seed * 7919 + (uint64_t)p, p == 0 ? 1.3f : 1.4f, pos, rgb);
            if (p == 1) {
                for (int i = 0; i < LAYERS * 3; i++) { /* no widening in the box */
                    pos[3 * i] *= 2.0f / -pos[3 * i + 2];
                    pos[3 * i + 1] *= 2.0f / -pos[3 * i + 2];
                }
            }
            render(ctx, SR_VISIBILITY_Z_BUFFER, pos, rgb, LAYERS, &proj[p], zb);
            render(ctx, SR_VISIBILITY_PAINTER, pos, rgb, LAYERS, &proj[p], pa);
            CHECK_EQ(count_differing(zb, pa), 0);
            /* The scenes need sorting: drawn in their own order without a
             * depth test, they come out wrong. */
            render_state(ctx, (sr_state){ .depth_test = SR_OFF }, pos, rgb, LAYERS, &proj[p], pa);
            unsorted_differ += count_differing(zb, pa);
            for (int i = 0; i < W * H; i++) {
                covered += zb[4 * i] | zb[4 * i + 1] | zb[4 * i + 2] ? 1 : 0;
            }
        }
    }
    printf("disjoint depth ranges: %ld covered pixels in 10 scenes, %ld wrong unsorted\n", covered,
           unsorted_differ);
    CHECK(unsorted_differ > covered / 4);
    CHECK(covered > 10 * W * H / 4); /* the scenes do cover the targets */
    sr_destroy_context(ctx);
}

/* Three long thin triangles ("pencils") along the sides of an equilateral
 * triangle, each from a wide near end at corner i to a far tip past corner
 * i+1: at each corner the pencil starting there (near) lies over the one
 * ending there (far), so 1 is over 0, 2 over 1 and 0 over 2.  All share
 * the same nearest and farthest depths, so the painter draws them in the
 * draw's order and 2 ends up over 0 at corner 0. */
static void cyclic_scene(float pos[27], float rgb[27])
{
    const float corner[3][2] = { { 0.0f, 0.6f }, { -0.52f, -0.3f }, { 0.52f, -0.3f } };
    for (int i = 0; i < 3; i++) {
        const float *a = corner[i], *b = corner[(i + 1) % 3];
        float dx = b[0] - a[0], dy = b[1] - a[1], len = sqrtf(dx * dx + dy * dy);
        dx /= len;
        dy /= len;
        float bx = a[0] - 0.3f * dx, by = a[1] - 0.3f * dy, hw = 0.25f;
        float v[3][3] = { { bx - hw * dy, by + hw * dx, -2.0f },
                          { bx + hw * dy, by - hw * dx, -2.0f },
                          { b[0] + 0.5f * dx, b[1] + 0.5f * dy, -8.0f } };
        memcpy(pos + 9 * i, v, sizeof v);
        for (int k = 0; k < 9; k++) {
            rgb[9 * i + k] = k % 3 == i ? 1.0f : 0.0f; /* red, green, blue */
        }
    }
}

static bool is_rgb(const uint8_t *px, int which)
{
    for (int c = 0; c < 3; c++) {
        if (px[c] != (c == which ? 255 : 0)) {
            return false;
        }
    }
    return true;
}

SR_TEST(painter_is_wrong_on_cyclic_overlap_at_the_corner_it_cannot_order)
{
    sr_context *ctx = context(1);
    sr_mat4 proj = sr_ortho(-1.2f, 1.2f, -1.2f, 1.2f, 1.0f, 10.0f, false);
    float pos[27], rgb[27];
    cyclic_scene(pos, rgb);
    static uint8_t zb[W * H * 4], pa[W * H * 4];
    render(ctx, SR_VISIBILITY_Z_BUFFER, pos, rgb, 3, &proj, zb);
    render(ctx, SR_VISIBILITY_PAINTER, pos, rgb, 3, &proj, pa);
    /* The z-buffer shows the cycle: somewhere each pencil covers the
     * previous one's colour... */
    int differ = 0, at_corner0 = 0;
    for (int i = 0; i < W * H; i++) {
        if (memcmp(zb + 4 * i, pa + 4 * i, 4) == 0) {
            continue;
        }
        differ++;
        /* ...and the painter differs only where pencil 0 should be over
         * pencil 2: red in the z-buffer, blue in the painter's image, in
         * the upper half (corner 0 is in it, corners 1 and 2 are in the lower half). */
        at_corner0 += is_rgb(zb + 4 * i, 0) && is_rgb(pa + 4 * i, 2) && i / W < H / 2;
    }
    printf("cyclic overlap: %d pixels differ, %d of them red over blue at corner 0\n", differ,
           at_corner0);
    CHECK(differ >= 20);
    CHECK_EQ(at_corner0, differ);

    /* No order is right: each of the six orders, drawn without a depth
     * test, differs from the z-buffer somewhere. */
    const int orders[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 },
                               { 1, 2, 0 }, { 2, 0, 1 }, { 2, 1, 0 } };
    for (int o = 0; o < 6; o++) {
        float p2[27], c2[27];
        for (int k = 0; k < 3; k++) {
            memcpy(p2 + 9 * k, pos + 9 * orders[o][k], 9 * sizeof(float));
            memcpy(c2 + 9 * k, rgb + 9 * orders[o][k], 9 * sizeof(float));
        }
        render_state(ctx, (sr_state){ .depth_test = SR_OFF }, p2, c2, 3, &proj, pa);
        CHECK(count_differing(zb, pa) > 0);
    }
    sr_destroy_context(ctx);
}

SR_TEST(painter_is_wrong_where_triangles_interpenetrate)
{
    /* Red at eye distance 5; green through it, from distance 3 at x = -1
     * to 7 at x = 1, so nearer than red where x < 0.  Green's farthest
     * vertex is farther, so the painter draws it first and red covers it
     * everywhere. */
    const float pos[18] = { -0.8f, -0.6f, -5.0f, 0.8f, -0.6f, -5.0f, 0.0f, 0.8f, -5.0f,
                            -1.0f, 0.3f,  -3.0f, 1.0f, 0.5f,  -7.0f, 1.0f, -0.1f, -7.0f };
    const float rgb[18] = { 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0 };
    sr_context *ctx = context(1);
    sr_mat4 proj = sr_ortho(-1.2f, 1.2f, -1.2f, 1.2f, 1.0f, 10.0f, false);
    static uint8_t zb[W * H * 4], pa[W * H * 4], red[W * H * 4], green[W * H * 4];
    render(ctx, SR_VISIBILITY_Z_BUFFER, pos, rgb, 2, &proj, zb);
    render(ctx, SR_VISIBILITY_PAINTER, pos, rgb, 2, &proj, pa);
    render(ctx, SR_VISIBILITY_Z_BUFFER, pos, rgb, 1, &proj, red);
    render(ctx, SR_VISIBILITY_Z_BUFFER, pos + 9, rgb + 9, 1, &proj, green);
    int differ = 0, expected = 0, misplaced = 0;
    for (int i = 0; i < W * H; i++) {
        /* The pixel centre's x in the ortho box: 40 pixels a unit. */
        float x = ((float)(i % W) + 0.5f) / 40.0f - 1.2f;
        bool both = is_rgb(red + 4 * i, 0) && is_rgb(green + 4 * i, 1);
        bool d = memcmp(zb + 4 * i, pa + 4 * i, 4) != 0;
        differ += d;
        /* Differences: green in the z-buffer, red in the painter's image,
         * where both cover and x < 0 (a pixel's width of slack at x = 0). */
        expected += both && x < -0.025f;
        misplaced += d && !(both && x < 0.025f && is_rgb(zb + 4 * i, 1) && is_rgb(pa + 4 * i, 0));
    }
    printf("interpenetration: %d pixels differ, %d expected left of x = 0, %d elsewhere\n",
           differ, expected, misplaced);
    CHECK(expected >= 100);
    CHECK(differ >= expected);
    CHECK(differ <= expected + H); /* at most one column at x = 0 */
    CHECK_EQ(misplaced, 0);
    sr_destroy_context(ctx);
}

SR_TEST(painter_gives_the_same_bytes_for_any_thread_count)
{
    float pos[LAYERS * 9], rgb[LAYERS * 9];
    layered_scene(4242, 0.9f, pos, rgb);
    /* Shared depths too, so ties are broken by the draw's order. */
    for (int k = 0; k < LAYERS; k += 2) {
        for (int v = 0; v < 3; v++) {
            pos[9 * k + 3 * v + 2] = -4.0f;
        }
    }
    sr_mat4 proj = sr_perspective(1.2f, 1.0f, 1.0f, 20.0f, false);
    static uint8_t one[W * H * 4], many[W * H * 4];
    sr_context *c1 = context(1);
    render(c1, SR_VISIBILITY_PAINTER, pos, rgb, LAYERS, &proj, one);
    sr_destroy_context(c1);
    for (int threads = 2; threads <= 4; threads++) {
        sr_context *cn = context(threads);
        render(cn, SR_VISIBILITY_PAINTER, pos, rgb, LAYERS, &proj, many);
        CHECK_EQ(count_differing(one, many), 0);
        sr_destroy_context(cn);
    }
}

SR_TEST(painter_neither_tests_nor_writes_depth)
{
    const float pos[9] = { -1, -1, -5, 1, -1, -5, 0, 1, -5 };
    sr_context *ctx = context(1);
    sr_mat4 proj = sr_ortho(-1.2f, 1.2f, -1.2f, 1.2f, 1.0f, 10.0f, false);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) ==
            SR_OK);
    /* Depth cleared to the near value: the z-buffer would draw nothing. */
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth_action = SR_ACTION_CLEAR,
                                        .depth = 0.0f });
    sr_state st = { .visibility = SR_VISIBILITY_PAINTER, .cull = SR_CULL_NONE };
    CHECK_EQ(sr_draw(ctx, fb, &st,
                     &(sr_draw_desc){ .positions = pos, .vertex_count = 3, .projection = &proj }),
             SR_OK);
    CHECK(sr_last_draw_info(ctx).fragments > 0);
    float depth[64];
    CHECK_EQ(sr_read_depth(ctx, fb, 0, 0, 8, 8, depth, 8), SR_OK);
    for (int i = 0; i < 64; i++) {
        CHECK_EQ(depth[i], 0.0f);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

static void vertex_passthrough(const void *u, const sr_vertex_input *in, float clip[4], float *v)
{
    (void)u;
    (void)v;
    memcpy(clip, in->position, sizeof in->position);
}
static void fragment_white(const void *u, sr_fragment_quad *q)
{
    (void)u;
    for (int c = 0; c < 4; c++) {
        for (int i = 0; i < 4; i++) {
            q->color[c][i] = 1.0f;
        }
    }
}

SR_TEST(painter_refusals_name_the_field)
{
    const float pos[9] = { -1, -1, -5, 1, -1, -5, 0, 1, -5 };
    const uint16_t bad[3] = { 0, 1, 7 };
    sr_context *ctx = context(1);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) ==
            SR_OK);
    sr_draw_desc d = { .positions = pos, .vertex_count = 3 };
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ .visibility = (sr_visibility)7 }, &d),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_state.visibility");
    sr_state st = { .visibility = SR_VISIBILITY_PAINTER };
    d.primitive = SR_PRIM_TRIANGLE_STRIP;
    CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "triangle lists");
    d.primitive = SR_PRIM_TRIANGLES;
    d.indices = bad;
    d.index_type = SR_INDEX_U16;
    d.index_count = 3;
    CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "indices[2] = 7");
    d.indices = NULL;
    d.index_type = SR_INDEX_NONE;
    d.index_count = 0;
    st.program = &(sr_program){ .vertex = vertex_passthrough, .fragment = fragment_white };
    CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "program");
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
