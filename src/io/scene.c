/*
 * scene.c - io stage: sr_load_scene, a model file as a scene to draw.
 * Consumes a path (or a glTF document in memory); glTF goes to gltf.c,
 * every other format through sr_load_mesh, its mesh wrapped as one
 * primitive per texture run with the default dielectric material.  Also
 * the scene's memory: malloc'd blocks freed together by sr_destroy_scene.
 * Any thread may call these with a context of its own.
 */
#include "io/io_util.h"
#include "io/scene.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct texture_source {
    size_t material;
    const uint8_t *bytes;       /* one of the blocks */
    size_t size;
} texture_source;

/* The blocks a scene owns, and the base color images sr_load_mesh
 * hands on. */
typedef struct sr_scene_store {
    void **blocks;
    size_t count, cap;
    texture_source *sources;
    size_t source_count;
    void *posing;                 /* what sr_scene_pose needs (gltf_pose.c), or NULL */
    void (*posing_free)(void *);
} sr_scene_store;

sr_scene *sr__scene_new(void)
{
    sr_scene *s = calloc(1, sizeof *s);
    if (s && !(s->store = calloc(1, sizeof *s->store))) {
        free(s);
        s = NULL;
    }
    if (s) {
        s->animation = -1;   /* the rest pose */
        s->default_material = -1;
        s->metadata.xmp_packet_index = -1;
    }
    return s;
}

bool sr__scene_keep(sr_scene *scene, void *block)
{
    sr_scene_store *st = scene->store;
    if (st->count == st->cap) {
        size_t cap = st->cap ? 2 * st->cap : 16;
        void **b = realloc(st->blocks, cap * sizeof *b);
        if (!b) {
            free(block);
            return false;
        }
        st->blocks = b;
        st->cap = cap;
    }
    st->blocks[st->count++] = block;
    return true;
}

bool sr__scene_set_posing(sr_scene *scene, void *posing, void (*release)(void *))
{
    scene->store->posing = posing;
    scene->store->posing_free = release;
    return true;
}

void *sr__scene_posing(const sr_scene *scene)
{
    return scene->store ? scene->store->posing : NULL;
}

void *sr__scene_alloc(sr_scene *scene, size_t size)
{
    void *p = calloc(1, size ? size : 1);
    return p && sr__scene_keep(scene, p) ? p : NULL;
}

void *sr__scene_grow(sr_scene *scene, void **items, size_t *count, size_t size, size_t n)
{
    (void)scene;
    size_t total, bytes;
    if (__builtin_add_overflow(*count, n, &total) || !sr__mul_ok(total, size, &bytes)) {
        return NULL;
    }
    /* Doubling capacity, kept implicit: the next power of two >= count. */
    size_t cap = 1;
    while (cap < total) {
        cap *= 2;
    }
    size_t old_cap = 1;
    while (old_cap < *count) {
        old_cap *= 2;
    }
    if (*items == NULL || cap > old_cap) {
        void *p = realloc(*items, cap * size);
        if (!p) {
            return NULL;
        }
        *items = p;
    }
    char *first = (char *)*items + *count * size;
    memset(first, 0, n * size);
    *count = total;
    return first;
}

bool sr__scene_add_texture(sr_context *ctx, sr_scene *scene, sr_texture *tex)
{
    sr_texture **slot = sr__scene_grow(scene, (void **)&scene->textures, &scene->texture_count,
                                       sizeof *slot, 1);
    if (!slot) {
        sr_destroy_texture(ctx, tex);
        return false;
    }
    *slot = tex;
    return true;
}

bool sr__scene_add_source(sr_scene *scene, size_t material, const uint8_t *bytes, size_t size)
{
    sr_scene_store *st = scene->store;
    texture_source *src = sr__scene_grow(scene, (void **)&st->sources, &st->source_count,
                                         sizeof *src, 1);
    if (!src) {
        return false;
    }
    *src = (texture_source){ .material = material, .bytes = bytes, .size = size };
    return true;
}

