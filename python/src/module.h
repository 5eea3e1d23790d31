/*
 * module.h - what the files of softrast._softrast share: the Mesh type
 * (mesh.c), the render entry point (render.c), the model readers (load.c),
 * the image files (image.c), the SVG reader (svg.c) and the 2D canvas
 * (path2d.c, canvas.c).
 * Every function here runs with the GIL held unless it says otherwise.
 */
#ifndef SR_PY_MODULE_H
#define SR_PY_MODULE_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL sr_py_ARRAY_API
#ifndef SR_PY_IMPORT_ARRAY
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include <softrast.h>
#include <softrast_io.h>

#include <stdbool.h>
#include <stdint.h>

/* A triangle mesh holding references to the caller's arrays (no copy
 * when they are C-contiguous float32/float64 and int32/int64).  The
 * renderer's programs read them in place; the float32 positions and
 * uint32 indices the built-in color pass needs are copied at each call. */
typedef struct MeshObject {
    PyObject_HEAD
    PyArrayObject *vertices;    /* (N, 3) float32 or float64 */
    PyArrayObject *faces;       /* (M, 3) int32 or int64 */
    PyArrayObject *normals;     /* (N, 3) float32, or NULL */
    PyArrayObject *colors;      /* (N, 3|4) float32, or NULL */
    PyArrayObject *uvs;         /* (N, 2) float32, or NULL */
    PyArrayObject *texture;     /* (H, W, 3|4) uint8, or NULL */
    float *zeros;               /* the draw's position array (render.c says why) */
    size_t zeros_count;
} MeshObject;

extern PyTypeObject sr_py_MeshType;

/* softrast.Path (path2d.c): an sr_path on a context of its own. */
typedef struct PathObject {
    PyObject_HEAD
    sr_context *ctx;
    sr_path *path;              /* NULL until __init__ */
    double tolerance;
    Py_ssize_t drawing;         /* draws reading it without the GIL: no changes meanwhile */
} PathObject;

extern PyTypeObject sr_py_PathType;
/* softrast.PathView (path_view.c): an sr_path_view. */
extern PyTypeObject sr_py_PathViewType;
/* obj (None or NULL: no view) as a view into *storage, *out pointing at
 * it or NULL; TypeError naming `name`, -1. */
int sr_py_path_view_arg(PyObject *obj, const char *name, const sr_path_view **out,
                        sr_path_view *storage);
/* A dash list (a sequence of at most SR_MAX_DASHES finite lengths >= 0)
 * into out[0 .. *count); TypeError or ValueError naming dashes[i], -1. */
int sr_py_dashes_arg(PyObject *obj, double *out, int *count);
/* softrast._softrast.Canvas2D (canvas.c): fills and strokes into an array. */
extern PyTypeObject sr_py_Canvas2DType;

/* A ValueError with a printf message (PyErr_Format has no %g); NULL. */
PyObject *sr_py_value_error(const char *format, ...);
/* obj as a finite double; TypeError or ValueError naming `name`, -1. */
int sr_py_real_arg(PyObject *obj, const char *name, double *out);
/* obj (any array-like of real numbers) as a new (N, 2) float64
 * C-contiguous array of finite points within SR_MAX_COORD2D; NULL with
 * TypeError or ValueError naming `name`. */
PyArrayObject *sr_py_points_arg(PyObject *obj, const char *name);

/* Checks `obj` is an ndarray of `ndim` dimensions, C-contiguous, of one of
 * the given type numbers (terminated by -1), with shape[d] == shape_want[d]
 * where shape_want[d] >= 0; raises TypeError or ValueError naming `name`
 * and returns NULL otherwise.  Returns a new reference: to obj itself, or
 * to an aligned copy when obj is not aligned. */
PyArrayObject *sr_py_take_array(PyObject *obj, const char *name, int ndim, const npy_intp *shape_want,
                                const int *types);

/* The mesh's float32 positions and uint32 indices for sr_draw: its own
 * arrays when they have those types, else copies made now, as the caller's
 * arrays hold them at this call (they may change between calls).  held[0]
 * and held[1] get new references (or NULL) to release after the draw.
 * -1 with an exception set on failure. */
int sr_py_mesh_draw_arrays(MeshObject *m, const float **positions, const uint32_t **indices,
                           PyObject *held[2]);

/* Scans faces for an index outside [0, N); returns the first offending
 * face or -1.  Needs no GIL. */
Py_ssize_t sr_py_mesh_bad_face(const MeshObject *m);

/* What render() draws with (context_cache.c): a context of `threads`
 * threads and its framebuffer (either NULL until made), and room for the
 * per-vertex data of a view (render.c). */
typedef struct sr_py_render_set {
    sr_context *ctx;
    sr_framebuffer *fb;
    int threads, width, height; /* the context's; the framebuffer's size */
    void *vertices;
    size_t vertices_bytes;
    void *visibility;           /* the visibility pass's buffers (visibility.c) */
    size_t visibility_bytes;
    size_t visibility_cleared;  /* its leading pixel words known to be 0 */
    bool cached;                /* the kept set, to be given back */
} sr_py_render_set;

