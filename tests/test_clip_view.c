/* test_clip_view.c - the view-volume clipper (SR_CLIPPER_VIEW_VOLUME)
 * against the homogeneous one: random triangles crossing the near plane,
 * the far plane and the sides, under a frustum and an orthographic box,
 * drawn with both clippers and compared pixel by pixel; nothing from
 * behind the eye; the refusals.  Fixed seeds. */
#include "sr_test.h"
#include "softrast.h"

#include <stdlib.h>

enum { W = 96, H = 72 };

/* What "the same pixels" means (docs/clipping.md): the two clippers cut
 * the same edges at the same points in exact arithmetic, but their float
 * intersection points can differ in the last bits, which can move a
 * snapped vertex by one 1/256 px step and a clip point's color by a
 * rounding.  Over all the scenes of a test: at most MAX_DIFF_PER_MILLION
 * of the covered pixels differ at all, at most MAX_COVER_DIFF_PER_MILLION
 * in coverage, and no channel by more than MAX_CHANNEL_DIFF.  Measured:
 * 11 of 1755547 pixels by 1 under the frustums, none under the box. */
#define MAX_DIFF_PER_MILLION 50
#define MAX_COVER_DIFF_PER_MILLION 10
#define MAX_CHANNEL_DIFF 1

typedef struct rng { uint64_t s; } rng;
static double uni(rng *r, double lo, double hi)
{
    r->s = r->s * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * (double)(r->s >> 11) / 9007199254740992.0;
}

typedef struct tally {
    long covered, cover_diff, pixel_diff, triangles;
    int max_channel;
} tally;

static sr_result draw(sr_context *ctx, sr_framebuffer *fb, sr_clipper clipper, const float *pos,
                      const float *rgb, int ntri, const sr_mat4 *proj, bool zero_to_one)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 }, .depth = 1.0f });
    sr_state st = { .clipper = clipper, .depth_zero_to_one = zero_to_one };
    return sr_draw(ctx, fb, &st,
                   &(sr_draw_desc){ .positions = pos, .vertex_count = (size_t)ntri * 3,
                                    .colors = rgb, .color_size = 3, .projection = proj });
}

/* Draw one triangle with both clippers and add up how the images differ. */
static void compare_one(sr_context *ctx, sr_framebuffer *fb[2], const float pos[9],
                        const float rgb[9], const sr_mat4 *proj, bool zero_to_one, tally *t)
{
    const sr_clipper which[2] = { SR_CLIPPER_HOMOGENEOUS, SR_CLIPPER_VIEW_VOLUME };
    for (int k = 0; k < 2; k++) {
        CHECK_EQ(draw(ctx, fb[k], which[k], pos, rgb, 1, proj, zero_to_one), SR_OK);
    }
    const uint8_t *a = sr_framebuffer_pixels(fb[0]), *b = sr_framebuffer_pixels(fb[1]);
    t->triangles++;
    for (int i = 0; i < W * H; i++) {
        bool ca = a[4 * i + 3] != 0, cb = b[4 * i + 3] != 0;
        t->covered += ca;
        t->cover_diff += ca != cb;
        int d = 0;
        for (int c = 0; c < 4; c++) {
            int e = abs(a[4 * i + c] - b[4 * i + c]);
            d = e > d ? e : d;
        }
        t->pixel_diff += d != 0;
        if (ca == cb && d > t->max_channel) {
            t->max_channel = d;
        }
    }
}

/* Random triangles in view space: one vertex near or behind the near plane
 * (or the eye), the others in front, spread past the side planes by
 * `spread` times the frustum's width (past the guard band when large). */
static void random_scene(uint64_t seed, const sr_mat4 *proj, bool ortho, bool zero_to_one,
                         double spread, tally *t)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb[2];
    for (int k = 0; k < 2; k++) {
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                                  .depth_format = SR_DEPTH_D24 },
                                    &fb[k]) == SR_OK);
    }
    rng r = { seed };
    for (int n = 0; n < 300; n++) {
        float pos[9], rgb[9];
        for (int v = 0; v < 3; v++) {
            /* Vertex 0 sits near or behind the eye (or, for the box, in
             * front of its near face); the others reach far to the sides. */
            double z = v == 0 ? uni(&r, ortho ? 0.5 : -0.9, 0.8) : uni(&r, -9.0, -1.5);
            double reach = spread * (ortho ? 3.0 : -z * 2.0 + 1.0);
            pos[3 * v + 0] = (float)uni(&r, -reach, reach);
            pos[3 * v + 1] = (float)uni(&r, -reach, reach);
            pos[3 * v + 2] = (float)z;
            for (int c = 0; c < 3; c++) {
                rgb[3 * v + c] = (float)uni(&r, 0.0, 1.0);
            }
        }
        compare_one(ctx, fb, pos, rgb, proj, zero_to_one, t);
    }
    for (int k = 0; k < 2; k++) {
        sr_destroy_framebuffer(ctx, fb[k]);
    }
    sr_destroy_context(ctx);
}

