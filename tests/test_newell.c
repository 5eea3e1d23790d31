/* test_newell.c - geometry stage: sr_newell_normal (src/geometry/newell.c)
 * against what the normal of a polygon must be: the plane's normal and
 * twice the area for planar polygons in any orientation, the symmetric
 * best fit for a non-planar quad, negation under reversed winding, and the
 * results for bad and degenerate input. */
#include "sr_test.h"
#include "softrast.h"

#include <float.h>
#include <math.h>

/* A random rotation: a unit quaternion from four normal-ish draws. */
static void random_rotation(sr_rng *rng, double r[3][3])
{
    double q[4], len = 0;
    do {
        len = 0;
        for (int k = 0; k < 4; k++) {
            q[k] = sr_rng_range(rng, -1, 1);
            len += q[k] * q[k];
        }
    } while (len > 1 || len < 1e-3);
    len = sqrt(len);
    double w = q[0] / len, x = q[1] / len, y = q[2] / len, z = q[3] / len;
    r[0][0] = 1 - 2 * (y * y + z * z);
    r[0][1] = 2 * (x * y - w * z);
    r[0][2] = 2 * (x * z + w * y);
    r[1][0] = 2 * (x * y + w * z);
    r[1][1] = 1 - 2 * (x * x + z * z);
    r[1][2] = 2 * (y * z - w * x);
    r[2][0] = 2 * (x * z - w * y);
    r[2][1] = 2 * (y * z + w * x);
    r[2][2] = 1 - 2 * (x * x + y * y);
}

static sr_vec3 apply(const double r[3][3], const double t[3], double x, double y, double z)
{
    return (sr_vec3){ (float)(r[0][0] * x + r[0][1] * y + r[0][2] * z + t[0]),
                      (float)(r[1][0] * x + r[1][1] * y + r[1][2] * z + t[1]),
                      (float)(r[2][0] * x + r[2][1] * y + r[2][2] * z + t[2]) };
}

static double length3(sr_vec3 v)
{
    return sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
}

/* Angle between the directions of a and b, in radians. */
static double angle_between(sr_vec3 a, sr_vec3 b)
{
    double d = ((double)a.x * b.x + (double)a.y * b.y + (double)a.z * b.z) /
               (length3(a) * length3(b));
    return acos(fmax(-1.0, fmin(1.0, d)));
}

#define MAX_CORNERS 16

/* A star-shaped polygon in the z = 0 plane around the origin, corners at
 * increasing angles (counter-clockwise seen from +z); returns its area
 * by the shoelace formula. */
static double random_star(sr_rng *rng, int n, double xy[][2])
{
    for (int i = 0; i < n; i++) {
        double a = 2 * M_PI * (i + sr_rng_range(rng, 0.1, 0.9)) / n;
        double rad = sr_rng_range(rng, 0.2, 3.0);
        xy[i][0] = rad * cos(a);
        xy[i][1] = rad * sin(a);
    }
    double area2 = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        area2 += xy[i][0] * xy[j][1] - xy[j][0] * xy[i][1];
    }
    return area2 / 2;
}

SR_TEST(planar_polygons_in_any_orientation_give_the_plane_normal_and_twice_the_area)
{
    sr_rng rng = { 0x5eed1e55u };
    for (int iter = 0; iter < 500; iter++) {
        int n = sr_rng_int(&rng, 3, MAX_CORNERS);
        double xy[MAX_CORNERS][2];
        double area = random_star(&rng, n, xy);
        REQUIRE(area > 0);
        double r[3][3], t[3];
        random_rotation(&rng, r);
        for (int k = 0; k < 3; k++) {
            t[k] = sr_rng_range(&rng, -100, 100);
        }
        sr_vec3 p[MAX_CORNERS];
        for (int i = 0; i < n; i++) {
            p[i] = apply(r, t, xy[i][0], xy[i][1], 0);
        }
        sr_vec3 out;
        REQUIRE(sr_newell_normal(p, n, &out) == SR_OK);
        /* The plane's normal is the rotated +z: the corners run
         * counter-clockwise seen from there. */
        const double zero[3] = { 0, 0, 0 };
        sr_vec3 plane_normal = apply(r, zero, 0, 0, 1);
        CHECK(angle_between(out, plane_normal) < 1e-4);
        /* Corners rounded to float after a translation of up to 100 move by
         * about 1e-5, which bounds the area's error. */
        CHECK_NEAR(length3(out), 2 * area, 1e-4 * (1 + 2 * area));
        CHECK_NEAR(length3(sr_vec3_normalize(out)), 1.0, 1e-6);
    }
}

SR_TEST(a_triangle_gives_the_cross_product_of_its_edges)
{
    sr_vec3 p[3] = { { 1, 2, 3 }, { 4, -1, 2 }, { 0, 5, -2 } };
    sr_vec3 out;
    REQUIRE(sr_newell_normal(p, 3, &out) == SR_OK);
    sr_vec3 c = sr_vec3_cross(sr_vec3_sub(p[1], p[0]), sr_vec3_sub(p[2], p[0]));
    CHECK_EQ(out.x, c.x);
    CHECK_EQ(out.y, c.y);
    CHECK_EQ(out.z, c.z);
}

