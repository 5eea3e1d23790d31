/*
 * scene_file.c - a loaded glTF scene kept for render()'s metallic-
 * roughness look: the library's own materials (every texture slot, with
 * its sampler and transform, on the loading context) and, for each
 * primitive drawn, the arrays the program reads: the file's normals, or
 * flat ones (the vertices split, as glTF asks of a primitive without
 * normals), both texture coordinate sets, the colors, and tangents,
 * MikkTSpace's where the file has none and the material has a normal
 * map, as softrast render makes them.  Made once by load, and once by
 * each Scene.pose of it; read by render's threads, never written after.
 * The library's scene is shared by every pose of one reading (posed
 * again in place under the GIL by sr_py_pose_scene): a capsule's draws
 * point to its arrays only where posing never writes them (the arrays
 * of the reading, those of no draw posed since), else to copies of
 * their own; the materials, which a pose may animate
 * (KHR_animation_pointer), are the capsule's own copy (their textures
 * the reading's).
 */
#include "module.h"

#include <stdlib.h>
#include <string.h>

#define CAPSULE_NAME "softrast._softrast.scene_file"

/* The reading every pose of it shares; freed with its last capsule
 * (capsules are freed under the GIL). */
typedef struct scene_master {
    sr_context *ctx;
    sr_scene *scene;
    size_t refs;
    const float **loaded;       /* 3 a primitive: positions, normals, tangents as read */
} scene_master;

typedef struct scene_file {
    scene_master *m;
    sr_py_file_draw *draws;     /* one a primitive */
    float **copies;             /* 3 a primitive: posed arrays copied, or NULL */
    sr_pbr_material *materials; /* the scene's as this pose has them */
} scene_file;

static void release_master(scene_master *m)
{
    if (m && --m->refs == 0) {
        sr_destroy_scene(m->ctx, m->scene);
        sr_destroy_context(m->ctx);
        free(m->loaded);
        free(m);
    }
}

static void free_file(scene_file *f)
{
    size_t n = f->m ? f->m->scene->primitive_count : 0;
    for (size_t i = 0; f->draws && i < n; i++) {
        sr_py_file_draw *d = &f->draws[i];
        if (d->owned_mesh) {
            sr_destroy_mesh(f->m->ctx, &d->mesh);
        }
        free(d->owned_tangents);
    }
    for (size_t i = 0; f->copies && i < 3 * n; i++) {
        free(f->copies[i]);
    }
    free(f->copies);
    free(f->draws);
    free(f->materials);
    release_master(f->m);
    free(f);
}

static void capsule_free(PyObject *capsule)
{
    scene_file *f = PyCapsule_GetPointer(capsule, CAPSULE_NAME);
    if (f) {
        free_file(f);
    }
}

/* Primitive p's arrays for the program, into d.  Needs no GIL. */
static sr_result prepare(sr_context *ctx, const sr_pbr_material *materials,
                         const sr_scene_primitive *p, float *const own[3], sr_py_file_draw *d)
{
    const float *arrays[3] = { own[0] ? own[0] : p->positions, own[1] ? own[1] : p->normals,
                               own[2] ? own[2] : p->tangents };
    sr_mesh src = { .vertex_count = p->vertex_count, .positions = (float *)arrays[0],
                    .normals = (float *)arrays[1], .texcoords = (float *)p->texcoords0,
                    .colors = (float *)p->colors, .triangle_count = p->triangle_count,
                    .indices = (uint32_t *)p->indices };
    d->material = &materials[p->material];
    d->mirrored = p->mirrored;
    if (p->normals) {
        d->mesh = src;
        d->texcoords1 = p->texcoords1;
        d->tangents = arrays[2];
    } else {
        /* The split vertices no longer match set 1 and the tangents. */
        sr_result r = sr_make_mesh(ctx, &src, &d->mesh);
        if (r != SR_OK) {
            return r;
        }
        d->owned_mesh = true;
        r = sr_mesh_compute_normals(ctx, &d->mesh, SR_NORMALS_FLAT);
        if (r != SR_OK) {
            return r;
        }
    }
    if (!d->tangents &&
        (d->material->normal_texture.texture || d->material->clearcoat_normal_texture.texture ||
         d->material->anisotropy_strength > 0.0f) &&
        d->mesh.texcoords &&
        d->mesh.vertex_count > 0) {
        d->owned_tangents = malloc(d->mesh.vertex_count * 4 * sizeof(float));
        if (!d->owned_tangents) {
            return SR_OUT_OF_MEMORY;
        }
        sr_result r = sr_mesh_compute_tangents(ctx, &d->mesh, d->owned_tangents);
        if (r != SR_OK) {
            return r;
        }
        d->tangents = d->owned_tangents;
    }
    return SR_OK;
}

