/*
 * gltf_pointer.c - io stage: KHR_animation_pointer and KHR_node_visibility
 * for the glTF reader.  Consumes a channel's JSON pointer (checked
 * against the document: its syntax, its indices, the object it names)
 * and the nodes' `visible`; produces the target a channel animates and,
 * at a time, the animated material, camera and light values and the
 * hidden draws written into the scene.  Called on the reading thread by
 * gltf_animation.c and gltf.c, and by gltf_pose.c for sr_scene_pose;
 * internal to src/io.
 */
#include "io/gltf.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define VIS "KHR_node_visibility"

/* A property softrast animates: its path under the object, the floats it
 * takes, where it sits in the scene's struct and the range its values
 * are clamped to (as the reader clamps the file's); `explicit`: glTF
 * gives it no default, so the pointer needs it written in the file. */
typedef struct prop_row {
    const char *path;
    int width;
    size_t offset;
    float lo, hi;
    bool explicit;
} prop_row;

#define M(field) offsetof(sr_pbr_material, field)
#define MX(ext, name) "extensions/KHR_materials_" ext "/" name
static const prop_row material_rows[] = {
    { "pbrMetallicRoughness/baseColorFactor", 4, M(base_color), 0, 1, false },
    { "pbrMetallicRoughness/metallicFactor", 1, M(metallic), 0, 1, false },
    { "pbrMetallicRoughness/roughnessFactor", 1, M(roughness), 0, 1, false },
    { "emissiveFactor", 3, M(emissive), 0, 1, false },
    { "alphaCutoff", 1, M(alpha_cutoff), 0, FLT_MAX, false },
    { "normalTexture/scale", 1, M(normal_scale), -FLT_MAX, FLT_MAX, false },
    { "occlusionTexture/strength", 1, M(occlusion_strength), 0, 1, false },
    { MX("emissive_strength", "emissiveStrength"), 1, M(emissive_strength), 0, FLT_MAX, false },
    { MX("ior", "ior"), 1, M(ior), 1, FLT_MAX, false },
    { MX("specular", "specularFactor"), 1, M(specular), 0, 1, false },
    { MX("specular", "specularColorFactor"), 3, M(specular_color), 0, FLT_MAX, false },
    { MX("clearcoat", "clearcoatFactor"), 1, M(clearcoat), 0, 1, false },
    { MX("clearcoat", "clearcoatRoughnessFactor"), 1, M(clearcoat_roughness), 0, 1, false },
    { MX("sheen", "sheenColorFactor"), 3, M(sheen_color), 0, 1, false },
    { MX("sheen", "sheenRoughnessFactor"), 1, M(sheen_roughness), 0, 1, false },
    { MX("transmission", "transmissionFactor"), 1, M(transmission), 0, 1, false },
    { MX("volume", "thicknessFactor"), 1, M(thickness), 0, FLT_MAX, false },
    { MX("volume", "attenuationColor"), 3, M(attenuation_color), 0, 1, false },
    /* Not positive: no absorption, the reader's 0. */
    { MX("volume", "attenuationDistance"), 1, M(attenuation_distance), 0, FLT_MAX, false },
    { MX("iridescence", "iridescenceFactor"), 1, M(iridescence), 0, 1, false },
    { MX("iridescence", "iridescenceIor"), 1, M(iridescence_ior), 1, FLT_MAX, false },
    { MX("iridescence", "iridescenceThicknessMinimum"), 1, M(iridescence_thickness_min), 0,
      FLT_MAX, false },
    { MX("iridescence", "iridescenceThicknessMaximum"), 1, M(iridescence_thickness_max), 0,
      FLT_MAX, false },
    { MX("anisotropy", "anisotropyStrength"), 1, M(anisotropy_strength), 0, 1, false },
    { MX("anisotropy", "anisotropyRotation"), 1, M(anisotropy_rotation), -FLT_MAX, FLT_MAX,
      false },
    { MX("dispersion", "dispersion"), 1, M(dispersion), 0, FLT_MAX, false },
    { MX("diffuse_transmission", "diffuseTransmissionFactor"), 1, M(diffuse_transmission), 0, 1,
      false },
    { MX("diffuse_transmission", "diffuseTransmissionColorFactor"), 3,
      M(diffuse_transmission_color), 0, 1, false },
    /* Specular-glossiness keeps its own factors (the diffuse one in the
     * base color's field), which the pbr program turns into F0 and
     * roughness when it is made: animated, they take that road per frame
     * as the file's do. */
    { MX("pbrSpecularGlossiness", "diffuseFactor"), 4, M(base_color), 0, 1, false },
    { MX("pbrSpecularGlossiness", "specularFactor"), 3, M(sg_specular), 0, 1, false },
    { MX("pbrSpecularGlossiness", "glossinessFactor"), 1, M(glossiness), 0, 1, false },
};
#undef MX

