/*
 * scene_file.c - a loaded glTF scene kept for render()'s metallic-
 * roughness look: the library's own materials (every texture slot, with
 * its sampler and transform, on the loading context) and, for each
 * primitive drawn, the arrays the program reads: the file's normals, or
 * flat ones (the vertices split, as glTF asks of a primitive without
 * normals), both texture coordinate sets, the colors, and tangents,
 * MikkTSpace's where the file has none and the material has a normal
 * map, as softrast render makes them.  Made once by load; read by
 * render's threads, never written after.
 */
#include "module.h"

#include <stdlib.h>
#include <string.h>

#define CAPSULE_NAME "softrast._softrast.scene_file"

typedef struct scene_file {
    sr_context *ctx;
    sr_scene *scene;
    sr_py_file_draw *draws;     /* one a primitive */
} scene_file;

static void free_file(scene_file *f)
{
    for (size_t i = 0; f->draws && i < f->scene->primitive_count; i++) {
        sr_py_file_draw *d = &f->draws[i];
        if (d->owned_mesh) {
            sr_destroy_mesh(f->ctx, &d->mesh);
        }
        free(d->owned_tangents);
    }
    free(f->draws);
    sr_destroy_scene(f->ctx, f->scene);
    sr_destroy_context(f->ctx);
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
static sr_result prepare(sr_context *ctx, const sr_scene *s, const sr_scene_primitive *p,
                         sr_py_file_draw *d)
{
    sr_mesh src = { .vertex_count = p->vertex_count, .positions = (float *)p->positions,
                    .normals = (float *)p->normals, .texcoords = (float *)p->texcoords0,
                    .colors = (float *)p->colors, .triangle_count = p->triangle_count,
                    .indices = (uint32_t *)p->indices };
    d->material = &s->materials[p->material];
    d->mirrored = p->mirrored;
    if (p->normals) {
        d->mesh = src;
        d->texcoords1 = p->texcoords1;
        d->tangents = p->tangents;
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

PyObject *sr_py_scene_file(sr_context *ctx, sr_scene *scene)
{
    scene_file *f = calloc(1, sizeof *f);
    size_t n = scene->primitive_count;
    sr_py_file_draw *draws = calloc(n ? n : 1, sizeof *draws);
    if (!f || !draws) {
        free(f);
        free(draws);
        sr_destroy_scene(ctx, scene);
        sr_destroy_context(ctx);
        return PyErr_NoMemory();
    }
    f->ctx = ctx;
    f->scene = scene;
    f->draws = draws;
    sr_result r = SR_OK;
    Py_BEGIN_ALLOW_THREADS
    for (size_t i = 0; i < n && r == SR_OK; i++) {
        r = prepare(ctx, scene, &scene->primitives[i], &draws[i]);
    }
    Py_END_ALLOW_THREADS
    if (r != SR_OK) {
        PyErr_Format(r == SR_OUT_OF_MEMORY ? PyExc_MemoryError : PyExc_ValueError,
                     "preparing the scene's primitives: %s", sr_context_error(ctx));
        free_file(f);
        return NULL;
    }
    PyObject *capsule = PyCapsule_New(f, CAPSULE_NAME, capsule_free);
    if (!capsule) {
        free_file(f);
    }
    return capsule;
}

const sr_py_file_draw *sr_py_file_draw_of(PyObject *capsule, Py_ssize_t index)
{
    scene_file *f = PyCapsule_IsValid(capsule, CAPSULE_NAME)
                        ? PyCapsule_GetPointer(capsule, CAPSULE_NAME) : NULL;
    if (!f || index < 0 || (size_t)index >= f->scene->primitive_count) {
        PyErr_SetString(PyExc_TypeError, "source: expected a loaded scene's primitive");
        return NULL;
    }
    return &f->draws[index];
}
