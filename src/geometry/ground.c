/* ground.c - geometry stage, before the vertex stage: a ground plane that
 * receives a scene's shadow (docs/shadows.md).  Consumes the scene's
 * world-space bounds; produces a two-triangle sr_mesh on the context.
 * Any thread, on its own context. */
#include "softrast.h"

#include "context.h"

#include <math.h>

static bool finite3(sr_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static sr_result validate(sr_context *ctx, const sr_ground_desc *d)
{
    if (!finite3(d->bounds_min) || !finite3(d->bounds_max)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_ground_desc.bounds_min and bounds_max must be finite");
    }
    if (d->bounds_min.x > d->bounds_max.x || d->bounds_min.y > d->bounds_max.y ||
        d->bounds_min.z > d->bounds_max.z) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_ground_desc.bounds_min must be <= bounds_max");
    }
    if (sr_vec3_length(d->bounds_max) > 1e18f || sr_vec3_length(d->bounds_min) > 1e18f) {
        return sr__fail(ctx, SR_TOO_LARGE, "sr_ground_desc bounds exceed 1e18");
    }
    if (!finite3(d->up) || !isfinite(sr_vec3_length(d->up))) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_ground_desc.up must be finite");
    }
    if (d->scale != 0.0f && !(d->scale >= 0.01f && d->scale <= 1000.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_ground_desc.scale must be 0 or 0.01 .. 1000 (got %g)",
                        d->scale);
    }
    if (!(d->drop >= 0.0f && d->drop <= 1.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_ground_desc.drop must be 0 .. 1 (got %g)", d->drop);
    }
    return SR_OK;
}

sr_result sr_make_ground_mesh(sr_context *ctx, const sr_ground_desc *desc, sr_mesh *out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_ground_mesh: ctx is NULL");
    }
    if (!desc || !out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_ground_mesh: desc and out must not be NULL");
    }
    sr_result r = validate(ctx, desc);
    if (r != SR_OK) {
        return r;
    }
    sr_vec3 up = sr_vec3_length(desc->up) > 0.0f ? sr_vec3_normalize(desc->up) : (sr_vec3){ 0, 1, 0 };
    /* t, b span the plane with t x b = up (so the corners below run
     * counter-clockwise seen from above); +Y up gives t = +X. */
    sr_vec3 axis = fabsf(up.z) < 0.9f ? (sr_vec3){ 0, 0, 1 } : (sr_vec3){ 1, 0, 0 };
    sr_vec3 t = sr_vec3_normalize(sr_vec3_cross(up, axis));
    sr_vec3 b = sr_vec3_cross(up, t);
    sr_vec3 lo = desc->bounds_min, hi = desc->bounds_max;
    float t0 = INFINITY, t1 = -INFINITY, b0 = INFINITY, b1 = -INFINITY, low = INFINITY;
    for (int i = 0; i < 8; i++) {
        sr_vec3 p = { i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z };
        float pt = sr_vec3_dot(p, t), pb = sr_vec3_dot(p, b);
        t0 = fminf(t0, pt), t1 = fmaxf(t1, pt);
        b0 = fminf(b0, pb), b1 = fmaxf(b1, pb);
        low = fminf(low, sr_vec3_dot(p, up));
    }
    float extent = fmaxf(t1 - t0, b1 - b0);
    if (!(extent > 0.0f)) {
        /* A box with no width across up (a vertical segment, a point). */
        extent = fmaxf(sr_vec3_length(sr_vec3_sub(hi, lo)), 1.0f);
    }
    float height = low - desc->drop * extent;
    float half = 0.5f * (desc->scale != 0.0f ? desc->scale : 4.0f) * extent;
    sr_vec3 c = sr_vec3_add(sr_vec3_add(sr_vec3_scale(t, 0.5f * (t0 + t1)),
                                        sr_vec3_scale(b, 0.5f * (b0 + b1))),
                            sr_vec3_scale(up, height));
    static const float corner[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
    float positions[12], normals[12], texcoords[8];
    for (int i = 0; i < 4; i++) {
        sr_vec3 p = sr_vec3_add(c, sr_vec3_add(sr_vec3_scale(t, corner[i][0] * half),
                                               sr_vec3_scale(b, corner[i][1] * half)));
        positions[3 * i + 0] = p.x, positions[3 * i + 1] = p.y, positions[3 * i + 2] = p.z;
        normals[3 * i + 0] = up.x, normals[3 * i + 1] = up.y, normals[3 * i + 2] = up.z;
        texcoords[2 * i + 0] = 0.5f + 0.5f * corner[i][0];
        texcoords[2 * i + 1] = 0.5f + 0.5f * corner[i][1];
    }
    uint32_t indices[6] = { 0, 1, 2, 0, 2, 3 };
    sr_mesh src = { .vertex_count = 4, .positions = positions, .normals = normals,
                    .texcoords = texcoords, .triangle_count = 2, .indices = indices };
    return sr_make_mesh(ctx, &src, out);
}