/* The textureInfos whose KHR_texture_transform softrast reads. */
#define MT(ext, name) "extensions/KHR_materials_" ext "/" name
static const struct {
    const char *path;
    size_t offset;
} slot_rows[] = {
    { "pbrMetallicRoughness/baseColorTexture", M(base_color_texture) },
    { "pbrMetallicRoughness/metallicRoughnessTexture", M(metallic_roughness_texture) },
    { "normalTexture", M(normal_texture) },
    { "occlusionTexture", M(occlusion_texture) },
    { "emissiveTexture", M(emissive_texture) },
    { MT("transmission", "transmissionTexture"), M(transmission_texture) },
    { MT("volume", "thicknessTexture"), M(thickness_texture) },
    { MT("specular", "specularTexture"), M(specular_texture) },
    { MT("specular", "specularColorTexture"), M(specular_color_texture) },
    { MT("clearcoat", "clearcoatTexture"), M(clearcoat_texture) },
    { MT("clearcoat", "clearcoatRoughnessTexture"), M(clearcoat_roughness_texture) },
    { MT("clearcoat", "clearcoatNormalTexture"), M(clearcoat_normal_texture) },
    { MT("sheen", "sheenColorTexture"), M(sheen_color_texture) },
    { MT("sheen", "sheenRoughnessTexture"), M(sheen_roughness_texture) },
    { MT("anisotropy", "anisotropyTexture"), M(anisotropy_texture) },
    { MT("iridescence", "iridescenceTexture"), M(iridescence_texture) },
    { MT("iridescence", "iridescenceThicknessTexture"), M(iridescence_thickness_texture) },
    { MT("diffuse_transmission", "diffuseTransmissionTexture"),
      M(diffuse_transmission_texture) },
    { MT("diffuse_transmission", "diffuseTransmissionColorTexture"),
      M(diffuse_transmission_color_texture) },
    { MT("pbrSpecularGlossiness", "diffuseTexture"), M(base_color_texture) },
    { MT("pbrSpecularGlossiness", "specularGlossinessTexture"),
      M(specular_glossiness_texture) },
};
#undef MT
#undef M
/* A transform's members, and the prop numbers they take after the rows:
 * TRANSFORM_PROP + 3 * slot row + member. */
static const char *const transform_members[] = { "offset", "rotation", "scale" };
enum { TRANSFORM_PROP = 1000 };

#define C(field) offsetof(sr_scene_camera, field)
static const prop_row camera_rows[] = {
    { "perspective/yfov", 1, C(yfov), 1e-6f, 3.1415f, false },
    { "perspective/znear", 1, C(znear), 1e-6f, FLT_MAX, false },
    { "perspective/zfar", 1, C(zfar), 1e-6f, FLT_MAX, true },
    { "perspective/aspectRatio", 1, C(aspect), 1e-6f, FLT_MAX, true },
    { "orthographic/xmag", 1, C(xmag), -FLT_MAX, FLT_MAX, false },
    { "orthographic/ymag", 1, C(ymag), -FLT_MAX, FLT_MAX, false },
    { "orthographic/znear", 1, C(znear), 0, FLT_MAX, false },
    { "orthographic/zfar", 1, C(zfar), 1e-6f, FLT_MAX, false },
};
#undef C