const uint8_t *sr__scene_source(const sr_scene *scene, size_t material, size_t *size)
{
    const sr_scene_store *st = scene->store;
    for (size_t i = 0; i < st->source_count; i++) {
        if (st->sources[i].material == material) {
            *size = st->sources[i].size;
            return st->sources[i].bytes;
        }
    }
    return NULL;
}

void sr__mat4_mul(const float *a, const float *b, float *out)
{
    float r[16];
    for (int c = 0; c < 4; c++) {
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++) {
                s += (double)a[k * 4 + row] * b[c * 4 + k];
            }
            r[c * 4 + row] = (float)s;
        }
    }
    memcpy(out, r, sizeof r);
}

void sr__scene_bounds(sr_scene *scene)
{
    float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t i = 0; i < scene->primitive_count; i++) {
        const sr_scene_primitive *p = &scene->primitives[i];
        const float *m = p->world;
        /* A draw without triangles (a hidden node's) shows nothing. */
        for (size_t v = 0; p->triangle_count > 0 && v < p->vertex_count; v++) {
            const float *x = p->positions + 3 * v;
            for (int c = 0; c < 3; c++) {
                float w = m[c] * x[0] + m[4 + c] * x[1] + m[8 + c] * x[2] + m[12 + c];
                lo[c] = fminf(lo[c], w);
                hi[c] = fmaxf(hi[c], w);
            }
        }
    }
    if (lo[0] > hi[0]) {
        return;   /* no vertices: the bounds stay zero */
    }
    scene->bounds_min = (sr_vec3){ lo[0], lo[1], lo[2] };
    scene->bounds_max = (sr_vec3){ hi[0], hi[1], hi[2] };
}

void sr_destroy_scene(sr_context *ctx, sr_scene *scene)
{
    if (!scene) {
        return;
    }
    for (size_t i = 0; i < scene->texture_count; i++) {
        sr_destroy_texture(ctx, scene->textures[i]);
    }
    if (scene->store) {
        if (scene->store->posing) {
            scene->store->posing_free(scene->store->posing);
        }
        for (size_t i = 0; i < scene->store->count; i++) {
            free(scene->store->blocks[i]);
        }
        free(scene->store->blocks);
        free(scene->store->sources);
        free(scene->store);
    }
    free(scene->textures);
    free(scene->primitives);
    free(scene->materials);
    free(scene->cameras);
    free(scene->lights);
    free(scene);
}

/* ---- cameras -------------------------------------------------------------- */

/* sr_scene_camera_matrices' refusal, with what is wrong. */
static sr_result camera_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