static void check_tally(const char *what, const tally *t)
{
    printf("%s: %ld triangles, %ld covered pixels, %ld differ (%ld in coverage), "
           "largest channel difference %d\n",
           what, t->triangles, t->covered, t->pixel_diff, t->cover_diff, t->max_channel);
    CHECK(t->covered > 100000); /* the scenes do draw */
    CHECK(t->pixel_diff * 1000000 <= t->covered * MAX_DIFF_PER_MILLION);
    CHECK(t->cover_diff * 1000000 <= t->covered * MAX_COVER_DIFF_PER_MILLION);
    CHECK(t->max_channel <= MAX_CHANNEL_DIFF);
}

SR_TEST(view_volume_clipper_draws_the_homogeneous_pixels_under_a_frustum)
{
    tally t = { 0 };
    for (int zo = 0; zo < 2; zo++) {
        sr_mat4 p = sr_frustum(-0.4f, 0.4f, -0.3f, 0.3f, 0.5f, 8.0f, zo != 0);
        for (uint64_t seed = 1; seed <= 3; seed++) {
            random_scene(seed * 7919 + (uint64_t)zo, &p, false, zo != 0, 1.0, &t);
        }
    }
    check_tally("frustum", &t);
}

SR_TEST(view_volume_clipper_draws_the_homogeneous_pixels_under_an_ortho_box)
{
    tally t = { 0 };
    sr_mat4 p = sr_ortho(-2.0f, 2.0f, -1.5f, 1.5f, 1.0f, 8.0f, false);
    for (uint64_t seed = 1; seed <= 3; seed++) {
        random_scene(seed * 104729, &p, true, false, 1.0, &t);
    }
    check_tally("ortho", &t);
}

/* Vertices hundreds of viewports off to the side: the guard band's planes
 * cut too. */
SR_TEST(view_volume_clipper_draws_the_homogeneous_pixels_past_the_guard_band)
{
    tally t = { 0 };
    sr_mat4 p = sr_frustum(-0.4f, 0.4f, -0.3f, 0.3f, 0.5f, 8.0f, false);
    for (uint64_t seed = 1; seed <= 3; seed++) {
        random_scene(seed * 31337, &p, false, false, 500.0, &t);
    }
    sr_mat4 o = sr_ortho(-2.0f, 2.0f, -1.5f, 1.5f, 1.0f, 8.0f, false);
    random_scene(4 * 31337, &o, true, false, 2000.0, &t);
    check_tally("guard band", &t);
}

SR_TEST(view_volume_clipper_draws_nothing_from_behind_the_eye)
{
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                            .depth_format = SR_DEPTH_D24 },
                                &fb) == SR_OK);
    /* Behind the eye (z > 0): after the divide it would land upside down
     * on the screen, since x/w and y/w lose the sign of w = -z. */
    const float pos[9] = { -1, -1, 2, 1, -1, 2, 0, 1, 2 };
    const float rgb[9] = { 1, 1, 1, 1, 1, 1, 1, 1, 1 };
    sr_mat4 p = sr_frustum(-0.4f, 0.4f, -0.3f, 0.3f, 0.5f, 8.0f, false);
    CHECK_EQ(draw(ctx, fb, SR_CLIPPER_VIEW_VOLUME, pos, rgb, 1, &p, false), SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    int lit = 0;
    for (int i = 0; i < W * H; i++) {
        lit += px[4 * i + 3] != 0;
    }
    CHECK_EQ(lit, 0);
    /* The same triangle in front of the eye is drawn. */
    const float front[9] = { -1, -1, -2, 1, -1, -2, 0, 1, -2 };
    CHECK_EQ(draw(ctx, fb, SR_CLIPPER_VIEW_VOLUME, front, rgb, 1, &p, false), SR_OK);
    px = sr_framebuffer_pixels(fb);
    for (int i = 0; i < W * H; i++) {
        lit += px[4 * i + 3] != 0;
    }
    CHECK(lit > 100);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

static void vs_pass(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    (void)u;
    (void)vary;
    memcpy(clip, in->position, sizeof in->position);
}

static void fs_white(const void *u, sr_fragment_quad *q)
{
    (void)u;
    for (int c = 0; c < 4; c++) {
        for (int i = 0; i < 4; i++) {
            q->color[c][i] = 1.0f;
        }
    }
}

SR_TEST(view_volume_clipper_refuses_a_program_a_singular_projection_and_bad_values)
{
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) ==
            SR_OK);
    const float pos[9] = { -1, -1, -2, 1, -1, -2, 0, 1, -2 };
    sr_draw_desc d = { .positions = pos, .vertex_count = 3 };
    sr_program prog = { .vertex = vs_pass, .fragment = fs_white };
    sr_state st = { .clipper = SR_CLIPPER_VIEW_VOLUME, .program = &prog };
    CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_state.clipper");
    st.clipper = SR_CLIPPER_HOMOGENEOUS;
    CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_OK);

    sr_mat4 flat = { { 0 } }; /* projects everything onto one point */
    d.projection = &flat;
    st = (sr_state){ .clipper = SR_CLIPPER_VIEW_VOLUME };
    CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "invertible");
    d.projection = NULL; /* identity: the box [-1, 1]^3 */
    CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_OK);
    st.clipper = (sr_clipper)(SR_CLIPPER_VIEW_VOLUME + 1);
    CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_INVALID_ARG);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
