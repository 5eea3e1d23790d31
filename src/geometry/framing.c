/* framing.c - geometry stage, before drawing: the default camera of a
 * model (softrast render's, the Python package's), fitted to its vertices.
 * Consumes positions and model matrices; produces an eye, a target and a
 * field of view.  Any thread, on its own context. */
#include "softrast.h"

#include "context.h"

#include <math.h>
#include <string.h>

#define PI_F 3.14159265358979f

sr_vec3 sr_framing_direction(void)
{
    return sr_vec3_normalize((sr_vec3){ 0.62f, 0.48f, 1.0f });
}

static double component(sr_vec3 a, int k)
{
    return k == 0 ? a.x : k == 1 ? a.y : a.z;
}

/* The rows of basis x model: a set's vertices straight into the camera
 * basis (u, v, w: across, up, and towards the eye). */
typedef struct to_camera {
    double row[3][4];
} to_camera;

static to_camera camera_rows(const sr_framing_points *set, const sr_camera_basis *b)
{
    const sr_mat4 identity = sr_mat4_identity();
    const float *a = set->model ? set->model->m : identity.m;
    const sr_vec3 axes[3] = { b->u, b->v, b->w };
    to_camera t;
    for (int k = 0; k < 3; k++) {
        for (int c = 0; c < 4; c++) {
            t.row[k][c] = (double)axes[k].x * a[c * 4] + (double)axes[k].y * a[c * 4 + 1] +
                          (double)axes[k].z * a[c * 4 + 2];
        }
    }
    return t;
}

static void apply(const to_camera *t, const float *p, double q[3])
{
    for (int k = 0; k < 3; k++) {
        q[k] = t->row[k][0] * p[0] + t->row[k][1] * p[1] + t->row[k][2] * p[2] + t->row[k][3];
    }
}

/* With the eye at depth ez in the camera basis, the offset along axis k
 * (0: u, 1: v) that centres the points' perspective projections on that
 * axis.  Each step places the eye exactly between the two points that
 * project farthest out, then looks again for those points; it stops when
 * they no longer change. */
static double centre_offset(const sr_framing_points *sets, int set_count, const sr_camera_basis *b,
                            int k, double ez, double start)
{
    double e = start;
    for (int step = 0; step < 16; step++) {
        double hi = -INFINITY, lo = INFINITY, hi_q[3] = { 0 }, lo_q[3] = { 0 };
        for (int s = 0; s < set_count; s++) {
            to_camera rows = camera_rows(&sets[s], b);
            for (size_t i = 0; i < sets[s].count; i++) {
                double q[3];
                apply(&rows, &sets[s].positions[i * 3], q);
                double t = (q[k] - e) / (ez - q[2]);
                if (t > hi) {
                    hi = t;
                    memcpy(hi_q, q, sizeof q);
                }
                if (t < lo) {
                    lo = t;
                    memcpy(lo_q, q, sizeof q);
                }
            }
        }
        /* (hi_q[k] - e) / d_hi = -(lo_q[k] - e) / d_lo, solved for e. */
        double d_hi = ez - hi_q[2], d_lo = ez - lo_q[2];
        double next = (hi_q[k] * d_lo + lo_q[k] * d_hi) / (d_hi + d_lo);
        if (next == e || !isfinite(next)) {
            break;
        }
        e = next;
    }
    return e;
}

typedef struct fit_view {
    sr_vec3 eye, target;
    float half_w, half_h;
} fit_view;

/* The view sr_fit_camera describes, the target the point of the gaze
 * nearest `centre`; false when the points give no frame. */