/* Copies, into f->copies, of the arrays of m's scene that posing may
 * write again (those that are not the reading's).  Needs no GIL. */
static bool copy_posed(const scene_master *m, scene_file *f)
{
    const sr_scene *s = m->scene;
    for (size_t i = 0; i < s->primitive_count; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        const float *now[3] = { p->positions, p->normals, p->tangents };
        for (int k = 0; k < 3; k++) {
            size_t bytes = p->vertex_count * (k == 2 ? 4 : 3) * sizeof(float);
            if (!now[k] || now[k] == m->loaded[3 * i + (size_t)k]) {
                continue;
            }
            if (!(f->copies[3 * i + (size_t)k] = malloc(bytes ? bytes : 1))) {
                return false;
            }
            memcpy(f->copies[3 * i + (size_t)k], now[k], bytes);
        }
    }
    return true;
}

/* A capsule of m's scene as it is posed now (m's reference taken over). */
static PyObject *make_file(scene_master *m, bool posed)
{
    scene_file *f = calloc(1, sizeof *f);
    size_t n = m->scene->primitive_count;
    sr_py_file_draw *draws = calloc(n ? n : 1, sizeof *draws);
    float **copies = calloc(n ? 3 * n : 1, sizeof *copies);
    size_t mn = m->scene->material_count;
    sr_pbr_material *materials = malloc((mn ? mn : 1) * sizeof *materials);
    if (!f || !draws || !copies || !materials) {
        free(f);
        free(draws);
        free(copies);
        free(materials);
        release_master(m);
        return PyErr_NoMemory();
    }
    f->m = m;
    f->draws = draws;
    f->copies = copies;
    f->materials = materials;
    if (mn) {
        memcpy(materials, m->scene->materials, mn * sizeof *materials);
    }
    sr_result r = SR_OK;
    Py_BEGIN_ALLOW_THREADS
    if (posed && !copy_posed(m, f)) {
        r = SR_OUT_OF_MEMORY;
    }
    for (size_t i = 0; i < n && r == SR_OK; i++) {
        r = prepare(m->ctx, materials, &m->scene->primitives[i], &copies[3 * i], &draws[i]);
    }
    Py_END_ALLOW_THREADS
    if (r != SR_OK) {
        PyErr_Format(r == SR_OUT_OF_MEMORY ? PyExc_MemoryError : PyExc_ValueError,
                     "preparing the scene's primitives: %s",
                     r == SR_OUT_OF_MEMORY ? "out of memory" : sr_context_error(m->ctx));
        free_file(f);
        return NULL;
    }
    PyObject *capsule = PyCapsule_New(f, CAPSULE_NAME, capsule_free);
    if (!capsule) {
        free_file(f);
    }
    return capsule;
}

PyObject *sr_py_scene_file(sr_context *ctx, sr_scene *scene)
{
    scene_master *m = calloc(1, sizeof *m);
    size_t n = scene->primitive_count;
    const float **loaded = calloc(n ? 3 * n : 1, sizeof *loaded);
    if (!m || !loaded) {
        free(m);
        free(loaded);
        sr_destroy_scene(ctx, scene);
        sr_destroy_context(ctx);
        return PyErr_NoMemory();
    }
    for (size_t i = 0; i < n; i++) {
        loaded[3 * i] = scene->primitives[i].positions;
        loaded[3 * i + 1] = scene->primitives[i].normals;
        loaded[3 * i + 2] = scene->primitives[i].tangents;
    }
    *m = (scene_master){ .ctx = ctx, .scene = scene, .refs = 1, .loaded = loaded };
    return make_file(m, false);
}

sr_scene *sr_py_scene_of(PyObject *capsule)
{
    scene_file *f = PyCapsule_IsValid(capsule, CAPSULE_NAME)
                        ? PyCapsule_GetPointer(capsule, CAPSULE_NAME) : NULL;
    if (!f) {
        PyErr_SetString(PyExc_TypeError, "expected a loaded glTF scene");
        return NULL;
    }
    return f->m->scene;
}

PyObject *sr_py_scene_file_again(PyObject *capsule)
{
    scene_file *f = PyCapsule_GetPointer(capsule, CAPSULE_NAME);
    if (!f) {
        return NULL;
    }
    f->m->refs++;
    return make_file(f->m, true);
}

const sr_py_file_draw *sr_py_file_draw_of(PyObject *capsule, Py_ssize_t index)
{
    scene_file *f = PyCapsule_IsValid(capsule, CAPSULE_NAME)
                        ? PyCapsule_GetPointer(capsule, CAPSULE_NAME) : NULL;
    if (!f || index < 0 || (size_t)index >= f->m->scene->primitive_count) {
        PyErr_SetString(PyExc_TypeError, "source: expected a loaded scene's primitive");
        return NULL;
    }
    return &f->draws[index];
}
