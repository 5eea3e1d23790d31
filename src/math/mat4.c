/* mat4.c - 4x4 matrices, column-major (m[col*4 + row]), and the model
 * transforms M_O: translate, scale, rotate about an axis (math stage). */
#include "softrast.h"

#include <math.h>
#include <string.h>

#define M(mat, row, col) ((mat).m[(col) * 4 + (row)])

sr_mat4 sr_mat4_identity(void)
{
    sr_mat4 r = {{ 0 }};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0f;
    return r;
}

/* A NULL matrix argument is the identity, as a NULL sr_draw_desc.model is. */
static const sr_mat4 identity = { { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 } };

sr_mat4 sr_mat4_mul(const sr_mat4 *a, const sr_mat4 *b)
{
    a = a ? a : &identity;
    b = b ? b : &identity;
    sr_mat4 r;
    for (int col = 0; col < 4; col++) {
        for (int row = 0; row < 4; row++) {
            /* Accumulate in double: composing many transforms stays stable. */
            double s = 0.0;
            for (int k = 0; k < 4; k++) {
                s += (double)M(*a, row, k) * (double)M(*b, k, col);
            }
            M(r, row, col) = (float)s;
        }
    }
    return r;
}

sr_vec4 sr_mat4_mul_vec4(const sr_mat4 *m, sr_vec4 v)
{
    const float *a = m ? m->m : identity.m;
    return (sr_vec4){
        a[0] * v.x + a[4] * v.y + a[8] * v.z + a[12] * v.w,
        a[1] * v.x + a[5] * v.y + a[9] * v.z + a[13] * v.w,
        a[2] * v.x + a[6] * v.y + a[10] * v.z + a[14] * v.w,
        a[3] * v.x + a[7] * v.y + a[11] * v.z + a[15] * v.w,
    };
}

sr_mat4 sr_mat4_transpose(const sr_mat4 *m)
{
    m = m ? m : &identity;
    sr_mat4 r;
    for (int row = 0; row < 4; row++) {
        for (int col = 0; col < 4; col++) {
            M(r, row, col) = M(*m, col, row);
        }
    }
    return r;
}

/* Cofactor expansion in double; singular when the determinant vanishes
 * relative to the matrix's scale. */
