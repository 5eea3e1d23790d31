/*
 * gltf_material.c - io stage: glTF materials as sr_pbr_material.
 * Consumes /materials, /textures, /samplers and /images (PNG, JPEG or
 * WebP, from a bufferView, a file or a data: URI); produces the scene's
 * materials and the textures they point to, made on the context once per
 * image and color space (base color and emissive sRGB, the others linear).
 * KHR_texture_transform, KHR_materials_emissive_strength,
 * KHR_materials_unlit, the physically based layers KHR_materials_ior,
 * _specular, _clearcoat and _sheen, the base lobe's _anisotropy and
 * _iridescence, KHR_materials_transmission, _volume and _dispersion, and
 * KHR_materials_diffuse_transmission are applied, and the archived
 * KHR_materials_pbrSpecularGlossiness is read over the metallic-roughness
 * values.  Called by the thread reading the document.
 */
#include "io/gltf.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Frees an image's bytes as sr__gltf_read_uri gave them (NULL: a
 * bufferView's, not owned). */
static void free_image_bytes(char *owned, size_t size, bool from_file)
{
    if (from_file) {
        sr__free_file(owned, size);
    } else {
        free(owned);
    }
}

/* Image i's object (named by `use` in messages), checked. */
static sr_result image_object(gltf_doc *d, long i, const char *use, json_t **out)
{
    json_t *images;
    size_t n;
    sr_result r = sr__gltf_array(d, d->root, "", "images", &images, &n);
    if (r != SR_OK) {
        return r;
    }
    if (i < 0 || (size_t)i >= n) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: image %ld does not exist (%zu images)", use,
                             i, n);
    }
    if (!json_is_object(*out = json_array_get(images, (size_t)i))) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "/images/%ld: not an object", i);
    }
    return SR_OK;
}

/* Image i (object img) decoded into *pixels (w x h RGBA8, malloc'd):
 * its bytes from its URI or its bufferView.  With `keep`, also a copy of
 * the encoded bytes the scene owns, in *keep and *keep_size. */
