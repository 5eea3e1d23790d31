/* test_math.c - the math stage: the viewport matrix S against the pixel-centre
 * formula, the camera frame (u, v, w) and E = M_cam^-1, the normal matrix
 * (inverse transpose) under non-uniform scale, the projections' near/far
 * mapping, sr_fit_fovy, sr_mat4_invert and rotations.  Fixed seeds. */
#include "sr_test.h"
#include "softrast.h"

#include <math.h>
#include <string.h>

/* Element (row, col) of a column-major matrix. */
static float at(const sr_mat4 *m, int row, int col) { return m->m[col * 4 + row]; }

static sr_vec4 xf(const sr_mat4 *m, float x, float y, float z, float w)
{
    return sr_mat4_mul_vec4(m, (sr_vec4){ x, y, z, w });
}

/* NaN when any difference is NaN (fmax would drop it); a comparison, also
 * because GCC 12 for aarch64 crashes vectorizing an fmax reduction. */
static double max_abs_diff(const sr_mat4 *a, const sr_mat4 *b)
{
    double d = 0.0;
    for (int i = 0; i < 16; i++) {
        double x = fabs((double)a->m[i] - b->m[i]);
        if (!(x <= d)) {
            d = x;
        }
    }
    return d;
}

static sr_vec3 rand_vec3(sr_rng *r, double lo, double hi)
{
    return (sr_vec3){ (float)sr_rng_range(r, lo, hi), (float)sr_rng_range(r, lo, hi),
                      (float)sr_rng_range(r, lo, hi) };
}

/* ---- viewport matrix S -------------------------------------------------- */

typedef struct vp_case { float x0, y0, w, h; } vp_case;

static const vp_case viewports[] = {
    { 0, 0, 640, 480 },
    { 0, 0, 1, 1 },
    { 10, 20, 100, 50 },
    { 3, 5, 33, 17 },        /* odd sizes: the centre is not a pixel edge */
    { -7, -11, 64, 128 },    /* offset partly off the framebuffer */
    { 1000, 300, 7, 3 },
};

/* The viewport in the pixel-centre convention (centres at integers), for pixels x1..x2:
 * x_S = x1 - 1/2 + (x + 1)/2 (x2 - x1 + 1).  softrast's pixel-edge
 * coordinate is that + 1/2. */
static double centre_x(double x_ndc, double x1, double x2)
{
    return x1 - 0.5 + (x_ndc + 1.0) * 0.5 * (x2 - x1 + 1.0);
}

SR_TEST(viewport_matrix_matches_the_pixel_centre_formula_at_ndc_edges_and_centre)
{
    for (size_t i = 0; i < sizeof viewports / sizeof viewports[0]; i++) {
        vp_case v = viewports[i];
        sr_mat4 s = sr_viewport_matrix(v.x0, v.y0, v.w, v.h, 0.0f, 1.0f, false);
        double x1 = v.x0, x2 = v.x0 + v.w - 1;
        double y1 = v.y0, y2 = v.y0 + v.h - 1;
        const double ndc[3] = { -1.0, 1.0, 0.0 };
        for (int k = 0; k < 3; k++) {
            sr_vec4 p = xf(&s, (float)ndc[k], (float)ndc[k], 0.0f, 1.0f);
            CHECK_NEAR(p.x, centre_x(ndc[k], x1, x2) + 0.5, 1e-4);
            /* y is flipped: NDC y maps like x of -y (NDC +1 is row y0). */
            CHECK_NEAR(p.y, centre_x(-ndc[k], y1, y2) + 0.5, 1e-4);
            CHECK_NEAR(p.w, 1.0, 0.0);
        }
        /* The NDC square maps onto the pixel edges of the rectangle. */
        sr_vec4 lo = xf(&s, -1, 1, 0, 1), hi = xf(&s, 1, -1, 0, 1);
        CHECK_NEAR(lo.x, v.x0, 1e-4);
        CHECK_NEAR(lo.y, v.y0, 1e-4);
        CHECK_NEAR(hi.x, v.x0 + v.w, 1e-4);
        CHECK_NEAR(hi.y, v.y0 + v.h, 1e-4);
    }
}

/* The NDC position of pixel i's centre in the pixel-centre convention maps to
 * exactly i there, and to i + 1/2 (the centre) in softrast's. */