SR_TEST(reversing_the_winding_negates_the_normal)
{
    sr_rng rng = { 0xf11bu };
    for (int iter = 0; iter < 200; iter++) {
        int n = sr_rng_int(&rng, 3, MAX_CORNERS);
        sr_vec3 p[MAX_CORNERS], q[MAX_CORNERS];
        /* Any corners at all, planar or not. */
        for (int i = 0; i < n; i++) {
            p[i] = (sr_vec3){ (float)sr_rng_range(&rng, -5, 5), (float)sr_rng_range(&rng, -5, 5),
                              (float)sr_rng_range(&rng, -5, 5) };
        }
        for (int i = 0; i < n; i++) {
            q[i] = p[n - 1 - i];
        }
        sr_vec3 a, b;
        REQUIRE(sr_newell_normal(p, n, &a) == SR_OK);
        REQUIRE(sr_newell_normal(q, n, &b) == SR_OK);
        double tol = 1e-9 * (1 + length3(a)) + 1e-4;
        CHECK_NEAR(a.x, -b.x, tol);
        CHECK_NEAR(a.y, -b.y, tol);
        CHECK_NEAR(a.z, -b.z, tol);
    }
}

SR_TEST(a_nonplanar_quad_gives_the_best_fit_direction)
{
    /* A saddle: the square [-1,1]^2 with its corners lifted alternately by
     * +h and -h.  Its least-squares plane is z = 0 by symmetry (the corners'
     * heights average to zero and are uncorrelated with x and y), so the
     * best-fit normal is +z and the projected area is the square's, 4.  The
     * cross product of two edges at one corner tilts by the saddle's slope. */
    const double h = 0.5;
    const double c[4][3] = { { -1, -1, h }, { 1, -1, -h }, { 1, 1, h }, { -1, 1, -h } };
    sr_rng rng = { 0x5add1eu };
    for (int iter = 0; iter < 100; iter++) {
        double r[3][3], t[3];
        random_rotation(&rng, r);
        for (int k = 0; k < 3; k++) {
            t[k] = sr_rng_range(&rng, -10, 10);
        }
        sr_vec3 p[4];
        for (int i = 0; i < 4; i++) {
            p[i] = apply(r, t, c[i][0], c[i][1], c[i][2]);
        }
        sr_vec3 out;
        REQUIRE(sr_newell_normal(p, 4, &out) == SR_OK);
        const double zero[3] = { 0, 0, 0 };
        sr_vec3 fit = apply(r, zero, 0, 0, 1);
        CHECK(angle_between(out, fit) < 1e-5);
        CHECK_NEAR(length3(out), 2 * 4.0, 1e-4);
        sr_vec3 corner = sr_vec3_cross(sr_vec3_sub(p[1], p[0]), sr_vec3_sub(p[3], p[0]));
        CHECK(angle_between(corner, fit) > 0.3);
    }
}

SR_TEST(a_small_polygon_far_from_the_origin_keeps_its_area)
{
    /* A 1 x 0.5 rectangle (area 0.5) at x = 1e5, where a float still holds
     * the corners to 1/128 but sums of raw coordinates would cancel badly. */
    sr_vec3 p[4] = { { 1e5f, 1e5f, 7 }, { 1e5f + 1, 1e5f, 7 }, { 1e5f + 1, 1e5f + 0.5f, 7 },
                     { 1e5f, 1e5f + 0.5f, 7 } };
    sr_vec3 out;
    REQUIRE(sr_newell_normal(p, 4, &out) == SR_OK);
    CHECK_EQ(out.x, 0);
    CHECK_EQ(out.y, 0);
    CHECK_EQ(out.z, 1);
}

SR_TEST(degenerate_polygons_give_the_zero_vector_and_ok)
{
    sr_vec3 line[4] = { { 0, 0, 0 }, { 1, 1, 1 }, { 3, 3, 3 }, { 2, 2, 2 } };
    sr_vec3 same[3] = { { 1, 2, 3 }, { 1, 2, 3 }, { 1, 2, 3 } };
    /* A figure eight: two equal loops of opposite winding cancel. */
    sr_vec3 eight[4] = { { 0, 0, 0 }, { 1, 1, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
    const sr_vec3 *cases[] = { line, same, eight };
    const int counts[] = { 4, 3, 4 };
    for (int i = 0; i < 3; i++) {
        sr_vec3 out = { 9, 9, 9 };
        CHECK_EQ(sr_newell_normal(cases[i], counts[i], &out), SR_OK);
        CHECK_EQ(out.x, 0);
        CHECK_EQ(out.y, 0);
        CHECK_EQ(out.z, 0);
        sr_vec3 u = sr_vec3_normalize(out);
        CHECK(u.x == 0 && u.y == 0 && u.z == 0);
    }
}

SR_TEST(bad_input_is_refused)
{
    sr_vec3 p[3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
    sr_vec3 out = { 9, 9, 9 };
    CHECK_EQ(sr_newell_normal(p, 3, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_newell_normal(NULL, 3, &out), SR_INVALID_ARG);
    CHECK(out.x == 0 && out.y == 0 && out.z == 0);
    out.z = 9;
    CHECK_EQ(sr_newell_normal(p, 2, &out), SR_INVALID_ARG);
    CHECK_EQ(out.z, 0);
    CHECK_EQ(sr_newell_normal(p, -1, &out), SR_INVALID_ARG);
    const float bad[] = { NAN, INFINITY, -INFINITY };
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++) {
            sr_vec3 q[3] = { p[0], p[1], p[2] };
            float *f = &q[1].x;
            f[k] = bad[i];
            CHECK_EQ(sr_newell_normal(q, 3, &out), SR_INVALID_ARG);
        }
    }
    /* Finite corners whose area exceeds FLT_MAX. */
    sr_vec3 big[3] = { { -FLT_MAX, -FLT_MAX, 0 }, { FLT_MAX, -FLT_MAX, 0 }, { 0, FLT_MAX, 0 } };
    CHECK_EQ(sr_newell_normal(big, 3, &out), SR_TOO_LARGE);
    sr_vec3 ok;
    CHECK_EQ(sr_newell_normal(p, 3, &ok), SR_OK);
    CHECK_EQ(ok.z, 1);
}
