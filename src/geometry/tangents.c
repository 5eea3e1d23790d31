/*
 * tangents.c - geometry stage, before the vertex stage: per-vertex
 * tangents for tangent-space normal maps, with MikkTSpace's conventions
 * (the frame normal maps are baked in by most tools).  Consumes a mesh
 * with normals and texcoords; writes 4 floats a vertex into the caller's
 * array.  Any thread may call it on its own mesh.
 */
#include "softrast.h"

#include "context.h"

#include <math.h>
#include <string.h>

static void add3(double *acc, const double v[3], double w)
{
    acc[0] += v[0] * w;
    acc[1] += v[1] * w;
    acc[2] += v[2] * w;
}

/* Triangle i's dP/du and dP/dv, from two edges and their texcoord steps:
 * e1 = T du1 + B dv1, e2 = T du2 + B dv2 solved for T and B.  False when
 * its texcoords are degenerate. */
static bool triangle_frame(const sr_mesh *m, const uint32_t *idx, double t[3], double b[3])
{
    const float *p0 = &m->positions[3 * idx[0]], *p1 = &m->positions[3 * idx[1]];
    const float *p2 = &m->positions[3 * idx[2]];
    const float *w0 = &m->texcoords[2 * idx[0]], *w1 = &m->texcoords[2 * idx[1]];
    const float *w2 = &m->texcoords[2 * idx[2]];
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)p1[k] - p0[k];
        e2[k] = (double)p2[k] - p0[k];
    }
    double du1 = (double)w1[0] - w0[0], dv1 = (double)w1[1] - w0[1];
    double du2 = (double)w2[0] - w0[0], dv2 = (double)w2[1] - w0[1];
    double det = du1 * dv2 - du2 * dv1;
    if (!(fabs(det) > 1e-20) || !isfinite(det)) {
        return false;
    }
    for (int k = 0; k < 3; k++) {
        t[k] = (e1[k] * dv2 - e2[k] * dv1) / det;
        b[k] = (e2[k] * du1 - e1[k] * du2) / det;
    }
    return true;
}

/* Any unit vector orthogonal to n. */
static void orthogonal(const double n[3], double out[3])
{
    double a[3] = { fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0 };
    double d = a[0] * n[0] + a[1] * n[1];
    double l = 0.0;
    for (int k = 0; k < 3; k++) {
        out[k] = a[k] - n[k] * d;
        l += out[k] * out[k];
    }
    l = l > 0.0 ? 1.0 / sqrt(l) : 0.0;
    for (int k = 0; k < 3; k++) {
        out[k] *= l;
    }
}

sr_result sr_mesh_compute_tangents(sr_context *ctx, const sr_mesh *mesh, float *tangents)
{
    static const char fn[] = "sr_mesh_compute_tangents";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_mesh_compute_tangents: ctx is NULL");
    }
    if (!mesh || !tangents) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn, mesh ? "tangents" : "mesh");
    }
    if (!mesh->positions || !mesh->normals || !mesh->texcoords ||
        (mesh->triangle_count && !mesh->indices)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: the mesh needs positions, normals, texcoords%s",
                        fn, mesh->triangle_count ? " and indices" : "");
    }
    size_t nv = mesh->vertex_count;
    for (size_t i = 0; i < 3 * mesh->triangle_count; i++) {
        if (mesh->indices[i] >= nv) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: index %zu is %u, past vertex_count %zu", fn,
                            i, mesh->indices[i], nv);
        }
    }
    if (nv > SIZE_MAX / (6 * sizeof(double))) {
        return sr__fail(ctx, SR_TOO_LARGE, "%s: vertex_count %zu is too large", fn, nv);
    }
    double *acc = sr__calloc(ctx, nv ? nv : 1, 6 * sizeof(double));   /* T and B sums */
    if (!acc) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: out of memory", fn);
    }
    for (size_t f = 0; f < mesh->triangle_count; f++) {
        const uint32_t *idx = &mesh->indices[3 * f];
        double t[3], b[3];
        if (!triangle_frame(mesh, idx, t, b)) {
            continue;
        }
        /* Weighted by the triangle's angle at each corner, as MikkTSpace
         * does, so a vertex's tangent does not depend on how its fan is
         * split into triangles. */
        for (int c = 0; c < 3; c++) {
            const float *p = &mesh->positions[3 * idx[c]];
            const float *pa = &mesh->positions[3 * idx[(c + 1) % 3]];
            const float *pb = &mesh->positions[3 * idx[(c + 2) % 3]];
            double ea[3], eb[3], la = 0, lb = 0, d = 0;
            for (int k = 0; k < 3; k++) {
                ea[k] = (double)pa[k] - p[k];
                eb[k] = (double)pb[k] - p[k];
                la += ea[k] * ea[k];
                lb += eb[k] * eb[k];
                d += ea[k] * eb[k];
            }
            double cosv = la > 0 && lb > 0 ? d / sqrt(la * lb) : 1.0;
            double angle = acos(cosv < -1.0 ? -1.0 : cosv > 1.0 ? 1.0 : cosv);
            add3(&acc[6 * idx[c]], t, angle);
            add3(&acc[6 * idx[c] + 3], b, angle);
        }
    }
    for (size_t v = 0; v < nv; v++) {
        const float *nf = &mesh->normals[3 * v];
        double n[3] = { nf[0], nf[1], nf[2] };
        double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3 && nl > 0; k++) {
            n[k] /= nl;
        }
        const double *t = &acc[6 * v], *b = &acc[6 * v + 3];
        double nt = n[0] * t[0] + n[1] * t[1] + n[2] * t[2];
        double o[3], l = 0;
        for (int k = 0; k < 3; k++) {
            o[k] = t[k] - n[k] * nt;
            l += o[k] * o[k];
        }
        if (l > 1e-30 && isfinite(l)) {
            l = 1.0 / sqrt(l);
            for (int k = 0; k < 3; k++) {
                o[k] *= l;
            }
        } else {
            orthogonal(n, o);
        }
        double c[3] = { n[1] * o[2] - n[2] * o[1], n[2] * o[0] - n[0] * o[2],
                        n[0] * o[1] - n[1] * o[0] };
        float *out = &tangents[4 * v];
        out[0] = (float)o[0];
        out[1] = (float)o[1];
        out[2] = (float)o[2];
        out[3] = c[0] * b[0] + c[1] * b[1] + c[2] * b[2] < 0.0 ? -1.0f : 1.0f;
    }
    sr__free(ctx, acc);
    sr__ok(ctx);
    return SR_OK;
}
