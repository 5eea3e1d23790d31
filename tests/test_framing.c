/* test_framing.c - geometry stage: sr_fit_camera (src/geometry/framing.c),
 * the default camera of softrast render and the Python package: its view
 * direction, the projected points spanning the image less the margin on
 * the limiting side and centred on the other, perspective and
 * orthographic, model matrices, and the errors for bad input. */
#include "sr_test.h"
#include "softrast.h"

#include <math.h>

/* The corners of a box from lo to hi, and a few points inside it. */
static void box_points(const float lo[3], const float hi[3], float out[10][3])
{
    for (int i = 0; i < 8; i++) {
        out[i][0] = i & 1 ? hi[0] : lo[0];
        out[i][1] = i & 2 ? hi[1] : lo[1];
        out[i][2] = i & 4 ? hi[2] : lo[2];
    }
    for (int k = 0; k < 3; k++) {
        out[8][k] = 0.5f * (lo[k] + hi[k]);
        out[9][k] = 0.25f * lo[k] + 0.75f * hi[k];
    }
}

/* The points' normalized device x, y extents under the fitted camera. */
static void ndc_extent(const sr_framing_info *info, const sr_mat4 *proj, float pts[][3], int n,
                       double lo[2], double hi[2])
{
    sr_mat4 view = sr_look_at(info->eye, info->target, info->up);
    sr_mat4 pv = sr_mat4_mul(proj, &view);
    lo[0] = lo[1] = INFINITY;
    hi[0] = hi[1] = -INFINITY;
    for (int i = 0; i < n; i++) {
        sr_vec4 c = sr_mat4_mul_vec4(&pv, (sr_vec4){ pts[i][0], pts[i][1], pts[i][2], 1.0f });
        double p[2] = { c.x / c.w, c.y / c.w };
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], p[k]);
            hi[k] = fmax(hi[k], p[k]);
        }
    }
}

SR_TEST(the_fit_fills_the_limiting_side_less_the_margin_and_centres_the_other)
{
    const float lo[3] = { -1.0f, 0.0f, -0.5f }, hi[3] = { 2.0f, 1.5f, 0.7f };
    float pts[10][3];
    box_points(lo, hi, pts);
    const int sizes[3][2] = { { 160, 120 }, { 90, 160 }, { 400, 60 } };
    for (int s = 0; s < 3; s++) {
        int w = sizes[s][0], h = sizes[s][1];
        sr_framing_info info;
        CHECK_EQ(sr_fit_camera(NULL, &(sr_framing_desc){
                     .sets = &(sr_framing_points){ &pts[0][0], 10, NULL }, .set_count = 1,
                     .width = w, .height = h }, &info), SR_OK);
        float fov = SR_FRAMING_FOV_DEG * 3.14159265358979f / 180.0f;
        CHECK_EQ(info.fovy, sr_fit_fovy(fov, w, h));
        CHECK_EQ(info.half_width, 0.0f);
        /* Seen along the default direction, +y up. */
        sr_vec3 back = sr_vec3_normalize(sr_vec3_sub(info.eye, info.target));
        sr_vec3 dir = sr_framing_direction();
        CHECK(sr_vec3_dot(back, dir) > 1.0f - 1e-6f);
        CHECK_EQ(info.up.y, 1.0f);
        CHECK_NEAR(info.centre.x, 0.5, 1e-6);
        CHECK_NEAR(info.centre.y, 0.75, 1e-6);
        CHECK_NEAR(info.centre.z, 0.1, 1e-6);
        sr_mat4 proj = sr_perspective(info.fovy, (float)w / (float)h, 0.01f, 100.0f, false);
        double nlo[2], nhi[2];
        ndc_extent(&info, &proj, pts, 10, nlo, nhi);
        double fill = 1.0 - 2.0 * SR_FRAMING_MARGIN;
        int limit = fmax(-nlo[0], nhi[0]) > fmax(-nlo[1], nhi[1]) ? 0 : 1;
        CHECK_NEAR(nhi[limit], fill, 1e-4);
        CHECK_NEAR(nlo[limit], -fill, 1e-4);
        CHECK_NEAR(nhi[1 - limit], -nlo[1 - limit], 1e-4);
        CHECK(nhi[1 - limit] < fill + 1e-4);
    }
}

SR_TEST(an_orthographic_fit_holds_the_points_with_the_image_aspect)
{
    const float lo[3] = { -1.0f, -1.0f, -1.0f }, hi[3] = { 1.0f, 3.0f, 1.0f };
    float pts[10][3];
    box_points(lo, hi, pts);
    sr_framing_info info;
    CHECK_EQ(sr_fit_camera(NULL, &(sr_framing_desc){
                 .sets = &(sr_framing_points){ &pts[0][0], 10, NULL }, .set_count = 1,
                 .width = 200, .height = 100, .ortho = true }, &info), SR_OK);
    CHECK_NEAR(info.half_width, 2.0 * info.half_height, 1e-5 * info.half_width);
    sr_mat4 proj = sr_ortho(-info.half_width, info.half_width, -info.half_height,
                            info.half_height, 0.01f, 100.0f, false);
    double nlo[2], nhi[2];
    ndc_extent(&info, &proj, pts, 10, nlo, nhi);
    /* The tall box limits the height. */
    CHECK_NEAR(nhi[1], 1.0 - 2.0 * SR_FRAMING_MARGIN, 1e-4);
    CHECK_NEAR(nlo[1], -(1.0 - 2.0 * SR_FRAMING_MARGIN), 1e-4);
    CHECK_NEAR(nhi[0], -nlo[0], 1e-4);
}