SR_TEST(viewport_matrix_puts_corner_and_centre_pixels_at_their_centres)
{
    for (size_t i = 0; i < sizeof viewports / sizeof viewports[0]; i++) {
        vp_case v = viewports[i];
        sr_mat4 s = sr_viewport_matrix(v.x0, v.y0, v.w, v.h, 0.0f, 1.0f, false);
        double x1 = v.x0, x2 = v.x0 + v.w - 1;
        int cols[3] = { (int)v.x0, (int)(v.x0 + v.w - 1), (int)(v.x0 + floorf(v.w / 2)) };
        int rows[3] = { (int)v.y0, (int)(v.y0 + v.h - 1), (int)(v.y0 + floorf(v.h / 2)) };
        for (int k = 0; k < 3; k++) {
            /* Invert that formula: x_ndc of the centre of column c. */
            double xn = (2.0 * (cols[k] - v.x0) + 1.0) / v.w - 1.0;
            double yn = 1.0 - (2.0 * (rows[k] - v.y0) + 1.0) / v.h; /* row y0 is the top */
            CHECK_NEAR(centre_x(xn, x1, x2), cols[k], 1e-9);
            sr_vec4 p = xf(&s, (float)xn, (float)yn, 0.0f, 1.0f);
            CHECK_NEAR(p.x, cols[k] + 0.5, 1e-3);
            CHECK_NEAR(p.y, rows[k] + 0.5, 1e-3);
            CHECK(floor(p.x) == cols[k]);
            CHECK(floor(p.y) == rows[k]);
        }
    }
}

SR_TEST(viewport_matrix_maps_depth_in_both_conventions)
{
    const float ranges[][2] = { { 0, 1 }, { 0.25f, 0.75f }, { 0.9f, 0.1f } };
    for (int i = 0; i < 3; i++) {
        float n = ranges[i][0], f = ranges[i][1];
        sr_mat4 gl = sr_viewport_matrix(0, 0, 16, 16, n, f, false);
        CHECK_NEAR(xf(&gl, 0, 0, -1, 1).z, n, 1e-6);
        CHECK_NEAR(xf(&gl, 0, 0, 1, 1).z, f, 1e-6);
        CHECK_NEAR(xf(&gl, 0, 0, 0, 1).z, 0.5 * (n + f), 1e-6);
        sr_mat4 d3d = sr_viewport_matrix(0, 0, 16, 16, n, f, true);
        CHECK_NEAR(xf(&d3d, 0, 0, 0, 1).z, n, 1e-6);
        CHECK_NEAR(xf(&d3d, 0, 0, 1, 1).z, f, 1e-6);
        CHECK_NEAR(xf(&d3d, 0, 0, 0.5f, 1).z, 0.5 * (n + f), 1e-6);
        /* Depth does not leak into x and y, nor x, y into depth. */
        CHECK_NEAR(at(&gl, 0, 2), 0, 0);
        CHECK_NEAR(at(&gl, 2, 0), 0, 0);
        CHECK_NEAR(at(&gl, 2, 1), 0, 0);
    }
}

/* The pipeline uses the same S: a full NDC quad drawn with an offset
 * viewport fills exactly the viewport rectangle. */
SR_TEST(pipeline_viewport_fills_exactly_the_viewport_rectangle)
{
    const sr_viewport vps[] = { { 3, 5, 8, 4 }, { 0, 0, 16, 16 }, { -4, 9, 9, 13 }, { 7, 0, 1, 1 } };
    for (size_t i = 0; i < sizeof vps / sizeof vps[0]; i++) {
        sr_context *ctx;
        sr_framebuffer *fb;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 16, .height = 16,
                                                                .depth_format = SR_DEPTH_NONE }, &fb) == SR_OK);
        const float pos[] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0 };
        sr_state st = { .viewport = vps[i], .material = { .diffuse = { 1, 1, 1 } } };
        REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 6 }) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(fb);
        int bad = 0;
        for (int y = 0; y < 16; y++) {
            for (int x = 0; x < 16; x++) {
                bool in = x >= vps[i].x && x < vps[i].x + vps[i].width &&
                          y >= vps[i].y && y < vps[i].y + vps[i].height;
                bad += (px[(y * 16 + x) * 4] != 0) != in;
            }
        }
        CHECK_EQ(bad, 0);
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
    }
}

/* ---- camera ------------------------------------------------------------- */

