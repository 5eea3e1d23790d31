/*
 * path_view.c - softrast.PathView, an sr_path_view: where a path far
 * larger than its target is seen (a map to device pixels and the
 * rectangle there that holds every pixel drawn), for Path.cull_curves,
 * Path.length and Path.dash (path2d.c); and the dash list those and
 * Canvas.stroke (canvas.c) take.  Values are checked once, when made,
 * with the argument's name; a view cannot be changed after.
 */
#include "module.h"

#include <stdio.h>

typedef struct PathViewObject {
    PyObject_HEAD
    sr_path_view view;
} PathViewObject;

/* obj, a sequence of n numbers, into out; TypeError or ValueError naming
 * name[i]. */
static int numbers_arg(PyObject *obj, const char *name, int n, double *out)
{
    if (PyUnicode_Check(obj) || PyBytes_Check(obj) || !PySequence_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "%s: expected a sequence of %d numbers, got %s", name, n,
                     Py_TYPE(obj)->tp_name);
        return -1;
    }
    PyObject *fast = PySequence_Fast(obj, name);
    if (!fast) {
        return -1;
    }
    int r = 0;
    if (PySequence_Fast_GET_SIZE(fast) != n) {
        PyErr_Format(PyExc_ValueError, "%s: expected %d numbers, got %zd", name, n,
                     PySequence_Fast_GET_SIZE(fast));
        r = -1;
    }
    for (int i = 0; r == 0 && i < n; i++) {
        char item[64];
        snprintf(item, sizeof item, "%s[%d]", name, i);
        r = sr_py_real_arg(PySequence_Fast_GET_ITEM(fast, i), item, &out[i]);
    }
    Py_DECREF(fast);
    return r;
}

static int view_init(PathViewObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "rect", "transform", NULL };
    PyObject *rect, *transform = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|O:PathView", kwlist, &rect, &transform)) {
        return -1;
    }
    sr_path_view v = { { 1, 0, 0, 1, 0, 0 }, 0, 0, 0, 0 };
    double r[4];
    if (numbers_arg(rect, "rect", 4, r) < 0 ||
        (transform && transform != Py_None && numbers_arg(transform, "transform", 6, v.m) < 0)) {
        return -1;
    }
    if (!(r[0] <= r[2]) || !(r[1] <= r[3])) {
        sr_py_value_error("rect: (x0, y0, x1, y1) is empty: x0 > x1 or y0 > y1, got (%g, %g, "
                          "%g, %g)", r[0], r[1], r[2], r[3]);
        return -1;
    }
    v.x0 = r[0];
    v.y0 = r[1];
    v.x1 = r[2];
    v.y1 = r[3];
    self->view = v;
    return 0;
}

static PyObject *view_get_rect(PathViewObject *self, void *closure)
{
    (void)closure;
    const sr_path_view *v = &self->view;
    return Py_BuildValue("(dddd)", v->x0, v->y0, v->x1, v->y1);
}

static PyObject *view_get_transform(PathViewObject *self, void *closure)
{
    (void)closure;
    const double *m = self->view.m;
    return Py_BuildValue("(dddddd)", m[0], m[1], m[2], m[3], m[4], m[5]);
}

static PyObject *view_repr(PathViewObject *self)
{
    PyObject *rect = view_get_rect(self, NULL), *transform = view_get_transform(self, NULL);
    PyObject *s = rect && transform ? PyUnicode_FromFormat("PathView(rect=%R, transform=%R)",
                                                           rect, transform)
                                    : NULL;
    Py_XDECREF(rect);
    Py_XDECREF(transform);
    return s;
}

int sr_py_path_view_arg(PyObject *obj, const char *name, const sr_path_view **out,
                        sr_path_view *storage)
{
    *out = NULL;
    if (obj == NULL || obj == Py_None) {
        return 0;
    }
    if (!PyObject_TypeCheck(obj, &sr_py_PathViewType)) {
        PyErr_Format(PyExc_TypeError, "%s: expected a softrast.PathView or None, got %s", name,
                     Py_TYPE(obj)->tp_name);
        return -1;
    }
    *storage = ((PathViewObject *)obj)->view;
    *out = storage;
    return 0;
}

int sr_py_dashes_arg(PyObject *obj, double *out, int *count)
{
    if (PyUnicode_Check(obj) || PyBytes_Check(obj) || !PySequence_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "dashes: expected a sequence of lengths, got %s",
                     Py_TYPE(obj)->tp_name);
        return -1;
    }
    PyObject *fast = PySequence_Fast(obj, "dashes");
    if (!fast) {
        return -1;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(fast);
    int r = 0;
    if (n > SR_MAX_DASHES) {
        sr_py_value_error("dashes: at most %d values, got %zd", SR_MAX_DASHES, n);
        r = -1;
    }
    for (Py_ssize_t i = 0; r == 0 && i < n; i++) {
        char name[32];
        snprintf(name, sizeof name, "dashes[%zd]", i);
        r = sr_py_real_arg(PySequence_Fast_GET_ITEM(fast, i), name, &out[i]);
        if (r == 0 && !(out[i] >= 0)) {
            sr_py_value_error("%s: must be >= 0, got %g", name, out[i]);
            r = -1;
        }
    }
    Py_DECREF(fast);
    *count = (int)n;
    return r;
}

PyDoc_STRVAR(view_doc,
"PathView(rect, transform=None)\n--\n\n"
"Where a path far larger than its target is seen (sr_path_view): `transform`\n"
"(a, b, c, d, e, f) maps path coordinates to device pixels (x' = a x + c y + e,\n"
"y' = b x + d y + f; None: the identity), and `rect` (x0, y0, x1, y1) there\n"
"holds every pixel drawn, grown by how far a stroke reaches from the path\n"
"(half its width times the miter limit or sqrt(2), whichever is larger).\n"
"For Path.cull_curves, Path.length and Path.dash.  Numbers must be finite\n"
"and the rectangle not empty (ValueError); read-only once made.");

static PyGetSetDef view_getset[] = {
    { "rect", (getter)view_get_rect, NULL, "(x0, y0, x1, y1) in device pixels", NULL },
    { "transform", (getter)view_get_transform, NULL,
      "(a, b, c, d, e, f): path coordinates to device pixels", NULL },
    { NULL, NULL, NULL, NULL, NULL },
};

PyTypeObject sr_py_PathViewType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "softrast.PathView",
    .tp_basicsize = sizeof(PathViewObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = view_doc,
    .tp_repr = (reprfunc)view_repr,
    .tp_getset = view_getset,
    .tp_init = (initproc)view_init,
    .tp_new = PyType_GenericNew,
};
