/*
 * load_gltf.c - io stage: glTF for sr_load_mesh through softrast's own
 * reader.  Consumes the sr_scene of sr_load_scene (the default scene's
 * node instances); produces one malloc'd sr_mesh in world space, as
 * Assimp's PreTransformVertices would, but with the reader that decodes
 * what Assimp misreads (KHR_mesh_quantization, meshopt, Draco).
 */
#include "io/io_util.h"
#include "io/readers.h"
#include "io/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The inverse transpose of world's upper 3x3 (column-major, as world),
 * up to a positive factor: normals are normalized after, so the
 * determinant's magnitude does not matter, only its sign. */
static void normal_matrix(const float *w, float n[9])
{
    float a = w[0], b = w[4], c = w[8];
    float d = w[1], e = w[5], f = w[9];
    float g = w[2], h = w[6], i = w[10];
    /* Cofactors of row-major [a b c; d e f; g h i]: the inverse transpose
     * times the determinant, here stored column-major. */
    float cof[9] = { e * i - f * h, -(d * i - f * g), d * h - e * g,
                     -(b * i - c * h), a * i - c * g, -(a * h - b * g),
                     b * f - c * e, -(a * f - c * d), a * e - b * d };
    float det = a * cof[0] + b * cof[1] + c * cof[2];
    float s = det < 0 ? -1.0f : 1.0f;
    /* cof[r * 3 + k] is row r, column k of the inverse transpose. */
    for (int r = 0; r < 3; r++) {
        for (int k = 0; k < 3; k++) {
            n[k * 3 + r] = s * cof[r * 3 + k];
        }
    }
}

static void put_point(const float *w, const float *p, float *o)
{
    for (int r = 0; r < 3; r++) {
        o[r] = w[r] * p[0] + w[4 + r] * p[1] + w[8 + r] * p[2] + w[12 + r];
    }
}

static void put_normal(const float *n, const float *v, float *o)
{
    float x = n[0] * v[0] + n[3] * v[1] + n[6] * v[2];
    float y = n[1] * v[0] + n[4] * v[1] + n[7] * v[2];
    float z = n[2] * v[0] + n[5] * v[1] + n[8] * v[2];
    float len = sqrtf(x * x + y * y + z * z);
    float k = len > 0 ? 1.0f / len : 0.0f;
    o[0] = x * k, o[1] = y * k, o[2] = z * k;
}

/* Whether the material tints its vertices: a base color other than white. */
static bool tints(const sr_scene *s, const sr_scene_primitive *p)
{
    if (p->material < 0 || (size_t)p->material >= s->material_count) {
        return false;
    }
    const float *c = s->materials[p->material].base_color;
    return c[0] != 1.0f || c[1] != 1.0f || c[2] != 1.0f || c[3] != 1.0f;
}

/* The base color slot of primitive p's material when it shows an image
 * (the for_mesh scene keeps its source), else NULL. */
static const sr_texture_slot *base_slot(const sr_scene *s, const sr_scene_primitive *p)
{
    size_t size;
    if (p->material < 0 || (size_t)p->material >= s->material_count ||
        !sr__scene_source(s, (size_t)p->material, &size)) {
        return NULL;
    }
    return &s->materials[p->material].base_color_texture;
}

/* The texture coordinates a primitive's mesh vertices take: the set its
 * base color texture reads (TEXCOORD_0 without one, or when the primitive
 * lacks TEXCOORD_1, which the reader warns about, as pbr falls back). */
static const float *mesh_uv(const sr_scene *s, const sr_scene_primitive *p)
{
    const sr_texture_slot *t = base_slot(s, p);
    return t && t->texcoord == 1 && p->texcoords1 ? p->texcoords1 : p->texcoords0;
}

/* The scene's instances as one mesh: an attribute some primitives lack is
 * dropped for all (as the Assimp reader does), but for color, which is the
 * vertex's own times the material's base color wherever any has either.
 * The texcoords are where the base color texture is sampled: its set and
 * KHR_texture_transform applied (exact: an affine map commutes with the
 * interpolation; its sampler a mesh cannot carry). */
