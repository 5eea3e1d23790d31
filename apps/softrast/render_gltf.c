/* render_gltf.c - a glTF file for `softrast render`: sr_load_scene's
 * primitives merged into one scene object in world space, a part per
 * primitive with its material (so the framing, --up and --turn treat the
 * file as one model), and the file's cameras for --camera-index. */
#include "cli.h"
#include "render_gltf.h"
#include "softrast_io.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

bool render_gltf_is(const char *path)
{
    const char *dot = path ? strrchr(path, '.') : NULL;
    return dot && (strcasecmp(dot, ".gltf") == 0 || strcasecmp(dot, ".glb") == 0);
}

/* The reader words its warnings "FILE: warning: ...": printed as they are,
 * like its errors, or held for a batch's log line. */
static void warn_line(void *user, const char *message)
{
    (void)user;
    cli_message("%s", message);
}

static void note_file(void *inputs, const char *path)
{
    cli_inputs_read(inputs, path, "glTF resource");
}

/* p's world matrix applied to a point (w = 1) or, with the normal matrix,
 * to a direction. */
static void transform(const float *m, const float *p, float w, float out[3])
{
    for (int k = 0; k < 3; k++) {
        out[k] = m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k] * w;
    }
}

/* Vertex v of primitive p into vertex o of the merged arrays, moved to
 * world space (normals by the normal matrix nm); the normal only when p
 * has them. */
static void copy_vertex(const sr_scene_primitive *p, size_t v, size_t o, const sr_mat4 *world,
                        const sr_mat4 *nm, sr_mesh *m, scene_object *ob)
{
    transform(world->m, &p->positions[3 * v], 1.0f, &m->positions[3 * o]);
    if (p->normals && m->normals) {
        transform(nm->m, &p->normals[3 * v], 0.0f, &m->normals[3 * o]);
    }
    if (ob->tangents) {
        /* The bitangent is w N x T: a mirror turns N x T, so w turns too. */
        transform(world->m, &p->tangents[4 * v], 0.0f, &ob->tangents[4 * o]);
        ob->tangents[4 * o + 3] = p->mirrored ? -p->tangents[4 * v + 3] : p->tangents[4 * v + 3];
    }
    if (p->texcoords0) {
        memcpy(&m->texcoords[2 * o], &p->texcoords0[2 * v], 2 * sizeof(float));
    }
    if (p->texcoords1) {
        memcpy(&ob->texcoords1[2 * o], &p->texcoords1[2 * v], 2 * sizeof(float));
    }
    if (m->colors) {
        static const float white[4] = { 1, 1, 1, 1 };
        memcpy(&m->colors[4 * o], p->colors ? &p->colors[4 * v] : white, sizeof white);
    }
}

/* The world-space normal of the triangle at o, o + 1, o + 2 (counter-
 * clockwise), on each of its corners. */
static void flat_normal(sr_mesh *m, size_t o)
{
    const float *a = &m->positions[3 * o], *b = a + 3, *c = a + 6;
    float u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    float w[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    float n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                   u[0] * w[1] - u[1] * w[0] };
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) {
        n[k] = len > 0 ? n[k] / len : (k == 2);   /* a degenerate triangle covers no pixel */
    }
    for (int corner = 0; corner < 3; corner++) {
        memcpy(&m->normals[3 * (o + corner)], n, sizeof n);
    }
}

/* Every primitive's arrays, moved to world space, one after the other;
 * a mirrored primitive's triangles turned back to counter-clockwise.
 * With `flat`, a primitive without normals gets flat ones, as glTF asks:
 * its triangles get their own corners (the renderer's smooth normals
 * would round a cube's edges), and its tangents, which glTF says to
 * ignore then, go. Without, the merged mesh has normals only when every
 * primitive has them (--normals computes them). */
