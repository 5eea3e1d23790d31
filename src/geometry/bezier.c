/* bezier.c - geometry stage, built-in surfaces: bicubic Bezier patches to
 * triangles.  Consumes patches of 16 control points ([u][v] row-major, xyz);
 * produces an sr_mesh with (detail+1)^2 vertices (position, unit normal,
 * texcoord = (u, v)) and 2 detail^2 triangles per patch, allocated on the
 * caller's context.  Any thread may call it with a context of its own.
 *
 * Method: the incremental evaluation of polynomials ("forward
 * differencing").  A cubic F(t) = a t^3 + b t^2 + c t + d sampled at steps of
 * h has constant third difference D3 = 6 a h^3, so once F, its first
 * difference DF and its second difference D2F are known at t = 0, every next
 * sample costs three additions:
 *     F += DF;   DF += D2F;   D2F += D3F.
 * A bicubic patch P(u, v) = sum_ij B_i(u) B_j(v) cp_ij is stepped this way in
 * two levels.  Each of the four columns of the control net, C_j(u) =
 * sum_i B_i(u) cp_ij, is a cubic in u; stepping them gives, at every u_i, the
 * four control points of the cubic curve v -> P(u_i, v), which is then
 * stepped along v.  The partial derivatives come the same way from their
 * own polynomials: dP/du uses the columns' derivatives (quadratics, whose
 * third difference is zero) as the control points of a cubic in v, and
 * dP/dv is the derivative of the row curve, a quadratic in v with control
 * points 3 (Q_{k+1} - Q_k).  The normal is dP/du x dP/dv, normalized.
 */
#include "softrast.h"
#include "geometry/bezier.h"
#include "context.h"
#include "math/dvec3.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* 257^2 vertices per patch keeps a whole teapot (32 patches) near 2.1 M
 * vertices; more than that is a mistake rather than a wish for quality. */
#define MAX_DETAIL 256

/* ---- direct evaluation (the reference) --------------------------------- */

/* Cubic Bernstein basis and its derivative at t. */
static void bernstein3(double t, double b[4], double db[4])
{
    double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
    db[0] = -3.0 * s * s;
    db[1] = 3.0 * s * s - 6.0 * t * s;
    db[2] = 6.0 * t * s - 3.0 * t * t;
    db[3] = 3.0 * t * t;
}

static void eval_direct(const float cp[16][3], double u, double v,
                        double pos[3], double du[3], double dv[3])
{
    double bu[4], dbu[4], bv[4], dbv[4];
    bernstein3(u, bu, dbu);
    bernstein3(v, bv, dbv);
    for (int k = 0; k < 3; k++) {
        pos[k] = du[k] = dv[k] = 0.0;
    }
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            const float *c = cp[4 * i + j];
            for (int k = 0; k < 3; k++) {
                pos[k] += bu[i] * bv[j] * c[k];
                du[k] += dbu[i] * bv[j] * c[k];
                dv[k] += bu[i] * dbv[j] * c[k];
            }
        }
    }
}

void sr__bezier_eval_direct(const float cp[16][3], float u, float v,
                            float pos[3], float du[3], float dv[3])
{
    double p[3], a[3], b[3];
    eval_direct(cp, u, v, p, a, b);
    for (int k = 0; k < 3; k++) {
        if (pos) {
            pos[k] = (float)p[k];
        }
        if (du) {
            du[k] = (float)a[k];
        }
        if (dv) {
            dv[k] = (float)b[k];
        }
    }
}

/* ---- forward differences ----------------------------------------------- */

/* A vector polynomial of degree <= 3 being stepped by forward differences.
 * Kept in double: after 256 steps the float version drifts by about 1e-5 of
 * the patch size, which would open hairline cracks between neighbouring
 * patches; double keeps the drift near 1e-13. */
typedef struct fwd_diff {
    double f[3];    /* F(t) */
    double d1[3];   /* DF(t)  = F(t + h) - F(t) */
    double d2[3];   /* D2F(t) = DF(t + h) - DF(t) */
    double d3[3];   /* D3F, constant: 6 a h^3 (zero for a quadratic) */
} fwd_diff;

