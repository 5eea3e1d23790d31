/*
 * canvas.c - softrast._softrast.Canvas2D, what softrast.Canvas draws
 * with: fills and strokes of paths and polygons with a paint
 * (sr_fill_polygon_paint, sr_make_stroke_outline, sr_path_dash_in_view)
 * into a caller's (H, W, 4) uint8 RGBA array, in place.  The library draws into a
 * framebuffer, not into caller memory, so the canvas keeps one of the
 * image's size as scratch: a draw copies the rectangle its polygon can
 * touch into it, fills, and copies the rectangle back (the array stays
 * the pixels' only truth: it may be changed between draws).  A draw
 * under softrast.Canvas's transform has its polygon (a stroke: its
 * outline, made in user space as SVG strokes) mapped to pixels here; a
 * clipped draw fills a transparent layer and blends it through the
 * clip's coverage (sr_draw_layer), as the SVG reader draws clip-path.
 * softrast/_draw.py keeps the transform and the clip and checks the
 * arguments' values and names; this file checks everything it
 * dereferences.  Large shapes are drawn without the GIL,
 * under the canvas's lock (one draw at a time per canvas).
 */
#include "module.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct CanvasObject {
    PyObject_HEAD
    PyArrayObject *image;   /* (H, W, 4) uint8, C-contiguous, writeable */
    sr_context *ctx;        /* one thread: the 2D fills run on the caller's */
    sr_framebuffer *fb;     /* scratch, the image's size, no depth */
    PyThread_type_lock lock;
} CanvasObject;

/* Shapes at least this large (points, or pixels of their box) are
 * drawn with the GIL released; smaller ones cost less than the switch. */
#define RELEASE_POINTS 256
#define RELEASE_PIXELS 16384.0

PyArrayObject *sr_py_points_arg(PyObject *obj, const char *name)
{
    PyArrayObject *a = (PyArrayObject *)PyArray_FromAny(obj, NULL, 0, 0, 0, NULL);
    if (!a) {
        bool value = PyErr_ExceptionMatches(PyExc_ValueError);
        PyErr_Clear();
        return (PyArrayObject *)PyErr_Format(value ? PyExc_ValueError : PyExc_TypeError,
                                             "%s: expected an (N, 2) array of numbers, got %s",
                                             name, Py_TYPE(obj)->tp_name);
    }
    if (!PyArray_ISINTEGER(a) && !PyArray_ISFLOAT(a)) {
        PyErr_Format(PyExc_TypeError, "%s: dtype must be a real number type, got %S", name,
                     (PyObject *)PyArray_DESCR(a));
        Py_DECREF(a);
        return NULL;
    }
    if (PyArray_NDIM(a) != 2 || PyArray_DIM(a, 1) != 2) {
        PyObject *shape = PyObject_GetAttrString((PyObject *)a, "shape");
        PyErr_Format(PyExc_ValueError, "%s: shape must be (N, 2), got %S", name,
                     shape ? shape : Py_None);
        Py_XDECREF(shape);
        Py_DECREF(a);
        return NULL;
    }
    PyArrayObject *f = (PyArrayObject *)PyArray_FROMANY(
        (PyObject *)a, NPY_FLOAT64, 2, 2,
        NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED | NPY_ARRAY_FORCECAST);
    Py_DECREF(a);
    if (!f) {
        return NULL;
    }
    const double *v = PyArray_DATA(f);
    for (npy_intp i = 0; i < 2 * PyArray_DIM(f, 0); i++) {
        if (!isfinite(v[i])) {
            sr_py_value_error("%s: point %zd is NaN or infinite", name, (Py_ssize_t)(i / 2));
            Py_DECREF(f);
            return NULL;
        }
    }
    return f;
}