static sr_result image_decode(gltf_doc *d, const json_t *img, long i, int *w, int *h,
                              uint8_t **pixels, const uint8_t **keep, size_t *keep_size)
{
    char ptr[GLTF_PTR];
    snprintf(ptr, sizeof ptr, "/images/%ld", i);
    json_t *uri = json_object_get(img, "uri");
    long view = -1;
    const uint8_t *bytes = NULL;
    size_t size = 0, stride;
    char *owned = NULL;
    bool from_file = false;
    sr_result r;
    if (uri) {
        char uptr[GLTF_PTR];
        snprintf(uptr, sizeof uptr, "%s/uri", ptr);
        if (!json_is_string(uri)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not a string", uptr);
        }
        if ((r = sr__gltf_read_uri(d, json_string_value(uri), uptr, &owned, &size,
                                   &from_file)) != SR_OK) {
            return r;
        }
        bytes = (const uint8_t *)owned;
    } else {
        char vptr[GLTF_PTR];
        snprintf(vptr, sizeof vptr, "%s/bufferView", ptr);
        if ((r = sr__gltf_index(d, img, ptr, "bufferView", (size_t)-1 / 2, true, &view)) !=
                SR_OK ||
            (r = sr__gltf_buffer_view(d, view, vptr, &bytes, &size, &stride)) != SR_OK) {
            return r;
        }
    }
    sr_io_error inner = {{0}};
    r = sr_decode_image(ptr, bytes, size, w, h, pixels, &inner);
    uint8_t *copy = r == SR_OK && keep ? malloc(size ? size : 1) : NULL;
    if (copy) {
        memcpy(copy, bytes, size);
    }
    free_image_bytes(owned, size, from_file);
    if (r != SR_OK) {
        /* inner reads "/images/N: what is wrong", the pointer first. */
        return sr__gltf_fail(d, r, "%s", inner.message);
    }
    if (keep && (!copy || !sr__scene_keep(d->scene, copy))) {
        free(*pixels);
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    if (keep) {
        *keep = copy;
        *keep_size = size;
    }
    return SR_OK;
}

/* Image i as a texture in the given color space, decoded on first use. */
static sr_result image_texture(gltf_doc *d, long i, const char *use, bool srgb,
                               const sr_texture **out)
{
    json_t *img;
    sr_result r = image_object(d, i, use, &img);
    if (r != SR_OK) {
        return r;
    }
    sr_texture **cached = &d->image_textures[2 * i + (srgb ? 1 : 0)];
    if (*cached) {
        *out = *cached;
        return SR_OK;
    }
    int w, h;
    uint8_t *pixels;
    if ((r = image_decode(d, img, i, &w, &h, &pixels, NULL, NULL)) != SR_OK) {
        return r;
    }
    sr_texture *tex = NULL;
    r = sr_make_texture(d->ctx, &(sr_texture_desc){ .width = w, .height = h, .pixels = pixels,
                                                    .srgb = srgb },
                        &tex);
    free(pixels);
    if (r != SR_OK || !sr__scene_add_texture(d->ctx, d->scene, tex)) {
        return sr__gltf_fail(d, r != SR_OK ? r : SR_OUT_OF_MEMORY, "/images/%ld: %s", i,
                             r != SR_OK ? sr_context_error(d->ctx) : "out of memory");
    }
    *cached = tex;
    *out = tex;
    return SR_OK;
}

/* for_mesh: image i's encoded bytes, kept by the scene, once checked by
 * decoding them (sr_load_mesh hands on only images that decode, with the
 * reader's error for one that does not); read on first use. */
static sr_result image_source(gltf_doc *d, long i, const char *use,
                              const gltf_image_source **out)
{
    json_t *img;
    sr_result r = image_object(d, i, use, &img);
    if (r != SR_OK) {
        return r;
    }
    gltf_image_source *cached = &d->image_sources[i];
    *out = cached;
    if (cached->bytes) {
        return SR_OK;
    }
    int w, h;
    uint8_t *pixels;
    if ((r = image_decode(d, img, i, &w, &h, &pixels, &cached->bytes, &cached->size)) ==
        SR_OK) {
        free(pixels);
    }
    return r;
}

/* A glTF sampler's filters and wraps on the slot. */
static sr_result read_sampler(gltf_doc *d, long s, const char *use, sr_texture_slot *slot)
{
    json_t *samplers, *sm;
    size_t n;
    sr_result r = sr__gltf_array(d, d->root, "", "samplers", &samplers, &n);
    if (r != SR_OK) {
        return r;
    }
    if (s < 0 || (size_t)s >= n || !json_is_object(sm = json_array_get(samplers, (size_t)s))) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: sampler %ld does not exist", use, s);
    }
    char ptr[GLTF_PTR];
    snprintf(ptr, sizeof ptr, "/samplers/%ld", s);
    long mag = 0, min = 0, wrap[2] = { 10497, 10497 };
    if ((r = sr__gltf_index(d, sm, ptr, "magFilter", 100000, false, &mag)) != SR_OK ||
        (r = sr__gltf_index(d, sm, ptr, "minFilter", 100000, false, &min)) != SR_OK ||
        (r = sr__gltf_index(d, sm, ptr, "wrapS", 100000, false, &wrap[0])) != SR_OK ||
        (r = sr__gltf_index(d, sm, ptr, "wrapT", 100000, false, &wrap[1])) != SR_OK) {
        return r;
    }
    /* One filter does for both: the minification filter decides (mipmaps
     * or not), NEAREST magnification alone asks for nearest texels. */
    switch (min) {
    case 9728: slot->filter = SR_FILTER_NEAREST; break;
    case 9729: slot->filter = SR_FILTER_BILINEAR; break;
    case 9984: case 9985: case 9986: case 9987: slot->filter = SR_FILTER_TRILINEAR; break;
    case 0: slot->filter = mag == 9728 ? SR_FILTER_NEAREST : SR_FILTER_TRILINEAR; break;
    default:
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/minFilter: %ld is not a filter", ptr, min);
    }
    if (mag != 0 && mag != 9728 && mag != 9729) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/magFilter: %ld is not a filter", ptr, mag);
    }
    sr_texture_wrap *out[2] = { &slot->wrap_u, &slot->wrap_v };
    for (int k = 0; k < 2; k++) {
        switch (wrap[k]) {
        case 10497: *out[k] = SR_WRAP_REPEAT; break;
        case 33071: *out[k] = SR_WRAP_CLAMP; break;
        case 33648: *out[k] = SR_WRAP_MIRROR; break;
        default:
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: %ld is not a wrap mode", ptr,
                                 k ? "wrapT" : "wrapS", wrap[k]);
        }
    }
    return SR_OK;
}

/* KHR_texture_transform into the slot, in sr_make_texture's uv (v up):
 * glTF's uv' = T(o) R(r) S(s) uv, with v flipped on both sides, is
 * T(o') R(r) S(s) with o' = (o.x + s.y sin r, 1 - o.y - s.y cos r), R
 * counter-clockwise in the flipped space (docs/gltf.md derives it). */
bool sr__gltf_slot_transform(sr_texture_slot *slot, const float o[2], float rot,
                             const float s[2])
{
    float offset[2] = { o[0] + s[1] * sinf(rot), 1.0f - o[1] - s[1] * cosf(rot) };
    if (!isfinite(offset[0]) || !isfinite(offset[1])) {
        return false;
    }
    slot->offset[0] = offset[0];
    slot->offset[1] = offset[1];
    slot->rotation = rot;
    slot->scale[0] = s[0];
    slot->scale[1] = s[1];
    slot->scale_set = true;
    return true;
}

static sr_result read_transform(gltf_doc *d, const json_t *info, const char *ptr,
                                sr_texture_slot *slot, long *texcoord)
{
    json_t *t = sr__gltf_extension(info, "KHR_texture_transform");
    float o[2] = { 0, 0 }, s[2] = { 1, 1 }, rot = 0;
    char tptr[GLTF_PTR];
    snprintf(tptr, sizeof tptr, "%s/extensions/KHR_texture_transform", ptr);
    if (t) {
        sr_result r;
        if ((r = sr__gltf_numbers(d, t, tptr, "offset", 2, o)) != SR_OK ||
            (r = sr__gltf_numbers(d, t, tptr, "scale", 2, s)) != SR_OK ||
            (r = sr__gltf_number(d, t, tptr, "rotation", &rot)) != SR_OK ||
            (r = sr__gltf_index(d, t, tptr, "texCoord", 1000, false, texcoord)) != SR_OK) {
            return r;
        }
    }
    /* Each value finite, their sum (offset plus scale) need not be. */
    if (!sr__gltf_slot_transform(slot, o, rot, s)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: offset (%g, %g) and scale (%g, %g) "
                             "overflow a float together", tptr, (double)o[0], (double)o[1],
                             (double)s[0], (double)s[1]);
    }
    return SR_OK;
}

