/*
 * gltf_morph.c - io stage: glTF morph targets (the specification's
 * 3.7.2.2).  Consumes a primitive's `targets` (POSITION, NORMAL and
 * TANGENT deltas, read by gltf_accessor.c: sparse and quantized ones too)
 * and the weights a node draws its mesh with; produces the node
 * instance's moved positions, normals and tangents.  Called by the thread
 * reading the document.
 */
#include "io/gltf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sr__gltf_pose_free(gltf_pose_source *src)
{
    for (size_t i = 0; src->deltas && i < 3 * src->target_count; i++) {
        free(src->deltas[i]);
    }
    free(src->deltas);
    free(src->joints);
    free(src->weights);
    memset(src, 0, sizeof *src);
}

sr_result sr__gltf_charge_posed(gltf_doc *d, const sr_scene_primitive *p, const char *ptr)
{
    size_t per = 3 + (p->normals ? 3 : 0) + (p->tangents ? 4 : 0), floats;
    if (!sr__mul_ok(p->vertex_count, per, &floats) || floats > d->elements_left) {
        return sr__gltf_fail(d, SR_TOO_LARGE,
                             "%s: posing %zu more vertices is more than a file of this size "
                             "may decode", ptr, p->vertex_count);
    }
    d->elements_left -= floats;
    return SR_OK;
}

sr_result sr__gltf_read_targets(gltf_doc *d, const json_t *prim, const char *ptr,
                                size_t vertex_count, gltf_pose_source *src)
{
    static const char *const names[3] = { "POSITION", "NORMAL", "TANGENT" };
    json_t *targets;
    size_t n;
    sr_result r = sr__gltf_array(d, prim, ptr, "targets", &targets, &n);
    if (r != SR_OK || n == 0) {
        return r;
    }
    src->deltas = calloc(3 * n, sizeof *src->deltas);
    if (!src->deltas) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s/targets: out of memory", ptr);
    }
    src->target_count = n;
    for (size_t t = 0; t < n; t++) {
        char tptr[GLTF_PTR], aptr[GLTF_PTR];
        json_t *target = json_array_get(targets, t);
        sr__json_pointer(tptr, sizeof tptr, "%s/targets/%zu", ptr, t);
        if (!json_is_object(target)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", tptr);
        }
        for (int k = 0; k < 3; k++) {
            long index = -1;
            if ((r = sr__gltf_index(d, target, tptr, names[k], (size_t)-1 / 2, false, &index)) !=
                SR_OK) {
                return r;
            }
            if (index < 0) {
                continue;
            }
            sr__json_pointer(aptr, sizeof aptr, "%s/%s", tptr, names[k]);
            gltf_accessor_info info;
            /* Tangent deltas move xyz alone: the handedness stays the base's. */
            if ((r = sr__gltf_read_floats(d, index, aptr, 1u << 3, &info,
                                          &src->deltas[3 * t + (size_t)k])) != SR_OK) {
                return r;
            }
            if (info.count != vertex_count) {
                return sr__gltf_fail(d, SR_BAD_FORMAT,
                                     "%s: accessor %ld has %zu elements, POSITION %zu", aptr,
                                     index, info.count, vertex_count);
            }
        }
    }
    return SR_OK;
}

/* The weights array obj[key] (JSON `ptr`), if any, checked to hold n
 * finite numbers; *found whether it is there. */
static sr_result weights_of(gltf_doc *d, const json_t *obj, const char *ptr, size_t n,
                            float *out, bool *found)
{
    json_t *w = json_object_get(obj, "weights");
    *found = w != NULL;
    if (!w) {
        return SR_OK;
    }
    if (!json_is_array(w)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/weights: not an array", ptr);
    }
    if (json_array_size(w) != n) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/weights: %zu weights, but the mesh's primitives have %zu morph "
                             "targets", ptr, json_array_size(w), n);
    }
    return sr__gltf_numbers(d, obj, ptr, "weights", n, out);
}

sr_result sr__gltf_check_targets(gltf_doc *d, const json_t *mesh, const char *ptr)
{
    json_t *prims = json_object_get(mesh, "primitives");
    size_t n = json_array_size(json_object_get(json_array_get(prims, 0), "targets"));
    for (size_t i = 1; i < json_array_size(prims); i++) {
        size_t k = json_array_size(json_object_get(json_array_get(prims, i), "targets"));
        if (k != n) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s/primitives/%zu/targets: %zu morph targets, primitive 0 "
                                 "has %zu (all of a mesh's primitives have the same number)",
                                 ptr, i, k, n);
        }
    }
    if (n == 0) {
        return SR_OK;
    }
    float *w = malloc(n * sizeof *w);
    if (!w) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s/weights: out of memory", ptr);
    }
    bool found;
    sr_result r = weights_of(d, mesh, ptr, n, w, &found);
    free(w);
    return r;
}

