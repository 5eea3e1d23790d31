/* framing.c - the default camera and lights of `softrast render` around
 * the library's sr_fit_camera: the sphere's framing, near and far planes
 * and the upright turn. */
#include "framing.h"

#include <math.h>

sr_vec3 framing_default_eye(sr_vec3 centre, float radius, float fov_radians)
{
    float dist = radius / sinf(fov_radians * 0.5f) * 1.04f;
    return sr_vec3_add(centre, sr_vec3_scale(sr_framing_direction(), dist));
}

void framing_near_far(sr_vec3 eye, sr_vec3 centre, float radius, float *near_z, float *far_z)
{
    float dc = sr_vec3_length(sr_vec3_sub(centre, eye));
    *far_z = (dc + radius) * 1.01f;
    /* Never closer than 1/1000 of far: depth precision stays usable when
     * the eye is inside the sphere. */
    *near_z = fmaxf(dc - radius, *far_z * 1e-3f) * 0.99f;
}

sr_mat4 framing_upright(int axis)
{
    /* The images of the model's x, y and z axes (the matrix's first three
     * columns), exact: each a signed unit vector.  The view faces +z, so
     * +z up turns the model's -y (its front in Z-up tools) towards the
     * viewer, and the flips of x and y keep the front facing it. */
    static const float columns[6][3][3] = {
        { { 0, 1, 0 }, { -1, 0, 0 }, { 0, 0, 1 } },   /* +x up */
        { { 0, -1, 0 }, { 1, 0, 0 }, { 0, 0, 1 } },   /* -x up */
        { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },    /* +y up */
        { { -1, 0, 0 }, { 0, -1, 0 }, { 0, 0, 1 } },  /* -y up */
        { { 1, 0, 0 }, { 0, 0, -1 }, { 0, 1, 0 } },   /* +z up */
        { { 1, 0, 0 }, { 0, 0, 1 }, { 0, -1, 0 } },   /* -z up */
    };
    sr_mat4 m = sr_mat4_identity();
    for (int c = 0; c < 3; c++) {
        for (int r = 0; r < 3; r++) {
            m.m[c * 4 + r] = columns[axis][c][r];
        }
    }
    return m;
}
