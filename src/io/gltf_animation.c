/*
 * gltf_animation.c - io stage: glTF animations for the glTF reader.
 * Consumes /animations (channels, samplers and their accessors), checked
 * whole; produces the list on sr_scene.animations and, when sr_load_desc
 * asks for one at a time, each targeted node's sampled translation,
 * rotation, scale or morph weights (d->pose), which gltf.c puts in place
 * of the node's own before its world matrix is made.  Called by gltf.c on
 * the reading thread; internal to src/io.
 */
#include "io/gltf.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const path_names[] = { "translation", "rotation", "scale", "weights" };
enum { PATH_TRANSLATION, PATH_ROTATION, PATH_SCALE, PATH_WEIGHTS, PATH_COUNT };

static sr_result read_sampler(gltf_doc *d, const json_t *obj, const char *ptr, gltf_sampler *s)
{
    sr_result r;
    if (!json_is_object(obj)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
    }
    long input = -1, output = -1;
    if ((r = sr__gltf_index(d, obj, ptr, "input", (size_t)-1 / 2, true, &input)) != SR_OK ||
        (r = sr__gltf_index(d, obj, ptr, "output", (size_t)-1 / 2, true, &output)) != SR_OK) {
        return r;
    }
    json_t *interp = json_object_get(obj, "interpolation");
    const char *name = json_is_string(interp) ? json_string_value(interp) : NULL;
    s->interp = !interp                            ? GLTF_INTERP_LINEAR
              : !name                              ? -1
              : strcmp(name, "LINEAR") == 0        ? GLTF_INTERP_LINEAR
              : strcmp(name, "STEP") == 0          ? GLTF_INTERP_STEP
              : strcmp(name, "CUBICSPLINE") == 0   ? GLTF_INTERP_CUBIC : -1;
    if (s->interp < 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/interpolation: expected LINEAR, STEP or CUBICSPLINE", ptr);
    }
    char iptr[GLTF_PTR], optr[GLTF_PTR];
    snprintf(iptr, sizeof iptr, "%s/input", ptr);
    snprintf(optr, sizeof optr, "%s/output", ptr);
    gltf_accessor_info in;
    if ((r = sr__gltf_read_floats(d, input, iptr, 1u << 1, &in, &s->times)) != SR_OK) {
        return r;
    }
    if (in.component_type != 5126 || in.normalized) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: accessor %ld is not a SCALAR of floats (key "
                             "times in seconds)", iptr, input);
    }
    s->count = in.count;
    for (size_t k = 0; k < s->count; k++) {
        if (s->times[k] < 0 || (k > 0 && !(s->times[k] > s->times[k - 1]))) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: key %zu is %g s, %s: key times must be at least 0 and "
                                 "strictly increase", iptr, k, s->times[k],
                                 s->times[k] < 0 ? "negative" : "not after the key before");
        }
    }
    if (s->interp == GLTF_INTERP_CUBIC && s->count < 2) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: CUBICSPLINE needs at least two keys", iptr);
    }
    if ((r = sr__gltf_read_floats(d, output, optr, 1u << 1 | 1u << 2 | 1u << 3 | 1u << 4,
                                  &s->out,
                                  &s->values)) != SR_OK) {
        return r;
    }
    s->value_count = s->out.count;
    return SR_OK;
}

/* The morph targets of mesh `index` (its first primitive's, which every
 * primitive must match), 0 when it has none or there is no such mesh. */
static size_t morph_target_count(const gltf_doc *d, json_int_t index)
{
    json_t *mesh = json_array_get(json_object_get(d->root, "meshes"), (size_t)index);
    json_t *prim = json_array_get(json_object_get(mesh, "primitives"), 0);
    return index >= 0 ? json_array_size(json_object_get(prim, "targets")) : 0;
}

/* The nodes that draw mesh c->index without weights of their own, whose
 * morph weights are the mesh's: into c (scene memory). */