SR_TEST(camera_frame_is_orthonormal_right_handed_and_looks_down_minus_w)
{
    sr_rng rng = { 0xca3e7a };
    for (int it = 0; it < 1000; it++) {
        sr_vec3 e = rand_vec3(&rng, -50, 50);
        sr_vec3 g = rand_vec3(&rng, -3, 3);
        sr_vec3 t = rand_vec3(&rng, -3, 3);
        if (sr_vec3_length(g) < 1e-2f ||
            sr_vec3_length(sr_vec3_cross(g, t)) < 1e-2f * sr_vec3_length(g) * sr_vec3_length(t)) {
            continue;
        }
        sr_camera_basis b;
        REQUIRE(sr_camera_frame(e, g, t, &b));
        CHECK_NEAR(sr_vec3_length(b.u), 1, 1e-5);
        CHECK_NEAR(sr_vec3_length(b.v), 1, 1e-5);
        CHECK_NEAR(sr_vec3_length(b.w), 1, 1e-5);
        CHECK_NEAR(sr_vec3_dot(b.u, b.v), 0, 1e-5);
        CHECK_NEAR(sr_vec3_dot(b.v, b.w), 0, 1e-5);
        CHECK_NEAR(sr_vec3_dot(b.w, b.u), 0, 1e-5);
        sr_vec3 uxv = sr_vec3_cross(b.u, b.v);
        CHECK_NEAR(uxv.x, b.w.x, 1e-5);
        CHECK_NEAR(uxv.y, b.w.y, 1e-5);
        CHECK_NEAR(uxv.z, b.w.z, 1e-5);
        sr_vec3 gn = sr_vec3_normalize(g);
        CHECK_NEAR(b.w.x, -gn.x, 1e-6);
        CHECK_NEAR(b.w.y, -gn.y, 1e-6);
        CHECK_NEAR(b.w.z, -gn.z, 1e-6);
        /* v lies in the plane of t and w, on t's side; u is perpendicular to t. */
        CHECK(sr_vec3_dot(b.v, t) > 0);
        CHECK_NEAR(sr_vec3_dot(b.u, t), 0, 1e-5 * sr_vec3_length(t));
        CHECK(b.e.x == e.x && b.e.y == e.y && b.e.z == e.z);
    }
    /* The textbook case: gaze -z, up +y gives the identity frame. */
    sr_camera_basis b;
    REQUIRE(sr_camera_frame(sr_vec3_make(0, 0, 0), sr_vec3_make(0, 0, -2), sr_vec3_make(0, 3, 0), &b));
    CHECK_NEAR(b.u.x, 1, 1e-7);
    CHECK_NEAR(b.v.y, 1, 1e-7);
    CHECK_NEAR(b.w.z, 1, 1e-7);
}

SR_TEST(camera_frame_rejects_zero_gaze_and_up_parallel_to_gaze)
{
    sr_camera_basis b;
    sr_vec3 e = sr_vec3_make(1, 2, 3);
    CHECK(!sr_camera_frame(e, sr_vec3_make(0, 0, 0), sr_vec3_make(0, 1, 0), &b));
    CHECK(!sr_camera_frame(e, sr_vec3_make(0, 1, 0), sr_vec3_make(0, 1, 0), &b));
    CHECK(!sr_camera_frame(e, sr_vec3_make(0, 1, 0), sr_vec3_make(0, -5, 0), &b));
    CHECK(!sr_camera_frame(e, sr_vec3_make(1, 2, 3), sr_vec3_make(2, 4, 6), &b));
    CHECK(!sr_camera_frame(e, sr_vec3_make(1, 0, 0), sr_vec3_make(0, 0, 0), &b));
    CHECK(!sr_camera_frame(e, sr_vec3_make(NAN, 0, 0), sr_vec3_make(0, 1, 0), &b));
    /* Nearly but not exactly parallel is a valid frame. */
    CHECK(sr_camera_frame(e, sr_vec3_make(0, 1, 0), sr_vec3_make(0.01f, 1, 0), &b));
}

/* M_cam = [u v w e; 0 0 0 1] (the camera's frame in world coordinates). */
static sr_mat4 m_cam(const sr_camera_basis *b)
{
    sr_mat4 m = sr_mat4_identity();
    const sr_vec3 cols[4] = { b->u, b->v, b->w, b->e };
    for (int c = 0; c < 4; c++) {
        m.m[c * 4 + 0] = cols[c].x;
        m.m[c * 4 + 1] = cols[c].y;
        m.m[c * 4 + 2] = cols[c].z;
    }
    return m;
}

