/*
 * module.c - the softrast._softrast extension module: its functions, the
 * Mesh type, and the library's version.  The Python package softrast
 * (softrast/__init__.py) wraps it; use that.
 */
#define SR_PY_IMPORT_ARRAY
#include "module.h"

PyDoc_STRVAR(render_doc,
"render(instances, K, width, height, near, threads, depth, triangle_id, instance_id,\n"
"       barycentric, normal, color, mask, background, lit, rgba=None, pbr=False,\n"
"       view=None, environment=None, shadows=False, general=False, ortho=False,\n"
"       far=0.0, msaa=1, ssaa=1, ground=False, cull=False, lights=None,\n"
"       lights_mode=0, exposure=0.0, tonemap=0, material_id=None, position=None,\n"
"       uv=None, flow=None, to_frame=None, materials=None, flow_K=None,\n"
"       flow_Rt=None, flow_ortho=False)\n"
"--\n"
"\n"
"The C renderer behind softrast.render (use that): one camera.\n"
"instances: a sequence of (Mesh, (3, 4) float64 object->camera matrix,\n"
"(3, 3) float64 normal matrix, int id[, the material tuple of pbr=True or\n"
"None[, the texture's (sr_texture_filter, wrap_u, wrap_v)]]);\n"
"K: (3, 3) float64.  The outputs (depth ... mask, rgba ... flow) are\n"
"written into the given C-contiguous arrays (None: not wanted).\n"
"to_frame: (3, 4) float64 camera -> the position output's frame (None:\n"
"the camera's); materials: an int a instance, its material_id (None:\n"
"-1); flow_K, flow_Rt (3, 4), flow_ortho: the next view's K, camera ->\n"
"its camera and projection, for flow (None: NaN, the last view).\n"
"lights, lights_mode (pbr): up to 8 (type, (vector), (color), intensity,\n"
"(direction), inner, outer, range) tuples of lit lights in world space,\n"
"and softrast render's --lights: 0 the default rig, 1 these, 2 both.\n"
"exposure, tonemap (pbr): --exposure in stops, --tonemap as sr_tonemap_op.\n"
"general: the geometry outputs through the library's pipeline even where\n"
"the visibility pass could draw them (the same bytes; for the tests).");

PyDoc_STRVAR(load_mesh_doc,
"load_mesh(path, /)\n--\n\n"
"sr_load_mesh: a dict of arrays (vertices, faces, normals, colors, uvs,\n"
"texture).  Use softrast.load_mesh.");

PyDoc_STRVAR(pose_scene_doc,
"pose_scene(file, path, animation=-1, time=0.0, /)\n--\n\n"
"The scene a load_scene `file` capsule draws posed again by sr_scene_pose\n"
"(animation -1: the rest pose), without reading `path` (named in errors):\n"
"load_scene's dict, its \"file\" a new capsule sharing the reading.");

PyDoc_STRVAR(load_scene_doc,
"load_scene(path, variant=None, animation=-1, time=0.0, /)\n--\n\n"
"sr_load_scene, posed by the file's animation `animation` at `time`\n"
"seconds (-1: the rest pose): {'meshes': [dict of arrays], 'instances':\n"
"[(mesh index, (4, 4) world matrix, material index)], 'materials': [dict\n"
"of factors], 'cameras': [dict of a camera's fields], 'variants': [names],\n"
"'animations': [(name, channels, duration)], 'file': the scene kept for\n"
"render's metallic-roughness look, or None}; variant (a name or a number\n"
"from 0) picks the materials of a glTF material variant.\n"
"Use softrast.load.");

PyDoc_STRVAR(texture_slot_uv_doc,
"texture_slot_uv(uvs, offset, rotation, scale, /)\n--\n\n"
"sr_texture_slot_uv: (N, 2) float32 uvs through a texture slot's\n"
"KHR_texture_transform, as the library applies it (a new array).");

PyDoc_STRVAR(make_environment_doc,
"make_environment(path, intensity, threads, /)\n--\n\n"
"An image-based light for render(pbr=True): the built-in studio (path '')\n"
"or an equirectangular .hdr file, prefiltered.  Use render(environment=).");

PyDoc_STRVAR(read_image_doc,
"read_image(path, /)\n--\n\n"
"A PNG, JPEG or WebP file (told apart by its first bytes; WebP when the\n"
"library was built with libwebp, still images only) as an (H, W, 4) uint8\n"
"RGBA array, row 0 at the top: a texture for softrast.Mesh.  Raises\n"
"OSError when the file cannot be read, ValueError when it is malformed or\n"
"of a format this build cannot read.");

