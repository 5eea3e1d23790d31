/*
 * path2d.c - softrast.Path: an sr_path (lines, Beziers, SVG arcs,
 * flattened as they are added) on a context of its own, for Canvas.fill
 * and Canvas.stroke (canvas.c).  Every coordinate is checked here, with
 * the argument's name, before the library sees it.  Runs with the GIL
 * held; a canvas may read the path without it while `drawing` is set,
 * and changes are refused until then.
 */
#include "module.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static void path_dealloc(PathObject *self)
{
    sr_destroy_path(self->ctx, self->path);
    sr_destroy_context(self->ctx);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

PyObject *sr_py_value_error(const char *format, ...)
{
    char msg[256];
    va_list ap;
    va_start(ap, format);
    vsnprintf(msg, sizeof msg, format, ap);
    va_end(ap);
    PyErr_SetString(PyExc_ValueError, msg);
    return NULL;
}

int sr_py_real_arg(PyObject *obj, const char *name, double *out)
{
    /* numpy's bool too: float() reads it as 0 or 1 */
    if (PyUnicode_Check(obj) || PyBytes_Check(obj) || PyBool_Check(obj) ||
        PyArray_IsScalar(obj, Bool)) {
        PyErr_Format(PyExc_TypeError, "%s: expected a number, got %s", name, Py_TYPE(obj)->tp_name);
        return -1;
    }
    double v = PyFloat_AsDouble(obj);
    if (v == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        PyErr_Format(PyExc_TypeError, "%s: expected a number, got %s", name, Py_TYPE(obj)->tp_name);
        return -1;
    }
    if (!isfinite(v)) {
        PyErr_Format(PyExc_ValueError, "%s: must be finite, got %R", name, obj);
        return -1;
    }
    *out = v;
    return 0;
}

/* The n numbers named by kwlist (all required) as finite coordinates
 * (any size: the fills cut what lies beyond SR_MAX_COORD2D to a guard band
 * around the image). */
static int coords_arg(PyObject *args, PyObject *kwargs, const char *format, char **kwlist,
                      int n, double *out)
{
    PyObject *obj[6] = { NULL };
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, format, kwlist, &obj[0], &obj[1], &obj[2],
                                     &obj[3], &obj[4], &obj[5])) {
        return -1;
    }
    for (int i = 0; i < n; i++) {
        if (sr_py_real_arg(obj[i], kwlist[i], &out[i]) < 0) {
            return -1;
        }
    }
    return 0;
}

static int check_not_drawn(PathObject *self)
{
    if (self->drawing > 0) {
        PyErr_SetString(PyExc_RuntimeError,
                        "Path: cannot change a path while a canvas draws it in another thread");
        return -1;
    }
    return 0;
}

/* self (a new reference) after r, or the library's error on the path's context. */
static PyObject *path_result(PathObject *self, sr_result r)
{
    if (r == SR_OUT_OF_MEMORY) {
        return PyErr_NoMemory();
    }
    if (r != SR_OK) {
        return PyErr_Format(PyExc_ValueError, "%s", sr_context_error(self->ctx));
    }
    Py_INCREF(self);
    return (PyObject *)self;
}

static int path_init(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "tolerance", NULL };
    PyObject *tol_obj = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|O:Path", kwlist, &tol_obj)) {
        return -1;
    }
    double tol = 0.1;
    if (tol_obj && sr_py_real_arg(tol_obj, "tolerance", &tol) < 0) {
        return -1;
    }
    if (!(tol > 0)) {
        PyErr_Format(PyExc_ValueError, "tolerance: must be > 0, got %R", tol_obj);
        return -1;
    }
    if (self->path) {
        if (check_not_drawn(self) < 0) {
            return -1;
        }
        sr_destroy_path(self->ctx, self->path);
        self->path = NULL;
    }
    if (!self->ctx && sr_make_context(&(sr_context_desc){ .threads = 1 }, &self->ctx) != SR_OK) {
        PyErr_NoMemory();
        return -1;
    }
    sr_result r = sr_make_path(self->ctx, tol, &self->path);
    if (r != SR_OK) {
        PyErr_SetString(r == SR_OUT_OF_MEMORY ? PyExc_MemoryError : PyExc_ValueError,
                        sr_context_error(self->ctx));
        return -1;
    }
    self->tolerance = tol;
    return 0;
}