static void canvas_dealloc(CanvasObject *self)
{
    sr_destroy_framebuffer(self->ctx, self->fb);
    sr_destroy_context(self->ctx);
    if (self->lock) {
        PyThread_free_lock(self->lock);
    }
    Py_XDECREF(self->image);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static int canvas_init(CanvasObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "image", NULL };
    PyObject *obj;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O:Canvas2D", kwlist, &obj)) {
        return -1;
    }
    if (self->image) {
        PyErr_SetString(PyExc_TypeError, "Canvas2D: already initialized");
        return -1;
    }
    if (!PyArray_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "image: expected a numpy array, got %s",
                     Py_TYPE(obj)->tp_name);
        return -1;
    }
    static const int u8[] = { NPY_UINT8, -1 };
    const npy_intp shape[3] = { -1, -1, 4 };
    PyArrayObject *a = sr_py_take_array(obj, "image", 3, shape, u8);
    if (!a) {
        return -1;
    }
    if ((PyObject *)a != obj || !PyArray_ISWRITEABLE(a)) {
        PyErr_SetString(PyExc_ValueError, "image: array is read-only (the canvas draws into it)");
        Py_DECREF(a);
        return -1;
    }
    npy_intp h = PyArray_DIM(a, 0), w = PyArray_DIM(a, 1);
    if (h < 1 || w < 1 || h > SR_MAX_FRAMEBUFFER_SIZE || w > SR_MAX_FRAMEBUFFER_SIZE) {
        PyErr_Format(PyExc_ValueError, "image: height and width must be in 1..%d, got %zd x %zd",
                     SR_MAX_FRAMEBUFFER_SIZE, (Py_ssize_t)h, (Py_ssize_t)w);
        Py_DECREF(a);
        return -1;
    }
    self->image = a;
    self->lock = PyThread_allocate_lock();
    sr_set_last_error(NULL);
    sr_result r = self->lock ? sr_make_context(&(sr_context_desc){ .threads = 1 }, &self->ctx)
                             : SR_OUT_OF_MEMORY;
    if (r == SR_OK) {
        sr_framebuffer_desc fd = { .width = (int)w, .height = (int)h,
                                   .depth_format = SR_DEPTH_NONE };
        r = sr_make_framebuffer(self->ctx, &fd, &self->fb);
    }
    if (r != SR_OK) {
        PyErr_SetString(r == SR_OUT_OF_MEMORY ? PyExc_MemoryError : PyExc_ValueError,
                        self->ctx ? sr_context_error(self->ctx) : sr_py_why(r));
        return -1;
    }
    return 0;
}

static int ready(CanvasObject *self)
{
    if (!self->fb) {
        PyErr_SetString(PyExc_ValueError, "Canvas2D: not initialized");
        return -1;
    }
    return 0;
}

/* The canvas's lock, waited for without the GIL when another thread holds it. */
static void lock_canvas(CanvasObject *self)
{
    if (!PyThread_acquire_lock(self->lock, NOWAIT_LOCK)) {
        Py_BEGIN_ALLOW_THREADS
        PyThread_acquire_lock(self->lock, WAIT_LOCK);
        Py_END_ALLOW_THREADS
    }
}

/* A paint tuple of softrast/_draw.py, its arrays held until paint_release. */
typedef struct paint_args {
    sr_paint paint;
    sr_point2 focal;
    sr_affine2 transform;
    sr_gradient_stop *stops;
    PyArrayObject *image;
} paint_args;

static void paint_release(paint_args *p)
{
    free(p->stops);
    Py_XDECREF(p->image);
}

/* (kind, (r, g, b, a), (six numbers: x1 y1 x2 y2 - -, or cx cy r fx fy fr),
 *  (N, 5) float64 stops [offset r g b a] or None, spread, (H, W, 4) uint8
 *  image or None, wrap, (a, b, c, d, e, f), opacity); kind, spread and
 *  wrap are the library's enum values (draw2d_names).  The library
 *  checks the values again. */