/* A textureInfo (material member `key`) into a slot; an absent one leaves
 * the slot empty.  `extra` ("scale", "strength") goes to *extra_value.
 * d->slot_image: the image it shows, or -1.  for_mesh reads no image
 * (read_material reads the base color's) and leaves the slot empty. */
static sr_result read_slot(gltf_doc *d, const json_t *owner, const char *owner_ptr,
                           const char *key, bool srgb, sr_texture_slot *slot, const char *extra,
                           float *extra_value)
{
    json_t *info;
    d->slot_image = -1;
    sr_result r = sr__gltf_object(d, owner, owner_ptr, key, &info);
    if (r != SR_OK || !info) {
        return r;
    }
    char ptr[GLTF_PTR];
    snprintf(ptr, sizeof ptr, "%s/%s", owner_ptr, key);
    long tex = -1, texcoord = 0;
    if ((r = sr__gltf_index(d, info, ptr, "index", (size_t)-1 / 2, true, &tex)) != SR_OK ||
        (r = sr__gltf_index(d, info, ptr, "texCoord", 1000, false, &texcoord)) != SR_OK ||
        (extra && (r = sr__gltf_number(d, info, ptr, extra, extra_value)) != SR_OK) ||
        (r = read_transform(d, info, ptr, slot, &texcoord)) != SR_OK) {
        return r;
    }
    json_t *textures, *t;
    size_t n;
    if ((r = sr__gltf_array(d, d->root, "", "textures", &textures, &n)) != SR_OK) {
        return r;
    }
    if ((size_t)tex >= n || !json_is_object(t = json_array_get(textures, (size_t)tex))) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/index: texture %ld does not exist", ptr, tex);
    }
    if (texcoord > 1) {
        sr__gltf_warn(d, "%s/texCoord: set %ld is not read (only 0 and 1), texture dropped", ptr,
                      texcoord);
        return SR_OK;
    }
    char tptr[GLTF_PTR];
    snprintf(tptr, sizeof tptr, "/textures/%ld", tex);
    long source = -1, sampler = -1;
    if ((r = sr__gltf_index(d, t, tptr, "source", (size_t)-1 / 2, false, &source)) != SR_OK ||
        (r = sr__gltf_index(d, t, tptr, "sampler", (size_t)-1 / 2, false, &sampler)) != SR_OK) {
        return r;
    }
    char use[GLTF_PTR];
    snprintf(use, sizeof use, "%s/source", tptr);
    /* EXT_texture_webp's image is taken over `source`, which is then a
     * fallback for readers without WebP. */
    json_t *webp = sr__gltf_extension(t, "EXT_texture_webp");
    if (webp && sr__io_have_webp()) {
        char wptr[GLTF_PTR];
        snprintf(wptr, sizeof wptr, "%s/extensions/EXT_texture_webp", tptr);
        if ((r = sr__gltf_index(d, webp, wptr, "source", (size_t)-1 / 2, true, &source)) !=
            SR_OK) {
            return r;
        }
        snprintf(use, sizeof use, "%s/source", wptr);
    }
    if (source < 0) {
        if (webp) {
            sr__gltf_warn(d, "%s: only a WebP source (EXT_texture_webp), and softrast was built "
                             "without libwebp: texture dropped", tptr);
        } else {
            sr__gltf_warn(d, "%s: no PNG or JPEG source, texture dropped", tptr);
        }
        return SR_OK;
    }
    json_t *img;
    if ((r = d->for_mesh ? image_object(d, source, use, &img)
                         : image_texture(d, source, use, srgb, &slot->texture)) != SR_OK) {
        return r;
    }
    d->slot_image = source;
    snprintf(use, sizeof use, "%s/sampler", tptr);
    if (sampler >= 0 && (r = read_sampler(d, sampler, use, slot)) != SR_OK) {
        return r;
    }
    slot->texcoord = (int)texcoord;
    return SR_OK;
}

static void default_material(sr_pbr_material *m)
{
    memset(m, 0, sizeof *m);
    for (int c = 0; c < 4; c++) {
        m->base_color[c] = 1;
    }
    m->metallic = m->roughness = 1;
    m->normal_scale = m->occlusion_strength = m->emissive_strength = 1;
    m->alpha_cutoff = 0.5f;
    for (int c = 0; c < 3; c++) {
        m->attenuation_color[c] = 1;
        m->diffuse_transmission_color[c] = 1;
    }
}

/* The specification's range of a factor: a value outside (which an
 * exporter's rounding cannot make, read as a float) is clamped with a
 * warning, since a metallic of 5 or a negative color draws black and a
 * negative emission takes light away. */