/* The path of a Path made by __new__ but never initialized is NULL. */
static int ready(PathObject *self)
{
    if (!self->path) {
        PyErr_SetString(PyExc_ValueError, "Path: not initialized (call Path())");
        return -1;
    }
    return check_not_drawn(self);
}

static PyObject *path_move_to(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "x", "y", NULL };
    double a[2];
    if (ready(self) < 0 || coords_arg(args, kwargs, "OO:move_to", kwlist, 2, a) < 0) {
        return NULL;
    }
    return path_result(self, sr_path_move_to(self->path, a[0], a[1]));
}

static PyObject *path_line_to(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "x", "y", NULL };
    double a[2];
    if (ready(self) < 0 || coords_arg(args, kwargs, "OO:line_to", kwlist, 2, a) < 0) {
        return NULL;
    }
    return path_result(self, sr_path_line_to(self->path, a[0], a[1]));
}

static PyObject *path_quad_to(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "x1", "y1", "x", "y", NULL };
    double a[4];
    if (ready(self) < 0 || coords_arg(args, kwargs, "OOOO:quad_to", kwlist, 4, a) < 0) {
        return NULL;
    }
    return path_result(self, sr_path_quad_to(self->path, a[0], a[1], a[2], a[3]));
}

static PyObject *path_cubic_to(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "x1", "y1", "x2", "y2", "x", "y", NULL };
    double a[6];
    if (ready(self) < 0 || coords_arg(args, kwargs, "OOOOOO:cubic_to", kwlist, 6, a) < 0) {
        return NULL;
    }
    return path_result(self, sr_path_cubic_to(self->path, a[0], a[1], a[2], a[3], a[4], a[5]));
}

/* An SVG arc flag: a bool, or the integer 0 or 1 as path data writes it. */
static int flag_arg(PyObject *obj, const char *name, bool *out)
{
    if (!PyLong_Check(obj) && !PyArray_IsScalar(obj, Bool)) {
        PyErr_Format(PyExc_TypeError, "%s: expected a bool, got %s", name, Py_TYPE(obj)->tp_name);
        return -1;
    }
    if (PyLong_Check(obj) && !PyBool_Check(obj)) {
        long v = PyLong_AsLong(obj);
        if (v != 0 && v != 1) {
            PyErr_Clear();
            PyErr_Format(PyExc_ValueError, "%s: must be 0 or 1 (or a bool), got %R", name, obj);
            return -1;
        }
    }
    *out = PyObject_IsTrue(obj) == 1;
    return 0;
}

static PyObject *path_arc_to(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "rx", "ry", "rotation", "large_arc", "sweep", "x", "y", NULL };
    PyObject *o[7];
    if (ready(self) < 0 ||
        !PyArg_ParseTupleAndKeywords(args, kwargs, "OOOOOOO:arc_to", kwlist, &o[0], &o[1], &o[2],
                                     &o[3], &o[4], &o[5], &o[6])) {
        return NULL;
    }
    double rx, ry, rot, x, y;
    bool large, sweep;
    if (sr_py_real_arg(o[0], "rx", &rx) < 0 || sr_py_real_arg(o[1], "ry", &ry) < 0 ||
        sr_py_real_arg(o[2], "rotation", &rot) < 0 || flag_arg(o[3], "large_arc", &large) < 0 ||
        flag_arg(o[4], "sweep", &sweep) < 0 || sr_py_real_arg(o[5], "x", &x) < 0 ||
        sr_py_real_arg(o[6], "y", &y) < 0) {
        return NULL;
    }
    /* The end point may lie anywhere; the flattener takes radii within
     * the budget (sr_flatten_arc). */
    const char *names[2] = { "rx", "ry" };
    double v[2] = { rx, ry };
    for (int i = 0; i < 2; i++) {
        if (v[i] > SR_MAX_COORD2D || v[i] < 0) {
            return sr_py_value_error("%s: must be within 0..%g, got %g", names[i],
                                     SR_MAX_COORD2D, v[i]);
        }
    }
    return path_result(self, sr_path_arc_to(self->path, rx, ry, rot, large, sweep, x, y));
}