#define L(field) offsetof(sr_scene_light, light.field)
static const prop_row light_rows[] = {
    { "color", 3, L(color), 0, FLT_MAX, false },
    { "intensity", 1, L(intensity), 0, FLT_MAX, false },
    { "range", 1, L(range), 1e-6f, FLT_MAX, true },
    { "spot/innerConeAngle", 1, L(inner_cone), 0, 1.5707963f, false },
    { "spot/outerConeAngle", 1, L(outer_cone), 1e-6f, 1.5707963f, false },
};
#undef L

static const char *const node_paths[] = { "translation", "rotation", "scale", "weights" };

/* RFC 6901 reference tokens: "/a/b~1c" -> "a", "b/c" into buf (each
 * NUL-ended, ~0 and ~1 unescaped), *count of them.  -1: the text is not a
 * JSON pointer; 0: it is longer or deeper than any property softrast
 * animates; 1: split. */
static int split_pointer(const char *s, char *buf, size_t cap, const char **tok, int max,
                         int *count)
{
    size_t at = 0;
    *count = 0;
    if (s[0] != '/') {
        return -1;
    }
    for (const char *p = s; *p; p++) {
        if ((*p == '~' && p[1] != '0' && p[1] != '1')) {
            return -1;
        }
    }
    for (const char *p = s; *p;) {
        if (*count == max || at >= cap) {
            return 0;
        }
        tok[(*count)++] = buf + at;
        for (p++; *p && *p != '/'; p++) {
            char c = *p;
            if (c == '~') {
                c = *++p == '0' ? '~' : '/';
            }
            if (at + 1 >= cap) {
                return 0;
            }
            buf[at++] = c;
        }
        buf[at++] = '\0';
    }
    return 1;
}

/* A token that is an array index (digits, no leading zero) below n;
 * -2 when it is not a number, -1 when its digits name no element: out
 * of range, too long for any array, or with the leading zero RFC 6901
 * leaves no element. */
static long token_index(const char *t, size_t n)
{
    if (!t[0] || strspn(t, "0123456789") != strlen(t)) {
        return -2;
    }
    if ((t[0] == '0' && t[1]) || strlen(t) > 12) {
        return -1;
    }
    long v = strtol(t, NULL, 10);
    return (size_t)v < n ? v : -1;
}

/* Whether the property at path (tokens) under obj is defined: its
 * enclosing objects present, and the property itself when it must be. */
static bool defined(const json_t *obj, const char *const *tok, int count, bool explicit)
{
    for (int k = 0; k < count - 1; k++) {
        obj = json_object_get(obj, tok[k]);
        if (!json_is_object(obj)) {
            return false;
        }
    }
    return !explicit || json_object_get(obj, tok[count - 1]) != NULL;
}

/* Whether the tokens are path's '/'-separated names, one for one: a
 * token holding an escaped '/' ("~1") names one member, which no path of
 * the tables is. */
static bool path_is(const char *path, const char *const *tok, int count)
{
    for (int k = 0; k < count; k++) {
        size_t len = strlen(tok[k]);
        if (strchr(tok[k], '/') || strncmp(path, tok[k], len) != 0 ||
            path[len] != (k + 1 < count ? '/' : '\0')) {
            return false;
        }
        path += len + 1;
    }
    return count > 0;
}

/* A material's ".../extensions/KHR_texture_transform/<member>" on a slot
 * softrast reads: its prop number, else -1. */
static int find_transform(const char *const *tok, int count)
{
    if (count < 4 || strcmp(tok[count - 3], "extensions") != 0 ||
        strcmp(tok[count - 2], "KHR_texture_transform") != 0) {
        return -1;
    }
    for (size_t i = 0; i < sizeof slot_rows / sizeof *slot_rows; i++) {
        for (int k = 0; k < 3 && path_is(slot_rows[i].path, tok, count - 3); k++) {
            if (strcmp(tok[count - 1], transform_members[k]) == 0) {
                return TRANSFORM_PROP + 3 * (int)i + k;
            }
        }
    }
    return -1;
}

static int find_row(const prop_row *rows, size_t n, const char *const *tok, int count)
{
    for (size_t i = 0; i < n; i++) {
        if (path_is(rows[i].path, tok, count)) {
            return (int)i;
        }
    }
    return -1;
}