static void clamp_factor(gltf_doc *d, const char *ptr, float *v, float lo, float hi)
{
    if (*v >= lo && *v <= hi) {
        return;
    }
    float to = *v < lo ? lo : hi;
    if (hi == FLT_MAX) {
        sr__gltf_warn(d, "%s: %g is negative, taken as 0", ptr, (double)*v);
    } else {
        sr__gltf_warn(d, "%s: %g is outside the specification's %g..%g, taken as %g", ptr,
                      (double)*v, (double)lo, (double)hi, (double)to);
    }
    *v = to;
}

/* clamp_factor on each of the n numbers of the array member `key` of
 * the object at ptr. */
static void clamp_each(gltf_doc *d, const char *ptr, const char *key, float *v, int n, float lo,
                       float hi)
{
    char at[GLTF_PTR + 64];
    for (int c = 0; c < n; c++) {
        snprintf(at, sizeof at, "%s/%s/%d", ptr, key, c);
        clamp_factor(d, at, &v[c], lo, hi);
    }
}

static void clamp_factors(gltf_doc *d, const char *ptr, sr_pbr_material *m)
{
    char at[GLTF_PTR + 64];
    for (int c = 0; c < 4; c++) {
        snprintf(at, sizeof at, "%s/pbrMetallicRoughness/baseColorFactor/%d", ptr, c);
        clamp_factor(d, at, &m->base_color[c], 0, 1);
    }
    snprintf(at, sizeof at, "%s/pbrMetallicRoughness/metallicFactor", ptr);
    clamp_factor(d, at, &m->metallic, 0, 1);
    snprintf(at, sizeof at, "%s/pbrMetallicRoughness/roughnessFactor", ptr);
    clamp_factor(d, at, &m->roughness, 0, 1);
    for (int c = 0; c < 3; c++) {
        snprintf(at, sizeof at, "%s/emissiveFactor/%d", ptr, c);
        clamp_factor(d, at, &m->emissive[c], 0, 1);
    }
    snprintf(at, sizeof at, "%s/extensions/KHR_materials_emissive_strength/emissiveStrength",
             ptr);
    clamp_factor(d, at, &m->emissive_strength, 0, FLT_MAX);
    snprintf(at, sizeof at, "%s/occlusionTexture/strength", ptr);
    clamp_factor(d, at, &m->occlusion_strength, 0, 1);
    snprintf(at, sizeof at, "%s/alphaCutoff", ptr);
    clamp_factor(d, at, &m->alpha_cutoff, 0, FLT_MAX);
}

/* KHR_materials_transmission's factor and texture (R), and
 * KHR_materials_volume's thickness factor and texture (G), attenuation
 * color and distance, their factors clamped to the extensions' ranges
 * with a warning each.  An absent attenuationDistance is infinite: no
 * absorption (0 in sr_pbr_material). */
static sr_result read_transmission(gltf_doc *d, const json_t *mat, const char *ptr,
                                   sr_pbr_material *m)
{
    char eptr[GLTF_PTR], at[GLTF_PTR + 64];
    sr_result r;
    json_t *tr = sr__gltf_extension(mat, "KHR_materials_transmission");
    if (tr) {
        snprintf(eptr, sizeof eptr, "%s/extensions/KHR_materials_transmission", ptr);
        if ((r = sr__gltf_number(d, tr, eptr, "transmissionFactor", &m->transmission)) != SR_OK ||
            (r = read_slot(d, tr, eptr, "transmissionTexture", false, &m->transmission_texture,
                           NULL, NULL)) != SR_OK) {
            return r;
        }
        snprintf(at, sizeof at, "%s/transmissionFactor", eptr);
        clamp_factor(d, at, &m->transmission, 0, 1);
    }
    json_t *vol = sr__gltf_extension(mat, "KHR_materials_volume");
    if (vol) {
        snprintf(eptr, sizeof eptr, "%s/extensions/KHR_materials_volume", ptr);
        float dist = 0;
        if ((r = sr__gltf_number(d, vol, eptr, "thicknessFactor", &m->thickness)) != SR_OK ||
            (r = read_slot(d, vol, eptr, "thicknessTexture", false, &m->thickness_texture, NULL,
                           NULL)) != SR_OK ||
            (r = sr__gltf_numbers(d, vol, eptr, "attenuationColor", 3, m->attenuation_color)) !=
                SR_OK ||
            (r = sr__gltf_number(d, vol, eptr, "attenuationDistance", &dist)) != SR_OK) {
            return r;
        }
        snprintf(at, sizeof at, "%s/thicknessFactor", eptr);
        clamp_factor(d, at, &m->thickness, 0, FLT_MAX);
        clamp_each(d, eptr, "attenuationColor", m->attenuation_color, 3, 0, 1);
        if (json_object_get(vol, "attenuationDistance") && !(dist > 0)) {
            sr__gltf_warn(d, "%s/attenuationDistance: %g is not positive, taken as infinite",
                          eptr, (double)dist);
            dist = 0;
        }
        m->attenuation_distance = dist;
    }
    return SR_OK;
}

/* KHR_materials_anisotropy (object x at xptr): strength, rotation and
 * texture, the strength clamped to 0..1 with a warning. */