SR_TEST(model_matrices_place_the_points)
{
    const float lo[3] = { 0.0f, 0.0f, 0.0f }, hi[3] = { 1.0f, 2.0f, 1.0f };
    float pts[10][3], moved[10][3];
    box_points(lo, hi, pts);
    for (int i = 0; i < 10; i++) {
        moved[i][0] = pts[i][0] + 4.0f;
        moved[i][1] = pts[i][1] - 2.0f;
        moved[i][2] = pts[i][2] + 8.0f;
    }
    sr_mat4 shift = sr_mat4_translate(4.0f, -2.0f, 8.0f);
    sr_framing_info a, b;
    CHECK_EQ(sr_fit_camera(NULL, &(sr_framing_desc){
                 .sets = &(sr_framing_points){ &pts[0][0], 10, &shift }, .set_count = 1,
                 .width = 64, .height = 64 }, &a), SR_OK);
    CHECK_EQ(sr_fit_camera(NULL, &(sr_framing_desc){
                 .sets = &(sr_framing_points){ &moved[0][0], 10, NULL }, .set_count = 1,
                 .width = 64, .height = 64 }, &b), SR_OK);
    CHECK_NEAR(a.eye.x, b.eye.x, 1e-5);
    CHECK_NEAR(a.eye.y, b.eye.y, 1e-5);
    CHECK_NEAR(a.eye.z, b.eye.z, 1e-5);
    CHECK_EQ(a.centre.x, b.centre.x);
    /* Two sets frame as their union. */
    sr_framing_points halves[2] = { { &pts[0][0], 5, NULL }, { &pts[5][0], 5, NULL } };
    sr_framing_info u, whole;
    CHECK_EQ(sr_fit_camera(NULL, &(sr_framing_desc){ .sets = halves, .set_count = 2,
                                                     .width = 64, .height = 48 }, &u), SR_OK);
    CHECK_EQ(sr_fit_camera(NULL, &(sr_framing_desc){
                 .sets = &(sr_framing_points){ &pts[0][0], 10, NULL }, .set_count = 1,
                 .width = 64, .height = 48 }, &whole), SR_OK);
    CHECK_EQ(u.eye.x, whole.eye.x);
    CHECK_EQ(u.eye.y, whole.eye.y);
    CHECK_EQ(u.eye.z, whole.eye.z);
}

static void check_rejected(sr_context *ctx, const sr_framing_desc *d, const char *needle)
{
    sr_framing_info info = { .fovy = 1.0f };
    CHECK_EQ(sr_fit_camera(ctx, d, &info), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), needle);
    CHECK_EQ(info.fovy, 0.0f);
}

SR_TEST(bad_arguments_and_points_that_give_no_frame_are_rejected_by_name)
{
    sr_context *ctx = NULL;
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx), SR_OK);
    float pts[2][3] = { { 0, 0, 0 }, { 1, 1, 1 } };
    float same[2][3] = { { 1, 2, 3 }, { 1, 2, 3 } };
    float nan[1][3] = { { NAN, 0, 0 } };
    sr_framing_points ok = { &pts[0][0], 2, NULL };
    sr_mat4 bad = sr_mat4_identity();
    bad.m[12] = INFINITY;
    CHECK_EQ(sr_fit_camera(ctx, NULL, &(sr_framing_info){ 0 }), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "desc and out");
    check_rejected(ctx, &(sr_framing_desc){ .set_count = 1, .width = 8, .height = 8 }, "sets");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &ok, .width = 8, .height = 8 }, "set_count");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &(sr_framing_points){ NULL, 2, NULL },
                                            .set_count = 1, .width = 8, .height = 8 },
                   "sets[0].positions");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &(sr_framing_points){ &pts[0][0], 2, &bad },
                                            .set_count = 1, .width = 8, .height = 8 },
                   "sets[0].model");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &ok, .set_count = 1, .height = 8 }, "width");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &ok, .set_count = 1, .width = 8,
                                            .height = SR_MAX_FRAMEBUFFER_SIZE + 1 }, "height");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &ok, .set_count = 1, .width = 8,
                                            .height = 8, .fov = 3.2f }, "fov");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &ok, .set_count = 1, .width = 8,
                                            .height = 8, .fov = NAN }, "fov");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &(sr_framing_points){ NULL, 0, NULL },
                                            .set_count = 1, .width = 8, .height = 8 },
                   "no frame");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &(sr_framing_points){ &same[0][0], 2, NULL },
                                            .set_count = 1, .width = 8, .height = 8 },
                   "no frame");
    check_rejected(ctx, &(sr_framing_desc){ .sets = &(sr_framing_points){ &nan[0][0], 1, NULL },
                                            .set_count = 1, .width = 8, .height = 8 },
                   "no frame");
    /* NaN points among finite ones are skipped. */
    float mixed[3][3] = { { 0, 0, 0 }, { NAN, NAN, NAN }, { 1, 1, 1 } };
    sr_framing_info a, b;
    CHECK_EQ(sr_fit_camera(ctx, &(sr_framing_desc){
                 .sets = &(sr_framing_points){ &mixed[0][0], 3, NULL }, .set_count = 1,
                 .width = 8, .height = 8 }, &a), SR_OK);
    CHECK_EQ(sr_fit_camera(ctx, &(sr_framing_desc){ .sets = &ok, .set_count = 1, .width = 8,
                                                    .height = 8 }, &b), SR_OK);
    CHECK_EQ(a.eye.x, b.eye.x);
    CHECK_EQ(a.target.z, b.target.z);
    sr_destroy_context(ctx);
}