SR_TEST(camera_matrix_moves_the_eye_to_the_origin_and_inverts_m_cam)
{
    sr_rng rng = { 0xe7e };
    for (int it = 0; it < 500; it++) {
        sr_vec3 e = rand_vec3(&rng, -10, 10);
        sr_vec3 g = rand_vec3(&rng, -1, 1);
        sr_vec3 t = rand_vec3(&rng, -1, 1);
        sr_camera_basis b;
        if (sr_vec3_length(g) < 0.1f || !sr_camera_frame(e, g, t, &b) ||
            sr_vec3_length(sr_vec3_cross(sr_vec3_normalize(g), sr_vec3_normalize(t))) < 0.1f) {
            continue;
        }
        sr_mat4 E = sr_camera_matrix(&b);
        sr_vec4 o = xf(&E, e.x, e.y, e.z, 1);
        CHECK_NEAR(o.x, 0, 1e-5);
        CHECK_NEAR(o.y, 0, 1e-5);
        CHECK_NEAR(o.z, 0, 1e-5);
        CHECK_NEAR(o.w, 1, 0);
        /* A point along the gaze ends up on the -z axis at its distance. */
        sr_vec3 ahead = sr_vec3_add(e, sr_vec3_scale(sr_vec3_normalize(g), 3.0f));
        sr_vec4 a = xf(&E, ahead.x, ahead.y, ahead.z, 1);
        CHECK_NEAR(a.x, 0, 1e-5);
        CHECK_NEAR(a.y, 0, 1e-5);
        CHECK_NEAR(a.z, -3, 1e-5);
        sr_mat4 mc = m_cam(&b), inv;
        REQUIRE(sr_mat4_invert(&mc, &inv));
        CHECK(max_abs_diff(&E, &inv) <= 1e-5);
        sr_mat4 prod = sr_mat4_mul(&E, &mc), id = sr_mat4_identity();
        CHECK(max_abs_diff(&prod, &id) <= 1e-5);
    }
    /* sr_look_at is the same matrix. */
    sr_vec3 eye = sr_vec3_make(1, 2, 5), target = sr_vec3_make(-1, 0, 0), up = sr_vec3_make(0, 1, 0);
    sr_camera_basis b;
    REQUIRE(sr_camera_frame(eye, sr_vec3_sub(target, eye), up, &b));
    sr_mat4 e1 = sr_camera_matrix(&b), e2 = sr_look_at(eye, target, up);
    CHECK(max_abs_diff(&e1, &e2) == 0.0);
}

/* ---- normal matrix ------------------------------------------------------ */

static sr_vec3 xf3(const sr_mat4 *m, sr_vec3 v)
{
    sr_vec4 r = xf(m, v.x, v.y, v.z, 0);
    return (sr_vec3){ r.x, r.y, r.z };
}

/* An example: the plane x = y has normal (1, -1, 0)/sqrt 2 and
 * tangents (1, 1, 0) and (0, 0, 1).  Under scale(1, 2, 1) the tangent
 * becomes (1, 2, 0); M n = (1, -2, 0)/sqrt 2 is no longer perpendicular to
 * it, but the inverse transpose gives (1, -1/2, 0)/sqrt 2, which is. */