static sr_result read_anisotropy(gltf_doc *d, const json_t *x, const char *xptr,
                                 sr_pbr_material *m)
{
    char at[GLTF_PTR + 64];
    sr_result r;
    if ((r = sr__gltf_number(d, x, xptr, "anisotropyStrength", &m->anisotropy_strength)) !=
            SR_OK ||
        (r = sr__gltf_number(d, x, xptr, "anisotropyRotation", &m->anisotropy_rotation)) !=
            SR_OK ||
        (r = read_slot(d, x, xptr, "anisotropyTexture", false, &m->anisotropy_texture, NULL,
                       NULL)) != SR_OK) {
        return r;
    }
    snprintf(at, sizeof at, "%s/anisotropyStrength", xptr);
    clamp_factor(d, at, &m->anisotropy_strength, 0, 1);
    return SR_OK;
}

/* KHR_materials_iridescence (object x at xptr) with the extension's
 * defaults (ior 1.3, thickness 100..400 nm), factors clamped with a
 * warning each.  The thicknesses are the file's (iridescence_thickness_set),
 * so a film 0 nm thick is no film while its factor stays the file's, for
 * an animation that thickens it. */
static sr_result read_iridescence(gltf_doc *d, const json_t *x, const char *xptr,
                                  sr_pbr_material *m)
{
    char at[GLTF_PTR + 64];
    sr_result r;
    float ior = 1.3f, lo = 100.0f, hi = 400.0f;
    if ((r = sr__gltf_number(d, x, xptr, "iridescenceFactor", &m->iridescence)) != SR_OK ||
        (r = sr__gltf_number(d, x, xptr, "iridescenceIor", &ior)) != SR_OK ||
        (r = sr__gltf_number(d, x, xptr, "iridescenceThicknessMinimum", &lo)) != SR_OK ||
        (r = sr__gltf_number(d, x, xptr, "iridescenceThicknessMaximum", &hi)) != SR_OK ||
        (r = read_slot(d, x, xptr, "iridescenceTexture", false, &m->iridescence_texture, NULL,
                       NULL)) != SR_OK ||
        (r = read_slot(d, x, xptr, "iridescenceThicknessTexture", false,
                       &m->iridescence_thickness_texture, NULL, NULL)) != SR_OK) {
        return r;
    }
    snprintf(at, sizeof at, "%s/iridescenceFactor", xptr);
    clamp_factor(d, at, &m->iridescence, 0, 1);
    if (!(ior >= 1.0f)) {
        sr__gltf_warn(d, "%s/iridescenceIor: %g is under the specification's minimum 1, "
                         "taken as 1", xptr, (double)ior);
        ior = 1.0f;
    }
    snprintf(at, sizeof at, "%s/iridescenceThicknessMinimum", xptr);
    clamp_factor(d, at, &lo, 0, FLT_MAX);
    snprintf(at, sizeof at, "%s/iridescenceThicknessMaximum", xptr);
    clamp_factor(d, at, &hi, 0, FLT_MAX);
    m->iridescence_ior = ior;
    m->iridescence_thickness_set = true;
    m->iridescence_thickness_min = lo;
    m->iridescence_thickness_max = hi;
    return SR_OK;
}

/* KHR_materials_dispersion's factor and KHR_materials_diffuse_transmission
 * (its factor and texture (A), color and texture (sRGB RGB)), their
 * factors clamped to the extensions' ranges with a warning each. */
static sr_result read_translucency(gltf_doc *d, const json_t *mat, const char *ptr,
                                   sr_pbr_material *m)
{
    char xptr[GLTF_PTR], at[GLTF_PTR + 64];
    sr_result r;
    json_t *x;
    if ((x = sr__gltf_extension(mat, "KHR_materials_dispersion"))) {
        snprintf(xptr, sizeof xptr, "%s/extensions/KHR_materials_dispersion", ptr);
        if ((r = sr__gltf_number(d, x, xptr, "dispersion", &m->dispersion)) != SR_OK) {
            return r;
        }
        snprintf(at, sizeof at, "%s/dispersion", xptr);
        clamp_factor(d, at, &m->dispersion, 0, FLT_MAX);
    }
    if ((x = sr__gltf_extension(mat, "KHR_materials_diffuse_transmission"))) {
        snprintf(xptr, sizeof xptr, "%s/extensions/KHR_materials_diffuse_transmission", ptr);
        if ((r = sr__gltf_number(d, x, xptr, "diffuseTransmissionFactor",
                                 &m->diffuse_transmission)) != SR_OK ||
            (r = read_slot(d, x, xptr, "diffuseTransmissionTexture", false,
                           &m->diffuse_transmission_texture, NULL, NULL)) != SR_OK ||
            (r = sr__gltf_numbers(d, x, xptr, "diffuseTransmissionColorFactor", 3,
                                  m->diffuse_transmission_color)) != SR_OK ||
            (r = read_slot(d, x, xptr, "diffuseTransmissionColorTexture", true,
                           &m->diffuse_transmission_color_texture, NULL, NULL)) != SR_OK) {
            return r;
        }
        snprintf(at, sizeof at, "%s/diffuseTransmissionFactor", xptr);
        clamp_factor(d, at, &m->diffuse_transmission, 0, 1);
        clamp_each(d, xptr, "diffuseTransmissionColorFactor", m->diffuse_transmission_color, 3,
                   0, 1);
    }
    return SR_OK;
}

