/*
 * texture_slot.c - a loaded material's texture slot for the classic color
 * pass: its KHR_texture_transform applied to a mesh's coordinates by the
 * library (sr_texture_slot_uv), so that Python draws the coordinates
 * softrast render and the physically based program sample.  Holds the GIL.
 */
#include "module.h"

PyObject *sr_py_texture_slot_uv(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *uv_obj;
    sr_texture_slot slot = { .scale_set = true };   /* the dict's scale is as drawn */
    if (!PyArg_ParseTuple(args, "O(ff)f(ff):texture_slot_uv", &uv_obj, &slot.offset[0],
                          &slot.offset[1], &slot.rotation, &slot.scale[0], &slot.scale[1])) {
        return NULL;
    }
    static const int types[] = { NPY_FLOAT32, -1 };
    PyArrayObject *uv = sr_py_take_array(uv_obj, "uvs", 2, (npy_intp[]){ -1, 2 }, types);
    if (!uv) {
        return NULL;
    }
    PyArrayObject *out = (PyArrayObject *)PyArray_SimpleNew(2, PyArray_DIMS(uv), NPY_FLOAT32);
    sr_context *ctx = NULL;
    sr_set_last_error(NULL);
    sr_result r = out ? sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) : SR_OK;
    if (out && r == SR_OK) {
        r = sr_texture_slot_uv(ctx, &slot, PyArray_DATA(uv), (size_t)PyArray_DIM(uv, 0),
                               PyArray_DATA(out));
    }
    if (r != SR_OK) {
        /* A transform that is not finite, or no memory for the context. */
        sr_py_value_error("texture_slot_uv: %s", ctx ? sr_context_error(ctx) : sr_py_why(r));
        Py_CLEAR(out);
    }
    if (ctx) {
        sr_destroy_context(ctx);
    }
    Py_DECREF(uv);
    return (PyObject *)out;
}