SR_TEST(normal_matrix_keeps_normals_perpendicular_under_nonuniform_scale)
{
    sr_mat4 m = sr_mat4_scale(1, 2, 1), nm;
    REQUIRE(sr_normal_matrix(&m, &nm));
    sr_vec3 n = sr_vec3_make(1 / sqrtf(2), -1 / sqrtf(2), 0);
    sr_vec3 t1 = sr_vec3_make(1, 1, 0), t2 = sr_vec3_make(0, 0, 1);
    sr_vec3 mt1 = xf3(&m, t1), mt2 = xf3(&m, t2);
    sr_vec3 good = xf3(&nm, n), bad = xf3(&m, n);
    CHECK_NEAR(sr_vec3_dot(mt1, good), 0, 1e-6);
    CHECK_NEAR(sr_vec3_dot(mt2, good), 0, 1e-6);
    CHECK_NEAR(good.x, 1 / sqrt(2), 1e-6);
    CHECK_NEAR(good.y, -0.5 / sqrt(2), 1e-6);
    CHECK_NEAR(sr_vec3_dot(mt1, bad), -3 / sqrt(2), 1e-6); /* the plain matrix fails */
    CHECK(fabsf(sr_vec3_dot(sr_vec3_normalize(mt1), sr_vec3_normalize(bad))) > 0.5f);

    /* Random non-uniform scales composed with rotations and translations:
     * the inverse transpose always works, the plain matrix does not. */
    sr_rng rng = { 0x7a9e };
    int plain_fails = 0;
    for (int it = 0; it < 300; it++) {
        sr_mat4 s = sr_mat4_scale((float)sr_rng_range(&rng, 0.2, 4), (float)sr_rng_range(&rng, 0.2, 4),
                                  (float)sr_rng_range(&rng, 0.2, 4));
        sr_mat4 r = sr_mat4_rotate((float)sr_rng_range(&rng, -3, 3), rand_vec3(&rng, -1, 1));
        sr_mat4 tr = sr_mat4_translate(3, -2, 7);
        sr_mat4 rs = sr_mat4_mul(&r, &s);
        sr_mat4 mv = sr_mat4_mul(&tr, &rs);
        REQUIRE(sr_normal_matrix(&mv, &nm));
        sr_vec3 a = sr_vec3_normalize(rand_vec3(&rng, -1, 1));
        sr_vec3 b = sr_vec3_normalize(rand_vec3(&rng, -1, 1));
        sr_vec3 nn = sr_vec3_normalize(sr_vec3_cross(a, b));
        if (sr_vec3_length(sr_vec3_cross(a, b)) < 0.1f) {
            continue;
        }
        sr_vec3 ta = sr_vec3_normalize(xf3(&mv, a)), tb = sr_vec3_normalize(xf3(&mv, b));
        sr_vec3 tn = sr_vec3_normalize(xf3(&nm, nn)), pn = sr_vec3_normalize(xf3(&mv, nn));
        CHECK_NEAR(sr_vec3_dot(ta, tn), 0, 1e-5);
        CHECK_NEAR(sr_vec3_dot(tb, tn), 0, 1e-5);
        plain_fails += fabsf(sr_vec3_dot(ta, pn)) > 1e-3f || fabsf(sr_vec3_dot(tb, pn)) > 1e-3f;
    }
    CHECK(plain_fails > 200);
    /* The translation column does not matter, a singular 3x3 is reported. */
    sr_mat4 flat = sr_mat4_scale(1, 0, 1);
    CHECK(!sr_normal_matrix(&flat, &nm));
    sr_mat4 id = sr_mat4_identity();
    CHECK(max_abs_diff(&nm, &id) == 0.0);
}

SR_TEST(normal_matrix_of_a_rotation_is_the_rotation)
{
    sr_mat4 r = sr_mat4_rotate(0.7f, sr_vec3_make(1, 2, 3)), nm;
    sr_mat4 mv = sr_mat4_translate(5, 6, 7);
    mv = sr_mat4_mul(&mv, &r);
    REQUIRE(sr_normal_matrix(&mv, &nm));
    for (int c = 0; c < 3; c++) {
        for (int row = 0; row < 3; row++) {
            CHECK_NEAR(at(&nm, row, c), at(&r, row, c), 1e-6);
        }
    }
}

/* ---- projections -------------------------------------------------------- */

/* Clip coordinates of an eye-space point, divided by w. */
static sr_vec3 ndc(const sr_mat4 *p, float x, float y, float z)
{
    sr_vec4 c = xf(p, x, y, z, 1);
    return (sr_vec3){ c.x / c.w, c.y / c.w, c.z / c.w };
}

SR_TEST(perspective_maps_near_and_far_planes_to_the_depth_range)
{
    const float fovy = 1.1f, aspect = 1.6f, n = 0.3f, f = 250.0f;
    for (int z01 = 0; z01 <= 1; z01++) {
        sr_mat4 p = sr_perspective(fovy, aspect, n, f, z01);
        double lo = z01 ? 0.0 : -1.0;
        float ty = n * tanf(fovy / 2), tx = ty * aspect;
        sr_vec3 a = ndc(&p, 0, 0, -n), b = ndc(&p, 0, 0, -f);
        CHECK_NEAR(a.z, lo, 1e-5);
        CHECK_NEAR(b.z, 1.0, 1e-4);
        /* Corners of the near rectangle go to the NDC square's corners. */
        sr_vec3 c = ndc(&p, tx, ty, -n), d = ndc(&p, -tx, -ty, -n);
        CHECK_NEAR(c.x, 1, 1e-5);
        CHECK_NEAR(c.y, 1, 1e-5);
        CHECK_NEAR(c.z, lo, 1e-5);
        CHECK_NEAR(d.x, -1, 1e-5);
        CHECK_NEAR(d.y, -1, 1e-5);
        /* The far rectangle too (the frustum's sides are planes). */
        sr_vec3 e = ndc(&p, tx * f / n, -ty * f / n, -f);
        CHECK_NEAR(e.x, 1, 1e-4);
        CHECK_NEAR(e.y, -1, 1e-4);
        CHECK_NEAR(e.z, 1, 1e-4);
        /* Depth increases monotonically from near to far. */
        double prev = -2;
        for (int k = 0; k <= 20; k++) {
            float z = -(n + (f - n) * k / 20.0f);
            double zz = ndc(&p, 0, 0, z).z;
            CHECK(zz > prev);
            prev = zz;
        }
        /* w_clip is the distance in front of the eye. */
        CHECK_NEAR(xf(&p, 1, 2, -7, 1).w, 7, 0);
    }
}

