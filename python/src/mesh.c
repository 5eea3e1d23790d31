/*
 * mesh.c - softrast.Mesh: a triangle mesh over the caller's numpy arrays.
 * Validates shapes, dtypes, layout, finiteness and index range once, at
 * construction, and keeps references (no copy) where the layout is one the
 * renderer reads in place.  GIL held throughout.
 */
#include "module.h"
#include "pipeline.h"
#include "raster/triangle_simd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *type_list(const int *types, char *buf, size_t size)
{
    buf[0] = '\0';
    for (int i = 0; types[i] >= 0; i++) {
        PyArray_Descr *d = PyArray_DescrFromType(types[i]);
        PyObject *s = PyObject_Str((PyObject *)d->typeobj);
        const char *name = NULL;
        /* "<class 'numpy.float32'>" -> "float32" */
        if (s && (name = PyUnicode_AsUTF8(s))) {
            const char *dot = strrchr(name, '.');
            size_t len = strlen(buf);
            snprintf(buf + len, size - len, "%s%.*s", i ? " or " : "",
                     dot ? (int)strcspn(dot + 1, "'") : 0, dot ? dot + 1 : "");
        }
        PyErr_Clear();
        Py_XDECREF(s);
        Py_DECREF(d);
    }
    return buf;
}

PyArrayObject *sr_py_take_array(PyObject *obj, const char *name, int ndim, const npy_intp *shape_want,
                                const int *types)
{
    PyArrayObject *a;
    if (PyArray_Check(obj)) {
        Py_INCREF(obj);
        a = (PyArrayObject *)obj;
    } else {
        /* A list or other array-like becomes a fresh array of the first
         * accepted type, as numpy functions take them; but not a list of
         * bools, which that would read as 0 and 1 (the dtype check below
         * refuses it, as it refuses a bool array). */
        a = (PyArrayObject *)PyArray_FromAny(obj, NULL, 0, 0, 0, NULL);
        if (a && !PyArray_ISBOOL(a)) {
            Py_DECREF(a);
            a = (PyArrayObject *)PyArray_FROMANY(obj, types[0], 0, 0, NPY_ARRAY_C_CONTIGUOUS);
        }
        if (!a) {
            PyErr_Clear();
            PyErr_Format(PyExc_TypeError, "%s: expected a numpy array, got %s", name,
                         Py_TYPE(obj)->tp_name);
            return NULL;
        }
    }
    bool type_ok = false;
    for (int i = 0; types[i] >= 0; i++) {
        type_ok |= PyArray_TYPE(a) == types[i];
    }
    char buf[128];
    if (!type_ok) {
        PyObject *dt = PyObject_Str((PyObject *)PyArray_DESCR(a));
        PyErr_Format(PyExc_TypeError, "%s: dtype must be %s, got %S", name,
                     type_list(types, buf, sizeof buf), dt ? dt : Py_None);
        Py_XDECREF(dt);
        Py_DECREF(a);
        return NULL;
    }
    bool shape_ok = PyArray_NDIM(a) == ndim;
    for (int d = 0; shape_ok && d < ndim; d++) {
        shape_ok = shape_want[d] < 0 || PyArray_DIM(a, d) == shape_want[d];
    }
    if (!shape_ok) {
        char want[96] = "(", got[96] = "(";
        for (int d = 0; d < ndim; d++) {
            size_t len = strlen(want);
            if (shape_want[d] < 0) {
                snprintf(want + len, sizeof want - len, "%s%c", d ? ", " : "", (ndim == 3 ? "HWC" : "NK")[d]);
            } else {
                snprintf(want + len, sizeof want - len, "%s%ld", d ? ", " : "", (long)shape_want[d]);
            }
        }
        for (int d = 0; d < PyArray_NDIM(a) && d < 8; d++) {
            size_t len = strlen(got);
            snprintf(got + len, sizeof got - len, "%s%ld", d ? ", " : "", (long)PyArray_DIM(a, d));
        }
        PyErr_Format(PyExc_ValueError, "%s: shape must be %s), got %s)", name, want, got);
        Py_DECREF(a);
        return NULL;
    }
    if (!PyArray_IS_C_CONTIGUOUS(a)) {
        PyErr_Format(PyExc_ValueError,
                     "%s: array must be C-contiguous (pass np.ascontiguousarray(%s))", name, name);
        Py_DECREF(a);
        return NULL;
    }
    if (!PyArray_ISALIGNED(a) || PyArray_ISBYTESWAPPED(a)) {
        /* Unpickled arrays may lie at any address, and a '>f4' array holds
         * its numbers in the other byte order: read a native, aligned copy. */
        PyArrayObject *copy = (PyArrayObject *)PyArray_FROMANY(
            (PyObject *)a, PyArray_TYPE(a), 0, 0, NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED);
        Py_DECREF(a);
        a = copy;
    }
    return a;
}