static sr_result find_users(gltf_doc *d, const char *ptr, gltf_channel *c)
{
    json_t *nodes = json_object_get(d->root, "nodes");
    size_t n = json_array_size(nodes);
    c->users = sr__scene_alloc(d->scene, (n ? n : 1) * sizeof *c->users);
    if (!c->users) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    for (size_t i = 0; i < n; i++) {
        json_t *node = json_array_get(nodes, i), *mesh = json_object_get(node, "mesh");
        if (json_is_integer(mesh) && json_integer_value(mesh) == c->index &&
            !json_object_get(node, "weights")) {
            c->users[c->user_count++] = (long)i;
        }
    }
    return SR_OK;
}

/* The targets an animation's channels have claimed so far: an open
 * addressing set of (kind, index, property) keys, 0 an empty slot; cap a
 * power of two above twice the channels so it never fills. */
typedef struct claims {
    uint64_t *keys;
    size_t cap;
} claims;

/* One rule for every target (a node's transform, weights or visibility, a
 * material's, camera's or light's property): glTF lets one channel of an
 * animation animate it.  `ptr` and `what` name the channel and its target
 * in the message. */
static sr_result claim(gltf_doc *d, claims *set, int kind, long index, int prop,
                       const char *ptr, const char *what)
{
    uint64_t key = ((uint64_t)index << 16 | (uint64_t)(kind + 1) << 12 | (uint64_t)prop) + 1;
    size_t at = (size_t)(key * 0x9E3779B97F4A7C15u >> 32) & (set->cap - 1);
    while (set->keys[at] && set->keys[at] != key) {
        at = (at + 1) & (set->cap - 1);
    }
    if (set->keys[at]) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: %s is animated by another channel of this "
                             "animation", ptr, what);
    }
    set->keys[at] = key;
    return SR_OK;
}

/* Checks channel ch's target and its sampler's output against each
 * other into c: its target, and the floats a key for sampling. */