sr_result sr__gltf_pointer_target(gltf_doc *d, const json_t *target, const char *tptr,
                                  gltf_pointer *out)
{
    char pptr[GLTF_PTR], buf[GLTF_PTR];
    int n, split;
    snprintf(pptr, sizeof pptr, "%s/extensions/KHR_animation_pointer/pointer", tptr);
    *out = (gltf_pointer){ .kind = GLTF_TARGET_NONE, .index = -1 };
    if (json_object_get(target, "node")) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/node: given with path \"pointer\", which "
                             "KHR_animation_pointer forbids", tptr);
    }
    json_t *ext = sr__gltf_extension(target, "KHR_animation_pointer");
    json_t *p = json_object_get(ext, "pointer");
    if (!json_is_string(p)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: missing or not a string", pptr);
    }
    const char *text = json_string_value(p), *tok[8];
    if ((split = split_pointer(text, buf, sizeof buf, tok, 8, &n)) < 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: \"%.120s\" is not a JSON pointer", pptr,
                             text);
    }
    if (split == 0) {
        n = 0;   /* nothing of softrast's: warned below */
    }
    /* The collection and the element the pointer names. */
    const json_t *root = d->root, *arr = NULL;
    int first = 2;
    out->kind = n == 0                           ? GLTF_TARGET_NONE
              : strcmp(tok[0], "nodes") == 0     ? GLTF_TARGET_NODE
              : strcmp(tok[0], "materials") == 0 ? GLTF_TARGET_MATERIAL
              : strcmp(tok[0], "cameras") == 0   ? GLTF_TARGET_CAMERA
              : strcmp(tok[0], "meshes") == 0    ? GLTF_TARGET_MESH_WEIGHTS : GLTF_TARGET_NONE;
    if (out->kind != GLTF_TARGET_NONE) {
        arr = json_object_get(root, tok[0]);
    } else if (n >= 4 && strcmp(tok[0], "extensions") == 0 &&
               strcmp(tok[1], "KHR_lights_punctual") == 0 && strcmp(tok[2], "lights") == 0) {
        out->kind = GLTF_TARGET_LIGHT;
        arr = json_object_get(json_object_get(json_object_get(root, "extensions"),
                                              "KHR_lights_punctual"), "lights");
        first = 4;
    }
    long index = -2;
    if (out->kind != GLTF_TARGET_NONE && n >= first) {
        index = token_index(tok[first - 1], json_array_size(arr));
        if (index == -1) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: \"%.120s\": %s %s is not in the file "
                                 "(it has %zu)", pptr, text, tok[first - 2], tok[first - 1],
                                 json_array_size(arr));
        }
    }
    const json_t *obj = index >= 0 ? json_array_get(arr, (size_t)index) : NULL;
    const char *const *rest = tok + first;
    int rn = n - first;
    const prop_row *rows = NULL;
    size_t row_count = 0;
    if (out->kind == GLTF_TARGET_NODE && obj && rn == 1) {
        for (int k = 0; k < 4; k++) {
            if (strcmp(rest[0], node_paths[k]) == 0) {
                out->index = index;
                out->node_path = k;
                return SR_OK;
            }
        }
    } else if (out->kind == GLTF_TARGET_MESH_WEIGHTS && obj && rn == 1 &&
               strcmp(rest[0], "weights") == 0) {
        /* The default weights of the nodes without their own: checked
         * with the node paths' weights (gltf_animation.c). */
        out->index = index;
        return SR_OK;
    } else if (out->kind == GLTF_TARGET_NODE && obj && rn == 3 &&
               strcmp(rest[0], "extensions") == 0 && strcmp(rest[1], VIS) == 0 &&
               strcmp(rest[2], "visible") == 0) {
        if (!defined(obj, rest, rn, false)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: \"%.120s\": node %ld has no %s object",
                                 pptr, text, index, VIS);
        }
        *out = (gltf_pointer){ .kind = GLTF_TARGET_VISIBLE, .index = index, .width = 1,
                               .boolean = true };
        return SR_OK;
    } else if (out->kind == GLTF_TARGET_MATERIAL) {
        rows = material_rows;
        row_count = sizeof material_rows / sizeof *material_rows;
    } else if (out->kind == GLTF_TARGET_CAMERA) {
        rows = camera_rows;
        row_count = sizeof camera_rows / sizeof *camera_rows;
    } else if (out->kind == GLTF_TARGET_LIGHT) {
        rows = light_rows;
        row_count = sizeof light_rows / sizeof *light_rows;
    }
    int row = obj && rn > 0 ? find_row(rows, row_count, rest, rn) : -1;
    int transform = obj && out->kind == GLTF_TARGET_MATERIAL ? find_transform(rest, rn) : -1;
    if (obj && out->kind == GLTF_TARGET_MATERIAL && rn > 0 &&
        strcmp(rest[0], "pbrMetallicRoughness") == 0 &&
        sr__gltf_extension(obj, "KHR_materials_pbrSpecularGlossiness")) {
        /* The material is drawn with its specular-glossiness values, whose
         * diffuse color fills the fields the metallic-roughness ones name. */
        sr__gltf_warn(d, "%s: \"%.120s\": material %ld is drawn with "
                         "KHR_materials_pbrSpecularGlossiness, not animated", pptr, text, index);
        *out = (gltf_pointer){ .kind = GLTF_TARGET_NONE, .index = -1 };
        return SR_OK;
    }
    if (obj && out->kind == GLTF_TARGET_MATERIAL && rn > 1 &&
        strcmp(rest[0], "extensions") == 0 && sr__gltf_spec_gloss_excludes(rest[1]) &&
        sr__gltf_extension(obj, "KHR_materials_pbrSpecularGlossiness")) {
        /* The reader drew none of the excluded extension (gltf_material.c). */
        sr__gltf_warn(d, "%s: \"%.120s\": material %ld is drawn with "
                         "KHR_materials_pbrSpecularGlossiness, which excludes %s, not animated",
                      pptr, text, index, rest[1]);
        *out = (gltf_pointer){ .kind = GLTF_TARGET_NONE, .index = -1 };
        return SR_OK;
    }
    if (transform >= 0) {
        if (!defined(obj, rest, rn, false)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: \"%.120s\" names a property the file "
                                 "does not define", pptr, text);
        }
        out->index = index;
        out->prop = transform;
        out->width = (transform - TRANSFORM_PROP) % 3 == 1 ? 1 : 2;
        return SR_OK;
    }
    if (row < 0) {
        sr__gltf_warn(d, "%s: \"%.120s\" is not a property softrast animates, not animated",
                      pptr, text);
        *out = (gltf_pointer){ .kind = GLTF_TARGET_NONE, .index = -1 };
        return SR_OK;
    }
    if (!defined(obj, rest, rn, rows[row].explicit)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: \"%.120s\" names a property the file does "
                             "not define%s", pptr, text,
                             rows[row].explicit ? " (it has no default)" : "");
    }
    out->index = index;
    out->prop = row;
    out->width = rows[row].width;
    /* The reader makes a MASK material with a cutoff of 0 OPAQUE: the
     * mode is the file's again once the cutoff is animated. */
    const json_t *mode = json_object_get(obj, "alphaMode");
    out->mask = rows == material_rows && rows[row].offset == offsetof(sr_pbr_material,
                                                                      alpha_cutoff) &&
                json_is_string(mode) && strcmp(json_string_value(mode), "MASK") == 0;
    return SR_OK;
}