PyDoc_STRVAR(decode_image_doc,
"decode_image(data, name, /)\n--\n\n"
"PNG, JPEG or WebP bytes (as read_image reads them) as an (H, W, 4) uint8\n"
"RGBA array, row 0 at the top;\n"
"`name` is used in the error, a ValueError when the data is malformed.");

PyDoc_STRVAR(write_png_doc,
"write_png(path, image, /)\n--\n\n"
"Write an (H, W, 3) or (H, W, 4) uint8 C-contiguous image as a PNG, row 0\n"
"at the top, atomically: a temporary file renamed over `path`, so a write\n"
"that fails or is killed leaves no partial file.");

PyDoc_STRVAR(render_svg_doc,
"render_svg(path, data, name, width, height, scale, background, /)\n--\n\n"
"sr_render_svg_file (path) or sr_render_svg (data, bytes-like), path or\n"
"data None: (an (H, W, 4) uint8 RGBA array or None, [the warnings' lines],\n"
"None or the error to raise after them).  name: the document's name and\n"
"directory, None for the default.  width, height 0: the drawing's size\n"
"times scale (0: 1); background (r, g, b, a) in [0, 1].  Use\n"
"softrast.render_svg.");

PyDoc_STRVAR(parse_color_doc,
"parse_color(text, /)\n--\n\n"
"sr_io_parse_color: a CSS color as SVG reads it, as (r, g, b, a) in\n"
"[0, 1]; ValueError when it is not one.");

PyDoc_STRVAR(check_memory_doc,
"check_memory(what, need, lower, /)\n--\n\n"
"sr_check_memory: None when `need` bytes of images fit the memory limit\n"
"(SR_MEMORY_LIMIT, else the physical memory or a ulimit), else MemoryError\n"
"\"WHAT needs about N of image memory, more than ...: LOWER\"; ValueError\n"
"for a malformed SR_MEMORY_LIMIT.");

PyDoc_STRVAR(fit_camera_doc,
"fit_camera(sets, width, height, fov, ortho, /)\n--\n\n"
"sr_fit_camera: softrast render's default camera framing the (vertices\n"
"(N, 3) float32, model (16,) float32 column-major) pairs: ((eye), (target),\n"
"(up), fovy, half_width, half_height).  Use softrast.fit_camera.");

static PyMethodDef methods[] = {
    { "render", (PyCFunction)(void (*)(void))sr_py_render, METH_VARARGS | METH_KEYWORDS, render_doc },
    { "load_mesh", sr_py_load_mesh, METH_VARARGS, load_mesh_doc },
    { "load_scene", sr_py_load_scene, METH_VARARGS, load_scene_doc },
    { "pose_scene", sr_py_pose_scene, METH_VARARGS, pose_scene_doc },
    { "texture_slot_uv", sr_py_texture_slot_uv, METH_VARARGS, texture_slot_uv_doc },
    { "make_environment", sr_py_make_environment, METH_VARARGS, make_environment_doc },
    { "read_image", sr_py_read_image, METH_VARARGS, read_image_doc },
    { "decode_image", sr_py_decode_image, METH_VARARGS, decode_image_doc },
    { "write_png", sr_py_write_png, METH_VARARGS, write_png_doc },
    { "render_svg", sr_py_render_svg, METH_VARARGS, render_svg_doc },
    { "parse_color", sr_py_parse_color, METH_VARARGS, parse_color_doc },
    { "fit_camera", sr_py_fit_camera, METH_VARARGS, fit_camera_doc },
    { "check_memory", sr_py_check_memory, METH_VARARGS, check_memory_doc },
    { NULL, NULL, 0, NULL },
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "softrast._softrast",
    .m_doc = "softrast's C extension: the renderer, the Mesh type and the model readers.",
    .m_size = -1,
    .m_methods = methods,
};

/* softrast.features: sr_io_features as a tuple of names. */
static int add_features(PyObject *m)
{
    PyObject *text = PyUnicode_FromString(sr_io_features());
    PyObject *list = text ? PyUnicode_Split(text, NULL, -1) : NULL;
    PyObject *tuple = list ? PyList_AsTuple(list) : NULL;
    Py_XDECREF(text);
    Py_XDECREF(list);
    if (!tuple || PyModule_AddObject(m, "features", tuple) < 0) {
        Py_XDECREF(tuple);
        return -1;
    }
    return 0;
}