static PyObject *path_close(PathObject *self, PyObject *unused)
{
    (void)unused;
    if (ready(self) < 0) {
        return NULL;
    }
    return path_result(self, sr_path_close(self->path));
}

static PyObject *path_clear(PathObject *self, PyObject *unused)
{
    (void)unused;
    if (ready(self) < 0) {
        return NULL;
    }
    sr_path_clear(self->path);
    Py_INCREF(self);
    return (PyObject *)self;
}

static PyObject *path_add_polygon(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "points", "close", NULL };
    PyObject *points;
    int close = 1;
    if (ready(self) < 0 ||
        !PyArg_ParseTupleAndKeywords(args, kwargs, "O|p:add_polygon", kwlist, &points, &close)) {
        return NULL;
    }
    PyArrayObject *a = sr_py_points_arg(points, "points");
    if (!a) {
        return NULL;
    }
    const sr_point2 *p = PyArray_DATA(a);
    npy_intp n = PyArray_DIM(a, 0);
    sr_result r = SR_OK;
    for (npy_intp i = 0; i < n && r == SR_OK; i++) {
        r = i == 0 ? sr_path_move_to(self->path, p[i].x, p[i].y)
                   : sr_path_line_to(self->path, p[i].x, p[i].y);
    }
    if (r == SR_OK && n > 0 && close) {
        r = sr_path_close(self->path);
    }
    Py_DECREF(a);
    return path_result(self, r);
}

/* The outlines of a line of text (sr_text_path), appended. */
static PyObject *path_text(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "text", "x", "y", "size", "family", "font_file", "weight",
                              "italic", "anchor", "rtl", NULL };
    const char *text, *family = NULL, *anchor = "start";
    PyObject *xo, *yo, *size_o = NULL, *file = NULL;
    int weight = 400, italic = 0, rtl = 0;
    if (ready(self) < 0 ||
        !PyArg_ParseTupleAndKeywords(args, kwargs, "sOO|$OzO&ipsp:text", kwlist, &text, &xo, &yo,
                                     &size_o, &family, PyUnicode_FSConverter, &file, &weight,
                                     &italic, &anchor, &rtl)) {
        return NULL;
    }
    double x, y, size = 16;
    static const char *const anchors[] = { "start", "middle", "end" };
    int a = 0;
    while (a < 3 && strcmp(anchor, anchors[a]) != 0) {
        a++;
    }
    PyObject *result = NULL;
    if (sr_py_real_arg(xo, "x", &x) < 0 || sr_py_real_arg(yo, "y", &y) < 0 ||
        (size_o && sr_py_real_arg(size_o, "size", &size) < 0)) {
        goto done;
    }
    if (a == 3) {
        PyErr_Format(PyExc_ValueError, "anchor: expected 'start', 'middle' or 'end', got %R",
                     PyTuple_Size(args) > 8 ? PyTuple_GetItem(args, 8)
                                            : PyDict_GetItemString(kwargs, "anchor"));
        goto done;
    }
    if (!(size > 0) || size > SR_MAX_COORD2D) {
        sr_py_value_error("size: must be in (0, %g], got %g", SR_MAX_COORD2D, size);
        goto done;
    }
    if (weight < 1 || weight > 1000) {
        sr_py_value_error("weight: must be 1..1000, got %d", weight);
        goto done;
    }
    sr_io_error err;
    sr_text_anchor anchor_value = (sr_text_anchor)(SR_TEXT_ANCHOR_START + a);
    sr_result r = sr_text_path(text,
                               &(sr_text_desc){ .family = family,
                                                .font_file = file ? PyBytes_AsString(file) : NULL,
                                                .size = size, .weight = weight,
                                                .italic = italic != 0, .x = x, .y = y,
                                                .anchor = anchor_value,
                                                .rtl = rtl != 0 },
                               self->path, NULL, &err);
    if (r == SR_OUT_OF_MEMORY) {
        PyErr_NoMemory();
    } else if (r == SR_UNSUPPORTED) {
        PyErr_SetString(PyExc_RuntimeError, err.message);
    } else if (r != SR_OK) {
        PyErr_SetString(PyExc_ValueError, err.message);
    } else {
        Py_INCREF(self);
        result = (PyObject *)self;
    }