sr_result sr__gltf_node_weights(gltf_doc *d, long node_index, long mesh, float *out, size_t n)
{
    /* An animation's weights channel, sampled for this node, comes first
     * (gltf_animation.c checked it holds one weight per target). */
    size_t animated;
    const float *sampled = sr__gltf_node_pose_weights(d, node_index, &animated);
    if (sampled && animated == n) {
        memcpy(out, sampled, n * sizeof *out);
        return SR_OK;
    }
    return sr__gltf_node_rest_weights(d, node_index, mesh, out, n);
}

sr_result sr__gltf_node_rest_weights(gltf_doc *d, long node_index, long mesh, float *out,
                                     size_t n)
{
    char ptr[GLTF_PTR];
    bool found;
    for (size_t i = 0; i < n; i++) {
        out[i] = 0;
    }
    json_t *node = json_array_get(json_object_get(d->root, "nodes"), (size_t)node_index);
    sr__json_pointer(ptr, sizeof ptr, "/nodes/%ld", node_index);
    sr_result r = weights_of(d, node, ptr, n, out, &found);
    if (r != SR_OK || found) {
        return r;
    }
    sr__json_pointer(ptr, sizeof ptr, "/meshes/%ld", mesh);
    return weights_of(d, json_array_get(json_object_get(d->root, "meshes"), (size_t)mesh), ptr,
                      n, out, &found);
}

static void normalize3(float *v)
{
    double len = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    if (len > 0) {
        v[0] = (float)(v[0] / len), v[1] = (float)(v[1] / len), v[2] = (float)(v[2] / len);
    }
}

sr_result sr__gltf_morph(gltf_doc *d, const gltf_pose_source *src, const float *weights,
                         const char *ptr, sr_scene_primitive *p)
{
    size_t n = p->vertex_count, active = 0;
    for (size_t t = 0; t < src->target_count; t++) {
        active += weights[t] != 0;
    }
    if (active == 0) {
        return SR_OK;
    }
    /* Each target in use costs a pass over the vertices, counted as
     * that many more vertices drawn. */
    size_t work;
    if (!sr__mul_ok(n, active, &work) || work > SR_SCENE_MAX_DRAWN_VERTICES - d->drawn_vertices) {
        return sr__gltf_fail(d, SR_TOO_LARGE, "%s: more than %zu vertices to draw in all", ptr,
                             SR_SCENE_MAX_DRAWN_VERTICES);
    }
    d->drawn_vertices += work;
    sr_result r = sr__gltf_charge_posed(d, p, ptr);
    if (r != SR_OK) {
        return r;
    }
    const float *base[3] = { p->positions, p->normals, p->tangents };
    float *out[3] = { NULL, NULL, NULL };
    for (int k = 0; k < 3; k++) {
        size_t stride = k == 2 ? 4 : 3;
        if (base[k] && !(out[k] = sr__scene_alloc(d->scene, n * stride * sizeof(float)))) {
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        }
    }
    sr__gltf_morph_vertices(src, weights, n, base, out);
    p->positions = out[0];
    p->normals = out[1];
    p->tangents = out[2];
    return SR_OK;
}

void sr__gltf_morph_vertices(const gltf_pose_source *src, const float *weights, size_t n,
                             const float *const base[3], float *const out[3])
{
    for (int k = 0; k < 3; k++) {
        size_t stride = k == 2 ? 4 : 3;
        if (!base[k]) {
            continue;
        }
        memcpy(out[k], base[k], n * stride * sizeof(float));
        for (size_t t = 0; t < src->target_count; t++) {
            const float *delta = src->deltas[3 * t + (size_t)k];
            float w = weights[t];
            if (!delta || w == 0) {
                continue;
            }
            for (size_t i = 0; i < n; i++) {
                for (int c = 0; c < 3; c++) {
                    out[k][i * stride + (size_t)c] += w * delta[3 * i + (size_t)c];
                }
            }
        }
        /* Moved directions stay unit length, as the shaders expect. */
        for (size_t i = 0; k > 0 && i < n; i++) {
            normalize3(out[k] + i * stride);
        }
    }
}
