/* depth_sort.c - geometry stage, before drawing: the order in which
 * see-through triangles are blended, farthest first, and the mean depth
 * that orders whole meshes.  Consumes positions, indices and a model-view
 * matrix; produces reordered indices.  Any thread (one call per mesh). */
#include "softrast.h"
#include "context.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct depth_key {
    float depth;
    size_t item;
} depth_key;

static int farther_first(const void *a, const void *b)
{
    const depth_key *x = a, *y = b;
    if (x->depth != y->depth) {
        return x->depth > y->depth ? -1 : 1;
    }
    return x->item < y->item ? -1 : x->item > y->item;
}

/* A triangle's key carries its corners, so that out may be indices itself
 * (sorting in place) or overlap it: out is written from the keys alone. */
typedef struct triangle_key {
    depth_key key;
    uint32_t v[3];
} triangle_key;

static int farther_triangle_first(const void *a, const void *b)
{
    return farther_first(&((const triangle_key *)a)->key, &((const triangle_key *)b)->key);
}

/* The eye-space z of position p (the eye looks down -z). */
static float view_z(const sr_mat4 *mv, const float *p)
{
    return mv->m[2] * p[0] + mv->m[6] * p[1] + mv->m[10] * p[2] + mv->m[14];
}

/* The arguments both take, the wrong one named in the message (ctx NULL
 * for sr_mean_view_depth, which has none). */
static sr_result check(sr_context *ctx, const char *fn, const float *positions,
                       size_t vertex_count, const uint32_t *indices, size_t triangle_count,
                       const sr_mat4 *mv)
{
    if (!positions || !indices || !mv) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn,
                        !positions ? "positions" : !indices ? "indices" : "model_view");
    }
    if (triangle_count > SIZE_MAX / 3) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: triangle_count %zu is too large", fn,
                        triangle_count);
    }
    for (int k = 0; k < 16; k++) {
        if (!isfinite(mv->m[k])) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: model_view->m[%d] is not finite", fn, k);
        }
    }
    for (size_t i = 0; i < 3 * triangle_count; i++) {
        if (indices[i] >= vertex_count) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "%s: indices[%zu] = %u is not below vertex_count %zu", fn, i,
                            (unsigned)indices[i], vertex_count);
        }
    }
    return SR_OK;
}

sr_result sr_sort_back_to_front(sr_context *ctx, const float *positions, size_t vertex_count,
                                const uint32_t *indices, size_t triangle_count,
                                const sr_mat4 *model_view, uint32_t *out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_sort_back_to_front: ctx is NULL");
    }
    if (triangle_count > SIZE_MAX / sizeof(triangle_key)) {
        return sr__fail(ctx, SR_TOO_LARGE,
                        "sr_sort_back_to_front: %zu triangles do not fit in memory",
                        triangle_count);
    }
    if (!out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_sort_back_to_front: out is NULL");
    }
    sr_result r = check(ctx, "sr_sort_back_to_front", positions, vertex_count, indices,
                        triangle_count, model_view);
    if (r != SR_OK) {
        return r;
    }
    triangle_key *keys = sr__alloc(ctx, (triangle_count ? triangle_count : 1) * sizeof *keys);
    if (!keys) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_sort_back_to_front: out of memory");
    }
    for (size_t t = 0; t < triangle_count; t++) {
        float z = 0.0f;
        for (int k = 0; k < 3; k++) {
            keys[t].v[k] = indices[t * 3 + k];
            z += view_z(model_view, &positions[(size_t)keys[t].v[k] * 3]);
        }
        keys[t].key = (depth_key){ -z, t };   /* distance is -z */
    }
    qsort(keys, triangle_count, sizeof *keys, farther_triangle_first);
    for (size_t t = 0; t < triangle_count; t++) {
        memcpy(&out[t * 3], keys[t].v, 3 * sizeof *out);
    }
    sr__free(ctx, keys);
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_mean_view_depth(const float *positions, size_t vertex_count, const uint32_t *indices,
                             size_t triangle_count, const sr_mat4 *model_view, float *out)
{
    if (!out) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_mean_view_depth: out is NULL");
    }
    sr_result r = check(NULL, "sr_mean_view_depth", positions, vertex_count, indices,
                        triangle_count, model_view);
    if (r != SR_OK) {
        return r;
    }
    double z = 0.0;
    for (size_t i = 0; i < 3 * triangle_count; i++) {
        z += view_z(model_view, &positions[(size_t)indices[i] * 3]);
    }
    *out = triangle_count ? (float)(-z / (double)(3 * triangle_count)) : 0.0f;
    return SR_OK;
}

sr_result sr_order_back_to_front(sr_context *ctx, const float *distances, size_t count,
                                 size_t *order)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_order_back_to_front: ctx is NULL");
    }
    if (count > SIZE_MAX / sizeof(depth_key)) {
        return sr__fail(ctx, SR_TOO_LARGE,
                        "sr_order_back_to_front: %zu distances do not fit in memory", count);
    }
    for (size_t i = 0; distances && i < count; i++) {
        if (isnan(distances[i])) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_order_back_to_front: distance %zu is NaN", i);
        }
    }
    if (!distances || !order) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_order_back_to_front: %s is NULL",
                        distances ? "order" : "distances");
    }
    depth_key *keys = sr__alloc(ctx, (count ? count : 1) * sizeof *keys);
    if (!keys) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_order_back_to_front: out of memory");
    }
    for (size_t i = 0; i < count; i++) {
        keys[i] = (depth_key){ distances[i], i };
    }
    qsort(keys, count, sizeof *keys, farther_first);
    for (size_t i = 0; i < count; i++) {
        order[i] = keys[i].item;
    }
    sr__free(ctx, keys);
    sr__ok(ctx);
    return SR_OK;
}