/* Start at t = 0 for F(t) = a t^3 + b t^2 + c t + d with step h:
 *   DF(0) = a h^3 + b h^2 + c h,  D2F(0) = 6 a h^3 + 2 b h^2,  D3F = 6 a h^3. */
static void fwd_diff_start(fwd_diff *s, const double a[3], const double b[3],
                           const double c[3], const double d[3], double h)
{
    double h2 = h * h;
    double h3 = h2 * h;
    for (int k = 0; k < 3; k++) {
        s->f[k] = d[k];
        s->d1[k] = a[k] * h3 + b[k] * h2 + c[k] * h;
        s->d2[k] = 6.0 * a[k] * h3 + 2.0 * b[k] * h2;
        s->d3[k] = 6.0 * a[k] * h3;
    }
}

/* The N-order forward difference update, for N = 3. */
static void fwd_diff_step(fwd_diff *s)
{
    for (int k = 0; k < 3; k++) {
        s->f[k] += s->d1[k];
        s->d1[k] += s->d2[k];
        s->d2[k] += s->d3[k];
    }
}

/* Cubic Bezier p0..p3 in power form: a = -p0 + 3p1 - 3p2 + p3,
 * b = 3p0 - 6p1 + 3p2, c = 3(p1 - p0), d = p0. */
static void start_cubic(fwd_diff *s, const double p[4][3], double h)
{
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
        a[k] = -p[0][k] + 3.0 * p[1][k] - 3.0 * p[2][k] + p[3][k];
        b[k] = 3.0 * p[0][k] - 6.0 * p[1][k] + 3.0 * p[2][k];
        c[k] = 3.0 * (p[1][k] - p[0][k]);
    }
    fwd_diff_start(s, a, b, c, p[0], h);
}

/* Quadratic Bezier q0..q2 in power form: b = q0 - 2q1 + q2, c = 2(q1 - q0),
 * d = q0 (and no cubic term, so D3F = 0). */
static void start_quadratic(fwd_diff *s, const double q[3][3], double h)
{
    static const double zero[3] = { 0.0, 0.0, 0.0 };
    double b[3], c[3];
    for (int k = 0; k < 3; k++) {
        b[k] = q[0][k] - 2.0 * q[1][k] + q[2][k];
        c[k] = 2.0 * (q[1][k] - q[0][k]);
    }
    fwd_diff_start(s, zero, b, c, q[0], h);
}

/* ---- normals ------------------------------------------------------------ */

/* Normalize du x dv into out; false when the tangents are (nearly)
 * parallel or zero, as on a collapsed patch edge, where the cross product
 * says nothing about the surface.  `extent2` is the squared size of the
 * control net, so tiny derivatives of a tiny patch still count. */
static bool normal_from_tangents(const double du[3], const double dv[3],
                                 double extent2, float out[3])
{
    double n[3];
    sr__dcross(du, dv, n);
    double n2 = sr__ddot(n, n);
    /* |du x dv| = |du| |dv| sin(angle): below 1e-7 the angle is noise. */
    if (n2 <= 1e-14 * sr__ddot(du, du) * sr__ddot(dv, dv) || n2 <= 1e-24 * extent2 * extent2) {
        return false;
    }
    double inv = 1.0 / sqrt(n2);
    for (int k = 0; k < 3; k++) {
        out[k] = (float)(n[k] * inv);
    }
    return true;
}

/* The normal at (u, v).  Where du x dv vanishes (the teapot's lid knob and
 * bottom come to a point: one whole edge of the control net collapses, so
 * dP/dv = 0 along it) the surface normal is the limit from inside the
 * patch: evaluate the derivatives a small parameter step towards the
 * interior.  At a smooth pole every vertex of the collapsed edge then gets
 * nearly the same normal (off by about the step times the curvature). */