static sr_result check_channel(gltf_doc *d, const json_t *ch, const char *ptr,
                               const gltf_sampler *samplers, size_t sampler_count,
                               claims *targeted, gltf_channel *c)
{
    sr_result r;
    json_t *target, *nodes = json_object_get(d->root, "nodes");
    size_t node_count = json_array_size(nodes);
    long *node = &c->node, *sampler = &c->sampler;
    int *path = &c->path;
    size_t *width = &c->width;
    *node = -1;
    if (!json_is_object(ch)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
    }
    if ((r = sr__gltf_index(d, ch, ptr, "sampler", sampler_count, true, sampler)) != SR_OK ||
        (r = sr__gltf_object(d, ch, ptr, "target", &target)) != SR_OK) {
        return r;
    }
    char tptr[GLTF_PTR], nptr[GLTF_PTR], sptr[GLTF_PTR];
    snprintf(tptr, sizeof tptr, "%s/target", ptr);
    snprintf(sptr, sizeof sptr, "%s/sampler", ptr);
    snprintf(nptr, sizeof nptr, "%s/node", tptr);
    if (!target) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: missing", tptr);
    }
    json_t *p = json_object_get(target, "path");
    const char *name = json_is_string(p) ? json_string_value(p) : "";
    for (*path = 0; *path < PATH_COUNT && strcmp(name, path_names[*path]) != 0; ++*path) {
    }
    if (strcmp(name, "pointer") == 0) {
        gltf_pointer to;
        if ((r = sr__gltf_pointer_target(d, target, tptr, &to)) != SR_OK) {
            return r;
        }
        c->kind = to.kind;
        c->index = to.index;
        if (to.kind == GLTF_TARGET_NONE) {
            return SR_OK;
        }
        if (to.kind != GLTF_TARGET_NODE && to.kind != GLTF_TARGET_MESH_WEIGHTS) {
            char pptr[GLTF_PTR], what[GLTF_PTR];
            snprintf(pptr, sizeof pptr, "%s/extensions/KHR_animation_pointer/pointer", tptr);
            snprintf(what, sizeof what, "\"%.120s\"", json_string_value(json_object_get(
                         sr__gltf_extension(target, "KHR_animation_pointer"), "pointer")));
            c->prop = to.prop;
            c->width = (size_t)to.width;
            c->mask = to.mask;
            if ((r = claim(d, targeted, to.kind, to.index, to.prop, pptr, what)) != SR_OK) {
                return r;
            }
            return sr__gltf_pointer_check(d, &to, &samplers[*sampler], sptr);
        }
        /* A node's transform or weights, or a mesh's weights: the checks
         * of the node paths. */
        *node = to.kind == GLTF_TARGET_NODE ? to.index : -1;
        *path = to.kind == GLTF_TARGET_NODE ? to.node_path : PATH_WEIGHTS;
        snprintf(nptr, sizeof nptr, "%s/extensions/KHR_animation_pointer/pointer", tptr);
    } else {
        /* Another path is an extension's to read: left alone, as a
         * channel without `node` is. */
        if (*path == PATH_COUNT && !json_is_string(p)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s/path: expected translation, rotation, scale, weights or "
                                 "pointer", tptr);
        }
        if ((r = sr__gltf_index(d, target, tptr, "node", node_count ? node_count : 1, false,
                                node)) != SR_OK) {
            return r;
        }
        if (json_object_get(target, "node") && node_count == 0) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/node: there are no nodes", tptr);
        }
        if (*path == PATH_COUNT || *node < 0) {
            sr__gltf_warn(d, "%s: %s, not animated", tptr,
                          *path == PATH_COUNT ? "a path an extension defines" : "no node");
            *node = -1;
            c->kind = GLTF_TARGET_NONE;
            return SR_OK;
        }
    }
    bool mesh = c->kind == GLTF_TARGET_MESH_WEIGHTS;
    json_t *n = mesh ? NULL : json_array_get(nodes, (size_t)*node);
    if (json_object_get(n, "matrix")) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s: node %ld has a matrix, which glTF does not animate (its "
                             "animated nodes have translation, rotation and scale)", nptr, *node);
    }
    char what[64];
    snprintf(what, sizeof what, "%s %ld's %s", mesh ? "mesh" : "node", mesh ? c->index : *node,
             path_names[*path]);
    if ((r = claim(d, targeted, mesh ? c->kind : GLTF_TARGET_NODE, mesh ? c->index : *node,
                   *path, strcmp(name, "pointer") == 0 ? nptr : tptr, what)) != SR_OK) {
        return r;
    }
    const gltf_sampler *s = &samplers[*sampler];
    static const int components[] = { 3, 4, 3, 1 };
    if (s->out.components != components[*path]) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: its output has %d components an element; "
                             "%s takes %s", sptr, s->out.components, path_names[*path],
                             *path == PATH_ROTATION ? "VEC4" : *path == PATH_WEIGHTS ? "SCALAR"
                                                                                     : "VEC3");
    }
    bool is_float = s->out.component_type == 5126;
    if ((*path == PATH_TRANSLATION || *path == PATH_SCALE) && !is_float) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: its output is not of floats, which %s takes",
                             sptr, path_names[*path]);
    }
    if (!is_float && !s->out.normalized) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s: its output is of integers not normalized; %s takes floats or "
                             "normalized integers", sptr, path_names[*path]);
    }
    *width = (size_t)components[*path];
    if (*path == PATH_WEIGHTS) {
        json_t *m = json_object_get(n, "mesh");
        *width = morph_target_count(d, mesh ? c->index : json_is_integer(m)
                                                           ? json_integer_value(m) : -1);
        if (*width == 0 && mesh) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: mesh %ld has no morph targets to weigh",
                                 nptr, c->index);
        }
        if (*width == 0) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: node %ld has no mesh with morph targets to weigh",
                                 nptr, *node);
        }
    }
    /* Elements a key: one vector, or a weight per target; three of them
     * with CUBICSPLINE's tangents. */
    size_t per_key = (*path == PATH_WEIGHTS ? *width : 1) * (s->interp == GLTF_INTERP_CUBIC ? 3 : 1);
    if (s->value_count / per_key != s->count || s->value_count % per_key != 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s: its output has %zu elements; %zu keys of %s%s need %zu", sptr,
                             s->value_count, s->count, path_names[*path],
                             s->interp == GLTF_INTERP_CUBIC ? " (CUBICSPLINE: with tangents)" : "",
                             s->count * per_key);
    }
    return mesh ? find_users(d, nptr, c) : SR_OK;
}

