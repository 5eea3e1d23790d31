/* draw_painter.c - the painter's algorithm (SR_VISIBILITY_PAINTER): sorts a
 * triangle list's triangles back to front by eye-space depth and hands
 * sr_draw the sorted list with the depth test and write off, so that the
 * tiles, which draw a tile's triangles in submission order, paint nearer
 * triangles over farther ones.  Application thread. */
#include "context.h"
#include "geometry/assembly.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct depth_key {
    float far_depth, near_depth; /* distance along the view direction, larger is farther */
    uint32_t tri;                /* the triangle's place in the draw */
} depth_key;

/* Farthest first, then by the nearest vertex, then in the draw's order: a
 * total order, so the result is the same whatever qsort does with ties. */
static int farther_first(const void *pa, const void *pb)
{
    const depth_key *a = pa, *b = pb;
    if (a->far_depth != b->far_depth) {
        return a->far_depth > b->far_depth ? -1 : 1;
    }
    if (a->near_depth != b->near_depth) {
        return a->near_depth > b->near_depth ? -1 : 1;
    }
    return a->tri < b->tri ? -1 : (a->tri > b->tri);
}

/* Vertex i's distance in front of the eye: -z of its eye-space position
 * (divided by w for homogeneous positions in front of w = 0).  NaN (a
 * non-finite vertex, which the pipeline drops) sorts as the farthest. */
static float eye_depth(const sr_draw_desc *d, const sr_mat4 *mv, uint32_t i)
{
    int psize = d->position_size ? d->position_size : 3;
    const float *p = (const float *)((const char *)d->positions +
                                     (size_t)i * sr__attr_step(d->position_stride, (size_t)psize));
    sr_vec4 e = sr_mat4_mul_vec4(mv, (sr_vec4){ p[0], p[1], p[2], psize == 4 ? p[3] : 1.0f });
    float z = e.w > 0.0f ? -e.z / e.w : -e.z;
    return isnan(z) ? INFINITY : z;
}

sr_result sr__draw_painter(sr_context *ctx, sr_framebuffer *fb, const sr_state *state,
                           const sr_draw_desc *d)
{
    size_t count = d->index_type == SR_INDEX_NONE ? d->vertex_count : d->index_count;
    size_t tris = count / 3;
    if (tris > UINT32_MAX / 3) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.visibility SR_VISIBILITY_PAINTER sorts at "
                        "most %u triangles (got %zu)", UINT32_MAX / 3, tris);
    }
    for (size_t i = 0; i < tris * 3; i++) {
        uint32_t ix = sr__index_at(d, i);
        if (ix >= d->vertex_count) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_draw_desc.indices[%zu] = %u is out of range (vertex_count %zu)",
                            i, ix, d->vertex_count);
        }
    }
    depth_key *keys = tris ? sr__alloc(ctx, tris * sizeof *keys) : NULL;
    uint32_t *sorted = tris ? sr__alloc(ctx, tris * 3 * sizeof *sorted) : NULL;
    if (tris && (!keys || !sorted)) {
        sr__free(ctx, keys);
        sr__free(ctx, sorted);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_draw: out of memory sorting %zu triangles",
                        tris);
    }
    sr_mat4 mo = d->model ? *d->model : sr_mat4_identity();
    sr_mat4 e = d->view ? *d->view : sr_mat4_identity();
    sr_mat4 mv = sr_mat4_mul(&e, &mo);
    for (size_t t = 0; t < tris; t++) {
        float z0 = eye_depth(d, &mv, sr__index_at(d, 3 * t));
        float z1 = eye_depth(d, &mv, sr__index_at(d, 3 * t + 1));
        float z2 = eye_depth(d, &mv, sr__index_at(d, 3 * t + 2));
        keys[t] = (depth_key){ fmaxf(z0, fmaxf(z1, z2)), fminf(z0, fminf(z1, z2)), (uint32_t)t };
    }
    if (tris) {
        qsort(keys, tris, sizeof *keys, farther_first);
    }
    for (size_t t = 0; t < tris; t++) {
        for (int k = 0; k < 3; k++) {
            sorted[3 * t + (size_t)k] = sr__index_at(d, 3 * (size_t)keys[t].tri + (size_t)k);
        }
    }
    sr_draw_desc sd = *d;
    sd.indices = sorted;
    sd.index_type = SR_INDEX_U32;
    sd.index_count = tris * 3;
    sr_state ss = *state;
    ss.visibility = SR_VISIBILITY_Z_BUFFER;
    ss.depth_test = SR_OFF;
    ss.depth_write = SR_OFF;
    sr_result r = sr_draw(ctx, fb, &ss, &sd);
    sr__free(ctx, keys);
    sr__free(ctx, sorted);
    return r;
}