static bool all_finite(PyArrayObject *a)
{
    size_t n = (size_t)PyArray_SIZE(a);
    if (PyArray_TYPE(a) == NPY_FLOAT32) {
        const float *p = PyArray_DATA(a);
        for (size_t i = 0; i < n; i++) {
            if (!isfinite(p[i])) {
                return false;
            }
        }
    } else {
        const double *p = PyArray_DATA(a);
        for (size_t i = 0; i < n; i++) {
            if (!isfinite(p[i])) {
                return false;
            }
        }
    }
    return true;
}

/* Indices [begin, end) of f as unsigned (a negative one becomes one too
 * large), in blocks whose largest is found without a branch, which the
 * compiler vectorizes; only a block holding a bad index is searched for
 * the first. */
#define BAD_FACE_SCAN(UT)                                                                 \
    for (size_t b = 0; b < count; b += block) {                                           \
        size_t end = count - b < block ? count : b + block;                               \
        UT most = 0;                                                                      \
        for (size_t i = b; i < end; i++) {                                                \
            most = (UT)f[i] > most ? (UT)f[i] : most;                                     \
        }                                                                                 \
        if ((uint64_t)most >= n) {                                                        \
            for (size_t i = b; i < end; i++) {                                            \
                if (f[i] < 0 || (uint64_t)f[i] >= n) {                                    \
                    return (Py_ssize_t)(i / 3);                                           \
                }                                                                         \
            }                                                                             \
        }                                                                                 \
    }

Py_ssize_t sr_py_mesh_bad_face(const MeshObject *m)
{
    size_t count = 3 * (size_t)PyArray_DIM(m->faces, 0), block = 3 << 10;
    uint64_t n = (uint64_t)PyArray_DIM(m->vertices, 0);
    if (PyArray_TYPE(m->faces) == NPY_INT32) {
        const int32_t *f = PyArray_DATA(m->faces);
        /* Read as unsigned, a negative index is at least 2^31: the
         * library's index check (AVX2 where the CPU has it: the same
         * largest index) clears the common case at once. */
        if (n <= (uint64_t)INT32_MAX + 1 &&
            sr__index_max(SR_INDEX_U32, f, 0, count, sr__simd_cpu_level() >= SR_SIMD_AVX2) < n) {
            return -1;
        }
        BAD_FACE_SCAN(uint32_t)
    } else {
        const int64_t *f = PyArray_DATA(m->faces);
        BAD_FACE_SCAN(uint64_t)
    }
    return -1;
}

/* An optional per-vertex array: float32 kept as it is, float64 converted
 * when `float32_only` (sr_draw reads normals, colors and uvs as floats). */