PyMODINIT_FUNC PyInit__softrast(void);

/* The default camera's direction, margin and field of view
 * (sr_framing_direction, SR_FRAMING_MARGIN, SR_FRAMING_FOV_DEG), for
 * softrast.orbit's defaults. */
static int add_framing_constants(PyObject *m)
{
    sr_vec3 d = sr_framing_direction();
    PyObject *dir = Py_BuildValue("(ddd)", (double)d.x, (double)d.y, (double)d.z);
    if (!dir || PyModule_AddObject(m, "framing_direction", dir) < 0) {
        Py_XDECREF(dir);
        return -1;
    }
    PyObject *margin = PyFloat_FromDouble(SR_FRAMING_MARGIN);
    if (!margin || PyModule_AddObject(m, "framing_margin", margin) < 0) {
        Py_XDECREF(margin);
        return -1;
    }
    PyObject *fov = PyFloat_FromDouble(SR_FRAMING_FOV_DEG);
    if (!fov || PyModule_AddObject(m, "framing_fov_deg", fov) < 0) {
        Py_XDECREF(fov);
        return -1;
    }
    return 0;
}

/* The names softrast.Canvas and its paints take, with the library's enum
 * values: {"rule": {"nonzero": SR_NONZERO, ...}, ...}; and
 * SR_MAX_GRADIENT_STOPS. */
static int add_draw2d_names(PyObject *m)
{
    PyObject *names = Py_BuildValue(
        "{s{sisi}s{sisisi}s{sisisi}s{sisisi}s{sisi}s{sisisisi}}",
        "rule", "nonzero", SR_NONZERO, "evenodd", SR_EVENODD,
        "join", "miter", SR_STROKE_JOIN_MITER, "round", SR_STROKE_JOIN_ROUND, "bevel",
        SR_STROKE_JOIN_BEVEL,
        "cap", "butt", SR_STROKE_CAP_BUTT, "round", SR_STROKE_CAP_ROUND, "square",
        SR_STROKE_CAP_SQUARE,
        "spread", "pad", SR_SPREAD_PAD, "reflect", SR_SPREAD_REFLECT, "repeat", SR_SPREAD_REPEAT,
        "wrap", "repeat", SR_WRAP_REPEAT, "clamp", SR_WRAP_CLAMP,
        "kind", "color", SR_PAINT_COLOR, "linear", SR_PAINT_LINEAR_GRADIENT, "radial",
        SR_PAINT_RADIAL_GRADIENT, "pattern", SR_PAINT_PATTERN);
    if (!names || PyModule_AddObject(m, "draw2d_names", names) < 0) {
        Py_XDECREF(names);
        return -1;
    }
    if (PyModule_AddIntConstant(m, "max_dashes", SR_MAX_DASHES) < 0) {
        return -1;
    }
    return PyModule_AddIntConstant(m, "max_gradient_stops", SR_MAX_GRADIENT_STOPS);
}

static int add_type(PyObject *m, const char *name, PyTypeObject *type)
{
    if (PyType_Ready(type) < 0) {
        return -1;
    }
    Py_INCREF(type);
    if (PyModule_AddObject(m, name, (PyObject *)type) < 0) {
        Py_DECREF(type);
        return -1;
    }
    return 0;
}

PyMODINIT_FUNC PyInit__softrast(void)
{
    import_array();
    if (PyType_Ready(&sr_py_MeshType) < 0) {
        return NULL;
    }
    PyObject *m = PyModule_Create(&module);
    if (!m) {
        return NULL;
    }
    Py_INCREF(&sr_py_MeshType);
    if (PyModule_AddObject(m, "Mesh", (PyObject *)&sr_py_MeshType) < 0 ||
        PyModule_AddStringConstant(m, "library_version", SR_VERSION_STRING) < 0 ||
        PyModule_AddObject(m, "have_svg", PyBool_FromLong(sr_io_have_svg())) < 0 ||
        PyModule_AddObject(m, "have_text", PyBool_FromLong(sr_io_have_text())) < 0 ||
        add_features(m) < 0 ||
        add_framing_constants(m) < 0 || add_type(m, "Path", &sr_py_PathType) < 0 ||
        add_type(m, "PathView", &sr_py_PathViewType) < 0 ||
        add_type(m, "Canvas2D", &sr_py_Canvas2DType) < 0 || add_draw2d_names(m) < 0) {
        Py_DECREF(&sr_py_MeshType);
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