done:
    Py_XDECREF(file);
    return result;
}

static PyObject *path_to_polygons(PathObject *self, PyObject *unused)
{
    (void)unused;
    if (!self->path) {
        return PyList_New(0);
    }
    sr_polygon2 poly = sr_path_polygon(self->path);
    PyObject *list = PyList_New(poly.contour_count);
    for (int c = 0, at = 0; list && c < poly.contour_count; at += poly.contour_counts[c++]) {
        npy_intp shape[2] = { poly.contour_counts[c], 2 };
        PyObject *a = PyArray_SimpleNew(2, shape, NPY_FLOAT64);
        if (!a) {
            Py_CLEAR(list);
            break;
        }
        memcpy(PyArray_DATA((PyArrayObject *)a), poly.points + at,
               (size_t)poly.contour_counts[c] * sizeof *poly.points);
        PyList_SET_ITEM(list, c, a);
    }
    return list;
}

/* Path.cull_curves(view): later curves far outside `view` flattened as
 * lines (sr_path_cull_curves); None turns it off. */
static PyObject *path_cull_curves(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "view", NULL };
    PyObject *view_obj;
    sr_path_view storage;
    const sr_path_view *view;
    if (ready(self) < 0 ||
        !PyArg_ParseTupleAndKeywords(args, kwargs, "O:cull_curves", kwlist, &view_obj) ||
        sr_py_path_view_arg(view_obj, "view", &view, &storage) < 0) {
        return NULL;
    }
    /* view NULL (None) turns culling off */
    return path_result(self, sr_path_cull_curves(self->path, view));
}

/* Path.length(view=None): sr_path_length, or sr_path_length_in_view. */
static PyObject *path_length(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "view", NULL };
    PyObject *view_obj = NULL;
    sr_path_view storage;
    const sr_path_view *view;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|O:length", kwlist, &view_obj) ||
        sr_py_path_view_arg(view_obj, "view", &view, &storage) < 0) {
        return NULL;
    }
    return PyFloat_FromDouble(self->path ? sr_path_length_in_view(self->path, view) : 0.0);
}

/* Path.dash(dashes, offset=0.0, *, view=None): a new path of the dashes
 * (sr_path_dash_in_view), the path's tolerance. */
static PyObject *path_dash(PathObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "dashes", "offset", "view", NULL };
    PyObject *dash_obj, *offset_obj = NULL, *view_obj = NULL;
    double dashes[SR_MAX_DASHES], offset = 0;
    int count;
    sr_path_view storage;
    const sr_path_view *view;
    if (ready(self) < 0 ||
        !PyArg_ParseTupleAndKeywords(args, kwargs, "O|O$O:dash", kwlist, &dash_obj, &offset_obj,
                                     &view_obj) ||
        sr_py_dashes_arg(dash_obj, dashes, &count) < 0 ||
        (offset_obj && sr_py_real_arg(offset_obj, "offset", &offset) < 0) ||
        sr_py_path_view_arg(view_obj, "view", &view, &storage) < 0) {
        return NULL;
    }
    PyObject *tol = PyFloat_FromDouble(self->tolerance);
    PathObject *out = tol ? (PathObject *)PyObject_CallFunctionObjArgs(
                                (PyObject *)&sr_py_PathType, tol, NULL)
                          : NULL;
    Py_XDECREF(tol);
    if (!out) {
        return NULL;
    }
    sr_result r = sr_path_dash_in_view(out->ctx, self->path, dashes, count, offset, view,
                                       out->path);
    if (r != SR_OK) {
        /* the message lives on out's context: raised before out goes */
        if (r == SR_OUT_OF_MEMORY) {
            PyErr_NoMemory();
        } else {
            sr_py_value_error("dashes: %s", sr_context_error(out->ctx));
        }
        Py_DECREF(out);
        return NULL;
    }
    return (PyObject *)out;
}

/* Path.from_svg(d, tolerance=0.1, strict=True): a new path of SVG path
 * data (sr_io_parse_path_data).  An error in the data raises unless
 * strict is false, which keeps the path up to it as SVG draws it; a
 * point that is not finite always raises. */