static int paint_arg(PyObject *obj, paint_args *p)
{
    memset(p, 0, sizeof *p);
    if (!PyTuple_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "paint: expected a paint tuple, got %s",
                     Py_TYPE(obj)->tp_name);
        return -1;
    }
    int kind, spread, wrap;
    double g[6], opacity;
    sr_rgba c;
    sr_affine2 *t = &p->transform;
    PyObject *stops, *image;
    if (!PyArg_ParseTuple(obj, "i(ffff)(dddddd)OiOi(dddddd)d:paint", &kind, &c.r, &c.g, &c.b,
                          &c.a, &g[0], &g[1], &g[2], &g[3], &g[4], &g[5], &stops, &spread,
                          &image, &wrap, &t->a, &t->b, &t->c, &t->d, &t->e, &t->f, &opacity)) {
        return -1;
    }
    p->paint = (sr_paint){ .kind = (sr_paint_kind)kind, .color = c,
                           .spread = (sr_gradient_spread)spread,
                           .image_wrap = (sr_texture_wrap)wrap, .transform = t,
                           .opacity = (float)opacity };
    if (kind == SR_PAINT_LINEAR_GRADIENT) {
        p->paint.x1 = g[0];
        p->paint.y1 = g[1];
        p->paint.x2 = g[2];
        p->paint.y2 = g[3];
    } else if (kind == SR_PAINT_RADIAL_GRADIENT) {
        p->paint.cx = g[0];
        p->paint.cy = g[1];
        p->paint.r = g[2];
        p->focal = (sr_point2){ g[3], g[4] };
        p->paint.focal = &p->focal;
        p->paint.fr = g[5];
    }
    if (stops != Py_None) {
        static const int f64[] = { NPY_FLOAT64, -1 };
        const npy_intp shape[2] = { -1, 5 };
        PyArrayObject *s = sr_py_take_array(stops, "stops", 2, shape, f64);
        if (!s) {
            return -1;
        }
        npy_intp n = PyArray_DIM(s, 0);
        const double *v = PyArray_DATA(s);
        bool finite = true;
        for (npy_intp i = 0; i < 5 * n; i++) {
            finite = finite && fabs(v[i]) <= FLT_MAX; /* a float each color component */
        }
        if (n < 1 || n > SR_MAX_GRADIENT_STOPS) {
            PyErr_Format(PyExc_ValueError, "stops: %zd stops, the library takes 1..%d",
                         (Py_ssize_t)n, SR_MAX_GRADIENT_STOPS);
        } else if (!finite) {
            PyErr_SetString(PyExc_ValueError, "stops: NaN, infinity or a value past float");
        } else if (!(p->stops = malloc((size_t)n * sizeof *p->stops))) {
            PyErr_NoMemory();
        } else {
            for (npy_intp i = 0; i < n; i++, v += 5) {
                p->stops[i] = (sr_gradient_stop){ v[0], { (float)v[1], (float)v[2], (float)v[3],
                                                          (float)v[4] } };
            }
            p->paint.stops = p->stops;
            p->paint.stop_count = (int)n;
        }
        Py_DECREF(s);
        if (!p->stops) {
            return -1;
        }
    }
    if (image != Py_None) {
        static const int u8[] = { NPY_UINT8, -1 };
        const npy_intp shape[3] = { -1, -1, 4 };
        p->image = sr_py_take_array(image, "image", 3, shape, u8);
        if (!p->image) {
            paint_release(p);
            return -1;
        }
        npy_intp h = PyArray_DIM(p->image, 0), w = PyArray_DIM(p->image, 1);
        if (h < 1 || w < 1 || h > SR_MAX_FRAMEBUFFER_SIZE || w > SR_MAX_FRAMEBUFFER_SIZE) {
            PyErr_Format(PyExc_ValueError, "image: height and width must be in 1..%d",
                         SR_MAX_FRAMEBUFFER_SIZE);
            paint_release(p);
            return -1;
        }
        p->paint.image = PyArray_DATA(p->image);
        p->paint.image_width = (int)w;
        p->paint.image_height = (int)h;
    }
    return 0;
}

/* The pixels a polygon's fill can touch, [x0, x1) x [y0, y1) within the
 * image; false when none.  A fill covers no pixel outside the box of its
 * points (snapping to 1/256 pixel keeps a point between the same two
 * integers); one pixel of margin all round. */