static bool fit(const sr_framing_points *sets, int set_count, sr_vec3 centre, float fov_radians,
                int width, int height, bool ortho, fit_view *out)
{
    /* The tangents of the half fields of view sr_perspective makes. */
    float tan_y = tanf(sr_fit_fovy(fov_radians, width, height) * 0.5f);
    float tan_x = tan_y * ((float)width / (float)height);
    sr_vec3 dir = sr_framing_direction();
    sr_camera_basis b;
    if (!sr_camera_frame((sr_vec3){ 0, 0, 0 }, sr_vec3_scale(dir, -1.0f), (sr_vec3){ 0, 1, 0 },
                         &b)) {
        return false;
    }
    /* The eye at (ex, ey, ez) in the basis sees a point q inside the
     * narrowed field when |q_x - ex| <= tx (ez - q_z): for every q,
     * ex + tx ez >= q_x + tx q_z and tx ez - ex >= tx q_z - q_x.  The
     * least ez meets the largest of each with equality. */
    double fill = 1.0 - 2.0 * SR_FRAMING_MARGIN;
    double t[2] = { (double)tan_x * fill, (double)tan_y * fill };
    double plus[2] = { -INFINITY, -INFINITY }, minus[2] = { -INFINITY, -INFINITY };
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int s = 0; s < set_count; s++) {
        to_camera rows = camera_rows(&sets[s], &b);
        for (size_t i = 0; i < sets[s].count; i++) {
            double q[3];
            apply(&rows, &sets[s].positions[i * 3], q);
            /* Comparisons, which skip a NaN as fmin/fmax do: GCC 12 for
             * aarch64 crashes vectorizing an fmin/fmax reduction. */
            for (int k = 0; k < 2; k++) {
                double p = q[k] + t[k] * q[2], m = t[k] * q[2] - q[k];
                plus[k] = p > plus[k] ? p : plus[k];
                minus[k] = m > minus[k] ? m : minus[k];
            }
            for (int k = 0; k < 3; k++) {
                lo[k] = q[k] < lo[k] ? q[k] : lo[k];
                hi[k] = q[k] > hi[k] ? q[k] : hi[k];
            }
        }
    }
    double ez_k[2] = { (plus[0] + minus[0]) / (2.0 * t[0]), (plus[1] + minus[1]) / (2.0 * t[1]) };
    int limit = ez_k[0] >= ez_k[1] ? 0 : 1;
    double ez = ez_k[limit], e[2];
    if (ortho) {
        /* Half extents that hold the points in the limiting dimension,
         * the aspect's in the other. */
        double need[2] = { (hi[0] - lo[0]) / (2.0 * fill), (hi[1] - lo[1]) / (2.0 * fill) };
        double aspect = (double)tan_x / tan_y;
        double hh = fmax(need[1], need[0] / aspect);
        out->half_w = (float)(hh * aspect);
        out->half_h = (float)hh;
        e[0] = (lo[0] + hi[0]) / 2.0;
        e[1] = (lo[1] + hi[1]) / 2.0;
        /* The eye stays at the perspective fit's distance: the depth range
         * is that of the same view. */
        if (!(hh > 0.0) || !isfinite(hh)) {
            return false;
        }
    } else {
        e[limit] = (plus[limit] - minus[limit]) / 2.0;
        int other = 1 - limit;
        e[other] = centre_offset(sets, set_count, &b, other, ez,
                                 (plus[other] - minus[other]) / 2.0);
    }
    if (!isfinite(ez) || !isfinite(e[0]) || !isfinite(e[1]) || !(ez > lo[2]) ||
        !(hi[0] > lo[0] || hi[1] > lo[1])) {
        return false;
    }
    /* The eye back in world space, and the target: the point of the gaze
     * (-w) nearest the centre. */
    double pos[3] = { e[0], e[1], ez }, eye[3], w[3] = { b.w.x, b.w.y, b.w.z };
    double c[3] = { centre.x, centre.y, centre.z }, along = 0.0;
    for (int k = 0; k < 3; k++) {
        eye[k] = pos[0] * component(b.u, k) + pos[1] * component(b.v, k) + pos[2] * w[k];
    }
    for (int k = 0; k < 3; k++) {
        along -= (c[k] - eye[k]) * w[k];
    }
    out->eye = (sr_vec3){ (float)eye[0], (float)eye[1], (float)eye[2] };
    out->target = (sr_vec3){ (float)(eye[0] - along * w[0]), (float)(eye[1] - along * w[1]),
                             (float)(eye[2] - along * w[2]) };
    return along > 0.0;
}