static void patch_normal(const float cp[16][3], double u, double v,
                         const double du[3], const double dv[3],
                         double extent2, float out[3])
{
    if (normal_from_tangents(du, dv, extent2, out)) {
        return;
    }
    static const double nudges[] = { 1e-4, 1e-2 };
    for (size_t n = 0; n < sizeof nudges / sizeof nudges[0]; n++) {
        double un = u < 0.5 ? u + nudges[n] : u - nudges[n];
        double vn = v < 0.5 ? v + nudges[n] : v - nudges[n];
        double p[3], a[3], b[3];
        eval_direct(cp, un, vn, p, a, b);
        if (normal_from_tangents(a, b, extent2, out)) {
            return;
        }
    }
    /* A patch with no area near this point has no normal to give. */
    out[0] = out[1] = out[2] = 0.0f;
}

/* ---- one patch ---------------------------------------------------------- */

/* Writes (detail+1)^2 vertices, row i = u_i = i/detail, column j = v_j. */
static void tessellate_patch(const float cp[16][3], int detail,
                             float *pos, float *nrm, float *uv)
{
    const double h = 1.0 / detail;
    double P[4][4][3];
    double lo[3] = { INFINITY, INFINITY, INFINITY };
    double hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            for (int k = 0; k < 3; k++) {
                P[i][j][k] = cp[4 * i + j][k];
                lo[k] = fmin(lo[k], P[i][j][k]);
                hi[k] = fmax(hi[k], P[i][j][k]);
            }
        }
    }
    double extent[3] = { hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] };
    double extent2 = sr__ddot(extent, extent);

    /* Column j as a cubic in u, and its derivative, a quadratic in u whose
     * Bezier control points are 3 (cp_{i+1,j} - cp_ij). */
    fwd_diff col[4], dcol[4];
    for (int j = 0; j < 4; j++) {
        double c[4][3], dc[3][3];
        for (int i = 0; i < 4; i++) {
            memcpy(c[i], P[i][j], sizeof c[i]);
        }
        for (int i = 0; i < 3; i++) {
            for (int k = 0; k < 3; k++) {
                dc[i][k] = 3.0 * (P[i + 1][j][k] - P[i][j][k]);
            }
        }
        start_cubic(&col[j], c, h);
        start_quadratic(&dcol[j], dc, h);
    }

    size_t out_index = 0;
    for (int i = 0; i <= detail; i++) {
        /* q: control points of the row curve v -> P(u_i, v); r: those of
         * v -> dP/du(u_i, v).  The last row takes the exact end values
         * rather than the stepped ones, so that two patches sharing an
         * edge produce bit-identical vertices along it (the first row is
         * exact anyway: F(0) = d). */
        double q[4][3], r[4][3], dq[3][3];
        for (int j = 0; j < 4; j++) {
            for (int k = 0; k < 3; k++) {
                if (i == detail) {
                    q[j][k] = P[3][j][k];
                    r[j][k] = 3.0 * (P[3][j][k] - P[2][j][k]);
                } else {
                    q[j][k] = col[j].f[k];
                    r[j][k] = dcol[j].f[k];
                }
            }
        }
        for (int j = 0; j < 3; j++) {
            for (int k = 0; k < 3; k++) {
                dq[j][k] = 3.0 * (q[j + 1][k] - q[j][k]);
            }
        }
        fwd_diff row, row_du, row_dv;
        start_cubic(&row, q, h);
        start_cubic(&row_du, r, h);
        start_quadratic(&row_dv, dq, h);

        for (int j = 0; j <= detail; j++) {
            /* Same exact-end rule along v. */
            const double *p = j == detail ? q[3] : row.f;
            const double *du = j == detail ? r[3] : row_du.f;
            const double *dv = j == detail ? dq[2] : row_dv.f;
            double u = (double)i * h;
            double v = (double)j * h;
            for (int k = 0; k < 3; k++) {
                pos[3 * out_index + k] = (float)p[k];
            }
            patch_normal(cp, u, v, du, dv, extent2, &nrm[3 * out_index]);
            uv[2 * out_index + 0] = (float)u;
            uv[2 * out_index + 1] = (float)v;
            out_index++;
            fwd_diff_step(&row);
            fwd_diff_step(&row_du);
            fwd_diff_step(&row_dv);
        }
        for (int j = 0; j < 4; j++) {
            fwd_diff_step(&col[j]);
            fwd_diff_step(&dcol[j]);
        }
    }
}