/* KHR_materials_ior, _specular, _clearcoat, _sheen, _anisotropy and
 * _iridescence into the material's extension fields (sr_pbr_material:
 * zero is absent), with
 * each extension's defaults where it is present; factors outside the
 * specification's ranges are clamped with one warning each. */
static sr_result read_layers(gltf_doc *d, const json_t *mat, const char *ptr,
                             sr_pbr_material *m)
{
    char xptr[GLTF_PTR], at[GLTF_PTR + 64];
    sr_result r;
    json_t *x;
    if ((x = sr__gltf_extension(mat, "KHR_materials_ior"))) {
        snprintf(xptr, sizeof xptr, "%s/extensions/KHR_materials_ior", ptr);
        m->ior = 1.5f;
        if ((r = sr__gltf_number(d, x, xptr, "ior", &m->ior)) != SR_OK) {
            return r;
        }
        if (!(m->ior >= 1.0f)) {
            sr__gltf_warn(d, "%s/ior: %g is under the specification's minimum 1, taken as 1",
                          xptr, (double)m->ior);
            m->ior = 1.0f;
        }
    }
    if ((x = sr__gltf_extension(mat, "KHR_materials_specular"))) {
        snprintf(xptr, sizeof xptr, "%s/extensions/KHR_materials_specular", ptr);
        m->specular_set = true;
        m->specular = 1.0f;
        m->specular_color[0] = m->specular_color[1] = m->specular_color[2] = 1.0f;
        if ((r = sr__gltf_number(d, x, xptr, "specularFactor", &m->specular)) != SR_OK ||
            (r = sr__gltf_numbers(d, x, xptr, "specularColorFactor", 3, m->specular_color)) !=
                SR_OK ||
            (r = read_slot(d, x, xptr, "specularTexture", false, &m->specular_texture, NULL,
                           NULL)) != SR_OK ||
            (r = read_slot(d, x, xptr, "specularColorTexture", true, &m->specular_color_texture,
                           NULL, NULL)) != SR_OK) {
            return r;
        }
        snprintf(at, sizeof at, "%s/specularFactor", xptr);
        clamp_factor(d, at, &m->specular, 0, 1);
        clamp_each(d, xptr, "specularColorFactor", m->specular_color, 3, 0, FLT_MAX);
    }
    if ((x = sr__gltf_extension(mat, "KHR_materials_clearcoat"))) {
        snprintf(xptr, sizeof xptr, "%s/extensions/KHR_materials_clearcoat", ptr);
        m->clearcoat_normal_scale = 1.0f;
        if ((r = sr__gltf_number(d, x, xptr, "clearcoatFactor", &m->clearcoat)) != SR_OK ||
            (r = sr__gltf_number(d, x, xptr, "clearcoatRoughnessFactor",
                                 &m->clearcoat_roughness)) != SR_OK ||
            (r = read_slot(d, x, xptr, "clearcoatTexture", false, &m->clearcoat_texture, NULL,
                           NULL)) != SR_OK ||
            (r = read_slot(d, x, xptr, "clearcoatRoughnessTexture", false,
                           &m->clearcoat_roughness_texture, NULL, NULL)) != SR_OK ||
            (r = read_slot(d, x, xptr, "clearcoatNormalTexture", false,
                           &m->clearcoat_normal_texture, "scale", &m->clearcoat_normal_scale)) !=
                SR_OK) {
            return r;
        }
        snprintf(at, sizeof at, "%s/clearcoatFactor", xptr);
        clamp_factor(d, at, &m->clearcoat, 0, 1);
        snprintf(at, sizeof at, "%s/clearcoatRoughnessFactor", xptr);
        clamp_factor(d, at, &m->clearcoat_roughness, 0, 1);
        if (m->clearcoat_normal_scale == 0.0f) {
            /* A flat map: the geometry's normal, which sr_pbr_material
             * says with an empty slot (its zero scale reads as 1). */
            m->clearcoat_normal_texture.texture = NULL;
        }
    }
    if ((x = sr__gltf_extension(mat, "KHR_materials_sheen"))) {
        snprintf(xptr, sizeof xptr, "%s/extensions/KHR_materials_sheen", ptr);
        if ((r = sr__gltf_numbers(d, x, xptr, "sheenColorFactor", 3, m->sheen_color)) != SR_OK ||
            (r = sr__gltf_number(d, x, xptr, "sheenRoughnessFactor", &m->sheen_roughness)) !=
                SR_OK ||
            (r = read_slot(d, x, xptr, "sheenColorTexture", true, &m->sheen_color_texture, NULL,
                           NULL)) != SR_OK ||
            (r = read_slot(d, x, xptr, "sheenRoughnessTexture", false,
                           &m->sheen_roughness_texture, NULL, NULL)) != SR_OK) {
            return r;
        }
        clamp_each(d, xptr, "sheenColorFactor", m->sheen_color, 3, 0, 1);
        snprintf(at, sizeof at, "%s/sheenRoughnessFactor", xptr);
        clamp_factor(d, at, &m->sheen_roughness, 0, 1);
    }
    if ((x = sr__gltf_extension(mat, "KHR_materials_anisotropy"))) {
        snprintf(xptr, sizeof xptr, "%s/extensions/KHR_materials_anisotropy", ptr);
        if ((r = read_anisotropy(d, x, xptr, m)) != SR_OK) {
            return r;
        }
    }
    if ((x = sr__gltf_extension(mat, "KHR_materials_iridescence"))) {
        snprintf(xptr, sizeof xptr, "%s/extensions/KHR_materials_iridescence", ptr);
        if ((r = read_iridescence(d, x, xptr, m)) != SR_OK) {
            return r;
        }
    }
    return read_translucency(d, mat, ptr, m);
}