static bool merge(const sr_scene *sc, bool flat, sr_mesh *m, sr_mesh_part *parts,
                  scene_object *ob)
{
    bool normals = true, tangents = true, uv0 = false, uv1 = false, colors = false;
    size_t nv = 0, nt = 0;
    for (size_t i = 0; i < sc->primitive_count; i++) {
        const sr_scene_primitive *p = &sc->primitives[i];
        normals &= p->normals != NULL;
        tangents &= p->tangents != NULL && p->normals != NULL;
        uv0 |= p->texcoords0 != NULL;
        uv1 |= p->texcoords1 != NULL;
        colors |= p->colors != NULL;
        nv += p->normals || !flat ? p->vertex_count : 3 * p->triangle_count;
        nt += p->triangle_count;
    }
    normals |= flat;
    if (nv > UINT32_MAX) {
        return false;
    }
    m->vertex_count = nv;
    m->triangle_count = nt;
    m->positions = malloc((nv ? nv : 1) * 3 * sizeof(float));
    m->normals = normals ? malloc((nv ? nv : 1) * 3 * sizeof(float)) : NULL;
    m->texcoords = uv0 ? calloc(nv ? nv : 1, 2 * sizeof(float)) : NULL;
    m->colors = colors ? malloc((nv ? nv : 1) * 4 * sizeof(float)) : NULL;
    m->indices = malloc((nt ? nt : 1) * 3 * sizeof(uint32_t));
    ob->tangents = tangents && uv0 ? malloc((nv ? nv : 1) * 4 * sizeof(float)) : NULL;
    ob->texcoords1 = uv1 ? calloc(nv ? nv : 1, 2 * sizeof(float)) : NULL;
    ob->part_material = malloc((sc->primitive_count ? sc->primitive_count : 1) * sizeof(int));
    if (!m->positions || (normals && !m->normals) || (uv0 && !m->texcoords) ||
        (colors && !m->colors) || !m->indices || (tangents && uv0 && !ob->tangents) ||
        (uv1 && !ob->texcoords1) || !ob->part_material) {
        return false;
    }
    size_t v0 = 0, t0 = 0;
    for (size_t i = 0; i < sc->primitive_count; i++) {
        const sr_scene_primitive *p = &sc->primitives[i];
        sr_mat4 world, nm;
        memcpy(world.m, p->world, sizeof world.m);
        if (!sr_normal_matrix(&world, &nm)) {
            nm = world;
        }
        bool split = flat && !p->normals;   /* into flat triangles */
        if (!split) {
            for (size_t v = 0; v < p->vertex_count; v++) {
                copy_vertex(p, v, v0 + v, &world, &nm, m, ob);
            }
        }
        for (size_t t = 0; t < p->triangle_count; t++) {
            uint32_t *dst = &m->indices[3 * (t0 + t)];
            const uint32_t *src = &p->indices[3 * t];
            /* A mirrored world matrix flips the winding: swap two corners. */
            const uint32_t corner[3] = { src[0], src[p->mirrored ? 2 : 1],
                                         src[p->mirrored ? 1 : 2] };
            for (int k = 0; k < 3; k++) {
                size_t o = split ? v0 + 3 * t + (size_t)k : v0 + corner[k];
                if (split) {
                    copy_vertex(p, corner[k], o, &world, &nm, m, ob);
                }
                dst[k] = (uint32_t)o;
            }
            if (split) {
                flat_normal(m, v0 + 3 * t);
            }
        }
        parts[i] = (sr_mesh_part){ .first_triangle = t0, .triangle_count = p->triangle_count };
        ob->part_material[i] = p->material;
        v0 += split ? 3 * p->triangle_count : p->vertex_count;
        t0 += p->triangle_count;
    }
    m->parts = parts;
    m->part_count = sc->primitive_count;
    return true;
}

/* The file's variants as "0 Red, 1 Blue", cut with ", ..." where they
 * would not fit a line. */
static void variant_list(const sr_scene *sc, char *list, size_t cap)
{
    size_t at = 0;
    list[0] = 0;
    for (size_t v = 0; v < sc->variant_count && at < cap; v++) {
        int n = snprintf(list + at, cap - at, "%s%zu %s", v ? ", " : "", v, sc->variants[v]);
        if (n < 0 || (size_t)n >= cap - at || at + (size_t)n > cap - 8) {
            snprintf(list + at, cap - at, ", ...");
            break;
        }
        at += (size_t)n;
    }
}