static int take_vertex_array(PyObject *obj, const char *name, npy_intp n, npy_intp cols,
                             bool float32_only, PyArrayObject **out)
{
    static const int float_types[] = { NPY_FLOAT32, NPY_FLOAT64, -1 };
    *out = NULL;
    if (!obj || obj == Py_None) {
        return 0;
    }
    npy_intp shape[2] = { n, cols };
    PyArrayObject *a = sr_py_take_array(obj, name, 2, shape, float_types);
    if (!a) {
        return -1;
    }
    if (!all_finite(a)) {
        PyErr_Format(PyExc_ValueError, "%s: contains NaN or infinity", name);
        Py_DECREF(a);
        return -1;
    }
    if (float32_only && PyArray_TYPE(a) != NPY_FLOAT32) {
        PyArrayObject *f = (PyArrayObject *)PyArray_FROMANY((PyObject *)a, NPY_FLOAT32, 2, 2,
                                                            NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_FORCECAST);
        Py_DECREF(a);
        a = f;
        if (!a) {
            return -1;
        }
    }
    *out = a;
    return 0;
}

static void mesh_clear_arrays(MeshObject *m)
{
    Py_CLEAR(m->vertices);
    Py_CLEAR(m->faces);
    Py_CLEAR(m->normals);
    Py_CLEAR(m->colors);
    Py_CLEAR(m->uvs);
    Py_CLEAR(m->texture);
    free(m->zeros);
    m->zeros = NULL;
    m->zeros_count = 0;
}

static int mesh_init(MeshObject *m, PyObject *args, PyObject *kwargs)
{
    static char *kwlist[] = { "vertices", "faces", "normals", "colors", "uvs", "texture", NULL };
    static const int float_types[] = { NPY_FLOAT32, NPY_FLOAT64, -1 };
    static const int int_types[] = { NPY_INT32, NPY_INT64, -1 };
    static const int u8_types[] = { NPY_UINT8, -1 };
    PyObject *vertices, *faces, *normals = NULL, *colors = NULL, *uvs = NULL, *texture = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|OOOO:Mesh", kwlist, &vertices, &faces,
                                     &normals, &colors, &uvs, &texture)) {
        return -1;
    }
    if (m->vertices) {
        /* Another thread may be drawing it with the GIL released. */
        PyErr_SetString(PyExc_TypeError, "Mesh: a mesh cannot be initialized twice; make a new one");
        return -1;
    }
    const npy_intp v_shape[2] = { -1, 3 };
    m->vertices = sr_py_take_array(vertices, "vertices", 2, v_shape, float_types);
    if (!m->vertices) {
        goto fail;
    }
    if (!all_finite(m->vertices)) {
        PyErr_SetString(PyExc_ValueError, "vertices: contains NaN or infinity");
        goto fail;
    }
    npy_intp n = PyArray_DIM(m->vertices, 0);
    if ((size_t)n > ((size_t)1 << 28)) {
        PyErr_SetString(PyExc_ValueError, "vertices: more than 2**28 vertices");
        goto fail;
    }
    m->faces = sr_py_take_array(faces, "faces", 2, v_shape, int_types);
    if (!m->faces) {
        goto fail;
    }
    if ((size_t)PyArray_DIM(m->faces, 0) > ((size_t)1 << 28) / 3) {
        /* The renderer draws 3 corners a face, at most 2**28 a draw. */
        PyErr_SetString(PyExc_ValueError, "faces: more than 2**28 / 3 faces");
        goto fail;
    }
    Py_ssize_t bad = sr_py_mesh_bad_face(m);
    if (bad >= 0) {
        PyErr_Format(PyExc_ValueError, "faces: face %zd has an index outside [0, %zd)", bad,
                     (Py_ssize_t)n);
        goto fail;
    }
    if (take_vertex_array(normals, "normals", n, 3, true, &m->normals) < 0) {
        goto fail;
    }
    if (colors && colors != Py_None) {
        PyObject *c = colors;
        npy_intp cols = PyArray_Check(c) && PyArray_NDIM((PyArrayObject *)c) == 2 &&
                                PyArray_DIM((PyArrayObject *)c, 1) == 4 ? 4 : 3;
        if (take_vertex_array(colors, "colors", n, cols, true, &m->colors) < 0) {
            goto fail;
        }
    }
    if (take_vertex_array(uvs, "uvs", n, 2, true, &m->uvs) < 0) {
        goto fail;
    }
    if (texture && texture != Py_None) {
        npy_intp t_shape[3] = { -1, -1, -1 };
        m->texture = sr_py_take_array(texture, "texture", 3, t_shape, u8_types);
        if (!m->texture) {
            goto fail;
        }
        npy_intp c = PyArray_DIM(m->texture, 2);
        if ((c != 3 && c != 4) || PyArray_DIM(m->texture, 0) < 1 ||
            PyArray_DIM(m->texture, 0) > 16384 || PyArray_DIM(m->texture, 1) < 1 ||
            PyArray_DIM(m->texture, 1) > 16384) {
            PyErr_SetString(PyExc_ValueError,
                            "texture: shape must be (H, W, 3) or (H, W, 4), 1 <= H, W <= 16384");
            goto fail;
        }
        if (!m->uvs) {
            PyErr_SetString(PyExc_ValueError, "texture: needs uvs");
            goto fail;
        }
    }
    return 0;