sr_result sr__gltf_pointer_check(gltf_doc *d, const gltf_pointer *p, const gltf_sampler *s,
                                 const char *sptr)
{
    if (s->out.components != p->width || s->out.matrix) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: its output has %d components an element; "
                             "the property takes %d", sptr, s->out.components, p->width);
    }
    if (p->boolean && (s->out.component_type != 5121 || s->out.normalized)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: its output is not of unsigned bytes, which "
                             "a boolean takes", sptr);
    }
    if (p->boolean && s->interp != GLTF_INTERP_STEP) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: a boolean is animated by STEP", sptr);
    }
    size_t per_key = s->interp == GLTF_INTERP_CUBIC ? 3 : 1;
    if (s->value_count != s->count * per_key) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: its output has %zu elements; %zu keys%s "
                             "need %zu", sptr, s->value_count, s->count,
                             per_key == 3 ? " (CUBICSPLINE: with tangents)" : "",
                             s->count * per_key);
    }
    return SR_OK;
}

/* KHR_texture_transform's member k (offset, rotation, scale) of slot
 * set to v: the file's values found back from the slot's, which keeps
 * them as sr_texture_slot's convention (v up) has them (gltf_material.c's
 * read_transform), changed and converted again. */
static void write_transform(sr_texture_slot *slot, int k, const float *v)
{
    if (!isfinite(v[0]) || (k != 1 && !isfinite(v[1]))) {
        return;   /* a spline's overflow: the transform stays finite */
    }
    float rot = slot->rotation, s[2] = { slot->scale[0], slot->scale[1] };
    if (!slot->scale_set && s[0] == 0.0f && s[1] == 0.0f) {
        s[0] = s[1] = 1.0f;   /* a zeroed slot's identity (sr_texture_slot) */
    }
    float o[2] = { slot->offset[0] - s[1] * sinf(rot), 1.0f - slot->offset[1] - s[1] * cosf(rot) };
    if (k == 0) {
        o[0] = v[0];
        o[1] = v[1];
    } else if (k == 1) {
        rot = v[0];
    } else {
        s[0] = v[0];
        s[1] = v[1];
    }
    /* Values that overflow together leave the transform as it was. */
    (void)sr__gltf_slot_transform(slot, o, rot, s);
}