/* KHR_materials_pbrSpecularGlossiness (object x at xptr) over the
 * metallic-roughness values, which the extension says a reader of it
 * draws instead: the diffuse factor and texture (sRGB, alpha) are the
 * base color, the specular color, glossiness and their texture (sRGB RGB,
 * linear A) sr_pbr_material's, with the extension's defaults (white,
 * glossiness 1); factors outside 0..1 clamped with a warning each.
 * *base_image: the diffuse texture's image, or -1. */
static sr_result read_spec_gloss(gltf_doc *d, const json_t *x, const char *xptr,
                                 sr_pbr_material *m, long *base_image)
{
    char at[GLTF_PTR + 64];
    sr_result r;
    m->specular_glossiness = true;
    for (int c = 0; c < 4; c++) {
        m->base_color[c] = 1.0f;
    }
    for (int c = 0; c < 3; c++) {
        m->sg_specular[c] = 1.0f;
    }
    m->glossiness = 1.0f;
    m->base_color_texture = (sr_texture_slot){ 0 };
    m->metallic_roughness_texture = (sr_texture_slot){ 0 };
    if ((r = sr__gltf_numbers(d, x, xptr, "diffuseFactor", 4, m->base_color)) != SR_OK ||
        (r = read_slot(d, x, xptr, "diffuseTexture", true, &m->base_color_texture, NULL,
                       NULL)) != SR_OK) {
        return r;
    }
    *base_image = d->slot_image;
    if ((r = sr__gltf_numbers(d, x, xptr, "specularFactor", 3, m->sg_specular)) != SR_OK ||
        (r = sr__gltf_number(d, x, xptr, "glossinessFactor", &m->glossiness)) != SR_OK ||
        (r = read_slot(d, x, xptr, "specularGlossinessTexture", true,
                       &m->specular_glossiness_texture, NULL, NULL)) != SR_OK) {
        return r;
    }
    clamp_each(d, xptr, "diffuseFactor", m->base_color, 4, 0, 1);
    clamp_each(d, xptr, "specularFactor", m->sg_specular, 3, 0, 1);
    snprintf(at, sizeof at, "%s/glossinessFactor", xptr);
    clamp_factor(d, at, &m->glossiness, 0, 1);
    return SR_OK;
}

/* The material extensions whose specifications exclude
 * KHR_materials_pbrSpecularGlossiness: each extends the metallic-roughness
 * model's BRDF, which the archived extension replaces with its own
 * inputs.  KHR_materials_emissive_strength and _unlit do not exclude it. */
static const char *const spec_gloss_excluded[] = {
    "KHR_materials_ior",          "KHR_materials_specular",     "KHR_materials_clearcoat",
    "KHR_materials_sheen",        "KHR_materials_transmission", "KHR_materials_volume",
    "KHR_materials_dispersion",   "KHR_materials_anisotropy",   "KHR_materials_iridescence",
    "KHR_materials_diffuse_transmission",
};

bool sr__gltf_spec_gloss_excludes(const char *name)
{
    for (size_t i = 0; i < sizeof spec_gloss_excluded / sizeof *spec_gloss_excluded; i++) {
        if (strcmp(name, spec_gloss_excluded[i]) == 0) {
            return true;
        }
    }
    return false;
}

/* Material `mat` into m; *base_image: the image its base color texture
 * shows, or -1. */