fail:
    mesh_clear_arrays(m);
    return -1;
}

/* `a` as an array of `type`: a new reference to a itself, or to a copy. */
static PyArrayObject *as_type(PyArrayObject *a, int type)
{
    if (PyArray_TYPE(a) == type) {
        Py_INCREF(a);
        return a;
    }
    return (PyArrayObject *)PyArray_FROMANY((PyObject *)a, type, 2, 2,
                                            NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_FORCECAST);
}

int sr_py_mesh_draw_arrays(MeshObject *m, const float **positions, const uint32_t **indices,
                           PyObject *held[2])
{
    /* int32 indices checked to lie in [0, N) read the same as uint32. */
    PyArrayObject *p = as_type(m->vertices, NPY_FLOAT32);
    PyArrayObject *f = p ? as_type(m->faces, PyArray_TYPE(m->faces) == NPY_INT32 ? NPY_INT32
                                                                                 : NPY_UINT32)
                         : NULL;
    if (!f) {
        Py_XDECREF(p);
        return -1;
    }
    *positions = PyArray_DATA(p);
    *indices = PyArray_DATA(f);
    held[0] = (PyObject *)p;
    held[1] = (PyObject *)f;
    return 0;
}

static int mesh_traverse(MeshObject *m, visitproc visit, void *arg)
{
    Py_VISIT(m->vertices);
    Py_VISIT(m->faces);
    Py_VISIT(m->normals);
    Py_VISIT(m->colors);
    Py_VISIT(m->uvs);
    Py_VISIT(m->texture);
    return 0;
}

static int mesh_clear(MeshObject *m)
{
    mesh_clear_arrays(m);
    return 0;
}

static void mesh_dealloc(MeshObject *m)
{
    PyObject_GC_UnTrack(m);
    mesh_clear_arrays(m);
    Py_TYPE(m)->tp_free((PyObject *)m);
}

static PyObject *get_array(PyArrayObject *a)
{
    if (!a) {
        Py_RETURN_NONE;
    }
    Py_INCREF(a);
    return (PyObject *)a;
}

static PyObject *mesh_vertices(MeshObject *m, void *c) { (void)c; return get_array(m->vertices); }
static PyObject *mesh_faces(MeshObject *m, void *c) { (void)c; return get_array(m->faces); }
static PyObject *mesh_normals(MeshObject *m, void *c) { (void)c; return get_array(m->normals); }
static PyObject *mesh_colors(MeshObject *m, void *c) { (void)c; return get_array(m->colors); }
static PyObject *mesh_uvs(MeshObject *m, void *c) { (void)c; return get_array(m->uvs); }
static PyObject *mesh_texture(MeshObject *m, void *c) { (void)c; return get_array(m->texture); }