static void write_row(const prop_row *row, void *base, const float *v)
{
    float *dst = (float *)((char *)base + row->offset);
    for (int c = 0; c < row->width; c++) {
        /* A spline's overshoot may overflow: NaN goes to the low end. */
        dst[c] = !(v[c] >= row->lo) ? row->lo : v[c] > row->hi ? row->hi : v[c];
    }
}

void sr__gltf_anim_apply_pointers(const gltf_anim *a, float t, sr_scene *scene,
                                  unsigned char *visible)
{
    for (size_t i = 0; i < a->channel_count; i++) {
        const gltf_channel *c = &a->channels[i];
        float v[4];
        if (c->kind == GLTF_TARGET_NODE || c->kind == GLTF_TARGET_MESH_WEIGHTS) {
            continue;   /* the node pose's (sr__gltf_anim_apply) */
        }
        sr__gltf_sample(&a->samplers[c->sampler], false, c->width, t, v);
        if (c->kind == GLTF_TARGET_VISIBLE) {
            visible[c->index] = v[0] != 0;
        } else if (c->kind == GLTF_TARGET_MATERIAL) {
            sr_pbr_material *m = &scene->materials[c->index];
            if (c->prop >= TRANSFORM_PROP) {
                int slot = (c->prop - TRANSFORM_PROP) / 3;
                write_transform((sr_texture_slot *)((char *)m + slot_rows[slot].offset),
                                (c->prop - TRANSFORM_PROP) % 3, v);
                continue;
            }
            write_row(&material_rows[c->prop], m, v);
            if (c->mask) {
                /* As the reader: a cutoff of 0 keeps every fragment. */
                m->alpha_mode = m->alpha_cutoff > 0 ? SR_ALPHA_MASK : SR_ALPHA_OPAQUE;
            }
            /* A strength of 0 or a film of no thickness needs nothing:
             * the reader keeps them as given (emissive_strength_set,
             * iridescence_thickness_set), with the file's factors. */
        } else if (c->kind == GLTF_TARGET_CAMERA) {
            for (size_t k = 0; k < scene->camera_count; k++) {
                sr_scene_camera *cam = &scene->cameras[k];
                if (cam->camera == c->index) {
                    write_row(&camera_rows[c->prop], cam, v);
                }
            }
        } else {
            for (size_t k = 0; k < scene->light_count; k++) {
                sr_scene_light *l = &scene->lights[k];
                /* Directional lights have no range (the reader's 0). */
                if (l->light_index == c->index &&
                    !(l->type == SR_LIGHT_DIRECTIONAL && light_rows[c->prop].offset ==
                                                             offsetof(sr_scene_light, light.range))) {
                    write_row(&light_rows[c->prop], l, v);
                }
            }
        }
    }
    for (size_t k = 0; k < scene->camera_count; k++) {
        /* A clip range the animation crosses over stays a range. */
        sr_scene_camera *cam = &scene->cameras[k];
        if (cam->zfar != 0 && cam->zfar <= cam->znear) {
            cam->zfar = cam->znear * (1 + FLT_EPSILON) + FLT_MIN;
        }
        if (cam->type == SR_SCENE_CAMERA_ORTHOGRAPHIC) {
            cam->xmag = cam->xmag == 0 ? FLT_MIN : cam->xmag;
            cam->ymag = cam->ymag == 0 ? FLT_MIN : cam->ymag;
        }
    }
    for (size_t k = 0; k < scene->light_count; k++) {
        sr_scene_light *l = &scene->lights[k];
        sr_light *g = &l->light;
        if (g->inner_cone >= g->outer_cone) {
            g->inner_cone = g->outer_cone * (1 - FLT_EPSILON);
        }
        bool dark = g->intensity == 0 || (g->color.x == 0 && g->color.y == 0 && g->color.z == 0);
        g->type = dark ? SR_LIGHT_OFF : l->type;
    }
}

