/*
 * gltf_instancing.c - io stage: glTF's EXT_mesh_gpu_instancing.  Consumes
 * a node's extension object (accessors of per-instance TRANSLATION,
 * ROTATION and SCALE); produces one matrix T * R * S per instance, which
 * the node walk (gltf.c) puts after the node's world matrix to draw the
 * node's mesh once per instance, sharing its arrays.  Called by the
 * thread reading the document.
 */
#include "io/gltf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define INSTANCING "EXT_mesh_gpu_instancing"

/* The transform attributes and what the extension lets each hold. */
enum { TRANSLATION, ROTATION, SCALE, TRANSFORMS };
static const char *const transform_names[TRANSFORMS] = { "TRANSLATION", "ROTATION", "SCALE" };

static bool quantization_used(const gltf_doc *d)
{
    json_t *used = json_object_get(d->root, "extensionsUsed");
    for (size_t i = 0; i < json_array_size(used); i++) {
        const char *name = json_string_value(json_array_get(used, i));
        if (name && strcmp(name, "KHR_mesh_quantization") == 0) {
            return true;
        }
    }
    return false;
}

/* Whether an accessor of `info`'s kind may hold attribute `which`: the
 * extension's table (TRANSLATION and SCALE floats, ROTATION floats or
 * normalized signed bytes or shorts) and, in a file that uses
 * KHR_mesh_quantization, that extension's widening of the same kind of
 * data on nodes' meshes (bytes and shorts, signed or not, normalized or
 * not), which gltfpack writes.  `want` says what it takes. */