SR_TEST(frustum_and_ortho_map_their_boxes_onto_the_ndc_cube)
{
    const float l = -0.3f, r = 0.7f, b = -0.2f, t = 0.5f, n = 0.5f, f = 40.0f;
    for (int z01 = 0; z01 <= 1; z01++) {
        double lo = z01 ? 0.0 : -1.0;
        sr_mat4 p = sr_frustum(l, r, b, t, n, f, z01);
        sr_vec3 a = ndc(&p, l, b, -n), c = ndc(&p, r, t, -n);
        CHECK_NEAR(a.x, -1, 1e-5);
        CHECK_NEAR(a.y, -1, 1e-5);
        CHECK_NEAR(a.z, lo, 1e-5);
        CHECK_NEAR(c.x, 1, 1e-5);
        CHECK_NEAR(c.y, 1, 1e-5);
        CHECK_NEAR(c.z, lo, 1e-5);
        sr_vec3 d = ndc(&p, r * f / n, b * f / n, -f);
        CHECK_NEAR(d.x, 1, 1e-4);
        CHECK_NEAR(d.y, -1, 1e-4);
        CHECK_NEAR(d.z, 1, 1e-4);

        sr_mat4 o = sr_ortho(l, r, b, t, n, f, z01);
        sr_vec3 e = ndc(&o, l, b, -n), g = ndc(&o, r, t, -f), h = ndc(&o, (l + r) / 2, (b + t) / 2, -(n + f) / 2);
        CHECK_NEAR(e.x, -1, 1e-6);
        CHECK_NEAR(e.y, -1, 1e-6);
        CHECK_NEAR(e.z, lo, 1e-6);
        CHECK_NEAR(g.x, 1, 1e-6);
        CHECK_NEAR(g.y, 1, 1e-6);
        CHECK_NEAR(g.z, 1, 1e-6);
        CHECK_NEAR(h.x, 0, 1e-6);
        CHECK_NEAR(h.y, 0, 1e-6);
        CHECK_NEAR(h.z, (lo + 1) / 2, 1e-6);
        CHECK_NEAR(xf(&o, 1, 2, 3, 1).w, 1, 0); /* affine */
    }
}

SR_TEST(fit_fovy_keeps_the_fov_across_the_smaller_dimension)
{
    const float fov = 1.0f;
    /* Wide and square viewports: the vertical fov is the requested one. */
    CHECK(sr_fit_fovy(fov, 640, 480) == fov);
    CHECK(sr_fit_fovy(fov, 100, 100) == fov);
    /* Tall viewports: the horizontal fov stays at the requested angle. */
    const int sizes[][2] = { { 480, 640 }, { 1, 100 }, { 99, 100 }, { 300, 1000 } };
    for (int i = 0; i < 4; i++) {
        int w = sizes[i][0], h = sizes[i][1];
        float fovy = sr_fit_fovy(fov, w, h);
        double aspect = (double)w / h;
        CHECK(fovy > fov);
        double fovx = 2 * atan(tan(fovy / 2.0) * aspect);
        CHECK_NEAR(fovx, fov, 1e-5);
        /* Through the projection: a point at half the angle off-axis to
         * the right lands on the right edge of NDC. */
        sr_mat4 p = sr_perspective(fovy, (float)aspect, 1, 10, false);
        sr_vec3 e = ndc(&p, tanf(fov / 2) * 5, 0, -5);
        CHECK_NEAR(e.x, 1, 1e-4);
    }
    /* Degenerate sizes leave it alone. */
    CHECK(sr_fit_fovy(fov, 0, 10) == fov);
}

/* ---- inverse and rotation ------------------------------------------------ */

