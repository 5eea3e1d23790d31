/*
 * memory_limit.c - check_memory(what, need, lower): sr_check_memory, the
 * memory limit the softrast tool checks too (SR_MEMORY_LIMIT, else the
 * physical memory or a ulimit), for the package's images before numpy
 * allocates them.  Over the limit it raises MemoryError (numpy's own kind
 * of failure to allocate) naming the sizes; a malformed SR_MEMORY_LIMIT
 * raises ValueError.
 */
#include "module.h"

PyObject *sr_py_check_memory(PyObject *self, PyObject *args)
{
    (void)self;
    const char *what, *lower;
    PyObject *need_obj;
    if (!PyArg_ParseTuple(args, "sO!s:check_memory", &what, &PyLong_Type, &need_obj, &lower)) {
        return NULL;
    }
    /* A count beyond 64 bits is beyond every limit. */
    unsigned long long need = PyLong_AsUnsignedLongLong(need_obj);
    if (need == (unsigned long long)-1 && PyErr_Occurred()) {
        if (!PyErr_ExceptionMatches(PyExc_OverflowError)) {
            return NULL;
        }
        PyErr_Clear();
        need = UINT64_MAX;
    }
    sr_io_error err = { { 0 } };
    sr_result r = sr_check_memory(&(sr_memory_check_desc){ .what = what, .bytes = need,
                                                           .memory = "image memory",
                                                           .lower = lower },
                                  &err);
    if (r == SR_OK) {
        Py_RETURN_NONE;
    }
    return sr_py_io_error(r == SR_TOO_LARGE ? SR_OUT_OF_MEMORY : r, &err, NULL);
}