static sr_result camera_fail(const char *fmt, ...)
{
    char reason[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    return sr__io_message(NULL, SR_INVALID_ARG, "sr_scene_camera_matrices: %s", reason);
}

sr_result sr_scene_camera_matrices(const sr_scene_camera *camera, float aspect, sr_mat4 *view,
                                   sr_mat4 *projection)
{
    if (!camera || !view || !projection) {
        return camera_fail("%s is NULL", !camera ? "camera" : !view ? "view" : "projection");
    }
    if (!(aspect > 0) || !isfinite(aspect)) {
        return camera_fail("aspect %g is not a finite number > 0", aspect);
    }
    if ((unsigned)camera->type > SR_SCENE_CAMERA_ORTHOGRAPHIC) {
        return camera_fail("camera->type %d is not an sr_scene_camera_type", (int)camera->type);
    }
    const float *w = camera->world;
    for (int i = 0; i < 16; i++) {
        if (!isfinite(w[i])) {
            return camera_fail("camera->world[%d] is not finite", i);
        }
    }
    /* An orthonormal frame from the world matrix: -Z (the gaze) kept,
     * X made perpendicular to it, Y completing a right-handed frame. */
    sr_vec3 z = sr_vec3_normalize(sr_vec3_make(w[8], w[9], w[10]));
    sr_vec3 x = sr_vec3_make(w[0], w[1], w[2]);
    x = sr_vec3_normalize(sr_vec3_sub(x, sr_vec3_scale(z, sr_vec3_dot(x, z))));
    sr_vec3 y = sr_vec3_cross(z, x);
    if (!(sr_vec3_length(y) >= 0.5f)) {
        return camera_fail("camera->world is degenerate (its X and Z axes are parallel or zero)");
    }
    sr_vec3 t = sr_vec3_make(w[12], w[13], w[14]);
    const sr_vec3 axes[3] = { x, y, z };
    sr_mat4 v = { { 0 } };
    for (int r = 0; r < 3; r++) {
        v.m[r] = axes[r].x;
        v.m[4 + r] = axes[r].y;
        v.m[8 + r] = axes[r].z;
        v.m[12 + r] = -sr_vec3_dot(axes[r], t);
    }
    v.m[15] = 1;
    /* Outputs are written only on success: a refused camera leaves them. */
    float n = camera->znear, f = camera->zfar;
    if (!isfinite(n) || !isfinite(f)) {
        return camera_fail("camera->%s is not finite", isfinite(n) ? "zfar" : "znear");
    }
    sr_mat4 p;
    if (camera->type == SR_SCENE_CAMERA_ORTHOGRAPHIC) {
        float ymag = fabsf(camera->ymag), xmag = ymag * aspect;
        if (!(ymag > 0) || !isfinite(xmag)) {
            return camera_fail("camera->ymag %g gives no finite, non-empty view",
                               camera->ymag);
        }
        if (!(f > n)) {
            return camera_fail("camera->zfar %g is not beyond znear %g", f, n);
        }
        p = sr_ortho(-xmag, xmag, -ymag, ymag, n, f, false);
    } else if (!(camera->yfov > 0 && camera->yfov < 3.14159265f)) {
        return camera_fail("camera->yfov %g is not in (0, pi)", camera->yfov);
    } else if (!(n > 0)) {
        return camera_fail("camera->znear %g is not > 0", n);
    } else if (f != 0 && !(f > n)) {
        return camera_fail("camera->zfar %g is not 0 or beyond znear %g", f, n);
    } else if (f != 0) {
        p = sr_perspective(camera->yfov, aspect, n, f, false);
    } else {
        /* glTF's infinite projection: the far row's limit as zfar grows. */
        float c = 1.0f / tanf(0.5f * camera->yfov);
        memset(&p, 0, sizeof p);
        p.m[0] = c / aspect;
        p.m[5] = c;
        p.m[10] = -1;
        p.m[11] = -1;
        p.m[14] = -2 * n;
    }
    /* Clip distances near FLT_MAX (or a position there) overflow the
     * matrices' products: no camera a draw could use. */
    for (int i = 0; i < 16; i++) {
        if (!isfinite(v.m[i]) || !isfinite(p.m[i])) {
            return camera_fail("the %s matrix is not finite (values near FLT_MAX)",
                               isfinite(v.m[i]) ? "projection" : "view");
        }
    }
    *view = v;
    *projection = p;
    return SR_OK;
}

/* ---- other formats as a scene ------------------------------------------- */

/* What glTF viewers show an untextured model with: a light grey
 * dielectric of middling roughness. */
static void dielectric(sr_pbr_material *m)
{
    memset(m, 0, sizeof *m);
    m->base_color[0] = m->base_color[1] = m->base_color[2] = 0.8f;
    m->base_color[3] = 1;
    m->metallic = 0;
    m->roughness = 0.5f;
    m->normal_scale = m->occlusion_strength = m->emissive_strength = 1;
    m->alpha_cutoff = 0.5f;
}

/* A copy of n floats the scene owns (NULL stays NULL). */
static const float *keep_copy(sr_scene *s, const float *src, size_t n, bool *ok)
{
    if (!src) {
        return NULL;
    }
    float *p = sr__scene_alloc(s, n * sizeof *p);
    if (!p) {
        *ok = false;
        return NULL;
    }
    memcpy(p, src, n * sizeof *p);
    return p;
}

/* The material of a texture run: the dielectric, white under a texture
 * (the texture is the base color) or vertex colors (an OBJ's Kd, a PLY's
 * colors: they are the base color, as glTF viewers take Kd), the texture
 * decoded as sRGB.  A texture that cannot be read is left out with a
 * warning, as the CLI does with a mesh's textures. */
static sr_result run_material(sr_context *ctx, const char *path, const sr_load_desc *desc,
                              sr_scene *s, const char *tex_path, const uint8_t *tex_data,
                              size_t tex_size, bool colors, int *material, sr_io_error *err)
{
    sr_pbr_material *m = sr__scene_grow(s, (void **)&s->materials, &s->material_count,
                                        sizeof *m, 1);
    if (!m) {
        return sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory");
    }
    dielectric(m);
    if (colors) {
        m->base_color[0] = m->base_color[1] = m->base_color[2] = 1;
    }
    *material = (int)(s->material_count - 1);
    if (!tex_path && !tex_data) {
        return SR_OK;
    }
    int w, h;
    uint8_t *pixels;
    sr_io_error inner = {{0}};
    sr_result r = tex_data ? sr_decode_image(path, tex_data, tex_size, &w, &h, &pixels, &inner)
                           : sr_read_image(tex_path, &w, &h, &pixels, &inner);
    if (r != SR_OK) {
        s->warning_count++;
        if (desc && desc->warn) {
            char line[sizeof inner.message + 32];
            snprintf(line, sizeof line, "%s (texture left out)", inner.message);
            desc->warn(desc->user, line);
        }
        return SR_OK;
    }
    if (tex_path && desc && desc->file_read) {
        desc->file_read(desc->user, tex_path);
    }
    sr_texture *tex = NULL;
    r = sr_make_texture(ctx, &(sr_texture_desc){ .width = w, .height = h, .pixels = pixels,
                                                 .srgb = true },
                        &tex);
    free(pixels);
    if (r != SR_OK || !sr__scene_add_texture(ctx, s, tex)) {
        return sr__io_fail(err, r != SR_OK ? r : SR_OUT_OF_MEMORY, path, 0, "texture: %s",
                           r != SR_OK ? sr_context_error(ctx) : "out of memory");
    }
    m = &s->materials[*material];
    m->base_color[0] = m->base_color[1] = m->base_color[2] = 1;
    m->base_color_texture = (sr_texture_slot){ .texture = tex, .scale = { 1, 1 } };
    return SR_OK;
}

static sr_result scene_from_mesh(sr_context *ctx, const char *path, const sr_load_desc *desc,
                                 sr_mesh *mesh, sr_scene *s, sr_io_error *err)
{
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    size_t n = mesh->vertex_count;
    bool ok = true;
    sr_scene_primitive base = { .material = 0, .node = -1, .mesh = -1, .vertex_count = n };
    memcpy(base.world, identity, sizeof identity);
    base.positions = keep_copy(s, mesh->positions, 3 * n, &ok);
    base.normals = keep_copy(s, mesh->normals, 3 * n, &ok);
    base.texcoords0 = keep_copy(s, mesh->texcoords, 2 * n, &ok);
    base.colors = keep_copy(s, mesh->colors, 4 * n, &ok);
    uint32_t *idx = sr__scene_alloc(s, mesh->triangle_count * 3 * sizeof *idx);
    if (!ok || !idx) {
        return sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory");
    }
    memcpy(idx, mesh->indices, mesh->triangle_count * 3 * sizeof *idx);
    /* One primitive per texture run, all sharing the vertex arrays. */
    sr_mesh_part whole = { .first_triangle = 0, .triangle_count = mesh->triangle_count,
                           .texture_path = mesh->texture_path, .texture_data = mesh->texture_data,
                           .texture_size = mesh->texture_size };
    const sr_mesh_part *parts = mesh->part_count ? mesh->parts : &whole;
    size_t part_count = mesh->part_count ? mesh->part_count : 1;
    for (size_t i = 0; i < part_count; i++) {
        sr_scene_primitive *p = sr__scene_grow(s, (void **)&s->primitives, &s->primitive_count,
                                               sizeof *p, 1);
        if (!p) {
            return sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory");
        }
        *p = base;
        p->indices = idx + 3 * parts[i].first_triangle;
        p->triangle_count = parts[i].triangle_count;
        int material = 0;
        sr_result r = run_material(ctx, path, desc, s, parts[i].texture_path,
                                   parts[i].texture_data, parts[i].texture_size,
                                   mesh->colors != NULL, &material, err);
        if (r != SR_OK) {
            return r;
        }
        s->primitives[s->primitive_count - 1].material = material;
    }
    sr__scene_bounds(s);
    return SR_OK;
}

/* ---- entry points --------------------------------------------------------- */

sr_result sr_scene_pose(sr_scene *scene, sr_load_pose pose, int animation, float time,
                        sr_io_error *err)
{
    sr_io_error spare;
    err = err ? err : &spare;
    err->message[0] = '\0';
    if (!scene) {
        return sr__io_fail(err, SR_INVALID_ARG, "sr_scene_pose", 0, "scene is NULL");
    }
    if ((unsigned)pose > SR_POSE_ANIMATION) {
        return sr__io_fail(err, SR_INVALID_ARG, "sr_scene_pose", 0,
                           "pose %d is not an sr_load_pose", (int)pose);
    }
    /* Messages name the file the scene was read from, when known. */
    void *posing = sr__scene_posing(scene);
    char name[400] = "sr_scene_pose";
#ifdef SR_HAVE_JANSSON
    if (posing) {
        snprintf(name, sizeof name, "%.360s: sr_scene_pose", sr__gltf_posing_name(posing));
    }
#endif
    bool animated = pose == SR_POSE_ANIMATION;
    if (animated && (animation < 0 || (size_t)animation >= scene->animation_count)) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "animation %d is not an animation of the scene (it has %zu)",
                           animation, scene->animation_count);
    }
    if (animated && !isfinite(time)) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0, "time %g is not finite", (double)time);
    }
    if (!posing) {
        return SR_OK;   /* no animations: the rest pose is the only one */
    }