SR_TEST(invert_round_trips_and_detects_singular_matrices)
{
    sr_rng rng = { 0x1a7e };
    sr_mat4 id = sr_mat4_identity();
    for (int it = 0; it < 500; it++) {
        sr_mat4 m;
        for (int i = 0; i < 16; i++) {
            m.m[i] = (float)sr_rng_range(&rng, -2, 2);
        }
        /* Diagonally dominant, so well conditioned. */
        for (int i = 0; i < 4; i++) {
            m.m[i * 5] += (float)(sr_rng_unit(&rng) < 0.5 ? -9 : 9);
        }
        sr_mat4 inv;
        REQUIRE(sr_mat4_invert(&m, &inv));
        sr_mat4 a = sr_mat4_mul(&m, &inv), b = sr_mat4_mul(&inv, &m);
        CHECK(max_abs_diff(&a, &id) < 1e-5);
        CHECK(max_abs_diff(&b, &id) < 1e-5);
        sr_mat4 back;
        REQUIRE(sr_mat4_invert(&inv, &back));
        CHECK(max_abs_diff(&back, &m) < 1e-4);
    }
    /* A composed transform with a known inverse. */
    sr_mat4 t = sr_mat4_translate(1, -2, 3), s = sr_mat4_scale(2, 4, 0.5f), inv;
    sr_mat4 ts = sr_mat4_mul(&t, &s);
    REQUIRE(sr_mat4_invert(&ts, &inv));
    sr_vec4 p = xf(&inv, 3, 2, 3.5f, 1);
    CHECK_NEAR(p.x, 1, 1e-6);
    CHECK_NEAR(p.y, 1, 1e-6);
    CHECK_NEAR(p.z, 1, 1e-6);
    /* Small but regular matrices are not singular. */
    sr_mat4 tiny = sr_mat4_scale(1e-3f, 1e-3f, 1e-3f);
    CHECK(sr_mat4_invert(&tiny, &inv));
    CHECK_NEAR(inv.m[0], 1000, 1e-2);

    /* Singular: zero, a flattening scale, two equal rows, a projection's
     * rank-3 matrix, NaN.  *out is left as the identity. */
    sr_mat4 zero = {{ 0 }};
    sr_mat4 flat = sr_mat4_scale(1, 1, 0);
    sr_mat4 rows = sr_mat4_identity();
    rows.m[0 * 4 + 1] = 1;  /* row 1 = row 0 = (1, 0, 0, 0)... */
    rows.m[1 * 4 + 1] = 0;  /* ...with (1,1) cleared */
    sr_mat4 nan = sr_mat4_identity();
    nan.m[6] = NAN;
    sr_mat4 rank3 = sr_mat4_identity();
    rank3.m[15] = 0;
    rank3.m[14] = 0;        /* last row and column zero */
    const sr_mat4 *sing[] = { &zero, &flat, &rows, &nan, &rank3 };
    for (int i = 0; i < 5; i++) {
        sr_mat4 out = zero;
        CHECK(!sr_mat4_invert(sing[i], &out));
        CHECK(max_abs_diff(&out, &id) == 0.0);
    }
}

