/*
 * warning_list.c - the readers' warnings, kept while a reader runs without
 * the GIL and handed to Python as a list of lines, which the Python layer
 * gives to the warnings module (softrast.SoftrastWarning) once the call is
 * back in Python code: a filter that turns them into exceptions then
 * raises where nothing of the C side is left to clean up.
 */
#include "module.h"

#include <stdlib.h>
#include <string.h>

void sr_py_keep_warning(void *user, const char *message)
{
    sr_py_warnings *w = user;
    if (w->count == w->capacity) {
        int capacity = w->capacity ? 2 * w->capacity : 8;
        char **lines = realloc(w->lines, (size_t)capacity * sizeof *lines);
        if (!lines) {
            w->lost = true;
            return;
        }
        w->lines = lines;
        w->capacity = capacity;
    }
    char *copy = strdup(message);
    if (!copy) {
        w->lost = true;
        return;
    }
    w->lines[w->count++] = copy;
}

void sr_py_drop_warnings(sr_py_warnings *w)
{
    for (int i = 0; i < w->count; i++) {
        free(w->lines[i]);
    }
    free(w->lines);
    *w = (sr_py_warnings){ 0 };
}

PyObject *sr_py_take_warnings(sr_py_warnings *w)
{
    PyObject *list = w->lost ? PyErr_NoMemory() : PyList_New(0);
    for (int i = 0; list && i < w->count; i++) {
        PyObject *s = sr_py_message_text(w->lines[i]);
        if (!s || PyList_Append(list, s) < 0) {
            Py_CLEAR(list);
        }
        Py_XDECREF(s);
    }
    sr_py_drop_warnings(w);
    return list;
}