static bool touched_box(sr_polygon2 poly, int w, int h, int box[4])
{
    double b[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
    for (int i = 0; i < poly.point_count; i++) {
        b[0] = fmin(b[0], poly.points[i].x);
        b[1] = fmin(b[1], poly.points[i].y);
        b[2] = fmax(b[2], poly.points[i].x);
        b[3] = fmax(b[3], poly.points[i].y);
    }
    if (poly.point_count < 1) {
        return false;
    }
    /* clamped to the image before the conversion to int */
    box[0] = (int)fmin(fmax(floor(b[0]) - 1, 0), w);
    box[1] = (int)fmin(fmax(floor(b[1]) - 1, 0), h);
    box[2] = (int)fmax(fmin(ceil(b[2]) + 1, w), 0);
    box[3] = (int)fmax(fmin(ceil(b[3]) + 1, h), 0);
    return box[2] > box[0] && box[3] > box[1];
}

/* A stroke's dashes (sr_path_dash_in_view): count 0 for none. */
typedef struct dash_args {
    double dashes[SR_MAX_DASHES];
    int count;
    double offset;
} dash_args;

/* poly's points mapped by m (NULL: kept) into *mapped, malloc'd, which
 * poly then points at; false when out of memory.  As the SVG reader maps
 * a point (svg.c mat_apply), so that a drawing gives its bytes. */
static bool map_polygon(sr_polygon2 *poly, const sr_affine2 *m, sr_point2 **mapped)
{
    *mapped = NULL;
    if (!m || poly->point_count == 0) {
        return true;
    }
    if (!(*mapped = malloc((size_t)poly->point_count * sizeof **mapped))) {
        return false;
    }
    for (int i = 0; i < poly->point_count; i++) {
        sr_point2 p = poly->points[i];
        (*mapped)[i] = (sr_point2){ m->a * p.x + m->c * p.y + m->e,
                                    m->b * p.x + m->d * p.y + m->f };
    }
    poly->points = *mapped;
    return true;
}

/* Where a stroke's dashes can reach the w x h image (sr_path_view): the
 * image grown by how far the stroke reaches from its path under m (NULL:
 * the identity), as the SVG reader dashes, so that a pattern along a path
 * far larger than the image cuts the dashes seen only; NULL (every dash)
 * when the reach overflows. */
static const sr_path_view *stroke_view(const sr_stroke_desc *sd, const sr_affine2 *m, int w,
                                       int h, sr_path_view *view)
{
    const sr_affine2 id = { 1, 0, 0, 1, 0, 0 }, *t = m ? m : &id;
    double stretch = fabs(t->a) + fabs(t->b) + fabs(t->c) + fabs(t->d); /* bounds the largest */
    double miter = sd->miter_limit > 0 ? sd->miter_limit : 4;
    double reach = sd->width / 2 * stretch * fmax(miter, 1.4142135623730951) + 1;
    *view = (sr_path_view){ { t->a, t->b, t->c, t->d, t->e, t->f }, -reach, -reach, w + reach,
                            h + reach };
    return isfinite(reach) ? view : NULL;
}

/* A clipped draw of poly: the box's pixels made transparent, filled,
 * read as a layer, the image's pixels put back and the layer blended
 * over them through the clip's coverage (the mask of the whole image). */
static sr_result fill_clipped(CanvasObject *self, sr_polygon2 poly, const sr_paint *paint,
                              const sr_fill_desc *fd, const uint8_t *clip, const int box[4],
                              uint8_t *px, size_t stride)
{
    int w = (int)PyArray_DIM(self->image, 1), bw = box[2] - box[0], bh = box[3] - box[1];
    uint8_t *layer = calloc((size_t)bw * (size_t)bh, 4);
    if (!layer) {
        return SR_OUT_OF_MEMORY; /* draw() raises MemoryError */
    }
    size_t lstride = (size_t)bw * 4;
    sr_result r = sr_write_pixels(self->ctx, self->fb, box[0], box[1], bw, bh, layer, lstride);
    if (r == SR_OK) {
        r = sr_fill_polygon_paint(self->ctx, self->fb, &poly, paint, fd);
    }
    if (r == SR_OK) {
        r = sr_read_pixels(self->ctx, self->fb, box[0], box[1], bw, bh, layer, lstride);
    }
    if (r == SR_OK) {
        r = sr_write_pixels(self->ctx, self->fb, box[0], box[1], bw, bh, px, stride);
    }
    if (r == SR_OK) {
        sr_layer_desc ld = { .mask = clip + (size_t)box[1] * (size_t)w + (size_t)box[0],
                             .mask_stride = (size_t)w };
        r = sr_draw_layer(self->ctx, self->fb, box[0], box[1], bw, bh, layer, lstride, &ld);
    }
    free(layer);
    return r;
}

/* One draw, the canvas locked (without the GIL when `release`): the
 * stroke outline of `stroked` (of its dashes when da has any) when it is
 * not NULL, else poly, mapped by m (NULL: as it is) and filled with the
 * paint over the image's pixels, through the coverage clip (NULL: none).
 * The library's message goes to msg on failure. */
static sr_result draw_locked(CanvasObject *self, sr_polygon2 poly, const PathObject *stroked,
                             const sr_stroke_desc *sd, const dash_args *da,
                             const sr_paint *paint, const sr_fill_desc *fd,
                             const sr_affine2 *m, const uint8_t *clip, char *msg,
                             size_t msg_size)
{
    sr_polygon2 outline = { 0 };
    sr_path *dashed = NULL;
    sr_point2 *mapped = NULL;
    sr_result r = SR_OK;
    int w = (int)PyArray_DIM(self->image, 1), h = (int)PyArray_DIM(self->image, 0), box[4];
    if (stroked && da->count > 0) {
        sr_path_view view;
        r = sr_make_path(self->ctx, stroked->tolerance, &dashed);
        if (r == SR_OK) {
            r = sr_path_dash_in_view(self->ctx, stroked->path, da->dashes, da->count, da->offset,
                                     stroke_view(sd, m, w, h, &view), dashed);
        }
    }
    if (stroked && r == SR_OK) {
        r = sr_make_stroke_outline(self->ctx, dashed ? dashed : stroked->path, sd, &outline);
        poly = outline;
    }
    if (r == SR_OK && !map_polygon(&poly, m, &mapped)) {
        r = SR_OUT_OF_MEMORY;
    }
    if (r == SR_OK && touched_box(poly, w, h, box)) {
        size_t stride = (size_t)w * 4;
        uint8_t *px = (uint8_t *)PyArray_DATA(self->image) + (size_t)box[1] * stride +
                      (size_t)box[0] * 4;
        int bw = box[2] - box[0], bh = box[3] - box[1];
        if (clip) {
            r = fill_clipped(self, poly, paint, fd, clip, box, px, stride);
        } else {
            r = sr_write_pixels(self->ctx, self->fb, box[0], box[1], bw, bh, px, stride);
            if (r == SR_OK) {
                r = sr_fill_polygon_paint(self->ctx, self->fb, &poly, paint, fd);
            }
        }
        if (r == SR_OK) {
            r = sr_read_pixels(self->ctx, self->fb, box[0], box[1], bw, bh, px, stride);
        }
    }
    if (r != SR_OK) {
        snprintf(msg, msg_size, "%s", sr_context_error(self->ctx));
    }
    free(mapped);
    if (stroked) {
        sr_destroy_stroke_outline(self->ctx, &outline);
    }
    sr_destroy_path(self->ctx, dashed);
    return r;
}

/* What a draw is under: softrast.Canvas's transform, m (NULL for the
 * identity) pointing at matrix, and its clip, an (H, W) uint8 coverage
 * of the image (NULL: none), held until state_release. */
typedef struct state_args {
    sr_affine2 matrix;
    const sr_affine2 *m;
    PyArrayObject *clip;
} state_args;

static void state_release(state_args *st)
{
    Py_CLEAR(st->clip);
}

/* (a, b, c, d, e, f), finite and invertible, and None or the clip. */
static int state_arg(CanvasObject *self, PyObject *transform, PyObject *clip, state_args *st)
{
    memset(st, 0, sizeof *st);
    sr_affine2 *t = &st->matrix;
    if (!PyTuple_Check(transform) ||
        !PyArg_ParseTuple(transform, "dddddd:transform", &t->a, &t->b, &t->c, &t->d, &t->e,
                          &t->f)) {
        if (!PyErr_Occurred() || PyErr_ExceptionMatches(PyExc_TypeError)) {
            PyErr_Clear();
            PyErr_SetString(PyExc_TypeError, "transform: expected a tuple of 6 numbers");
        }
        return -1;
    }
    double det = t->a * t->d - t->b * t->c;
    bool finite = isfinite(t->a) && isfinite(t->b) && isfinite(t->c) && isfinite(t->d) &&
                  isfinite(t->e) && isfinite(t->f);
    if (!finite || !isfinite(det) || det == 0) {
        sr_py_value_error(finite ? "transform: the matrix is singular (determinant %g)"
                                 : "transform: contains NaN or infinity", det);
        return -1;
    }
    bool identity = t->a == 1 && t->b == 0 && t->c == 0 && t->d == 1 && t->e == 0 && t->f == 0;
    st->m = identity ? NULL : t;
    if (clip != Py_None) {
        static const int u8[] = { NPY_UINT8, -1 };
        const npy_intp shape[2] = { PyArray_DIM(self->image, 0), PyArray_DIM(self->image, 1) };
        if (!(st->clip = sr_py_take_array(clip, "clip", 2, shape, u8))) {
            return -1;
        }
    }
    return 0;
}

/* Draw and raise what failed; `path` (or NULL) is marked as drawn
 * meanwhile.  sd and da (NULL for fills) are the stroke's. */
static PyObject *draw(CanvasObject *self, PathObject *path, sr_polygon2 poly,
                      const sr_stroke_desc *sd, const dash_args *da, const sr_paint *paint,
                      const sr_fill_desc *fd, double reach, const state_args *st)
{
    int box[4];
    bool release = poly.point_count >= RELEASE_POINTS || st->clip;
    if (!release && st->m) {
        release = true; /* the box in user space says little of the pixels */
    } else if (!release && touched_box(poly, (int)PyArray_DIM(self->image, 1),
                                       (int)PyArray_DIM(self->image, 0), box)) {
        release = (box[2] - box[0] + 2 * reach) * (box[3] - box[1] + 2 * reach) >= RELEASE_PIXELS;
    }
    const uint8_t *clip = st->clip ? PyArray_DATA(st->clip) : NULL;
    char msg[256] = "";
    sr_result r;
    if (path) {
        path->drawing++;
    }
    lock_canvas(self);
    if (release) {
        Py_BEGIN_ALLOW_THREADS
        r = draw_locked(self, poly, sd ? path : NULL, sd, da, paint, fd, st->m, clip, msg,
                        sizeof msg);
        Py_END_ALLOW_THREADS
    } else {
        r = draw_locked(self, poly, sd ? path : NULL, sd, da, paint, fd, st->m, clip, msg,
                        sizeof msg);
    }
    PyThread_release_lock(self->lock);
    if (path) {
        path->drawing--;
    }
    if (r == SR_OUT_OF_MEMORY) {
        return PyErr_NoMemory();
    }
    if (r != SR_OK) {
        return PyErr_Format(PyExc_ValueError, "%s", msg);
    }
    Py_RETURN_NONE;
}

/* The polygon of a list of (N, 2) point arrays, its points and counts
 * malloc'd (freed by the caller, also on failure). */
static int contours_arg(PyObject *list, sr_polygon2 *poly, sr_point2 **pts, int **counts)
{
    *pts = NULL;
    *counts = NULL;
    if (!PyList_Check(list)) {
        PyErr_Format(PyExc_TypeError, "shape: expected a Path or a list of point arrays, got %s",
                     Py_TYPE(list)->tp_name);
        return -1;
    }
    /* A tuple of the items: converting one may run code that changes the list. */
    PyObject *items = PySequence_Tuple(list);
    if (!items) {
        return -1;
    }
    Py_ssize_t nc = PyTuple_GET_SIZE(items), total = 0;
    int status = 0;
    if (nc > INT_MAX || !(*counts = malloc((size_t)(nc ? nc : 1) * sizeof **counts))) {
        PyErr_NoMemory();
        status = -1;
    }
    for (Py_ssize_t c = 0; c < nc && status == 0; c++) {
        char name[48] = "shape";
        if (nc > 1) {
            snprintf(name, sizeof name, "shape[%zd]", c);
        }
        PyArrayObject *a = sr_py_points_arg(PyTuple_GET_ITEM(items, c), name);
        npy_intp n = a ? PyArray_DIM(a, 0) : 0;
        sr_point2 *grown = a && n <= INT_MAX - total
                               ? realloc(*pts, (size_t)(total + n + 1) * sizeof **pts) : NULL;
        if (!grown) {
            if (a) {
                PyErr_NoMemory();
            }
            status = -1;
        } else {
            *pts = grown;
            memcpy(*pts + total, PyArray_DATA(a), (size_t)n * sizeof **pts);
            (*counts)[c] = (int)n;
            total += n;
        }
        Py_XDECREF(a);
    }
    Py_DECREF(items);
    *poly = (sr_polygon2){ *pts, (int)total, *counts, (int)nc };
    return status;
}

/* The polygon of a shape: a Path's (*path set; its points are the
 * path's own) or a list of contours' (*pts and *counts malloc'd, freed
 * by the caller, also on failure). */
static int shape_arg(PyObject *shape, sr_polygon2 *poly, sr_point2 **pts, int **counts,
                     PathObject **path)
{
    *pts = NULL;
    *counts = NULL;
    *path = NULL;
    if (PyObject_TypeCheck(shape, &sr_py_PathType)) {
        if (!((PathObject *)shape)->path) {
            PyErr_SetString(PyExc_ValueError, "shape: the Path is not initialized");
            return -1;
        }
        *path = (PathObject *)shape;
        *poly = sr_path_polygon((*path)->path);
        return 0;
    }
    return contours_arg(shape, poly, pts, counts);
}

static PyObject *canvas_fill(CanvasObject *self, PyObject *args)
{
    PyObject *shape, *paint_obj, *transform, *clip;
    int rule, aa;
    if (ready(self) < 0 || !PyArg_ParseTuple(args, "OOipOO:fill", &shape, &paint_obj, &rule,
                                             &aa, &transform, &clip)) {
        return NULL;
    }
    state_args st;
    if (state_arg(self, transform, clip, &st) < 0) {
        return NULL;
    }
    paint_args p;
    if (paint_arg(paint_obj, &p) < 0) {
        state_release(&st);
        return NULL;
    }
    sr_polygon2 poly = { 0 };
    sr_point2 *pts;
    int *counts;
    PathObject *path;
    PyObject *result = NULL;
    if (shape_arg(shape, &poly, &pts, &counts, &path) == 0) {
        sr_fill_desc fd = { .rule = (sr_fill_rule)rule,
                            .antialias = aa ? SR_AA_AREA : SR_AA_NONE };
        result = draw(self, path, poly, NULL, NULL, &p.paint, &fd, 0, &st);
    }
    free(pts);
    free(counts);
    paint_release(&p);
    state_release(&st);
    return result;
}

/* The coverage of a shape mapped by the transform, as a new (H, W) uint8
 * array: what softrast.Canvas.clip intersects its clip with. */
static PyObject *canvas_coverage(CanvasObject *self, PyObject *args)
{
    PyObject *shape, *transform;
    int rule, aa;
    if (ready(self) < 0 || !PyArg_ParseTuple(args, "OipO:coverage", &shape, &rule, &aa,
                                             &transform)) {
        return NULL;
    }
    state_args st;
    if (state_arg(self, transform, Py_None, &st) < 0) {
        return NULL;
    }
    sr_polygon2 poly = { 0 };
    sr_point2 *pts, *mapped = NULL;
    int *counts;
    PathObject *path;
    PyObject *mask = NULL;
    if (shape_arg(shape, &poly, &pts, &counts, &path) < 0) {
        goto done;
    }
    if (!map_polygon(&poly, st.m, &mapped)) {
        PyErr_NoMemory();
        goto done;
    }
    npy_intp shape2[2] = { PyArray_DIM(self->image, 0), PyArray_DIM(self->image, 1) };
    if (!(mask = PyArray_SimpleNew(2, shape2, NPY_UINT8))) {
        goto done;
    }
    sr_fill_desc fd = { .rule = (sr_fill_rule)rule, .antialias = aa ? SR_AA_AREA : SR_AA_NONE };
    lock_canvas(self); /* the canvas's context */
    sr_result r = sr_polygon_coverage(self->ctx, &poly, &fd, 0, 0, (int)shape2[1],
                                      (int)shape2[0], PyArray_DATA((PyArrayObject *)mask),
                                      (size_t)shape2[1]);
    if (r != SR_OK) {
        if (r == SR_OUT_OF_MEMORY) {
            PyErr_NoMemory();
        } else {
            PyErr_Format(PyExc_ValueError, "%s", sr_context_error(self->ctx));
        }
        Py_CLEAR(mask);
    }
    PyThread_release_lock(self->lock);
done:
    free(mapped);
    free(pts);
    free(counts);
    return mask;
}

static PyObject *canvas_stroke(CanvasObject *self, PyObject *args)
{
    PyObject *paint_obj, *dash_obj, *transform, *clip;
    PathObject *path;
    sr_stroke_desc sd = { 0 };
    dash_args da = { .count = 0 };
    int join, cap, aa;
    if (ready(self) < 0 ||
        !PyArg_ParseTuple(args, "O!OdiidpO!dOO:stroke", &sr_py_PathType, &path, &paint_obj,
                          &sd.width, &join, &cap, &sd.miter_limit, &aa, &PyTuple_Type, &dash_obj,
                          &da.offset, &transform, &clip)) {
        return NULL;
    }
    if (sr_py_dashes_arg(dash_obj, da.dashes, &da.count) < 0) {
        return NULL;
    }
    if (!isfinite(da.offset)) {
        return sr_py_value_error("dash_offset: must be finite, got %g", da.offset);
    }
    if (!path->path) {
        PyErr_SetString(PyExc_ValueError, "path: the Path is not initialized");
        return NULL;
    }
    if (!(sd.width > 0) || !(sd.width <= SR_MAX_COORD2D)) {
        return sr_py_value_error("width: must be in (0, %g], got %g", SR_MAX_COORD2D, sd.width);
    }
    sd.join = (sr_stroke_join)join;
    sd.cap = (sr_stroke_cap)cap;
    state_args st;
    if (state_arg(self, transform, clip, &st) < 0) {
        return NULL;
    }
    paint_args p;
    if (paint_arg(paint_obj, &p) < 0) {
        state_release(&st);
        return NULL;
    }
    /* The outline reaches half the width past the path, more at miters. */
    double reach = sd.width * fmax(sd.miter_limit, 1);
    sr_fill_desc fd = { .rule = SR_NONZERO, .antialias = aa ? SR_AA_AREA : SR_AA_NONE };
    PyObject *result = draw(self, path, sr_path_polygon(path->path), &sd, &da, &p.paint, &fd,
                            reach, &st);
    paint_release(&p);
    state_release(&st);
    return result;
}

static PyObject *canvas_clear(CanvasObject *self, PyObject *args)
{
    sr_clear_desc cd = { .color_action = SR_ACTION_CLEAR };
    if (ready(self) < 0 || !PyArg_ParseTuple(args, "(ffff):clear", &cd.color[0], &cd.color[1],
                                             &cd.color[2], &cd.color[3])) {
        return NULL;
    }
    int w = (int)PyArray_DIM(self->image, 1), h = (int)PyArray_DIM(self->image, 0);
    char msg[256] = "";
    lock_canvas(self);
    sr_result r;
    Py_BEGIN_ALLOW_THREADS
    r = sr_clear(self->ctx, self->fb, &cd);
    if (r == SR_OK) {
        r = sr_read_pixels(self->ctx, self->fb, 0, 0, w, h, PyArray_DATA(self->image),
                           (size_t)w * 4);
    }
    if (r != SR_OK) {
        snprintf(msg, sizeof msg, "%s", sr_context_error(self->ctx));
    }
    Py_END_ALLOW_THREADS
    PyThread_release_lock(self->lock);
    if (r != SR_OK) {
        return PyErr_Format(PyExc_ValueError, "color: %s", msg);
    }
    Py_RETURN_NONE;
}

static PyObject *canvas_get_image(CanvasObject *self, void *closure)
{
    (void)closure;
    if (ready(self) < 0) {
        return NULL;
    }
    Py_INCREF(self->image);
    return (PyObject *)self->image;
}

#define CANVAS_METHOD(name, doc) { #name, (PyCFunction)canvas_##name, METH_VARARGS, doc }

static PyMethodDef canvas_methods[] = {
    CANVAS_METHOD(fill, "fill($self, shape, paint, rule, antialias, transform, clip, /)\n--\n\n"
                        "sr_fill_polygon_paint of a Path or a list of (N, 2) point arrays,\n"
                        "mapped by transform (a, b, c, d, e, f), through clip (an (H, W)\n"
                        "uint8 coverage, or None).  Use softrast.Canvas.fill."),
    CANVAS_METHOD(stroke, "stroke($self, path, paint, width, join, cap, miter_limit, antialias,\n"
                          "       dashes, dash_offset, transform, clip, /)\n--\n\n"
                          "The stroke outline of a Path (sr_make_stroke_outline), of its\n"
                          "dashes (sr_path_dash) when the tuple `dashes` is not empty,\n"
                          "mapped and filled as fill's.  Use softrast.Canvas.stroke."),
    CANVAS_METHOD(coverage, "coverage($self, shape, rule, antialias, transform, /)\n--\n\n"
                            "The (H, W) uint8 coverage of a shape mapped by transform\n"
                            "(sr_polygon_coverage).  Use softrast.Canvas.clip."),
    CANVAS_METHOD(clear, "clear($self, color, /)\n--\n\n"
                         "Every pixel to (r, g, b, a) in [0, 1] as sr_clear quantizes it."),
    { NULL, NULL, 0, NULL },
};

static PyGetSetDef canvas_getset[] = {
    { "image", (getter)canvas_get_image, NULL, "the (H, W, 4) uint8 array drawn into", NULL },
    { NULL, NULL, NULL, NULL, NULL },
};

PyTypeObject sr_py_Canvas2DType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "softrast._softrast.Canvas2D",
    .tp_basicsize = sizeof(CanvasObject),
    .tp_dealloc = (destructor)canvas_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Canvas2D(image)\n--\n\n"
              "The drawing state of softrast.Canvas over an (H, W, 4) uint8 array.",
    .tp_methods = canvas_methods,
    .tp_getset = canvas_getset,
    .tp_init = (initproc)canvas_init,
    .tp_new = PyType_GenericNew,
};