SR_TEST(rotate_is_right_handed_about_its_axis)
{
    const float q = (float)(M_PI / 2);
    struct { sr_vec3 axis, from, to; } cases[] = {
        { { 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 } },   /* z: x -> y */
        { { 0, 0, 1 }, { 0, 1, 0 }, { -1, 0, 0 } },
        { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },   /* x: y -> z */
        { { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 0 } },   /* y: z -> x */
        { { 0, 0, 5 }, { 1, 0, 0 }, { 0, 1, 0 } },   /* the axis is normalized */
        { { 0, 0, -1 }, { 1, 0, 0 }, { 0, -1, 0 } }, /* reversed axis, reversed turn */
    };
    for (int i = 0; i < 6; i++) {
        sr_mat4 r = sr_mat4_rotate(q, cases[i].axis);
        sr_vec3 v = xf3(&r, cases[i].from);
        CHECK_NEAR(v.x, cases[i].to.x, 1e-6);
        CHECK_NEAR(v.y, cases[i].to.y, 1e-6);
        CHECK_NEAR(v.z, cases[i].to.z, 1e-6);
    }
    /* About the diagonal by 120 degrees the axes cycle x -> y -> z. */
    sr_mat4 r = sr_mat4_rotate((float)(2 * M_PI / 3), sr_vec3_make(1, 1, 1));
    sr_vec3 v = xf3(&r, sr_vec3_make(1, 0, 0));
    CHECK_NEAR(v.x, 0, 1e-6);
    CHECK_NEAR(v.y, 1, 1e-6);
    CHECK_NEAR(v.z, 0, 1e-6);
    /* Random rotations keep lengths and the axis, and have det +1. */
    sr_rng rng = { 0x407a7e };
    for (int it = 0; it < 200; it++) {
        sr_vec3 axis = rand_vec3(&rng, -1, 1);
        if (sr_vec3_length(axis) < 0.1f) {
            continue;
        }
        sr_mat4 m = sr_mat4_rotate((float)sr_rng_range(&rng, -7, 7), axis);
        sr_vec3 p = rand_vec3(&rng, -5, 5);
        CHECK_NEAR(sr_vec3_length(xf3(&m, p)), sr_vec3_length(p), 1e-4);
        sr_vec3 a = xf3(&m, axis);
        CHECK_NEAR(a.x, axis.x, 1e-5);
        CHECK_NEAR(a.y, axis.y, 1e-5);
        CHECK_NEAR(a.z, axis.z, 1e-5);
        sr_vec3 c0 = { at(&m, 0, 0), at(&m, 1, 0), at(&m, 2, 0) };
        sr_vec3 c1 = { at(&m, 0, 1), at(&m, 1, 1), at(&m, 2, 1) };
        sr_vec3 c2 = { at(&m, 0, 2), at(&m, 1, 2), at(&m, 2, 2) };
        CHECK_NEAR(sr_vec3_dot(sr_vec3_cross(c0, c1), c2), 1, 1e-5);
        CHECK_NEAR(at(&m, 3, 3), 1, 0);
    }
    /* A zero axis is the identity. */
    sr_mat4 z = sr_mat4_rotate(1, sr_vec3_make(0, 0, 0)), id = sr_mat4_identity();
    CHECK(max_abs_diff(&z, &id) == 0.0);
}

SR_TEST(matrix_product_composes_right_to_left)
{
    /* T * R applies R first: rotating x to y, then translating. */
    sr_mat4 t = sr_mat4_translate(10, 0, 0);
    sr_mat4 r = sr_mat4_rotate((float)(M_PI / 2), sr_vec3_make(0, 0, 1));
    sr_mat4 tr = sr_mat4_mul(&t, &r);
    sr_vec4 p = xf(&tr, 1, 0, 0, 1);
    CHECK_NEAR(p.x, 10, 1e-6);
    CHECK_NEAR(p.y, 1, 1e-6);
    /* Directions (w = 0) ignore translation. */
    sr_vec4 d = xf(&tr, 1, 0, 0, 0);
    CHECK_NEAR(d.x, 0, 1e-6);
    CHECK_NEAR(d.y, 1, 1e-6);
    sr_mat4 tt = sr_mat4_transpose(&tr);
    CHECK(at(&tt, 0, 3) == at(&tr, 3, 0) && at(&tt, 3, 0) == at(&tr, 0, 3));
}

SR_TEST(null_matrix_arguments_are_the_identity_and_null_outputs_fail)
{
    sr_mat4 r = sr_mat4_rotate(0.7f, (sr_vec3){ 1, 2, 3 });
    sr_mat4 p = sr_mat4_mul(NULL, &r);
    CHECK(memcmp(&p, &r, sizeof p) == 0);
    p = sr_mat4_mul(&r, NULL);
    CHECK(memcmp(&p, &r, sizeof p) == 0);
    sr_mat4 id = sr_mat4_identity(), t = sr_mat4_transpose(NULL);
    CHECK(memcmp(&t, &id, sizeof t) == 0);
    sr_vec4 v = sr_mat4_mul_vec4(NULL, (sr_vec4){ 1, 2, 3, 4 });
    CHECK(v.x == 1 && v.y == 2 && v.z == 3 && v.w == 4);
    sr_mat4 c = sr_camera_matrix(NULL);
    CHECK(memcmp(&c, &id, sizeof c) == 0);
    sr_mat4 inv;
    CHECK(sr_mat4_invert(NULL, &inv));
    CHECK(memcmp(&inv, &id, sizeof inv) == 0);
    CHECK(!sr_mat4_invert(&r, NULL));
    CHECK(sr_normal_matrix(NULL, &inv));
    CHECK(memcmp(&inv, &id, sizeof inv) == 0);
    CHECK(!sr_normal_matrix(&r, NULL));
}