#ifdef SR_HAVE_JANSSON
    sr_result r = sr__gltf_pose(posing, scene, animated, animation, time, err);
    if (r != SR_OK) {
        return r;
    }
#endif
    sr__scene_bounds(scene);
    scene->animation = animated ? animation : -1;
    scene->animation_time = animated ? time : 0.0f;
    return SR_OK;
}

bool sr_io_have_gltf(void)
{
#ifdef SR_HAVE_JANSSON
    return true;
#else
    return false;
#endif
}

static bool is_gltf_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    return dot && (strcasecmp(dot, ".gltf") == 0 || strcasecmp(dot, ".glb") == 0);
}

/* A GLB's magic, or a JSON object that names an asset, in the first bytes. */
static bool is_gltf_content(const char *path)
{
    FILE *f;
    unsigned long long size;
    if (sr__open_regular(path, "a model file", &f, &size, NULL) != SR_OK) {
        return false;
    }
    char head[256];
    size_t n = fread(head, 1, sizeof head - 1, f);
    fclose(f);
    head[n] = 0;
    if (n >= 4 && memcmp(head, "glTF", 4) == 0) {
        return true;
    }
    size_t i = strspn(head, " \t\r\n");
    return head[i] == '{' && strstr(head, "\"asset\"") != NULL;
}