static sr_result read_material(gltf_doc *d, const json_t *mat, const char *ptr,
                               sr_pbr_material *m, long *base_image)
{
    *base_image = -1;
    default_material(m);
    if (!json_is_object(mat)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
    }
    json_t *pbr;
    char pptr[GLTF_PTR];
    snprintf(pptr, sizeof pptr, "%s/pbrMetallicRoughness", ptr);
    sr_result r;
    if ((r = sr__gltf_object(d, mat, ptr, "pbrMetallicRoughness", &pbr)) != SR_OK) {
        return r;
    }
    if (pbr && ((r = sr__gltf_numbers(d, pbr, pptr, "baseColorFactor", 4, m->base_color)) !=
                    SR_OK ||
                (r = sr__gltf_number(d, pbr, pptr, "metallicFactor", &m->metallic)) != SR_OK ||
                (r = sr__gltf_number(d, pbr, pptr, "roughnessFactor", &m->roughness)) != SR_OK ||
                (r = read_slot(d, pbr, pptr, "baseColorTexture", true, &m->base_color_texture,
                               NULL, NULL)) != SR_OK)) {
        return r;
    }
    *base_image = pbr ? d->slot_image : -1;
    if (pbr && (r = read_slot(d, pbr, pptr, "metallicRoughnessTexture", false,
                              &m->metallic_roughness_texture, NULL, NULL)) != SR_OK) {
        return r;
    }
    if ((r = read_slot(d, mat, ptr, "normalTexture", false, &m->normal_texture, "scale",
                       &m->normal_scale)) != SR_OK ||
        (r = read_slot(d, mat, ptr, "occlusionTexture", false, &m->occlusion_texture, "strength",
                       &m->occlusion_strength)) != SR_OK ||
        (r = read_slot(d, mat, ptr, "emissiveTexture", true, &m->emissive_texture, NULL, NULL)) !=
            SR_OK ||
        (r = sr__gltf_numbers(d, mat, ptr, "emissiveFactor", 3, m->emissive)) != SR_OK ||
        (r = sr__gltf_number(d, mat, ptr, "alphaCutoff", &m->alpha_cutoff)) != SR_OK) {
        return r;
    }
    json_t *mode = json_object_get(mat, "alphaMode"), *ds = json_object_get(mat, "doubleSided");
    if (mode) {
        const char *s = json_is_string(mode) ? json_string_value(mode) : "";
        if (strcmp(s, "OPAQUE") == 0) {
            m->alpha_mode = SR_ALPHA_OPAQUE;
        } else if (strcmp(s, "MASK") == 0) {
            m->alpha_mode = SR_ALPHA_MASK;
        } else if (strcmp(s, "BLEND") == 0) {
            m->alpha_mode = SR_ALPHA_BLEND;
        } else {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/alphaMode: not OPAQUE, MASK or BLEND", ptr);
        }
    }
    if (ds && !json_is_boolean(ds)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/doubleSided: not true or false", ptr);
    }
    m->double_sided = json_is_true(ds);
    json_t *es = sr__gltf_extension(mat, "KHR_materials_emissive_strength");
    if (es) {
        char eptr[GLTF_PTR];
        snprintf(eptr, sizeof eptr, "%s/extensions/KHR_materials_emissive_strength", ptr);
        if ((r = sr__gltf_number(d, es, eptr, "emissiveStrength", &m->emissive_strength)) !=
            SR_OK) {
            return r;
        }
    }
    m->unlit = sr__gltf_extension(mat, "KHR_materials_unlit") != NULL;
    json_t *sg = sr__gltf_extension(mat, "KHR_materials_pbrSpecularGlossiness");
    if (sg) {
        char sptr[GLTF_PTR];
        snprintf(sptr, sizeof sptr, "%s/extensions/KHR_materials_pbrSpecularGlossiness", ptr);
        if ((r = read_spec_gloss(d, sg, sptr, m, base_image)) != SR_OK) {
            return r;
        }
    }
    if (sg) {
        /* Each of these says it must not be used with the archived
         * extension, whose BRDF inputs it would change: not read, as a
         * reader of the specification draws such a (non-conforming)
         * material, one warning each. */
        for (size_t i = 0; i < sizeof spec_gloss_excluded / sizeof *spec_gloss_excluded; i++) {
            if (sr__gltf_extension(mat, spec_gloss_excluded[i])) {
                sr__gltf_warn(d, "%s/extensions/%s: not read on a material with "
                                 "KHR_materials_pbrSpecularGlossiness (the extensions exclude "
                                 "each other)", ptr, spec_gloss_excluded[i]);
            }
        }
    } else if ((r = read_transmission(d, mat, ptr, m)) != SR_OK ||
               (!m->unlit && (r = read_layers(d, mat, ptr, m)) != SR_OK)) {
        return r;
    }
    clamp_factors(d, ptr, m);
    /* The strength is the file's (emissive_strength_set): 0 is no
     * emission while the factor stays the file's, for an animation that
     * raises the strength.  A cutoff of 0, which sr_pbr_material reads as
     * its default, keeps every fragment: opaque. */
    m->emissive_strength_set = true;
    if (m->alpha_mode == SR_ALPHA_MASK && m->alpha_cutoff <= 0) {
        m->alpha_mode = SR_ALPHA_OPAQUE;
    }
    return SR_OK;
}

sr_result sr__gltf_read_materials(gltf_doc *d)
{
    json_t *mats;
    size_t n;
    sr_result r = sr__gltf_array(d, d->root, "", "materials", &mats, &n);
    if (r != SR_OK) {
        return r;
    }
    sr_pbr_material *m = sr__scene_grow(d->scene, (void **)&d->scene->materials,
                                        &d->scene->material_count, sizeof *m, n + 1);
    if (!m) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/materials: out of memory");
    }
    for (size_t i = 0; i < n; i++) {
        char ptr[GLTF_PTR];
        snprintf(ptr, sizeof ptr, "/materials/%zu", i);
        long base = -1;
        if ((r = read_material(d, json_array_get(mats, i), ptr, &m[i], &base)) != SR_OK) {
            return r;
        }
        if (d->for_mesh && base >= 0) {
            /* sr_load_mesh hands on the base color images, encoded. */
            char use[GLTF_PTR];
            snprintf(use, sizeof use, "%s/%s", ptr,
                     m[i].specular_glossiness
                         ? "extensions/KHR_materials_pbrSpecularGlossiness/diffuseTexture"
                         : "pbrMetallicRoughness/baseColorTexture");
            const gltf_image_source *src;
            if ((r = image_source(d, base, use, &src)) != SR_OK) {
                return r;
            }
            if (!sr__scene_add_source(d->scene, i, src->bytes, src->size)) {
                return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
            }
        }
    }
    default_material(&m[n]);
    d->scene->default_material = (int)n;
    return SR_OK;
}