static PyObject *mesh_repr(MeshObject *m)
{
    if (!m->vertices) {
        return PyUnicode_FromString("<softrast.Mesh (uninitialized)>");
    }
    return PyUnicode_FromFormat("<softrast.Mesh %zd vertices, %zd faces%s%s%s%s>",
                                (Py_ssize_t)PyArray_DIM(m->vertices, 0),
                                (Py_ssize_t)PyArray_DIM(m->faces, 0), m->normals ? ", normals" : "",
                                m->colors ? ", colors" : "", m->uvs ? ", uvs" : "",
                                m->texture ? ", texture" : "");
}

/* Pickling (Dask sends meshes to its workers): the arrays, by value. */
static PyObject *mesh_reduce(MeshObject *m, PyObject *unused)
{
    (void)unused;
    if (!m->vertices) {
        PyErr_SetString(PyExc_ValueError, "cannot pickle an uninitialized Mesh");
        return NULL;
    }
    PyObject *none = Py_None;
#define SR_PY_OR_NONE(a) ((a) ? (PyObject *)(a) : none)
    return Py_BuildValue("(O(OOOOOO))", (PyObject *)Py_TYPE(m), (PyObject *)m->vertices,
                         (PyObject *)m->faces, SR_PY_OR_NONE(m->normals), SR_PY_OR_NONE(m->colors),
                         SR_PY_OR_NONE(m->uvs), SR_PY_OR_NONE(m->texture));
#undef SR_PY_OR_NONE
}

static PyMethodDef mesh_methods[] = {
    { "__reduce__", (PyCFunction)mesh_reduce, METH_NOARGS, "Pickle support." },
    { NULL, NULL, 0, NULL },
};

static PyGetSetDef mesh_getset[] = {
    { "vertices", (getter)mesh_vertices, NULL, "(N, 3) float32 or float64 vertex positions.", NULL },
    { "faces", (getter)mesh_faces, NULL, "(M, 3) int32 or int64 vertex indices of the triangles.", NULL },
    { "normals", (getter)mesh_normals, NULL, "(N, 3) float32 vertex normals, or None.", NULL },
    { "colors", (getter)mesh_colors, NULL, "(N, 3|4) float32 vertex colors in [0, 1], or None.", NULL },
    { "uvs", (getter)mesh_uvs, NULL, "(N, 2) float32 texture coordinates, or None.", NULL },
    { "texture", (getter)mesh_texture, NULL, "(H, W, 3|4) uint8 texture, or None.", NULL },
    { NULL, NULL, NULL, NULL, NULL },
};

PyDoc_STRVAR(mesh_doc,
"Mesh(vertices, faces, normals=None, colors=None, uvs=None, texture=None)\n"
"--\n"
"\n"
"A triangle mesh over numpy arrays.\n"
"\n"
"vertices: (N, 3) float32 or float64 positions.\n"
"faces: (M, 3) int32 or int64 indices into vertices; (0, 3) is an empty mesh.\n"
"normals: (N, 3) vertex normals (float64 is converted; face normals are\n"
"    used without them).\n"
"colors: (N, 3) or (N, 4) vertex colors in [0, 1] (float64 is converted).\n"
"uvs: (N, 2) texture coordinates, (0, 0) the image's bottom-left corner.\n"
"texture: (H, W, 3) or (H, W, 4) uint8 image, row 0 at the top; needs uvs.\n"
"\n"
"C-contiguous arrays of these dtypes are kept by reference, not copied:\n"
"changing them later changes the mesh (indices are checked again at each\n"
"render).  Raises TypeError for a wrong dtype, ValueError for a wrong\n"
"shape, a non-contiguous array, NaN or infinity, or an index out of range.");

PyTypeObject sr_py_MeshType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "softrast.Mesh",
    .tp_basicsize = sizeof(MeshObject),
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_HAVE_GC,
    .tp_doc = mesh_doc,
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)mesh_init,
    .tp_dealloc = (destructor)mesh_dealloc,
    .tp_traverse = (traverseproc)mesh_traverse,
    .tp_clear = (inquiry)mesh_clear,
    .tp_getset = mesh_getset,
    .tp_methods = mesh_methods,
    .tp_repr = (reprfunc)mesh_repr,
};