static sr_result parse_gltf(sr_context *ctx, const char *name, const char *dir,
                            const uint8_t *data, size_t size, const sr_load_desc *desc,
                            bool for_mesh, sr_scene **out, sr_io_error *err)
{
#ifdef SR_HAVE_JANSSON
    return sr__parse_gltf(ctx, name, dir, data, size, desc, for_mesh, out, err);
#else
    (void)ctx, (void)dir, (void)data, (void)size, (void)desc, (void)for_mesh, (void)out;
    return sr__io_fail(err, SR_UNSUPPORTED, name, 0,
                       "cannot read glTF (softrast was built without jansson; install "
                       "libjansson-dev and rebuild)");
#endif
}

/* The directory part of a path, with its '/' ("" for none): malloc'd. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) + 1 : 0;
    char *dir = malloc(n + 1);
    if (dir) {
        memcpy(dir, path, n);
        dir[n] = 0;
    }
    return dir;
}

static sr_result parse_gltf_at(sr_context *ctx, const char *name, const uint8_t *data,
                               size_t size, const sr_load_desc *desc, bool for_mesh,
                               sr_scene **out, sr_io_error *err)
{
    char *dir = dir_of(name);
    if (!dir) {
        return sr__io_fail(err, SR_OUT_OF_MEMORY, name, 0, "out of memory");
    }
    sr_result r = parse_gltf(ctx, name, dir, data, size, desc, for_mesh, out, err);
    free(dir);
    return r;
}

static sr_result parse_gltf_doc(sr_context *ctx, const char *name, const uint8_t *data, size_t size,
                                const sr_load_desc *desc, sr_scene **out, sr_io_error *err)
{
    if (err) {
        err->message[0] = 0;
    }
    if (!name) {
        name = "<memory>";
    }
    if (out) {
        *out = NULL;
    }
    if (!ctx || !out || (!data && size > 0)) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0, "%s",
                           !ctx ? "no context given" : !out ? "no output scene given"
                                                            : "data must not be NULL");
    }
    sr_result r = sr__check_load_pose(desc, name, err);
    if (r != SR_OK) {
        return r;
    }
    return parse_gltf_at(ctx, name, data, size, desc, false, out, err);
}

sr_result sr_parse_gltf(sr_context *ctx, const char *name, const uint8_t *data, size_t size,
                        const sr_load_desc *desc, sr_scene **out, sr_io_error *err)
{
    sr_io_error saved;
    sr__last_error_save(&saved);
    return sr__last_error_keep(parse_gltf_doc(ctx, name, data, size, desc, out, err), &saved);
}

sr_result sr__load_gltf_scene(sr_context *ctx, const char *path, const sr_load_desc *desc,
                              bool for_mesh, sr_scene **out, sr_io_error *err)
{
    if (err) {
        err->message[0] = 0;   /* the glTF reader keeps the first message */
    }
    char *data;
    size_t size;
    sr_result r = sr__read_file(path, &data, &size, err);
    if (r != SR_OK) {
        return r;
    }
    r = parse_gltf_at(ctx, path, (const uint8_t *)data, size, desc, for_mesh, out, err);
    sr__free_file(data, size);
    return r;
}