static sr_result flatten(sr_context *ctx, const char *path, const sr_scene *s, sr_mesh *out,
                         sr_io_error *err)
{
    size_t verts = 0, tris = 0;
    bool normals = true, texcoords = true, colors = false;
    for (size_t i = 0; i < s->primitive_count; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        if (p->triangle_count == 0) {
            continue;
        }
        verts += p->vertex_count;
        tris += p->triangle_count;
        normals &= p->normals != NULL;
        texcoords &= mesh_uv(s, p) != NULL;
        colors |= p->colors != NULL || tints(s, p);
    }
    if (tris == 0) {
        return sr__io_fail(err, SR_BAD_FORMAT, path, 0, "contains no faces");
    }
    if (verts > SR_IO_MAX_VERTICES || tris > SR_IO_MAX_TRIANGLES) {
        return sr__io_fail(err, SR_TOO_LARGE, path, 0,
                           "%zu vertices and %zu triangles exceed the limits (%zu, %zu)", verts,
                           tris, (size_t)SR_IO_MAX_VERTICES, (size_t)SR_IO_MAX_TRIANGLES);
    }
    sr_mesh m;
    if (!sr__alloc_malloc_mesh(&m, verts, tris, normals, colors, texcoords)) {
        return sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory for %zu vertices",
                           verts);
    }
    size_t base = 0, t = 0;
    for (size_t i = 0; i < s->primitive_count; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        if (p->triangle_count == 0) {
            continue;
        }
        float nm[9];
        normal_matrix(p->world, nm);
        static const float white[4] = { 1, 1, 1, 1 };
        const float *tint = p->material >= 0 && (size_t)p->material < s->material_count
                                ? s->materials[p->material].base_color
                                : white;
        const float *uv = mesh_uv(s, p);
        for (size_t v = 0; v < p->vertex_count; v++) {
            size_t o = base + v;
            put_point(p->world, &p->positions[3 * v], &m.positions[3 * o]);
            if (normals) {
                put_normal(nm, &p->normals[3 * v], &m.normals[3 * o]);
            }
            if (texcoords) {
                memcpy(&m.texcoords[2 * o], &uv[2 * v], 2 * sizeof(float));
            }
            for (int k = 0; colors && k < 4; k++) {
                m.colors[4 * o + k] = (p->colors ? p->colors[4 * v + k] : 1.0f) * tint[k];
            }
        }
        /* A mirroring transform turns the front faces clockwise: swap two
         * corners to keep them counter-clockwise in world space. */
        for (size_t k = 0; k < p->triangle_count; k++, t++) {
            const uint32_t *src = &p->indices[3 * k];
            uint32_t *dst = &m.indices[3 * t];
            dst[0] = (uint32_t)base + src[0];
            dst[1] = (uint32_t)base + src[p->mirrored ? 2 : 1];
            dst[2] = (uint32_t)base + src[p->mirrored ? 1 : 2];
        }
        const sr_texture_slot *slot = base_slot(s, p);
        if (texcoords && slot &&
            sr_texture_slot_uv(ctx, slot, &m.texcoords[2 * base], p->vertex_count,
                               &m.texcoords[2 * base]) != SR_OK) {
            sr__free_malloc_mesh(&m);
            return sr__io_fail(err, SR_BAD_FORMAT, path, 0, "%s", sr_context_error(ctx));
        }
        base += p->vertex_count;
    }
    *out = m;
    return SR_OK;
}

/* The encoded base color image of primitive p's material, or NULL. */
static const uint8_t *base_image(const sr_scene *s, const sr_scene_primitive *p, size_t *size)
{
    if (p->material < 0 || (size_t)p->material >= s->material_count) {
        return NULL;
    }
    return sr__scene_source(s, (size_t)p->material, size);
}

static uint8_t *copy_bytes(const uint8_t *bytes, size_t size)
{
    uint8_t *c = malloc(size ? size : 1);
    if (c) {
        memcpy(c, bytes, size);
    }
    return c;
}

/* The base color images as the Assimp path gives textures: the first for
 * the whole mesh, and runs of primitives that take one image (or none)
 * as parts when there are several.  False when out of memory. */
static bool textures(const sr_scene *s, sr_mesh *m)
{
    size_t runs = 0, size = 0, first_size = 0;
    const uint8_t *prev = NULL, *first = NULL;
    for (size_t i = 0; i < s->primitive_count; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        if (p->triangle_count == 0) {
            continue;
        }
        const uint8_t *img = base_image(s, p, &size);
        runs += runs == 0 || img != prev;
        if (img && !first) {
            first = img;
            first_size = size;
        }
        prev = img;
    }
    if (!first) {
        return true;
    }
    if (!(m->texture_data = copy_bytes(first, first_size))) {
        return false;
    }
    m->texture_size = first_size;
    if (runs < 2) {
        return true;
    }
    if (!(m->parts = calloc(runs, sizeof *m->parts))) {
        return false;
    }
    size_t n = 0, t = 0;
    prev = NULL;
    for (size_t i = 0; i < s->primitive_count; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        if (p->triangle_count == 0) {
            continue;
        }
        const uint8_t *img = base_image(s, p, &size);
        if (n == 0 || img != prev) {
            sr_mesh_part *part = &m->parts[n++];
            m->part_count = n;
            part->first_triangle = t;
            if (img) {
                if (!(part->texture_data = copy_bytes(img, size))) {
                    return false; /* sr__free_malloc_mesh frees what the parts hold */
                }
                part->texture_size = size;
            }
        }
        m->parts[n - 1].triangle_count += p->triangle_count;
        t += p->triangle_count;
        prev = img;
    }
    return true;
}

sr_result sr__load_gltf_mesh(sr_context *ctx, const char *path, const sr_load_desc *desc,
                             sr_mesh *out, sr_io_error *err)
{
    sr_scene *s = NULL;
    sr_result r = sr__load_gltf_scene(ctx, path, desc, true, &s, err);
    if (r != SR_OK) {
        return r;
    }
    r = flatten(ctx, path, s, out, err);
    if (r == SR_OK && !textures(s, out)) {
        sr__free_malloc_mesh(out);
        r = sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory (the textures)");
    }
    sr_destroy_scene(ctx, s);
    return r;
}
