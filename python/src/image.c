/*
 * image.c - image files to and from numpy arrays: read_image
 * (sr_read_image: PNG, JPEG, WebP) and decode_image (sr_decode_image,
 * for the images a glTF file embeds) for textures, write_png
 * (sr_write_png, atomic) for the color images of softrast.dask's shards.
 */
#include "module.h"

#include <stdlib.h>
#include <string.h>

static void free_pixels(PyObject *capsule)
{
    free(PyCapsule_GetPointer(capsule, "softrast.pixels"));
}

PyObject *sr_py_image_array(uint8_t *px, int w, int h)
{
    /* The array takes px over (its base, a capsule, frees it): the
     * pixels are copied once, by whoever filled px, not again here. */
    npy_intp shape[3] = { h, w, 4 };
    PyObject *owner = PyCapsule_New(px, "softrast.pixels", free_pixels);
    if (!owner) {
        free(px);
        return NULL;
    }
    PyObject *a = PyArray_SimpleNewFromData(3, shape, NPY_UINT8, px);
    if (!a) {
        Py_DECREF(owner);
        return NULL;
    }
    /* Steals owner, also when it fails. */
    if (PyArray_SetBaseObject((PyArrayObject *)a, owner) < 0) {
        Py_DECREF(a);
        return NULL;
    }
    return a;
}

PyObject *sr_py_read_image(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_obj;
    if (!PyArg_ParseTuple(args, "O&:read_image", PyUnicode_FSConverter, &path_obj)) {
        return NULL;
    }
    int w = 0, h = 0;
    uint8_t *px = NULL;
    sr_io_error err = { { 0 } };
    const char *path = PyBytes_AS_STRING(path_obj);
    sr_result r;
    Py_BEGIN_ALLOW_THREADS
    r = sr_read_image(path, &w, &h, &px, &err);
    Py_END_ALLOW_THREADS
    PyObject *out = r == SR_OK ? sr_py_image_array(px, w, h)
                               : sr_py_io_error(r, &err, PyBytes_AS_STRING(path_obj));
    Py_DECREF(path_obj);
    return out;
}

PyObject *sr_py_decode_image(PyObject *self, PyObject *args)
{
    (void)self;
    Py_buffer data;
    const char *name;
    if (!PyArg_ParseTuple(args, "y*s:decode_image", &data, &name)) {
        return NULL;
    }
    int w = 0, h = 0;
    uint8_t *px = NULL;
    sr_io_error err = { { 0 } };
    sr_result r;
    Py_BEGIN_ALLOW_THREADS
    r = sr_decode_image(name, data.buf, (size_t)data.len, &w, &h, &px, &err);
    Py_END_ALLOW_THREADS
    PyBuffer_Release(&data);
    if (r != SR_OK) {
        return sr_py_io_error(r, &err, NULL);
    }
    return sr_py_image_array(px, w, h);
}

PyObject *sr_py_write_png(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_obj, *image;
    if (!PyArg_ParseTuple(args, "O&O:write_png", PyUnicode_FSConverter, &path_obj, &image)) {
        return NULL;
    }
    static const int u8[] = { NPY_UINT8, -1 };
    const npy_intp shape[3] = { -1, -1, -1 };
    PyArrayObject *a = sr_py_take_array(image, "image", 3, shape, u8);
    if (!a) {
        Py_DECREF(path_obj);
        return NULL;
    }
    npy_intp h = PyArray_DIM(a, 0), w = PyArray_DIM(a, 1), c = PyArray_DIM(a, 2);
    if ((c != 3 && c != 4) || h < 1 || w < 1 || h > 65535 || w > 65535) {
        PyErr_SetString(PyExc_ValueError, "image: shape must be (H, W, 3) or (H, W, 4), "
                                          "1 <= H, W <= 65535");
        Py_DECREF(a);
        Py_DECREF(path_obj);
        return NULL;
    }
    const uint8_t *src = PyArray_DATA(a);
    uint8_t *rgba = NULL;
    if (c == 3) {
        rgba = malloc((size_t)w * (size_t)h * 4);
        if (!rgba) {
            Py_DECREF(a);
            Py_DECREF(path_obj);
            return PyErr_NoMemory();
        }
        for (size_t p = 0; p < (size_t)w * (size_t)h; p++) {
            memcpy(rgba + 4 * p, src + 3 * p, 3);
            rgba[4 * p + 3] = 255;
        }
    }
    sr_io_error err = { { 0 } };
    const char *path = PyBytes_AS_STRING(path_obj);
    sr_png_write_desc desc = { .channels = c == 3 ? SR_PNG_RGB : SR_PNG_RGBA };
    sr_result r;
    Py_BEGIN_ALLOW_THREADS
    r = sr_write_png(path, (int)w, (int)h, rgba ? rgba : src, (size_t)w * 4, &desc, &err);
    Py_END_ALLOW_THREADS
    free(rgba);
    Py_DECREF(a);
    Py_DECREF(path_obj);
    if (r != SR_OK) {
        /* No errno: the path not existing says nothing of why a write failed. */
        return sr_py_io_error(r, &err, NULL);
    }
    Py_RETURN_NONE;
}