/* ---- the mesh ----------------------------------------------------------- */

sr_result sr_make_bezier_mesh(sr_context *ctx, const float (*patches)[16][3],
                              size_t patch_count, int detail, sr_mesh *out)
{
    static const char fn[] = "sr_make_bezier_mesh";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_bezier_mesh: ctx is NULL");
    }
    if (!out) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out is NULL", fn);
    }
    memset(out, 0, sizeof *out);
    if (!patches || patch_count == 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: no patches given", fn);
    }
    if (detail < 1 || detail > MAX_DETAIL) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: detail %d is not in 1..%d", fn, detail,
                        MAX_DETAIL);
    }
    const size_t side = (size_t)detail + 1;
    const size_t verts_per_patch = side * side;
    const size_t tris_per_patch = 2 * (size_t)detail * (size_t)detail;
    /* Checked before a control point is read.  Indices are uint32; the largest array is 3 uint32 per triangle and
     * triangles < 2 * vertices, so bounding vertices by 2^32 / 8 keeps every
     * byte count below 2^32 (safe for a 32-bit size_t too). */
    if (patch_count > (UINT32_MAX / 8) / verts_per_patch) {
        return sr__fail(ctx, SR_TOO_LARGE, "%s: %zu patches at detail %d exceed 2^29 vertices",
                        fn, patch_count, detail);
    }

    for (size_t p = 0; p < patch_count; p++) {
        for (int c = 0; c < 16; c++) {
            for (int k = 0; k < 3; k++) {
                if (!isfinite(patches[p][c][k])) {
                    return sr__fail(ctx, SR_INVALID_ARG,
                                    "%s: control point %d of patch %zu is not finite", fn, c,
                                    p);
                }
            }
        }
    }

    const size_t vertex_count = patch_count * verts_per_patch;
    const size_t triangle_count = patch_count * tris_per_patch;

    float *positions = sr__alloc(ctx, vertex_count * 3 * sizeof(float));
    float *normals = sr__alloc(ctx, vertex_count * 3 * sizeof(float));
    float *texcoords = sr__alloc(ctx, vertex_count * 2 * sizeof(float));
    uint32_t *indices = sr__alloc(ctx, triangle_count * 3 * sizeof(uint32_t));
    if (!positions || !normals || !texcoords || !indices) {
        sr__free(ctx, positions);
        sr__free(ctx, normals);
        sr__free(ctx, texcoords);
        sr__free(ctx, indices);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory", fn);
    }

    uint32_t *ix = indices;
    for (size_t p = 0; p < patch_count; p++) {
        size_t base = p * verts_per_patch;
        tessellate_patch(patches[p], detail, positions + 3 * base,
                         normals + 3 * base, texcoords + 2 * base);
        /* Quad (i, j)-(i+1, j+1) as two triangles.  Going +u then +v turns
         * counter-clockwise about du x dv, so both are front faces on the
         * side the normal points to.  Where an edge of the net collapses
         * one of the two has zero area; it is kept so that every patch has
         * the same layout (the rasterizer drops zero-area triangles). */
        for (size_t i = 0; i < (size_t)detail; i++) {
            for (size_t j = 0; j < (size_t)detail; j++) {
                uint32_t a = (uint32_t)(base + i * side + j);
                uint32_t b = a + (uint32_t)side;  /* (i+1, j) */
                uint32_t c = b + 1;               /* (i+1, j+1) */
                uint32_t d = a + 1;               /* (i, j+1) */
                *ix++ = a; *ix++ = b; *ix++ = c;
                *ix++ = a; *ix++ = c; *ix++ = d;
            }
        }
    }

    out->vertex_count = vertex_count;
    out->positions = positions;
    out->normals = normals;
    out->texcoords = texcoords;
    out->triangle_count = triangle_count;
    out->indices = indices;
    sr__ok(ctx);
    return SR_OK;
}
