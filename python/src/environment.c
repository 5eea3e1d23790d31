/*
 * environment.c - softrast._softrast.make_environment: an image-based
 * light for render()'s metallic-roughness look, the built-in studio or an
 * equirectangular Radiance file, prefiltered once (sr_make_environment on
 * a context of its own, the GIL released) and kept in a capsule that the
 * Python layer caches.
 */
#include "module.h"

#include <stdlib.h>

#define CAPSULE_NAME "softrast._softrast.environment"

typedef struct environment {
    sr_context *ctx;
    sr_environment *env;
} environment;

static void capsule_free(PyObject *capsule)
{
    environment *e = PyCapsule_GetPointer(capsule, CAPSULE_NAME);
    if (e) {
        sr_destroy_environment(e->ctx, e->env);
        sr_destroy_context(e->ctx);
        free(e);
    }
}

PyObject *sr_py_make_environment(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_obj = NULL;
    float intensity;
    int threads;
    if (!PyArg_ParseTuple(args, "O&fi:make_environment", PyUnicode_FSConverter, &path_obj,
                          &intensity, &threads)) {
        return NULL;
    }
    const char *path = PyBytes_AS_STRING(path_obj);
    bool studio = path[0] == '\0';
    environment *e = calloc(1, sizeof *e);
    if (!e) {
        Py_DECREF(path_obj);
        return PyErr_NoMemory();
    }
    sr_io_error err = { { 0 } };
    sr_result r, rr = SR_OK;
    float *px = NULL;
    sr_environment_desc d = { .intensity = intensity };
    Py_BEGIN_ALLOW_THREADS
    sr_set_last_error(NULL);
    r = sr_make_context(&(sr_context_desc){ .threads = threads }, &e->ctx);
    if (r == SR_OK && !studio) {
        rr = sr_read_hdr(path, &d.width, &d.height, &px, &err);
        d.pixels = px;
    }
    if (r == SR_OK && rr == SR_OK) {
        r = sr_make_environment(e->ctx, &d, &e->env);
    }
    free(px);
    Py_END_ALLOW_THREADS
    PyObject *out = NULL;
    if (rr != SR_OK) {
        sr_py_io_error(rr, &err, PyBytes_AS_STRING(path_obj));
    } else if (r != SR_OK) {
        PyErr_Format(r == SR_OUT_OF_MEMORY ? PyExc_MemoryError : PyExc_ValueError,
                     "environment: %s", e->ctx ? sr_context_error(e->ctx) : sr_py_why(r));
    } else {
        out = PyCapsule_New(e, CAPSULE_NAME, capsule_free);
    }
    if (!out) {
        sr_destroy_environment(e->ctx, e->env);
        sr_destroy_context(e->ctx);
        free(e);
    }
    Py_DECREF(path_obj);
    return out;
}

const sr_environment *sr_py_environment_of(PyObject *capsule)
{
    if (!PyCapsule_IsValid(capsule, CAPSULE_NAME)) {
        PyErr_SetString(PyExc_TypeError, "environment: expected softrast's environment");
        return NULL;
    }
    return ((environment *)PyCapsule_GetPointer(capsule, CAPSULE_NAME))->env;
}