/* The shorter way between unit quaternions a and b at s in [0, 1],
 * normalized (spec's appendix: slerp). */
static void slerp(const float *a, const float *b, double s, float *out)
{
    double dot = 0, sign = 1;
    for (int c = 0; c < 4; c++) {
        dot += (double)a[c] * b[c];
    }
    if (dot < 0) {
        dot = -dot;
        sign = -1;
    }
    double wa = 1 - s, wb = s;
    /* Nearly the same rotation: sin(theta) would divide by almost 0, and
     * the chord is the arc to float's precision. */
    if (dot < 0.9995) {
        double theta = acos(dot), st = sin(theta);
        wa = sin((1 - s) * theta) / st;
        wb = sin(s * theta) / st;
    }
    double q[4], len = 0;
    for (int c = 0; c < 4; c++) {
        q[c] = wa * a[c] + wb * sign * b[c];
        len += q[c] * q[c];
    }
    len = sqrt(len);
    for (int c = 0; c < 4; c++) {
        out[c] = len > 0 ? (float)(q[c] / len) : (c == 3);
    }
}

static void normalize4(float *q)
{
    double len = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2] +
                      (double)q[3] * q[3]);
    for (int c = 0; c < 4; c++) {
        q[c] = len > 0 ? (float)(q[c] / len) : (float)(c == 3);
    }
}

/* Key k's value (width floats) of s. */
static const float *key_value(const gltf_sampler *s, size_t k, size_t width)
{
    return s->interp == GLTF_INTERP_CUBIC ? s->values + (3 * k + 1) * width : s->values + k * width;
}

/* Sampler s at time t: clamped to the first and
 * the last key, else STEP, LINEAR (slerp for rotations) or the cubic
 * Hermite spline of the spec's appendix; rotations normalized. */