static PyObject *path_from_svg(PyObject *cls, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "d", "tolerance", "strict", NULL };
    PyObject *d_obj, *tol_obj = NULL;
    int strict = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|O$p:from_svg", kwlist, &d_obj, &tol_obj,
                                     &strict)) {
        return NULL;
    }
    if (!PyUnicode_Check(d_obj)) {
        return PyErr_Format(PyExc_TypeError, "d: expected a str of SVG path data, got %s",
                            Py_TYPE(d_obj)->tp_name);
    }
    Py_ssize_t size;
    const char *d = PyUnicode_AsUTF8AndSize(d_obj, &size);
    if (!d) {
        return NULL;
    }
    if ((size_t)size != strlen(d)) {
        return sr_py_value_error("d: contains a NUL character at offset %zu", strlen(d));
    }
    /* no tolerance: tol_obj NULL ends the arguments at once */
    PathObject *self = (PathObject *)PyObject_CallFunctionObjArgs(cls, tol_obj, NULL);
    if (!self) {
        return NULL;
    }
    if (!PyObject_TypeCheck(self, &sr_py_PathType) || ready(self) < 0) {
        Py_DECREF(self);
        return PyErr_Format(PyExc_TypeError, "from_svg: %R does not make a softrast.Path", cls);
    }
    long offset;
    sr_io_error err;
    sr_result r = sr_io_parse_path_data(d, self->path, &(sr_io_path_data_desc){ 0 }, &offset,
                                        &err);
    if (r == SR_OK || (r == SR_BAD_FORMAT && !strict)) {
        return (PyObject *)self;
    }
    if (r != SR_BAD_FORMAT) { /* a point the path refused: its message */
        snprintf(err.message, sizeof err.message, "%s (the command at offset %ld)",
                 sr_context_error(self->ctx), offset);
    }
    Py_DECREF(self);
    if (r == SR_OUT_OF_MEMORY) {
        return PyErr_NoMemory();
    }
    return sr_py_value_error("d: %s", err.message);
}

static PyObject *path_get_tolerance(PathObject *self, void *closure)
{
    (void)closure;
    return PyFloat_FromDouble(self->tolerance);
}

PyDoc_STRVAR(path_doc,
"Path(tolerance=0.1)\n--\n\n"
"A 2D path in pixels (x right, y down; pixel (i, j) covers [i, i+1) x [j, j+1)):\n"
"subpaths of lines, quadratic and cubic Beziers and SVG arcs, flattened to\n"
"lines within `tolerance` pixels as they are added (sr_path).  Each method\n"
"returns the path, so calls chain.  Fill it or stroke it with a Canvas.");

