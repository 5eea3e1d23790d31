/*
 * framing.c - softrast._softrast.fit_camera: the library's sr_fit_camera
 * (softrast render's default camera) for softrast.fit_camera, which passes
 * every instance's vertices as float32 and its pose as a float32 model
 * matrix, as the command frames its objects.
 */
#include "module.h"

#include <stdlib.h>
#include <string.h>

PyObject *sr_py_fit_camera(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *seq;
    int width, height, ortho;
    float fov;
    if (!PyArg_ParseTuple(args, "Oiifp", &seq, &width, &height, &fov, &ortho)) {
        return NULL;
    }
    PyObject *list = PySequence_Fast(seq, "sets: expected a sequence of (vertices, model)");
    if (!list) {
        return NULL;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(list);
    sr_framing_points *sets = calloc(n ? (size_t)n : 1, sizeof *sets);
    sr_mat4 *models = calloc(n ? (size_t)n : 1, sizeof *models);
    PyArrayObject **held = calloc(n ? (size_t)n : 1, sizeof *held);
    PyObject *result = NULL;
    if (!sets || !models || !held) {
        PyErr_NoMemory();
        goto done;
    }
    static const int f32[] = { NPY_FLOAT32, -1 };
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *vertices, *model;
        if (!PyArg_ParseTuple(PySequence_Fast_GET_ITEM(list, i), "OO", &vertices, &model)) {
            goto done;
        }
        const npy_intp v_shape[2] = { -1, 3 }, m_shape[1] = { 16 };
        held[i] = sr_py_take_array(vertices, "vertices", 2, v_shape, f32);
        if (!held[i]) {
            goto done;
        }
        PyArrayObject *m = sr_py_take_array(model, "model", 1, m_shape, f32);
        if (!m) {
            goto done;
        }
        memcpy(models[i].m, PyArray_DATA(m), sizeof models[i].m);
        Py_DECREF(m);
        sets[i] = (sr_framing_points){ .positions = PyArray_DATA(held[i]),
                                       .count = (size_t)PyArray_DIM(held[i], 0),
                                       .model = &models[i] };
    }
    sr_framing_info info;
    sr_result r;
    Py_BEGIN_ALLOW_THREADS
    r = sr_fit_camera(NULL, &(sr_framing_desc){ .sets = sets, .set_count = (int)n,
                                                .width = width, .height = height, .fov = fov,
                                                .ortho = ortho }, &info);
    Py_END_ALLOW_THREADS
    if (r != SR_OK) {
        /* Python checked the arguments: what is left is a scene that gives
         * no frame. */
        PyErr_SetString(PyExc_ValueError, "scene: its vertices give no frame (none, all in one "
                                          "point, not finite, or beyond the range of float32)");
        goto done;
    }
    result = Py_BuildValue("(fff)(fff)(fff)fff", info.eye.x, info.eye.y, info.eye.z,
                           info.target.x, info.target.y, info.target.z, info.up.x, info.up.y,
                           info.up.z, info.fovy, info.half_width, info.half_height);
done:
    for (Py_ssize_t i = 0; held && i < n; i++) {
        Py_XDECREF(held[i]);
    }
    free(held);
    free(models);
    free(sets);
    Py_DECREF(list);
    return result;
}