/* The set kept from an earlier call when it is free and was made for
 * `threads` (and the same SR_THREADS and SR_SIMD), else an empty one to
 * fill.  Give every set taken back: `keep` (false after a failed draw)
 * keeps it for the next call when none is kept, else it is released. */
void sr_py_take_render_set(int threads, sr_py_render_set *out);
void sr_py_give_back_render_set(sr_py_render_set *s, bool keep);
/* Frees what the set holds and empties it.  Needs no GIL. */
void sr_py_release_render_set(sr_py_render_set *s);

/* A loaded glTF primitive as the metallic-roughness look draws it
 * (scene_file.c): its material and the arrays to draw. */
typedef struct sr_py_file_draw {
    const sr_pbr_material *material;
    bool mirrored;              /* its world matrix mirrors */
    sr_mesh mesh;               /* positions, normals, texcoords (set 0), colors, indices */
    const float *texcoords1;    /* or NULL */
    const float *tangents;      /* 4 a vertex, or NULL */
    bool owned_mesh;            /* mesh made here (flat normals) */
    float *owned_tangents;
} sr_py_file_draw;

/* A capsule keeping ctx and scene (sr_load_scene's, both taken over,
 * also on failure) with each primitive prepared to draw; NULL with an
 * exception set on failure. */
PyObject *sr_py_scene_file(sr_context *ctx, sr_scene *scene);
/* The library's scene such a capsule draws, shared by every pose of one
 * reading (posed only under the GIL); NULL with TypeError. */
sr_scene *sr_py_scene_of(PyObject *capsule);
/* A new capsule of that scene as it is posed now, sharing the reading. */
PyObject *sr_py_scene_file_again(PyObject *capsule);
/* Primitive `index` of such a capsule, or NULL with TypeError. */
const sr_py_file_draw *sr_py_file_draw_of(PyObject *capsule, Py_ssize_t index);
/* make_environment(path, intensity, threads): a capsule holding an
 * sr_environment (path "": the built-in studio); environment.c. */
PyObject *sr_py_make_environment(PyObject *self, PyObject *args);
/* The environment of such a capsule, or NULL with TypeError. */
const sr_environment *sr_py_environment_of(PyObject *capsule);

PyObject *sr_py_render(PyObject *self, PyObject *args, PyObject *kwargs);
PyObject *sr_py_load_scene(PyObject *self, PyObject *args);
PyObject *sr_py_pose_scene(PyObject *self, PyObject *args);
/* texture_slot_uv(uvs, offset, rotation, scale): sr_texture_slot_uv. */
PyObject *sr_py_texture_slot_uv(PyObject *self, PyObject *args);
PyObject *sr_py_load_mesh(PyObject *self, PyObject *args);
PyObject *sr_py_read_image(PyObject *self, PyObject *args);
PyObject *sr_py_decode_image(PyObject *self, PyObject *args);
PyObject *sr_py_write_png(PyObject *self, PyObject *args);
/* render_svg(path, data, name, width, height, scale, background) and
 * parse_color(text): svg.c. */
PyObject *sr_py_render_svg(PyObject *self, PyObject *args);
PyObject *sr_py_parse_color(PyObject *self, PyObject *args);

/* check_memory(what, need, lower): sr_check_memory's limit, MemoryError
 * beyond it (memory_limit.c). */
PyObject *sr_py_check_memory(PyObject *self, PyObject *args);
/* sr_fit_camera of (vertices, model) pairs (framing.c). */
PyObject *sr_py_fit_camera(PyObject *self, PyObject *args);
/* Raises a reader's or writer's error with its one-line message (io_error.c):
 * for SR_IO_ERROR an OSError, of the subclass the errno of `path` (NULL:
 * none) names, with `path` as its filename; MemoryError; else ValueError.
 * Returns NULL. */
PyObject *sr_py_io_error(sr_result r, const sr_io_error *err, const char *path);
/* Why a library call just failed with r: the thread's sr_last_error, which
 * names the argument, or r's text when it left none (clear it with
 * sr_set_last_error(NULL) before the calls, so that an older one cannot
 * answer).  Any thread, the GIL held or not. */
const char *sr_py_why(sr_result r);
/* A message of the library as str: a name in it need not be UTF-8, and
 * one cut from the left may start inside a character. */
PyObject *sr_py_message_text(const char *message);

/* A reader's warnings, kept as they come (warning_list.c). */
typedef struct sr_py_warnings {
    char **lines;
    int count, capacity;
    bool lost;          /* a line that could not be kept (no memory) */
} sr_py_warnings;
/* A reader's warn callback, user an sr_py_warnings: runs without the GIL. */
void sr_py_keep_warning(void *user, const char *message);
/* The kept lines as a new list of str, emptying w; NULL with an exception
 * set (MemoryError when a line was lost). */
PyObject *sr_py_take_warnings(sr_py_warnings *w);
/* The kept lines freed, unread. */
void sr_py_drop_warnings(sr_py_warnings *w);
/* An (h, w, 4) uint8 array over the RGBA pixels px, which it takes over
 * and frees (they come from malloc: the readers', render_svg's); NULL on
 * failure, px freed. */
PyObject *sr_py_image_array(uint8_t *px, int w, int h);

#endif