#define PATH_METHOD(name, flags, doc) \
    { #name, (PyCFunction)(void (*)(void))path_##name, flags, doc }

static PyMethodDef path_methods[] = {
    PATH_METHOD(move_to, METH_VARARGS | METH_KEYWORDS,
                "move_to($self, x, y)\n--\n\nStart a new subpath at (x, y)."),
    PATH_METHOD(line_to, METH_VARARGS | METH_KEYWORDS,
                "line_to($self, x, y)\n--\n\nA line to (x, y)."),
    PATH_METHOD(quad_to, METH_VARARGS | METH_KEYWORDS,
                "quad_to($self, x1, y1, x, y)\n--\n\n"
                "A quadratic Bezier through control point (x1, y1)."),
    PATH_METHOD(cubic_to, METH_VARARGS | METH_KEYWORDS,
                "cubic_to($self, x1, y1, x2, y2, x, y)\n--\n\n"
                "A cubic Bezier with control points (x1, y1), (x2, y2)."),
    PATH_METHOD(arc_to, METH_VARARGS | METH_KEYWORDS,
                "arc_to($self, rx, ry, rotation, large_arc, sweep, x, y)\n--\n\n"
                "An SVG elliptical arc to (x, y): radii rx, ry >= 0, the ellipse's x axis\n"
                "rotated by `rotation` degrees, flags as SVG's A command."),
    PATH_METHOD(close, METH_NOARGS,
                "close($self)\n--\n\nClose the subpath (a line back to its start)."),
    PATH_METHOD(clear, METH_NOARGS, "clear($self)\n--\n\nRemove every subpath."),
    PATH_METHOD(add_polygon, METH_VARARGS | METH_KEYWORDS,
                "add_polygon($self, points, close=True)\n--\n\n"
                "A subpath through the rows of an (N, 2) array of x, y, closed unless\n"
                "close=False."),
    PATH_METHOD(from_svg, METH_VARARGS | METH_KEYWORDS | METH_CLASS,
                "from_svg($type, d, tolerance=0.1, *, strict=True)\n--\n\n"
                "A new path of SVG path data, the `d` attribute of a <path>: every\n"
                "command (M L H V C S Q T A Z, absolute and relative), numbers in SVG's\n"
                "compact forms.  An error in the data raises ValueError with its\n"
                "offset; strict=False keeps the path up to it, as SVG draws it."),
    PATH_METHOD(text, METH_VARARGS | METH_KEYWORDS,
                "text($self, text, x, y, *, size=16.0, family=None, font_file=None, weight=400,\n"
                "     italic=False, anchor='start', rtl=False)\n--\n\n"
                "The glyph outlines of a line of text (sr_text_path), its baseline starting\n"
                "at (x, y) (anchor 'middle' or 'end': x is its middle or end): the font\n"
                "fontconfig matches for `family` (a CSS font-family list; None is\n"
                "sans-serif), `weight` and `italic`, or the file `font_file`; shaped by\n"
                "HarfBuzz (kerning, ligatures, right to left), mixed directions ordered\n"
                "by the bidi algorithm (rtl=True: the line's base direction is right to\n"
                "left), `size` pixels to the em.\n"
                "Fill the path with a Canvas.  RuntimeError in a build without\n"
                "fontconfig, HarfBuzz and FreeType (softrast.have_text)."),
    PATH_METHOD(cull_curves, METH_VARARGS | METH_KEYWORDS,
                "cull_curves($self, view)\n--\n\n"
                "From now on (until clear() or cull_curves(None)), a quadratic or cubic\n"
                "added whose control polygon, mapped by the PathView `view`, lies wholly\n"
                "beyond one side of its rectangle is a line to its end point; one that\n"
                "crosses the edge is halved until each half is outside, inside or under\n"
                "4096 px, and only those are flattened (sr_path_cull_curves).  Fills and\n"
                "strokes within the rectangle do not change; the length and bounds do."),
    PATH_METHOD(length, METH_VARARGS | METH_KEYWORDS,
                "length($self, view=None)\n--\n\n"
                "The length of the flattened path, closing segments included\n"
                "(sr_path_length); with a PathView, of the parts within its rectangle\n"
                "(sr_path_length_in_view)."),
    PATH_METHOD(dash, METH_VARARGS | METH_KEYWORDS,
                "dash($self, dashes, offset=0.0, *, view=None)\n--\n\n"
                "A new path (this one's tolerance) of the dashes of this one, each an open\n"
                "subpath, as SVG's stroke-dasharray and stroke-dashoffset (sr_path_dash):\n"
                "`dashes` at most 32 lengths >= 0, dashes and gaps in turn (an odd count\n"
                "repeats once; empty or all zeros: a copy), the pattern starting `offset`\n"
                "into itself at every subpath.  With a PathView, only the dashes within\n"
                "its rectangle, at the phase a full walk reaches (sr_path_dash_in_view).\n"
                "ValueError when the dashes would pass 2^26 points."),
    PATH_METHOD(to_polygons, METH_NOARGS,
                "to_polygons($self)\n--\n\n"
                "The flattened subpaths, each an (n, 2) float64 array of x, y."),
    { NULL, NULL, 0, NULL },
};

static PyGetSetDef path_getset[] = {
    { "tolerance", (getter)path_get_tolerance, NULL, "the flattening tolerance in pixels", NULL },
    { NULL, NULL, NULL, NULL, NULL },
};

PyTypeObject sr_py_PathType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "softrast.Path",
    .tp_basicsize = sizeof(PathObject),
    .tp_dealloc = (destructor)path_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = path_doc,
    .tp_methods = path_methods,
    .tp_getset = path_getset,
    .tp_init = (initproc)path_init,
    .tp_new = PyType_GenericNew,
};
