/*
 * svg.c - render_svg: an SVG document (a file, or bytes in memory) to an
 * (H, W, 4) uint8 RGBA array with the library's SVG reader
 * (sr_render_svg_file, sr_render_svg).  The render runs without the GIL
 * on a context of its own with no worker threads (the reader draws on the
 * calling thread); the warnings it gives are collected and handed back,
 * with the error when it fails, for softrast.render_svg to raise through
 * the warnings module before the error.  The drawing's layers (group
 * opacity, masks, clip paths) get what the memory limit leaves after the
 * image, as in the softrast tool, and a layer past it is a MemoryError.
 * parse_color: sr_io_parse_color, the reader's CSS colors for the
 * background.
 */
#include "module.h"

#include <stdlib.h>
#include <string.h>

/* The exception set, taken out as an object; NULL when none could be made. */
static PyObject *take_error(void)
{
#if PY_VERSION_HEX >= 0x030c0000
    return PyErr_GetRaisedException();
#else
    PyObject *type, *value, *tb;
    PyErr_Fetch(&type, &value, &tb);
    PyErr_NormalizeException(&type, &value, &tb);
    if (value && tb) {
        PyException_SetTraceback(value, tb);
    }
    Py_XDECREF(type);
    Py_XDECREF(tb);
    return value;
#endif
}

PyObject *sr_py_parse_color(PyObject *self, PyObject *args)
{
    (void)self;
    const char *text;
    Py_ssize_t len;
    if (!PyArg_ParseTuple(args, "s#:parse_color", &text, &len)) {
        return NULL;
    }
    sr_rgba c;
    if ((size_t)len != strlen(text) || sr_io_parse_color(text, &c) != SR_OK) {
        return PyErr_Format(PyExc_ValueError, "not a CSS color: %R", PyTuple_GET_ITEM(args, 0));
    }
    return Py_BuildValue("(ffff)", c.r, c.g, c.b, c.a);
}

PyObject *sr_py_render_svg(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_obj = NULL, *name_obj = NULL;
    Py_buffer data = { 0 };
    int width, height;
    double scale;
    float bg[4];
    /* render_svg(path, data, name, width, height, scale, (r, g, b, a)):
     * exactly one of path and data is not None; name (None: the path, or
     * "<svg>" with no files read) names the document and the directory
     * its images are read from; softrast.render_svg has checked the
     * values. */
    PyObject *path_arg, *data_arg, *name_arg;
    if (!PyArg_ParseTuple(args, "OOOiid(ffff):render_svg", &path_arg, &data_arg, &name_arg,
                          &width, &height, &scale, &bg[0], &bg[1], &bg[2], &bg[3])) {
        return NULL;
    }
    if ((path_arg == Py_None) == (data_arg == Py_None)) {
        PyErr_SetString(PyExc_TypeError, "render_svg: give a path or data, not both");
        return NULL;
    }
    if (path_arg != Py_None && !PyUnicode_FSConverter(path_arg, &path_obj)) {
        return NULL;
    }
    if (name_arg != Py_None && !PyUnicode_FSConverter(name_arg, &name_obj)) {
        Py_XDECREF(path_obj);
        return NULL;
    }
    if (data_arg != Py_None && PyObject_GetBuffer(data_arg, &data, PyBUF_SIMPLE) < 0) {
        Py_XDECREF(path_obj);
        Py_XDECREF(name_obj);
        return NULL;
    }
    /* What softrast.render_svg counted (check_memory) for the drawing and
     * the array, when the size is given; the layers may take the rest.
     * A size from the document is the library's to refuse. */
    sr_memory_limit_info limit;
    sr_io_error err = { { 0 } };
    if (sr_query_memory_limit(&limit, &err) != SR_OK) {
        Py_XDECREF(path_obj);
        Py_XDECREF(name_obj);
        if (data.obj) {
            PyBuffer_Release(&data);
        }
        return sr_py_io_error(SR_INVALID_ARG, &err, NULL);
    }
    uint64_t counted = (uint64_t)width * (uint64_t)height * 8;
    sr_py_warnings warnings = { 0 };
    sr_svg_desc desc = {
        .name = name_obj ? PyBytes_AS_STRING(name_obj) : NULL,
        .width = width,
        .height = height,
        .scale = scale,
        .background = { bg[0], bg[1], bg[2], bg[3] },
        .max_layer_bytes = limit.bytes > counted ? limit.bytes - counted : 1, /* 0: no limit */
        .warn = sr_py_keep_warning,
        .warn_user = &warnings,
    };
    sr_framebuffer *fb = NULL;
    sr_svg_info info = { 0 };
    sr_context *ctx = NULL;
    uint8_t *px = NULL;
    int w = 0, h = 0;
    sr_result r;
    Py_BEGIN_ALLOW_THREADS
    r = sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    if (r == SR_OK) {
        r = path_obj ? sr_render_svg_file(ctx, PyBytes_AS_STRING(path_obj), &desc, &fb, &info, &err)
                     : sr_render_svg(ctx, data.buf, (size_t)data.len, &desc, &fb, &info, &err);
    }
    if (r == SR_OK) {
        /* Copied out while the GIL is free: the one copy, which the array
         * made after takes over (sr_py_image_array). */
        w = sr_framebuffer_width(fb);
        h = sr_framebuffer_height(fb);
        px = malloc((size_t)w * (size_t)h * 4);
        if (px) {
            memcpy(px, sr_framebuffer_pixels(fb), (size_t)w * (size_t)h * 4);
        } else {
            r = SR_OUT_OF_MEMORY;
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    Py_END_ALLOW_THREADS
    if (data.obj) {
        PyBuffer_Release(&data);
    }
    PyObject *lines = sr_py_take_warnings(&warnings);
    PyObject *result = NULL;
    if (r != SR_OK) {
        free(px);
    }
    if (!lines) {
        if (r == SR_OK) {
            free(px);
        }
    } else if (r == SR_IO_ERROR && path_obj) {
        sr_py_io_error(r, &err, PyBytes_AS_STRING(path_obj));
    } else if (r != SR_OK) {
        /* A malformed document, a reference cycle, a size or budget
         * refused: "NAME:LINE: what is wrong".  Layers past the memory
         * limit are numpy's kind of failure to allocate, as an image
         * past it is (check_memory); a work budget is the document's. */
        bool memory = r == SR_OUT_OF_MEMORY || (r == SR_TOO_LARGE && info.over_layer_limit);
        PyObject *text = sr_py_message_text(err.message[0] ? err.message : sr_result_text(r));
        if (text) {
            PyErr_SetObject(memory ? PyExc_MemoryError : PyExc_ValueError, text);
            Py_DECREF(text);
        }
    } else {
        PyObject *image = sr_py_image_array(px, w, h);
        result = image ? Py_BuildValue("(NOO)", image, lines, Py_None) : NULL;
    }
    if (lines && r != SR_OK) {
        /* The failure goes back as an object after the warnings, which
         * came first and are raised first. */
        PyObject *error = take_error();
        result = error ? Py_BuildValue("(ONN)", Py_None, lines, error) : NULL;
        lines = NULL;
    }
    Py_XDECREF(lines);
    Py_XDECREF(path_obj);
    Py_XDECREF(name_obj);
    return result;
}