sr_result sr__gltf_read_visibility(gltf_doc *d, unsigned char *visible, size_t n)
{
    json_t *nodes = json_object_get(d->root, "nodes");
    for (size_t i = 0; i < n; i++) {
        json_t *node = json_array_get(nodes, i);
        json_t *ext = json_object_get(json_object_get(node, "extensions"), VIS);
        json_t *v = json_object_get(ext, "visible");
        visible[i] = 1;
        if (ext && !json_is_object(ext)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "/nodes/%zu/extensions/" VIS ": not an object",
                                 i);
        }
        if (v && !json_is_boolean(v)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "/nodes/%zu/extensions/" VIS "/visible: not true or false", i);
        }
        visible[i] = !json_is_false(v);
    }
    return SR_OK;
}

void sr__gltf_hide(sr_scene *scene, const long *parent, size_t n, const unsigned char *visible,
                   unsigned char *state, long *chain)
{
    /* state: 0 not known yet, 1 shown, 2 hidden; each node's found once
     * by walking up to the first known one. */
    memset(state, 0, n);
    for (size_t i = 0; i < n; i++) {
        size_t depth = 0;
        long v = (long)i;
        while (v >= 0 && !state[v]) {
            chain[depth++] = v;
            v = parent[v];
        }
        unsigned char up = v >= 0 ? state[v] : 1;
        while (depth > 0) {
            long w = chain[--depth];
            up = state[w] = up == 2 || !visible[w] ? 2 : 1;
        }
    }
    for (size_t i = 0; i < scene->primitive_count; i++) {
        int node = scene->primitives[i].node;
        if (node >= 0 && (size_t)node < n && state[node] == 2) {
            scene->primitives[i].triangle_count = 0;
        }
    }
    for (size_t i = 0; i < scene->light_count; i++) {
        int node = scene->lights[i].node;
        if (node >= 0 && (size_t)node < n && state[node] == 2) {
            scene->lights[i].light.type = SR_LIGHT_OFF;
        }
    }
}

sr_result sr__gltf_pointers_finish(gltf_doc *d, const long *parent, size_t n)
{
    size_t room = n ? n : 1;
    unsigned char *visible = malloc(room), *state = malloc(room);
    long *chain = malloc(room * sizeof *chain);
    sr_result r = visible && state && chain
                      ? sr__gltf_read_visibility(d, visible, n)
                      : sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/nodes: out of memory");
    if (r == SR_OK && !sr__gltf_posing_rest(d, visible)) {
        r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/animations: out of memory");
    }
    if (r == SR_OK) {
        if (d->applied) {
            sr__gltf_anim_apply_pointers(d->applied, d->desc->animation_time, d->scene, visible);
        }
        sr__gltf_hide(d->scene, parent, n, visible, state, chain);
    }
    free(visible);
    free(state);
    free(chain);
    return r;
}
