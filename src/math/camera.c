/* camera.c - viewing: the camera frame (u, v, w) and E = M_cam^-1, the
 * projections P, the viewport matrix S, the normal matrix and aspect-ratio
 * helpers (math stage; any thread). */
#include "softrast.h"

#include <math.h>

#define M(mat, row, col) ((mat).m[(col) * 4 + (row)])

bool sr_camera_frame(sr_vec3 e, sr_vec3 g, sr_vec3 t, sr_camera_basis *out)
{
    float glen = sr_vec3_length(g);
    if (!(glen > 0.0f) || !out) {
        return false;
    }
    sr_vec3 w = sr_vec3_scale(g, -1.0f / glen);          /* w = -g/|g| */
    sr_vec3 txw = sr_vec3_cross(t, w);
    float len = sr_vec3_length(txw);
    if (!(len > 1e-12f * sr_vec3_length(t))) {
        return false;                                    /* up parallel to gaze */
    }
    sr_vec3 u = sr_vec3_scale(txw, 1.0f / len);          /* u = t x w / |t x w| */
    sr_vec3 v = sr_vec3_cross(w, u);                     /* v = w x u */
    *out = (sr_camera_basis){ u, v, w, e };
    return true;
}

/* M_cam = [u v w e; 0 0 0 1] is a rotation then a translation, so its
 * inverse is the transposed rotation with the translation rotated into the
 * frame: rows u, v, w and the column (-u.e, -v.e, -w.e). */
sr_mat4 sr_camera_matrix(const sr_camera_basis *b)
{
    sr_mat4 r = sr_mat4_identity();
    if (!b) {
        return r;   /* NULL: the identity, as for every matrix argument */
    }
    const sr_vec3 axes[3] = { b->u, b->v, b->w };
    for (int row = 0; row < 3; row++) {
        M(r, row, 0) = axes[row].x;
        M(r, row, 1) = axes[row].y;
        M(r, row, 2) = axes[row].z;
        M(r, row, 3) = -sr_vec3_dot(axes[row], b->e);
    }
    return r;
}

sr_mat4 sr_look_at(sr_vec3 eye, sr_vec3 target, sr_vec3 up)
{
    sr_camera_basis b;
    if (!sr_camera_frame(eye, sr_vec3_sub(target, eye), up, &b)) {
        /* Degenerate request: keep the position, look down -z. */
        b = (sr_camera_basis){ { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, eye };
    }
    return sr_camera_matrix(&b);
}

sr_mat4 sr_ortho(float l, float r, float b, float t, float n, float f, bool zero_to_one)
{
    sr_mat4 m = sr_mat4_identity();
    M(m, 0, 0) = 2.0f / (r - l);
    M(m, 1, 1) = 2.0f / (t - b);
    M(m, 0, 3) = -(r + l) / (r - l);
    M(m, 1, 3) = -(t + b) / (t - b);
    if (zero_to_one) {
        M(m, 2, 2) = -1.0f / (f - n);
        M(m, 2, 3) = -n / (f - n);
    } else {
        M(m, 2, 2) = -2.0f / (f - n);
        M(m, 2, 3) = -(f + n) / (f - n);
    }
    return m;
}

sr_mat4 sr_frustum(float l, float r, float b, float t, float n, float f, bool zero_to_one)
{
    sr_mat4 m = {{ 0 }};
    M(m, 0, 0) = 2.0f * n / (r - l);
    M(m, 1, 1) = 2.0f * n / (t - b);
    M(m, 0, 2) = (r + l) / (r - l);
    M(m, 1, 2) = (t + b) / (t - b);
    M(m, 3, 2) = -1.0f;
    if (zero_to_one) {
        M(m, 2, 2) = -f / (f - n);
        M(m, 2, 3) = -f * n / (f - n);
    } else {
        M(m, 2, 2) = -(f + n) / (f - n);
        M(m, 2, 3) = -2.0f * f * n / (f - n);
    }
    return m;
}

sr_mat4 sr_perspective(float fovy, float aspect, float n, float f, bool zero_to_one)
{
    float t = n * tanf(fovy * 0.5f);
    float r = t * aspect;
    return sr_frustum(-r, r, -t, t, n, f, zero_to_one);
}

/* Deriving the x and y fields of view from the viewport: the field of
 * view is wanted across the smaller dimension; in a tall viewport the
 * vertical one must grow so the horizontal one keeps the requested angle. */
float sr_fit_fovy(float fov, int width, int height)
{
    if (width <= 0 || height <= 0 || width >= height) {
        return fov;
    }
    double aspect = (double)width / height;
    return (float)(2.0 * atan(tan(fov * 0.5) / aspect));
}

sr_mat4 sr_viewport_matrix(float x0, float y0, float width, float height,
                           float dn, float df, bool zero_to_one)
{
    sr_mat4 s = sr_mat4_identity();
    M(s, 0, 0) = width * 0.5f;
    M(s, 0, 3) = x0 + width * 0.5f;
    M(s, 1, 1) = -height * 0.5f;            /* y down: NDC +1 is the top row */
    M(s, 1, 3) = y0 + height * 0.5f;
    if (zero_to_one) {
        M(s, 2, 2) = df - dn;
        M(s, 2, 3) = dn;
    } else {
        M(s, 2, 2) = (df - dn) * 0.5f;
        M(s, 2, 3) = (df + dn) * 0.5f;
    }
    return s;
}

bool sr_normal_matrix(const sr_mat4 *mv, sr_mat4 *out)
{
    if (!out) {
        return false;
    }
    sr_mat4 upper = sr_mat4_identity();
    if (!mv) {
        *out = upper;
        return true;
    }
    for (int c = 0; c < 3; c++) {
        for (int r = 0; r < 3; r++) {
            M(upper, r, c) = M(*mv, r, c);
        }
    }
    sr_mat4 inv;
    if (!sr_mat4_invert(&upper, &inv)) {
        *out = sr_mat4_identity();
        return false;
    }
    *out = sr_mat4_transpose(&inv);
    return true;
}