/* --variant's variant, counted as sr_load_desc.variant (from 1): a name
 * the file gives, else a number; 0 after one line when it has none such. */
static size_t find_variant(const char *path, const sr_scene *sc, const char *want)
{
    for (size_t v = 0; v < sc->variant_count; v++) {
        if (strcmp(sc->variants[v], want) == 0) {
            return v + 1;
        }
    }
    char *end = NULL;
    unsigned long n = strtoul(want, &end, 10);
    if (want[0] >= '0' && want[0] <= '9' && *end == 0 && n < sc->variant_count) {
        return (size_t)n + 1;
    }
    char list[400];
    variant_list(sc, list, sizeof list);
    if (sc->variant_count == 0) {
        cli_error("%s: --variant %s: the file has no material variants "
                  "(KHR_materials_variants)", path, want);
    } else {
        cli_error("%s: --variant %s: no such variant (the file has %s)", path, want, list);
    }
    return 0;
}

/* The animations of sc as "0 (walk), 1 (run)" into out. */
static void animation_names(const sr_scene *sc, char *out, size_t size)
{
    size_t at = 0;
    out[0] = 0;
    for (size_t i = 0; i < sc->animation_count && at < size; i++) {
        int n = snprintf(out + at, size - at, "%s%zu%s%.40s%s", i ? ", " : "", i,
                         sc->animations[i].name[0] ? " (" : "", sc->animations[i].name,
                         sc->animations[i].name[0] ? ")" : "");
        at += n > 0 ? (size_t)n : 0;
    }
}

/* --animation's index among sc's animations: a number, else a name;
 * -1 after one line. */
static int find_animation(const sr_scene *sc, const char *path, const char *which)
{
    char *end = NULL;
    long n = strtol(which, &end, 10);
    bool number = end != which && *end == 0 && n >= 0;
    for (size_t i = 0; i < sc->animation_count; i++) {
        if (number ? (size_t)n == i : strcmp(sc->animations[i].name, which) == 0) {
            return (int)i;
        }
    }
    char names[400];
    animation_names(sc, names, sizeof names);
    if (sc->animation_count == 0) {
        cli_error("--animation %s: %s has no animations", which, path);
    } else {
        cli_error("--animation %s: %s has no animation %s %s (it has %s)", which, path,
                  number ? "number" : "named", which, names);
    }
    return -1;
}

/* Reads path once, in its rest pose, then poses it by --animation (a
 * number or a name the file has) at `time` without reading it again.
 * An exit status after one line, or -1. */