bool sr_mat4_invert(const sr_mat4 *src, sr_mat4 *out)
{
    if (!out) {
        return false;
    }
    src = src ? src : &identity;
    double a[16], inv[16];
    for (int i = 0; i < 16; i++) {
        a[i] = src->m[i];
    }
    inv[0] = a[5] * a[10] * a[15] - a[5] * a[11] * a[14] - a[9] * a[6] * a[15]
           + a[9] * a[7] * a[14] + a[13] * a[6] * a[11] - a[13] * a[7] * a[10];
    inv[4] = -a[4] * a[10] * a[15] + a[4] * a[11] * a[14] + a[8] * a[6] * a[15]
           - a[8] * a[7] * a[14] - a[12] * a[6] * a[11] + a[12] * a[7] * a[10];
    inv[8] = a[4] * a[9] * a[15] - a[4] * a[11] * a[13] - a[8] * a[5] * a[15]
           + a[8] * a[7] * a[13] + a[12] * a[5] * a[11] - a[12] * a[7] * a[9];
    inv[12] = -a[4] * a[9] * a[14] + a[4] * a[10] * a[13] + a[8] * a[5] * a[14]
            - a[8] * a[6] * a[13] - a[12] * a[5] * a[10] + a[12] * a[6] * a[9];
    inv[1] = -a[1] * a[10] * a[15] + a[1] * a[11] * a[14] + a[9] * a[2] * a[15]
           - a[9] * a[3] * a[14] - a[13] * a[2] * a[11] + a[13] * a[3] * a[10];
    inv[5] = a[0] * a[10] * a[15] - a[0] * a[11] * a[14] - a[8] * a[2] * a[15]
           + a[8] * a[3] * a[14] + a[12] * a[2] * a[11] - a[12] * a[3] * a[10];
    inv[9] = -a[0] * a[9] * a[15] + a[0] * a[11] * a[13] + a[8] * a[1] * a[15]
           - a[8] * a[3] * a[13] - a[12] * a[1] * a[11] + a[12] * a[3] * a[9];
    inv[13] = a[0] * a[9] * a[14] - a[0] * a[10] * a[13] - a[8] * a[1] * a[14]
            + a[8] * a[2] * a[13] + a[12] * a[1] * a[10] - a[12] * a[2] * a[9];
    inv[2] = a[1] * a[6] * a[15] - a[1] * a[7] * a[14] - a[5] * a[2] * a[15]
           + a[5] * a[3] * a[14] + a[13] * a[2] * a[7] - a[13] * a[3] * a[6];
    inv[6] = -a[0] * a[6] * a[15] + a[0] * a[7] * a[14] + a[4] * a[2] * a[15]
           - a[4] * a[3] * a[14] - a[12] * a[2] * a[7] + a[12] * a[3] * a[6];
    inv[10] = a[0] * a[5] * a[15] - a[0] * a[7] * a[13] - a[4] * a[1] * a[15]
            + a[4] * a[3] * a[13] + a[12] * a[1] * a[7] - a[12] * a[3] * a[5];
    inv[14] = -a[0] * a[5] * a[14] + a[0] * a[6] * a[13] + a[4] * a[1] * a[14]
            - a[4] * a[2] * a[13] - a[12] * a[1] * a[6] + a[12] * a[2] * a[5];
    inv[3] = -a[1] * a[6] * a[11] + a[1] * a[7] * a[10] + a[5] * a[2] * a[11]
           - a[5] * a[3] * a[10] - a[9] * a[2] * a[7] + a[9] * a[3] * a[6];
    inv[7] = a[0] * a[6] * a[11] - a[0] * a[7] * a[10] - a[4] * a[2] * a[11]
           + a[4] * a[3] * a[10] + a[8] * a[2] * a[7] - a[8] * a[3] * a[6];
    inv[11] = -a[0] * a[5] * a[11] + a[0] * a[7] * a[9] + a[4] * a[1] * a[11]
            - a[4] * a[3] * a[9] - a[8] * a[1] * a[7] + a[8] * a[3] * a[5];
    inv[15] = a[0] * a[5] * a[10] - a[0] * a[6] * a[9] - a[4] * a[1] * a[10]
            + a[4] * a[2] * a[9] + a[8] * a[1] * a[6] - a[8] * a[2] * a[5];

    double det = a[0] * inv[0] + a[1] * inv[4] + a[2] * inv[8] + a[3] * inv[12];
    double scale = 0.0;
    for (int i = 0; i < 16; i++) {
        scale = fmax(scale, fabs(a[i]));
    }
    *out = sr_mat4_identity();
    if (!(fabs(det) > 1e-30 * scale * scale * scale * scale) || !isfinite(det)) {
        return false;
    }
    for (int i = 0; i < 16; i++) {
        out->m[i] = (float)(inv[i] / det);
    }
    return true;
}

sr_mat4 sr_mat4_translate(float x, float y, float z)
{
    sr_mat4 r = sr_mat4_identity();
    r.m[12] = x;
    r.m[13] = y;
    r.m[14] = z;
    return r;
}

sr_mat4 sr_mat4_scale(float x, float y, float z)
{
    sr_mat4 r = sr_mat4_identity();
    r.m[0] = x;
    r.m[5] = y;
    r.m[10] = z;
    return r;
}

/* Rodrigues' rotation about a unit axis; a zero axis gives the identity. */
sr_mat4 sr_mat4_rotate(float angle, sr_vec3 axis)
{
    sr_vec3 a = sr_vec3_normalize(axis);
    if (a.x == 0.0f && a.y == 0.0f && a.z == 0.0f) {
        return sr_mat4_identity();
    }
    double c = cos(angle), s = sin(angle), t = 1.0 - c;
    double x = a.x, y = a.y, z = a.z;
    sr_mat4 r = sr_mat4_identity();
    M(r, 0, 0) = (float)(t * x * x + c);
    M(r, 0, 1) = (float)(t * x * y - s * z);
    M(r, 0, 2) = (float)(t * x * z + s * y);
    M(r, 1, 0) = (float)(t * x * y + s * z);
    M(r, 1, 1) = (float)(t * y * y + c);
    M(r, 1, 2) = (float)(t * y * z - s * x);
    M(r, 2, 0) = (float)(t * x * z - s * y);
    M(r, 2, 1) = (float)(t * y * z + s * x);
    M(r, 2, 2) = (float)(t * z * z + c);
    return r;
}