void sr__gltf_sample(const gltf_sampler *s, bool rotation, size_t width, float t, float *out)
{
    size_t k = 0;
    if (!(t > s->times[0])) {
        memcpy(out, key_value(s, 0, width), width * sizeof *out);
    } else if (t >= s->times[s->count - 1]) {
        memcpy(out, key_value(s, s->count - 1, width), width * sizeof *out);
    } else {
        /* The last key at or before t: binary search, keys strictly increase. */
        size_t lo = 0, hi = s->count - 1;
        while (hi - lo > 1) {
            size_t mid = lo + (hi - lo) / 2;
            if (s->times[mid] <= t) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        k = lo;
        double t0 = s->times[k], t1 = s->times[k + 1], td = t1 - t0, u = (t - t0) / td;
        const float *v0 = key_value(s, k, width), *v1 = key_value(s, k + 1, width);
        if (s->interp == GLTF_INTERP_STEP) {
            memcpy(out, v0, width * sizeof *out);
        } else if (s->interp == GLTF_INTERP_LINEAR && rotation) {
            slerp(v0, v1, u, out);
        } else if (s->interp == GLTF_INTERP_LINEAR) {
            for (size_t c = 0; c < width; c++) {
                out[c] = (float)((1 - u) * v0[c] + u * v1[c]);
            }
        } else {
            /* p(u) = (2u^3 - 3u^2 + 1) v_k + td (u^3 - 2u^2 + u) b_k
             *      + (-2u^3 + 3u^2) v_k+1 + td (u^3 - u^2) a_k+1,
             * b the out-tangents, a the in-tangents, in units per second. */
            const float *b0 = v0 + width, *a1 = v1 - width;
            double u2 = u * u, u3 = u2 * u;
            double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u;
            double h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
            for (size_t c = 0; c < width; c++) {
                out[c] = (float)(h00 * v0[c] + td * h10 * b0[c] + h01 * v1[c] +
                                 td * h11 * a1[c]);
            }
        }
    }
    if (rotation) {
        normalize4(out);
    }
}

void sr__gltf_anim_apply(const gltf_anim *a, float t, gltf_node_pose *pose)
{
    for (size_t i = 0; i < a->channel_count; i++) {
        const gltf_channel *c = &a->channels[i];
        if (c->kind == GLTF_TARGET_MESH_WEIGHTS) {
            /* The mesh's weights, for its nodes whose own weights no
             * channel animates (they come first whichever the order). */
            sr__gltf_sample(&a->samplers[c->sampler], false, c->width, t, c->weights);
            for (size_t k = 0; k < c->user_count; k++) {
                gltf_node_pose *p = &pose[c->users[k]];
                if (!(p->animated & GLTF_POSE_WEIGHTS)) {
                    p->weights = c->weights;
                    p->weight_count = c->width;
                }
            }
            continue;
        }
        if (c->kind != GLTF_TARGET_NODE) {
            continue;
        }
        gltf_node_pose *p = &pose[c->node];
        float *dst = c->path == PATH_TRANSLATION ? p->translation
                   : c->path == PATH_ROTATION    ? p->rotation
                   : c->path == PATH_SCALE       ? p->scale : c->weights;
        if (c->path == PATH_WEIGHTS) {
            p->weights = c->weights;
            p->weight_count = c->width;
        }
        sr__gltf_sample(&a->samplers[c->sampler], c->path == PATH_ROTATION, c->width, t, dst);
        p->animated |= 1u << c->path;
    }
}

void sr__gltf_anim_free(gltf_anim *a)
{
    for (size_t i = 0; a->samplers && i < a->sampler_count; i++) {
        free(a->samplers[i].times);
        free(a->samplers[i].values);
    }
    free(a->samplers);
    free(a->channels);
    memset(a, 0, sizeof *a);
}

/* Animation `index` (its JSON obj at ptr): checked, listed in *out,
 * applied at d->desc's time when `apply`, and its decoded samplers handed
 * to d->posing for sr_scene_pose when the scene keeps them. */
static sr_result read_animation(gltf_doc *d, const json_t *obj, const char *ptr, size_t index,
                                bool apply, sr_scene_animation *out)
{
    sr_result r;
    if (!json_is_object(obj)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
    }
    json_t *channels, *samplers, *name = json_object_get(obj, "name");
    size_t nc, ns;
    if ((r = sr__gltf_array(d, obj, ptr, "channels", &channels, &nc)) != SR_OK ||
        (r = sr__gltf_array(d, obj, ptr, "samplers", &samplers, &ns)) != SR_OK) {
        return r;
    }
    if (nc == 0 || ns == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: missing or empty", ptr,
                             nc == 0 ? "channels" : "samplers");
    }
    if (name && !json_is_string(name)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/name: not a string", ptr);
    }
    const char *text = name ? json_string_value(name) : "";
    char *copy = sr__scene_alloc(d->scene, strlen(text) + 1);
    gltf_anim a = { .samplers = calloc(ns, sizeof *a.samplers), .sampler_count = ns,
                    .channels = calloc(nc, sizeof *a.channels) };
    claims targeted = { .cap = 16 };
    while (targeted.cap <= 2 * nc) {
        targeted.cap *= 2;
    }
    targeted.keys = calloc(targeted.cap, sizeof *targeted.keys);
    if (!copy || !a.samplers || !a.channels || !targeted.keys) {
        free(targeted.keys);
        sr__gltf_anim_free(&a);
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    gltf_sampler *s = a.samplers;
    memcpy(copy, text, strlen(text) + 1);
    out->name = copy;
    out->channel_count = nc;
    out->duration = 0;
    for (size_t i = 0; i < ns && r == SR_OK; i++) {
        char sptr[GLTF_PTR];
        snprintf(sptr, sizeof sptr, "%s/samplers/%zu", ptr, i);
        r = read_sampler(d, json_array_get(samplers, i), sptr, &s[i]);
        if (r == SR_OK && s[i].times[s[i].count - 1] > out->duration) {
            out->duration = s[i].times[s[i].count - 1];
        }
    }
    /* The channels that animate a node, kept when they are sampled now
     * or may be later (sr_scene_pose). */
    bool keep = apply || d->posing;
    for (size_t i = 0; i < nc && r == SR_OK; i++) {
        char cptr[GLTF_PTR];
        snprintf(cptr, sizeof cptr, "%s/channels/%zu", ptr, i);
        gltf_channel c = { .sampler = -1, .node = -1, .index = -1 };
        r = check_channel(d, json_array_get(channels, i), cptr, s, ns, &targeted, &c);
        if (r != SR_OK || !keep || c.kind == GLTF_TARGET_NONE) {
            continue;
        }
        if (c.path == PATH_WEIGHTS &&
            !(c.weights = sr__scene_alloc(d->scene, c.width * sizeof *c.weights))) {
            r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", cptr);
        }
        a.channels[a.channel_count++] = c;
    }
    free(targeted.keys);
    if (r == SR_OK && apply) {
        sr__gltf_anim_apply(&a, d->desc->animation_time, d->pose);
    }
    if (r == SR_OK && d->posing) {
        if (!sr__gltf_posing_anim(d, index, &a)) {   /* takes a */
            r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        } else if (apply) {
            d->applied = sr__gltf_posing_anim_at(d, index);
        }
    } else if (r == SR_OK && apply && (d->applied_own = malloc(sizeof a)) != NULL) {
        /* Its pointer channels are applied once the scene is whole. */
        *d->applied_own = a;
        d->applied = d->applied_own;
    } else if (r == SR_OK && apply) {
        sr__gltf_anim_free(&a);
        r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    } else {
        sr__gltf_anim_free(&a);
    }
    return r;
}

sr_result sr__gltf_read_animations(gltf_doc *d)
{
    json_t *anims;
    size_t n, node_count = json_array_size(json_object_get(d->root, "nodes"));
    sr_result r = sr__gltf_array(d, d->root, "", "animations", &anims, &n);
    if (r != SR_OK) {
        return r;
    }
    d->scene->animation = -1;
    bool posed = d->desc && d->desc->pose == SR_POSE_ANIMATION;
    if (posed && (d->desc->animation < 0 || (size_t)d->desc->animation >= n)) {
        return sr__gltf_fail(d, SR_INVALID_ARG,
                             "sr_load_desc.animation %d is not an animation of the file (it has "
                             "%zu)", d->desc->animation, n);
    }
    if (n == 0) {
        return SR_OK;
    }
    d->scene->animations = sr__scene_alloc(d->scene, n * sizeof *d->scene->animations);
    if (!d->for_mesh && !sr__gltf_posing_start(d, n)) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/animations: out of memory");
    }
    d->pose = posed ? sr__scene_alloc(d->scene, (node_count ? node_count : 1) * sizeof *d->pose)
                    : NULL;
    if (!d->scene->animations || (posed && !d->pose)) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/animations: out of memory");
    }
    d->scene->animation_count = n;
    for (size_t i = 0; i < n && r == SR_OK; i++) {
        char ptr[GLTF_PTR];
        snprintf(ptr, sizeof ptr, "/animations/%zu", i);
        r = read_animation(d, json_array_get(anims, i), ptr, i,
                           posed && (size_t)d->desc->animation == i, &d->scene->animations[i]);
    }
    if (r == SR_OK && posed) {
        d->scene->animation = d->desc->animation;
        d->scene->animation_time = d->desc->animation_time;
    }
    return r;
}

const float *sr__gltf_node_pose_weights(const gltf_doc *d, long node, size_t *count)
{
    const gltf_node_pose *p = d->pose ? &d->pose[node] : NULL;
    *count = p && p->weights ? p->weight_count : 0;
    return *count ? p->weights : NULL;
}