static sr_result load_scene(sr_context *ctx, const char *path, const sr_load_desc *desc,
                            sr_scene **out, sr_io_error *err)
{
    if (err) {
        err->message[0] = 0;
    }
    if (out) {
        *out = NULL;
    }
    if (!path || !ctx || !out) {
        return sr__io_fail(err, SR_INVALID_ARG, path ? path : "<null>", 0, "%s",
                           !path ? "no file name given" : !ctx ? "no context given"
                                                               : "no output scene given");
    }
    sr_result r = sr__check_load_pose(desc, path, err);
    if (r != SR_OK) {
        return r;
    }
    sr_model_format format = desc ? desc->format : SR_FORMAT_AUTO;
    if (format == SR_FORMAT_GLTF ||
        (format == SR_FORMAT_AUTO && (is_gltf_name(path) || is_gltf_content(path)))) {
        return sr__load_gltf_scene(ctx, path, desc, false, out, err);
    }
    sr_mesh mesh;
    r = sr_load_mesh(ctx, path, desc, &mesh, err);
    if (r != SR_OK) {
        return r;
    }
    sr_scene *s = sr__scene_new();
    r = s ? scene_from_mesh(ctx, path, desc, &mesh, s, err)
          : sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory");
    sr_destroy_mesh(ctx, &mesh);
    if (r != SR_OK) {
        sr_destroy_scene(ctx, s);
        return r;
    }
    *out = s;
    return SR_OK;
}

sr_result sr_load_scene(sr_context *ctx, const char *path, const sr_load_desc *desc,
                        sr_scene **out, sr_io_error *err)
{
    sr_io_error saved;
    sr__last_error_save(&saved);
    return sr__last_error_keep(load_scene(ctx, path, desc, out, err), &saved);
}
