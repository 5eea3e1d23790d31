/*
 * io_error.c - a reader's or writer's error as a Python exception: an
 * OSError of the subclass its errno names (FileNotFoundError,
 * PermissionError, IsADirectoryError ...) with the path as its filename
 * when the file could not be read, ValueError with the reader's
 * "FILE:LINE: what is wrong" when it is malformed.
 */
#include "module.h"

#include <errno.h>
#include <string.h>
#include <sys/stat.h>

PyObject *sr_py_message_text(const char *message)
{
    return PyUnicode_DecodeUTF8(message, (Py_ssize_t)strlen(message), "backslashreplace");
}

/* The library's message does not carry errno: stat the path again, as
 * open saw it moments earlier, for the subclass OSError picks from it. */
static int path_errno(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        return errno;
    }
    return S_ISDIR(st.st_mode) ? EISDIR : 0;
}

const char *sr_py_why(sr_result r)
{
    return sr_last_error()[0] ? sr_last_error() : sr_result_text(r);
}

PyObject *sr_py_io_error(sr_result r, const sr_io_error *err, const char *path)
{
    PyObject *text = sr_py_message_text(err->message[0] ? err->message : sr_result_text(r));
    if (!text) {
        return NULL;
    }
    if (r == SR_OUT_OF_MEMORY) {
        PyErr_SetObject(PyExc_MemoryError, text);
    } else if (r != SR_IO_ERROR) {
        PyErr_SetObject(PyExc_ValueError, text);
    } else {
        int e = path ? path_errno(path) : 0;
        PyObject *filename = path ? PyUnicode_DecodeFSDefault(path) : NULL;
        PyObject *exc = NULL;
        if (!path || filename) {
            exc = e ? PyObject_CallFunction(PyExc_OSError, "iOO", e, text, filename)
                    : PyObject_CallFunction(PyExc_OSError, "O", text);
        }
        if (exc) {
            PyErr_SetObject((PyObject *)Py_TYPE(exc), exc);
            Py_DECREF(exc);
        }
        Py_XDECREF(filename);
    }
    Py_DECREF(text);
    return NULL;
}