static int load_posed(const char *path, const char *animation, float time, sr_context *ctx,
                      cli_inputs *inputs, sr_scene **out)
{
    sr_io_error err;
    sr_load_desc desc = { .format = SR_FORMAT_GLTF, .file_read = note_file, .user = inputs,
                          .warn = warn_line };
    cli_inputs_read(inputs, path, "model");
    sr_result r = sr_load_scene(ctx, path, &desc, out, &err);
    if (r == SR_OK && animation) {
        int index = find_animation(*out, path, animation);
        if (index < 0) {
            sr_destroy_scene(ctx, *out);
            *out = NULL;
            return EXIT_USAGE;
        }
        r = sr_scene_pose(*out, SR_POSE_ANIMATION, index, time, &err);
        if (r != SR_OK) {
            sr_destroy_scene(ctx, *out);
            *out = NULL;
        }
    }
    if (r != SR_OK) {
        cli_message("%s", err.message);
        return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    return -1;
}

/* A load that fails leaves no scene behind: the caller frees only the
 * ones that loaded. */
static int drop_scene(sr_context *ctx, scene *s, int status)
{
    sr_destroy_scene(ctx, s->gltf);
    s->gltf = NULL;
    return status;
}

int render_gltf_load(const char *path, bool flat_normals, const char *variant, bool verbose,
                     const char *animation, float time, sr_context *ctx, cli_inputs *inputs,
                     scene *s)
{
    sr_scene *sc = NULL;
    int status = load_posed(path, animation, time, ctx, inputs, &sc);
    return status >= 0 ? status
                       : render_gltf_build(path, flat_normals, variant, verbose, sc, ctx, s);
}

int render_gltf_build(const char *path, bool flat_normals, const char *variant, bool verbose,
                      sr_scene *sc, sr_context *ctx, scene *s)
{
    scene_object *ob = &s->objects[0];
    sr_result r = SR_OK;
    s->gltf = sc;
    /* Read with no variant, so that a name can be looked up, then each
     * primitive given the variant's material. */
    size_t v = variant ? find_variant(path, sc, variant) : 0;
    if (variant && v == 0) {
        return drop_scene(ctx, s, EXIT_USAGE);
    }
    for (size_t i = 0; i < sc->primitive_count; i++) {
        if (sc->primitives[i].variant_materials) {
            sc->primitives[i].material = sc->primitives[i].variant_materials[v];
        }
    }
    if (verbose && sc->variant_count > 0) {
        char list[400];
        variant_list(sc, list, sizeof list);
        fprintf(stderr, "softrast: %s: material variants %s; drawn: %s\n", path, list,
                v ? sc->variants[v - 1] : "none (the primitives' own materials)");
    }
    if (sc->primitive_count == 0 || sc->primitive_count > UINT32_MAX) {
        cli_error("%s: the scene has no triangles to draw", path);
        return drop_scene(ctx, s, EXIT_USAGE);
    }
    sr_mesh merged = { 0 };
    sr_mesh_part *parts = calloc(sc->primitive_count, sizeof *parts);
    bool ok = parts && merge(sc, flat_normals, &merged, parts, ob);
    if (ok) {
        r = sr_make_mesh(ctx, &merged, &ob->mesh);
    }
    free(merged.positions);
    free(merged.normals);
    free(merged.texcoords);
    free(merged.colors);
    free(merged.indices);
    free(parts);
    if (!ok || r != SR_OK) {
        cli_error("%s: %s", path, ok ? sr_context_error(ctx) : "out of memory");
        return drop_scene(ctx, s, EXIT_FAILURE_RUN);
    }
    s->count = 1;
    ob->model = sr_mat4_identity();
    ob->frame = true;
    ob->material = (sr_material){ .diffuse = { 1, 1, 1 } };
    return -1;
}

/* Whether the slot samples other coordinates than texcoords: set 1, or
 * a transform other than the identity. */
static bool moves_uv(const sr_texture_slot *t)
{
    bool unit = (t->scale[0] == 1 && t->scale[1] == 1) ||
                (!t->scale_set && t->scale[0] == 0 && t->scale[1] == 0);
    return t->texture && (t->texcoord != 0 || t->offset[0] != 0 || t->offset[1] != 0 ||
                          t->rotation != 0 || !unit);
}

sr_result render_gltf_base_uv(sr_context *ctx, const scene *s, scene_object *ob)
{
    free(ob->base_uv);
    ob->base_uv = NULL;
    const sr_mesh *m = &ob->mesh;
    bool moved = false;
    for (size_t p = 0; s->gltf && ob->part_material && p < m->part_count; p++) {
        moved |= moves_uv(&s->gltf->materials[ob->part_material[p]].base_color_texture);
    }
    if (!moved) {
        return SR_OK;
    }
    ob->base_uv = calloc(m->vertex_count ? m->vertex_count : 1, 2 * sizeof(float));
    if (!ob->base_uv) {
        return SR_OUT_OF_MEMORY;
    }
    /* A transform is affine: transformed at the corners and interpolated
     * is the fragment's coordinates transformed.  Each part owns a run of
     * vertices (a primitive's, or its split corners after --normals
     * flat), transformed in one call. */
    for (size_t p = 0; p < m->part_count; p++) {
        const sr_texture_slot *t = &s->gltf->materials[ob->part_material[p]].base_color_texture;
        /* Without set 1 (none in the file, or dropped by --normals flat)
         * pbr reads set 1's slots from set 0. */
        const float *src = t->texcoord == 1 && ob->texcoords1 ? ob->texcoords1 : m->texcoords;
        const sr_mesh_part *part = &m->parts[p];
        if (!t->texture || !src || part->triangle_count == 0) {
            continue;   /* nothing sampled */
        }
        const uint32_t *idx = &m->indices[3 * part->first_triangle];
        uint32_t lo = idx[0], hi = idx[0];
        for (size_t k = 1; k < 3 * part->triangle_count; k++) {
            lo = idx[k] < lo ? idx[k] : lo;
            hi = idx[k] > hi ? idx[k] : hi;
        }
        sr_result r = sr_texture_slot_uv(ctx, t, &src[2 * (size_t)lo], (size_t)(hi - lo) + 1,
                                         &ob->base_uv[2 * (size_t)lo]);
        if (r != SR_OK) {
            return r;
        }
    }
    return SR_OK;
}

sr_material render_gltf_classic(const sr_pbr_material *m, bool vertex_colors)
{
    /* Diffuse: the base color as it is.  sr_material reads a zero diffuse
     * as its default gray, so a black one (a purely emissive material)
     * is kept black by a value no pixel can show. */
    sr_vec3 kd = { m->base_color[0], m->base_color[1], m->base_color[2] };
    if (m->specular_glossiness) {
        /* The extension's diffuse weight, 1 - max(F0). */
        float top = fmaxf(fmaxf(m->sg_specular[0], m->sg_specular[1]), m->sg_specular[2]);
        float w = 1.0f - fminf(fmaxf(top, 0.0f), 1.0f);
        kd = (sr_vec3){ kd.x * w, kd.y * w, kd.z * w };
    }
    if (kd.x == 0 && kd.y == 0 && kd.z == 0) {
        kd = (sr_vec3){ 1e-9f, 1e-9f, 1e-9f };
    }
    /* The highlight: glTF's reflectance at normal incidence (4% for a
     * dielectric, the base color for a metal), at the Blinn-Phong exponent
     * whose lobe matches GGX's at alpha = roughness^2, 2 / alpha^2 - 2,
     * with the lobe's normalization (n + 8) / 8 folded into the color so
     * that a smooth surface's small highlight is as bright as glTF's.
     * The diffuse keeps the base color (the classic lights have no
     * environment for a metal to reflect), so the highlight fades with
     * roughness: a rough metal's wide lobe over the diffuse would wash it
     * out white. */
    bool sg = m->specular_glossiness;
    float rough = fminf(fmaxf(sg ? 1.0f - m->glossiness : m->roughness, 0.0f), 1.0f);
    float a2 = fmaxf(rough * rough * rough * rough, 1e-6f);
    float n = fminf(fmaxf(2.0f / a2 - 2.0f, 1.0f), 2048.0f);
    float metal = fminf(fmaxf(m->metallic, 0.0f), 1.0f), gain = (n + 8.0f) / 8.0f;
    float ks[3];
    for (int c = 0; c < 3; c++) {
        /* Specular-glossiness gives F0 itself. */
        float f0 = sg ? fminf(fmaxf(m->sg_specular[c], 0.0f), 1.0f)
                      : 0.04f + (m->base_color[c] - 0.04f) * metal;
        ks[c] = fminf(f0 * gain * (1.0f - rough), 1.0f);
    }
    return (sr_material){
        .diffuse = kd,
        .specular = { ks[0], ks[1], ks[2] },
        .shininess = n,
        .opacity = m->alpha_mode == SR_ALPHA_BLEND ? fmaxf(m->base_color[3], 1e-6f) : 1.0f,
        .vertex_color = vertex_colors ? SR_ON : SR_OFF,
    };
}

const char *render_gltf_camera(const scene *s, int index, float aspect, sr_mat4 *view,
                               sr_mat4 *projection)
{
    static char why[320];
    size_t n = s->gltf ? s->gltf->camera_count : 0;
    if ((size_t)index >= n) {
        snprintf(why, sizeof why, "--camera-index %d: the model has %zu camera%s", index, n,
                 n == 1 ? "" : "s");
        return why;
    }
    sr_result r = sr_scene_camera_matrices(&s->gltf->cameras[index], aspect, view, projection);
    if (r != SR_OK) {
        /* Which value of the camera (sr_last_error names it). */
        snprintf(why, sizeof why, "--camera-index %d: %s", index, sr_last_error());
        return why;
    }
    return NULL;
}