/* The centre of the points' world box, as softrast render's bounding
 * sphere has it: each vertex placed by its model matrix in float (as
 * sr_mat4_mul_vec4 computes it, w = 1), NaN skipped, the midpoint in
 * double rounded to float; false when no point is finite. */
static bool box_centre(const sr_framing_points *sets, int set_count, sr_vec3 *centre)
{
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    const sr_mat4 identity = sr_mat4_identity();
    for (int s = 0; s < set_count; s++) {
        const float *a = sets[s].model ? sets[s].model->m : identity.m;
        for (size_t i = 0; i < sets[s].count; i++) {
            const float *p = &sets[s].positions[i * 3];
            for (int k = 0; k < 3; k++) {
                double q = a[k] * p[0] + a[4 + k] * p[1] + a[8 + k] * p[2] + a[12 + k] * 1.0f;
                lo[k] = q < lo[k] ? q : lo[k];
                hi[k] = q > hi[k] ? q : hi[k];
            }
        }
    }
    double c[3] = { (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2 };
    *centre = (sr_vec3){ (float)c[0], (float)c[1], (float)c[2] };
    return isfinite(c[0]) && isfinite(c[1]) && isfinite(c[2]);
}

static sr_result validate(sr_context *ctx, const sr_framing_desc *d)
{
    if (!d->sets || d->set_count < 1) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_framing_desc.sets must not be NULL and set_count must be >= 1");
    }
    for (int s = 0; s < d->set_count; s++) {
        const sr_framing_points *set = &d->sets[s];
        if (set->count && !set->positions) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_framing_desc.sets[%d].positions is NULL", s);
        }
        for (int i = 0; set->model && i < 16; i++) {
            if (!isfinite(set->model->m[i])) {
                return sr__fail(ctx, SR_INVALID_ARG,
                                "sr_framing_desc.sets[%d].model must be finite", s);
            }
        }
    }
    if (d->width < 1 || d->width > SR_MAX_FRAMEBUFFER_SIZE || d->height < 1 ||
        d->height > SR_MAX_FRAMEBUFFER_SIZE) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_framing_desc.width and height must be 1 .. %d (got %d x %d)",
                        SR_MAX_FRAMEBUFFER_SIZE, d->width, d->height);
    }
    if (d->fov != 0.0f && !(d->fov > 0.0f && d->fov < PI_F)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_framing_desc.fov must be 0 or in (0, pi) radians (got %g)", d->fov);
    }
    return SR_OK;
}

sr_result sr_fit_camera(sr_context *ctx, const sr_framing_desc *desc, sr_framing_info *out)
{
    if (!desc || !out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_fit_camera: desc and out must not be NULL");
    }
    memset(out, 0, sizeof *out);
    sr_result r = validate(ctx, desc);
    if (r != SR_OK) {
        return r;
    }
    float fov = desc->fov != 0.0f ? desc->fov : SR_FRAMING_FOV_DEG * PI_F / 180.0f;
    sr_vec3 centre;
    fit_view v;
    if (!box_centre(desc->sets, desc->set_count, &centre) ||
        !fit(desc->sets, desc->set_count, centre, fov, desc->width, desc->height, desc->ortho,
             &v)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_fit_camera: the points give no frame (none, all in one point, not "
                        "finite, or beyond the range of float)");
    }
    *out = (sr_framing_info){ .eye = v.eye, .target = v.target, .up = { 0, 1, 0 },
                              .fovy = sr_fit_fovy(fov, desc->width, desc->height),
                              .half_width = desc->ortho ? v.half_w : 0.0f,
                              .half_height = desc->ortho ? v.half_h : 0.0f, .centre = centre };
    return SR_OK;
}