static bool transform_accepts(int which, const gltf_accessor_info *info, bool quantized,
                              const char **want)
{
    int ct = info->component_type;
    if (which == ROTATION) {
        *want = "VEC4 of floats, or of normalized bytes or shorts";
        return !info->matrix && info->components == 4 &&
               (ct == 5126 || (info->normalized && (ct == 5120 || ct == 5122)));
    }
    *want = quantized ? "VEC3 of floats, bytes or shorts"
                      : "VEC3 of floats (bytes and shorts need KHR_mesh_quantization)";
    return !info->matrix && info->components == 3 &&
           (ct == 5126 || (quantized && ct >= 5120 && ct <= 5123));
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* Every attribute's accessor checked without decoding it: an index,
 * `room` instances at most, the same count as the others (*count).  The
 * custom ones ("_ID" ...) are checked and left for the application, as
 * the extension says; they are visited by name so that a message names
 * the same one every time (jansson's order is seeded at random). */
static sr_result check_counts(gltf_doc *d, const json_t *attrs, const char *aptr, size_t room,
                              long index[TRANSFORMS], size_t *count)
{
    size_t n = json_object_size(attrs), at = 0;
    const char **names = malloc((n ? n : 1) * sizeof *names);
    if (!names) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", aptr);
    }
    const char *key;
    json_t *value;
    json_object_foreach((json_t *)attrs, key, value) {
        (void)value;
        names[at++] = key;
    }
    qsort(names, n, sizeof *names, compare_names);
    /* The transforms first, then the custom attributes in name order. */
    const char *first = NULL;
    sr_result r = SR_OK;
    for (size_t pass = 0; pass < 2 && r == SR_OK; pass++) {
        for (size_t i = 0; i < (pass ? n : TRANSFORMS) && r == SR_OK; i++) {
            const char *name = pass ? names[i] : transform_names[i];
            int which = -1;
            for (int t = 0; t < TRANSFORMS; t++) {
                which = strcmp(name, transform_names[t]) == 0 ? t : which;
            }
            if ((pass == 1 && which >= 0) || !json_object_get(attrs, name)) {
                continue;
            }
            long idx = -1;
            char ptr[GLTF_PTR];
            sr__json_pointer(ptr, sizeof ptr, "%s/%s", aptr, name);
            gltf_accessor_info info;
            if ((r = sr__gltf_index(d, attrs, aptr, name, (size_t)-1 / 2, true, &idx)) != SR_OK ||
                (r = sr__gltf_accessor_info(d, idx, ptr, &info)) != SR_OK) {
                break;
            }
            if (which >= 0) {
                index[which] = idx;
            }
            if (!first) {
                first = name;
                *count = info.count;
                if (info.count > room) {
                    r = sr__gltf_fail(d, SR_TOO_LARGE,
                                      "%s: accessor %ld gives %zu instances, more than the %zu "
                                      "draws the scene has room for (of %zu)",
                                      ptr, idx, info.count, room, SR_SCENE_MAX_DRAWS);
                }
            } else if (info.count != *count) {
                r = sr__gltf_fail(d, SR_BAD_FORMAT,
                                  "%s: accessor %ld has %zu elements, %s %zu (every attribute "
                                  "has one an instance)",
                                  ptr, idx, info.count, first, *count);
            }
        }
    }
    free(names);
    return r;
}

sr_result sr__gltf_read_instances(gltf_doc *d, const json_t *node, const char *ptr, long mesh,
                                  size_t room, float **out, size_t *count)
{
    *out = NULL;
    *count = 0;
    json_t *ext = json_object_get(json_object_get(node, "extensions"), INSTANCING);
    if (!ext) {
        return SR_OK;
    }
    char eptr[GLTF_PTR], aptr[GLTF_PTR];
    sr__json_pointer(eptr, sizeof eptr, "%s/extensions/" INSTANCING, ptr);
    sr__json_pointer(aptr, sizeof aptr, "%s/attributes", eptr);
    if (!json_is_object(ext)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", eptr);
    }
    /* The extension defines no meaning for it without a mesh; silence
     * would hide a file that lost its mesh, as for a skin. */
    if (mesh < 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: on a node without a mesh (it instances the "
                             "node's mesh)", eptr);
    }
    json_t *attrs;
    sr_result r = sr__gltf_object(d, ext, eptr, "attributes", &attrs);
    if (r != SR_OK) {
        return r;
    }
    if (!attrs || json_object_size(attrs) == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: missing or empty (the extension needs one "
                             "attribute at least)", aptr);
    }
    long index[TRANSFORMS] = { -1, -1, -1 };
    size_t n = 0;
    if ((r = check_counts(d, attrs, aptr, room, index, &n)) != SR_OK) {
        return r;
    }
    bool quantized = quantization_used(d);
    float *values[TRANSFORMS] = { NULL, NULL, NULL };
    for (int t = 0; t < TRANSFORMS && r == SR_OK; t++) {
        if (index[t] < 0) {
            continue;
        }
        char tptr[GLTF_PTR];
        sr__json_pointer(tptr, sizeof tptr, "%s/%s", aptr, transform_names[t]);
        gltf_accessor_info info;
        const char *want;
        if ((r = sr__gltf_accessor_info(d, index[t], tptr, &info)) != SR_OK) {
            break;
        }
        if (!transform_accepts(t, &info, quantized, &want)) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT,
                              "%s: accessor %ld is %d component%s of type %d%s, not a %s", tptr,
                              index[t], info.components, info.components == 1 ? "" : "s",
                              info.component_type, info.normalized ? " normalized" : "", want);
            break;
        }
        r = sr__gltf_read_floats(d, index[t], tptr, 1u << info.components, &info, &values[t]);
    }
    /* A rotation of length zero turns nothing into anything: no rounding
     * of a unit quaternion comes near it. */
    for (size_t i = 0; r == SR_OK && values[ROTATION] && i < n; i++) {
        const float *q = values[ROTATION] + 4 * i;
        if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT,
                              "%s/ROTATION: element %zu is (0, 0, 0, 0), not a rotation", aptr, i);
        }
    }
    float *m = r == SR_OK ? malloc(n * 16 * sizeof *m + 1) : NULL;
    if (r == SR_OK && !m) {
        r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", eptr);
    }
    static const float t0[3] = { 0, 0, 0 }, q0[4] = { 0, 0, 0, 1 }, s0[3] = { 1, 1, 1 };
    for (size_t i = 0; r == SR_OK && i < n; i++) {
        sr__gltf_trs(values[TRANSLATION] ? values[TRANSLATION] + 3 * i : t0,
                     values[ROTATION] ? values[ROTATION] + 4 * i : q0,
                     values[SCALE] ? values[SCALE] + 3 * i : s0, m + 16 * i);
    }
    for (int t = 0; t < TRANSFORMS; t++) {
        free(values[t]);
    }
    if (r != SR_OK) {
        free(m);
        return r;
    }
    *out = m;
    *count = n;
    return SR_OK;
}
